"""The explorer's input widgets: a checkbox, a dropdown or a spinner for each planner input.

Each `Parameter` of the catalogue becomes the widget a user expects (issue 27):
- true/false: a checkbox; a choice among names (collocation scheme, formulation, seeds): a
  dropdown of the planner's own names;
- a number: a spinner whose limits are the physical range of its quantity
  (`glideplan.validation.PHYSICAL_RANGES`, the one range table: the browser clamps a typed
  value into it; the server still checks, as the CLI does) shown rounded to 4 significant
  digits (`44.44` m/s, not `44.44444444`); turn rates in deg/s (rad/s inside);
- the wind: its speed in a unit of the user's choice (m/s, km/h, kt), and the compass
  direction it blows FROM (deg), as every `--wind` of the CLI;
- the polar: its three coefficients a, b, c.

The page's state (and its URL) keeps the CLI's values as text, exact to 10 digits (m/s, rad/s,
compass FROM deg): a widget shows them rounded and writes back only what the user changes.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import panel as pn

from glideplan.explore.catalog import Parameter
from glideplan.explore.layout import NOT_BUSY
from glideplan.validation import PHYSICAL_RANGES

__all__ = [
    "WIND_UNITS",
    "InputControl",
    "build_input",
    "display_format",
    "number_input",
    "number_text",
    "wind_input",
]

# m/s per unit of the wind's speed (1 kt = 1852 m / 3600 s, 1 km/h = 1/3.6 m/s: exact)
WIND_UNITS: Mapping[str, float] = {"m/s": 1.0, "km/h": 1.0 / 3.6, "kt": 1852.0 / 3600.0}
# The physical range (PHYSICAL_RANGES key) of a field, by the last part of its name.
RANGE_OF: Mapping[str, str] = {
    "speed": "speed",
    "v_min": "speed",
    "v_max": "speed",
    "v_stall": "speed",
    "turn_radius": "turn_radius",
    "mc": "mc",
    "wind_speed": "wind_speed",
    "bank_max": "bank",
    "mass_kg": "mass",
    "reference_mass_kg": "mass",
    "wing_area_m2": "area",
    "l_over_d_max": "coefficient",
}
# Bounds of the pure numbers (not physical quantities; the planner's own rules).
NUMBER_BOUNDS: Mapping[str, tuple[float | None, float | None]] = {
    "disturbance_ratio": (0.0, 0.99),
    "bugs_pct": (0.0, 100.0),
    "max_ballast_l": (0.0, None),
    "n_max": (1.0, None),
    "mesh_tol": (0.0, 1.0),
    "classification_tol": (0.0, 1.0),
}
# Fields shown in deg/s (rad/s inside and in the URL, as the CLI's --u-max).
TURN_RATES = frozenset({"u_max", "turn_rate_max"})


class _FloatInput(pn.widgets.FloatInput):
    """A spinner whose change reaches the server at once (Panel waits 50 ms by default)."""

    _debounce = 0
    _busy__ignore = NOT_BUSY


class _IntInput(pn.widgets.IntInput):
    _debounce = 0
    _busy__ignore = NOT_BUSY


class _Select(pn.widgets.Select):
    _debounce = 0
    _busy__ignore = NOT_BUSY


class _Checkbox(pn.widgets.Checkbox):
    _debounce = 0
    _busy__ignore = NOT_BUSY


def _choices() -> Mapping[str, tuple[str, ...]]:
    """The names a text option may take: the planners' own tables."""
    from glideplan.planners.direct.collocation import SCHEMES
    from glideplan.planners.load_factor import FORMULATIONS
    from glideplan.planners.min_altitude.direct import SEEDS

    return {"scheme": tuple(SCHEMES), "formulation": tuple(FORMULATIONS), "seeds": tuple(SEEDS)}


def number_text(value: float) -> str:
    """A number as the URL carries it: up to 10 significant digits, no '-0'."""
    text = f"{value:.10g}"
    return "0" if text == "-0" else text


def display_format(value: float | None, digits: int = 4) -> str:
    """A numbro format that shows `value` to `digits` significant digits, no trailing zeros
    (44.44444444 -> '0,0.[00]' shows 44.44; 0.002712528 -> 6 decimals shows 0.002713)."""
    if value is None or value == 0.0 or not math.isfinite(value):
        decimals = 3
    else:
        decimals = max(0, min(10, digits - 1 - math.floor(math.log10(abs(value)))))
    return "0,0" if decimals == 0 else "0,0.[" + "0" * decimals + "]"


def _step(value: float | None) -> float:
    """A spinner step of about a tenth of the value's size (1, 2 or 5 times a power of ten)."""
    if value is None or value == 0.0 or not math.isfinite(value):
        return 0.1
    return float(10.0 ** (math.floor(math.log10(abs(value))) - 1))


def _bounds(p: Parameter, nondimensional: bool) -> tuple[float | None, float | None, str]:
    """(low, high, rule) of a number's field in its SI (URL) units."""
    last = p.fields[0].rpartition(".")[2]
    kind = RANGE_OF.get(last)
    if kind == "speed" and nondimensional:
        return 0.0, None, "> 0 (units of the reference speed)"
    if kind is not None:
        r = PHYSICAL_RANGES[kind]
        return r.low, r.high, r.rule().removeprefix("must lie in ")
    if last in NUMBER_BOUNDS:
        lo, hi = NUMBER_BOUNDS[last]
        return lo, hi, ""
    if last in TURN_RATES:
        return 0.0, None, "> 0"
    return None, None, ""


@dataclass
class InputControl:
    """The widgets of one input, their value as URL text, and how to show a new text."""

    name: str
    widgets: list[Any]
    get_text: Callable[[], str]
    set_text: Callable[[str], None]


def _float(text: str) -> float | None:
    try:
        value = float(str(text).strip())
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _spinner(
    label: str, si: float | None, factor: float, low: float | None, high: float | None, **kw: Any
) -> _FloatInput:
    """A spinner showing `si * factor` rounded, clamped in the browser to [low, high] * factor."""
    shown = None if si is None else si * factor
    return _FloatInput(
        label=label,
        value=shown,
        start=None if low is None else low * factor,
        end=None if high is None else high * factor,
        step=_step(shown),
        format=display_format(shown),
        sizing_mode="stretch_width",
        margin=(2, 5),
        **kw,
    )


def build_input(
    p: Parameter,
    text: str,
    nondimensional: bool,
    on_text: Callable[[str], None],
    wind_unit: str = "m/s",
    on_unit: Callable[[str], None] | None = None,
) -> InputControl:
    """The widgets of parameter `p` showing the URL text `text`; a user's change calls
    `on_text(new text)` (the unit dropdown of the wind calls `on_unit(unit)`)."""
    last = tuple(f.rpartition(".")[2] for f in p.fields)
    if p.kind == "wind":  # the (east, north) wind entered as speed, compass FROM
        return _wind_input(p.name, text, on_text, wind_unit, on_unit)
    if p.kind == "group":
        return _group_input(p, text, on_text)
    css = [f"gp-input-{p.name}"]
    if p.kind == "bool":
        box = _Checkbox(
            label=p.caption(nondimensional).replace(" (true/false)", ""),
            value=str(text).strip().lower() in ("true", "1", "yes"),
            css_classes=css,
            margin=(6, 5),
        )
        return _wire(p.name, [box], lambda: str(box.value), _bool_setter(box), on_text)
    choices = _choices().get(last[0])
    if p.kind == "str" and choices:
        options = list(choices) if text in choices else [text, *choices]
        sel = _Select(
            label=p.caption(nondimensional), options=options, value=text,
            sizing_mode="stretch_width", css_classes=css, margin=(2, 5),
        )
        return _wire(p.name, [sel], lambda: str(sel.value), _select_setter(sel), on_text)
    if p.kind == "str":
        entry = pn.widgets.TextInput(
            label=p.caption(nondimensional), value=text, sizing_mode="stretch_width",
            css_classes=css, margin=(2, 5),
        )
        return _wire(p.name, [entry], lambda: str(entry.value), _text_setter(entry), on_text)
    if p.kind == "int":
        spin = _IntInput(
            label=p.caption(nondimensional), value=_int(text), start=1, step=1,
            sizing_mode="stretch_width", css_classes=css, margin=(2, 5),
        )
        return _wire(p.name, [spin], lambda: _num_text(spin.value, 1.0), _int_setter(spin),
                     on_text)
    return _float_input(p, text, nondimensional, on_text)


def _int(text: str) -> int | None:
    value = _float(text)
    return int(value) if value is not None and value == int(value) else None


def _num_text(value: Any, factor: float) -> str:
    """The URL text of a widget's number (shown in units of `factor` per SI unit)."""
    if value is None:
        return ""
    return number_text(float(value) / factor) if factor != 1.0 else number_text(float(value))


def _float_input(
    p: Parameter, text: str, nondimensional: bool, on_text: Callable[[str], None]
) -> InputControl:
    last = p.fields[0].rpartition(".")[2]
    factor = 180.0 / math.pi if last in TURN_RATES else 1.0
    low, high, rule = _bounds(p, nondimensional)
    label = p.caption(nondimensional)
    if factor != 1.0:
        label = label.replace("(rad/s)", "(deg/s)")
    help_text = f"{label}: {rule}" if rule else label
    if p.optional:
        help_text += "; empty: none"
    return _number_control(p.name, label, text, factor, low, high, help_text, on_text)


def number_input(
    name: str, label: str, text: str, kind: str, on_text: Callable[[str], None]
) -> InputControl:
    """A spinner (class `gp-input-NAME`) for a quantity of `PHYSICAL_RANGES[kind]` in its
    table unit, showing `text` rounded; `on_text(new text)` on a user's change."""
    r = PHYSICAL_RANGES[kind]
    rule = r.rule().removeprefix("must lie in ")
    return _number_control(name, label, text, 1.0, r.low, r.high, f"{label}: {rule}", on_text)


def wind_input(name: str, text: str, on_text: Callable[[str], None]) -> InputControl:
    """The wind's widgets (speed with its unit, compass FROM) for the text `SPEED_MS,FROM_DEG`."""
    return _wind_input(name, text, on_text, "m/s", None)


def _number_control(
    name: str, label: str, text: str, factor: float, low: float | None, high: float | None,
    help_text: str, on_text: Callable[[str], None],
) -> InputControl:
    """A spinner showing the URL text `text` times `factor`; the text stays exact until the
    user changes the number."""
    spin = _spinner(
        label, _float(text), factor, low, high, css_classes=[f"gp-input-{name}"],
        description=help_text,
    )
    state = {"text": text}

    def get() -> str:
        shown = spin.value
        old = _float(state["text"])
        if shown is not None and old is not None and math.isclose(
            shown, old * factor, rel_tol=1e-12, abs_tol=0.0
        ):
            return state["text"]  # unchanged: the exact text (the URL keeps its digits)
        return _num_text(shown, factor)

    def set_(new: str) -> None:
        state["text"] = new
        value = _float(new)
        spin.value = None if value is None else value * factor

    def on_change(_event: Any) -> None:
        state["text"] = get()
        on_text(state["text"])

    spin.param.watch(on_change, "value")
    return InputControl(name, [spin], get, set_)


def _wire(
    name: str, widgets: list[Any], get: Callable[[], str], set_: Callable[[str], None],
    on_text: Callable[[str], None],
) -> InputControl:
    widgets[0].param.watch(lambda _e: on_text(get()), "value")
    return InputControl(name, widgets, get, set_)


def _bool_setter(box: Any) -> Callable[[str], None]:
    def set_(text: str) -> None:
        box.value = str(text).strip().lower() in ("true", "1", "yes")

    return set_


def _select_setter(sel: Any) -> Callable[[str], None]:
    def set_(text: str) -> None:
        if text not in sel.options:
            sel.options = [text, *[o for o in sel.options if o != text]]
        sel.value = text

    return set_


def _text_setter(box: Any) -> Callable[[str], None]:
    def set_(text: str) -> None:
        box.value = text

    return set_


def _int_setter(spin: Any) -> Callable[[str], None]:
    def set_(text: str) -> None:
        spin.value = _int(text)

    return set_


def _items(text: str, n: int) -> list[float | None]:
    parts = str(text).replace(",", " ").split()
    if len(parts) != n:
        return [None] * n
    return [_float(t) for t in parts]


def _group_input(p: Parameter, text: str, on_text: Callable[[str], None]) -> InputControl:
    """A comma group (the polar a, b, c): one spinner per item."""
    names = [f.rpartition(".")[2] for f in p.fields]
    units = {"a": "s/m", "b": "", "c": "m/s"}
    state = {"items": str(text).replace(",", " ").split()}
    spins = []
    for i, (n, v) in enumerate(zip(names, _items(text, len(names)), strict=True)):
        unit = units.get(n, "")
        label = f"{p.name.replace('_', ' ')} {n}" + (f" ({unit})" if unit else "")
        spins.append(_spinner(label, v, 1.0, None, None, css_classes=[f"gp-input-{p.name}-{i}"]))

    def get() -> str:
        items = list(state["items"]) if len(state["items"]) == len(spins) else [""] * len(spins)
        for i, s in enumerate(spins):
            old = _float(items[i]) if items[i] else None
            if s.value is None:
                items[i] = ""
            elif old is None or not math.isclose(s.value, old, rel_tol=1e-12, abs_tol=0.0):
                items[i] = number_text(float(s.value))
        return ",".join(items)

    def set_(new: str) -> None:
        state["items"] = str(new).replace(",", " ").split()
        for s, v in zip(spins, _items(new, len(spins)), strict=True):
            s.value = v

    def on_change(_event: Any) -> None:
        new = get()
        state["items"] = new.split(",")
        on_text(new)

    for s in spins:
        s.param.watch(on_change, "value")
    title = pn.pane.HTML(
        '<div class="gp-help">polar: sink rate w = a v² + b v + c (v, w in m/s)</div>',
        margin=(4, 5, 0, 5),
    )
    return InputControl(p.name, [title, *spins], get, set_)


def _wind_widgets(name: str, text: str, unit: str) -> tuple[Any, Any, Any]:
    """The wind's speed spinner (in `unit`, limited to the wind-speed range), its unit
    dropdown and the compass FROM spinner, showing the link's text `SPEED_MS,FROM_DEG`."""
    speed_ms, frm = _items(text, 2)
    wr = PHYSICAL_RANGES["wind_speed"]
    speed = _spinner(
        "wind speed", speed_ms, 1.0 / WIND_UNITS[unit], wr.low, wr.high,
        css_classes=[f"gp-input-{name}-speed"],
        description=f"wind speed: {wr.rule().removeprefix('must lie in ')}",
    )
    speed.format = "0,0.[00]"
    units = _Select(
        label="unit", options=list(WIND_UNITS), value=unit, width=78, margin=(2, 5),
        css_classes=[f"gp-input-{name}-unit"],
    )
    direction = _FloatInput(
        label="from (deg)", value=frm, start=0.0, end=360.0, step=5.0,
        format="0,0.[0]", sizing_mode="stretch_width", margin=(2, 5),
        css_classes=[f"gp-input-{name}-from"],
        description="the compass direction the wind blows FROM (deg): 0 north, 90 east",
    )
    return speed, units, direction


def _wind_text(items: list[str], unit: str, speed: Any, direction: Any) -> str:
    """The link's `SPEED_MS,FROM_DEG` for the shown speed (in `unit`) and direction; an item
    the user did not change keeps its text `items` (exact to the digit)."""
    items = list(items) if len(items) == 2 else ["", ""]
    factor = 1.0 / WIND_UNITS[unit]
    old = _float(items[0]) if items[0] else None
    if speed is None:
        items[0] = ""
    elif old is None or not math.isclose(speed, old * factor, rel_tol=1e-12):
        items[0] = number_text(float(speed) / factor)
    old_dir = _float(items[1]) if items[1] else None
    if direction is None:
        items[1] = ""
    elif old_dir is None or not math.isclose(direction, old_dir, rel_tol=1e-12):
        items[1] = number_text(float(direction))
    return ",".join(items)


def _wind_input(
    name: str,
    text: str,
    on_text: Callable[[str], None],
    unit: str,
    on_unit: Callable[[str], None] | None,
) -> InputControl:
    """The wind: speed (in the chosen unit), the unit, and the compass direction FROM (deg).

    The URL text is `SPEED_MS,FROM_DEG` (m/s and compass degrees, as `--wind SPEED FROM`)."""
    unit = unit if unit in WIND_UNITS else "m/s"
    state: dict[str, Any] = {"items": str(text).replace(",", " ").split(), "unit": unit}
    wr = PHYSICAL_RANGES["wind_speed"]
    speed, units, direction = _wind_widgets(name, text, unit)

    def get() -> str:
        return _wind_text(state["items"], state["unit"], speed.value, direction.value)

    def set_(new: str) -> None:
        state["items"] = str(new).replace(",", " ").split()
        s, d = _items(new, 2)
        speed.value = None if s is None else s / WIND_UNITS[state["unit"]]
        direction.value = d

    quiet = {"on": False}

    def on_change(_event: Any) -> None:
        if quiet["on"]:
            return  # a new unit shows the same speed: no new state
        new = get()
        state["items"] = new.split(",")
        on_text(new)

    def on_unit_change(event: Any) -> None:
        state["unit"] = event.new
        s, _ = _items(",".join(state["items"]), 2)
        quiet["on"] = True
        try:
            speed.end = wr.high / WIND_UNITS[event.new]
            speed.value = None if s is None else s / WIND_UNITS[event.new]  # the same wind
        finally:
            quiet["on"] = False
        if on_unit is not None:
            on_unit(event.new)

    speed.param.watch(on_change, "value")
    direction.param.watch(on_change, "value")
    units.param.watch(on_unit_change, "value")
    title = pn.pane.HTML(
        '<div class="gp-help">wind: speed, and the compass direction it blows FROM '
        "(as <code>--wind SPEED FROM_DEG</code>)</div>",
        margin=(4, 5, 0, 5),
    )
    return InputControl(name, [title, pn.Row(speed, units, direction, margin=0)], get, set_)
