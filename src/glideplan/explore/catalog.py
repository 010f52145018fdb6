"""The explorer's planner catalogue, built from the planner registry and the vehicle dataclasses.

Every registered planner becomes an entry; its inputs are the vehicle's dataclass fields and the
planner's keyword options, named like the `glideplan plan PLANNER` command-line options (the
field `turn_radius` is `--radius`, the three polar coefficients are `--polar A B C`, the wind
is `--wind SPEED FROM_DEG`, compass, converted by `glideplan.units.wind_from_compass`).
Nothing here knows a planner by name except the readable labels, which fall back to the
registry's description; a planner registered later appears with its fields as inputs.
"""

from __future__ import annotations

import dataclasses
import inspect
import math
import sys
import typing
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any, cast

from glideplan.errors import InvalidParameterError
from glideplan.explore.field_labels import CAPTION_NAMES as _CAPTION_NAMES
from glideplan.explore.field_labels import DEGREE_FIELDS as _DEGREE_FIELDS
from glideplan.explore.field_labels import FIELD_UNITS as _FIELD_UNITS
from glideplan.validation import check_finite

__all__ = [
    "Catalog",
    "Parameter",
    "PlannerEntry",
    "build_catalog",
    "parse_number",
    "planner_key",
]

# Field (or option) name -> the command-line option name, where they differ.
CLI_NAMES: Mapping[str, str] = {
    "turn_radius": "radius",
    "l_over_d_max": "l_over_d",
    "disturbance_ratio": "eps",
}
# Groups of fields entered as one comma-separated option, with per-item converters to SI.
_GROUPS: tuple[tuple[str, tuple[str, ...], tuple[str, ...]], ...] = (
    # (option, fields, units of the entered items: "" as is, "deg" converted to radians)
    ("polar", ("a", "b", "c"), ("", "", "")),
)
# Readable labels for the built-in planners (key -> label); others use their description.
LABELS: Mapping[str, str] = {
    "dubins": "Dubins car: shortest path (ch. 2-3)",
    "dubins/time": "Dubins car: minimum time (ch. 2-3)",
    "wind": "Dubins car in a steady wind: minimum time (ch. 3, app. A)",
    "time-optimal": "Variable speed: minimum time, synthesis (ch. 4)",
    "time-optimal-direct": "Variable speed: minimum time, direct method (ch. 4)",
    "min-altitude": "Glider, quadratic polar: minimum altitude loss, synthesis (ch. 5)",
    "min-altitude-direct": "Glider, quadratic polar: minimum altitude loss, direct method (ch. 5)",
    "load-factor": "Glider, speed and load factor: minimum altitude loss, synthesis (ch. 6)",
    "load-factor-direct": (
        "Glider, speed and load factor: minimum altitude loss, direct method (ch. 6)"
    ),
}
# The page's key of a registered planner where it differs from the registered name: the
# load-factor page is the chapter 6 synthesis (`plan load-factor --method synthesis`, the
# direct method answering where it finds no candidate), its direct method is
# `load-factor-direct`, as `time-optimal-direct` and `min-altitude-direct`. Links naming the
# registered synthesis (`planner=load-factor-synthesis`) still open it.
PAGE_KEYS: Mapping[str, str] = {
    "load-factor-synthesis": "load-factor",
    "load-factor": "load-factor-direct",
}
_ALIASES: Mapping[str, str] = {"load-factor-synthesis": "load-factor"}
# Syntheses that fall back to a direct method (seconds) where they find no candidate: they
# are planned on the page's worker thread, so that a fallback never stalls the page.
_FALLS_BACK = frozenset({"load-factor"})
# Option types the page can enter as text.
_SCALARS = (bool, int, float, str)


def parse_number(name: str, text: str) -> float:
    """A finite number from entered text; `InvalidParameterError` naming `name` otherwise."""
    try:
        value = float(str(text).strip())
    except ValueError:
        raise InvalidParameterError(name, text, "must be a real number") from None
    return check_finite(name, value)


def planner_key(name: str) -> str:
    """The URL and catalogue key of a registered planner name ('min_altitude' -> 'min-altitude')."""
    return name.strip().lower().replace("_", "-")


@dataclass(frozen=True)
class Parameter:
    """One input of the page: its option name, the fields it sets, its default text and kind.

    `kind` is "float", "int", "str" or "bool" for one field, "group" for a comma-separated
    group, "wind" for a vehicle's (east, north) wind entered as "speed, compass FROM deg";
    `target` is "vehicle" or "option" (a keyword option of the planner function).
    """

    name: str
    fields: tuple[str, ...]
    default: str
    kind: str
    target: str
    units: tuple[str, ...] = ()
    optional: bool = False

    @property
    def label(self) -> str:
        return self.name.replace("_", "-")

    def caption(self, nondimensional: bool = False) -> str:
        """The page's label: words and units, e.g. 'v min (m/s)', 'bank max (deg)'.

        Speeds and lengths of a nondimensional vehicle read '(nondim.)'; pure numbers
        (counts, names, switches) have no unit.
        """
        if self.kind == "wind":
            return "wind: speed (m/s), from (deg compass)"
        if self.kind == "group":
            return _group_caption(self, nondimensional)
        words = _CAPTION_NAMES.get(self.name, self.name.replace("_", " "))
        for tail in ("kg", "m2", "pct", "l"):
            if words.endswith(" " + tail) and not words.endswith(" " + self.name):
                words = words[: -len(tail) - 1]
        unit = _FIELD_UNITS.get(self.fields[0].rpartition(".")[2], "")
        if unit in ("speed", "length"):
            unit = "nondim." if nondimensional else ("m/s" if unit == "speed" else "m")
        if self.kind == "bool":
            unit = "true/false"
        return f"{words} ({unit})" if unit else words

    @property
    def flag(self) -> str:
        """The command-line flag, as the CLI's messages name it (`--radius`)."""
        return f"--{self.label}"

    def parse(self, text: str) -> dict[str, Any]:
        """The field values for the entered `text`; raises `InvalidParameterError` naming it."""
        raw = str(text).strip()
        if self.optional and raw.lower() in ("", "none"):
            return dict.fromkeys(self.fields)
        if self.kind == "wind":  # the compass edge: speed, FROM deg -> (east, north) m/s
            from glideplan.units import wind_from_compass

            parts = raw.replace(",", " ").split()
            if len(parts) != 2:
                raise InvalidParameterError(self.flag, text, "needs 2 numbers: speed, from")
            speed, frm = (parse_number(self.flag, t) for t in parts)
            return {self.fields[0]: wind_from_compass(speed, frm, param=self.flag)}
        if self.kind == "group":
            items = [p for p in raw.replace(",", " ").split()]
            if len(items) != len(self.fields):
                names = ", ".join(f.rpartition(".")[2] for f in self.fields)
                raise InvalidParameterError(
                    self.flag, text, f"needs {len(self.fields)} numbers: {names}"
                )
            out: dict[str, Any] = {}
            for field, item, unit in zip(self.fields, items, self.units, strict=True):
                value = parse_number(self.flag, item)
                out[field] = _to_si(value, unit)
            return out
        field = self.fields[0]
        if self.kind == "float":
            value = parse_number(self.flag, raw)
            return {field: math.radians(value) if self.units == ("deg",) else value}
        if self.kind == "int":
            try:
                return {field: int(raw)}
            except ValueError:
                raise InvalidParameterError(self.flag, text, "must be an integer") from None
        if self.kind == "bool":
            if raw.lower() not in ("true", "false", "1", "0", "yes", "no"):
                raise InvalidParameterError(self.flag, text, "must be true or false")
            return {field: raw.lower() in ("true", "1", "yes")}
        return {field: raw}


@dataclass(frozen=True)
class PlannerEntry:
    """A planner of the page: a registered planner with its objective, label and inputs."""

    key: str
    label: str
    spec: Any  # glideplan.planning.PlannerSpec
    default_vehicle: Any  # an instance of spec.vehicle, or None when it has no defaults
    parameters: tuple[Parameter, ...]

    @property
    def vehicle_type(self) -> type:
        return cast(type, self.spec.vehicle)

    @property
    def objective(self) -> str:
        return str(self.spec.objective)

    @property
    def method(self) -> str:
        return str(self.spec.method)

    @property
    def slow(self) -> bool:
        """Direct (optimisation) methods take seconds: the page shows that it is working."""
        return self.method != "synthesis"

    @property
    def background(self) -> bool:
        """Planned on the page's worker thread: a direct method, or a synthesis that may fall
        back to one."""
        return self.slow or self.key in _FALLS_BACK

    @property
    def length_scale(self) -> float:
        v = self.default_vehicle
        return float(v.length_scale) if v is not None else 1.0

    @property
    def help(self) -> str:
        """The vehicle's one-paragraph description (code quotes removed)."""
        doc = inspect.getdoc(self.vehicle_type) or ""
        return " ".join(doc.split("\n\n")[0].split()).replace("`", "")

    @property
    def nondimensional(self) -> bool:
        """Lengths and speeds in reference units (the vehicle says so), not m and m/s."""
        return "nondimensional" in (inspect.getdoc(self.vehicle_type) or "").lower()

    @property
    def length_unit(self) -> str:
        """'m', or 'nondim.' for a nondimensional vehicle (axes, costs, endpoint errors)."""
        return "nondim." if self.nondimensional else "m"

    def build_vehicle(self, values: Mapping[str, Any]) -> Any:
        """The vehicle from field values keyed by dotted paths ('polar.a' sets a nested field)."""
        return _construct(self.vehicle_type, values)

    def parameter(self, name: str) -> Parameter | None:
        for p in self.parameters:
            if p.name == name or name in p.fields:
                return p
        for p in self.parameters:
            if any(f.rpartition(".")[2] == name for f in p.fields):
                return p
        return None


@dataclass(frozen=True)
class Catalog:
    """All planner entries, in a stable order (by vehicle model, then method)."""

    entries: tuple[PlannerEntry, ...]

    def __post_init__(self) -> None:
        if not self.entries:
            raise InvalidParameterError("planners", (), "no planner is registered")

    def get(self, key: str) -> PlannerEntry:
        k = planner_key(key)
        k = _ALIASES.get(k, k) if k not in self.keys else k
        for e in self.entries:
            if e.key == k:
                return e
        known = ", ".join(e.key for e in self.entries)
        raise InvalidParameterError("planner", key, f"must be one of {known}")

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(e.key for e in self.entries)


def _group_caption(p: Parameter, nondimensional: bool) -> str:
    """'polar a, b, c of w = a v² + b v + c (SI)'."""
    last = tuple(f.rpartition(".")[2] for f in p.fields)
    if last == ("a", "b", "c"):
        return "polar: sink w = a v² + b v + c; a (s/m), b, c (m/s)"
    items = [n + (" (deg)" if u == "deg" else "") for n, u in zip(last, p.units, strict=True)]
    return f"{p.name.replace('_', ' ')}: {', '.join(items)}"


def _to_si(value: float, unit: str) -> float:
    """An entered item in the vehicle's units: degrees to radians; a compass FROM (deg)
    to the direction it blows towards (rad, counter-clockwise from +x): 270 deg - FROM."""
    if unit == "deg":
        return math.radians(value)
    if unit == "from":
        return math.radians(270.0 - value)
    return value


def _from_si(value: float, unit: str) -> float:
    """The inverse of `_to_si` (a compass FROM in [0, 360))."""
    if unit == "deg":
        return math.degrees(value)
    if unit == "from":
        return round((270.0 - math.degrees(value)) % 360.0, 9) % 360.0
    return value


def _fmt(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.10g}"
    return str(value)


def default_vehicle(vehicle_type: type) -> Any:
    """The vehicle with its dataclass defaults, else the first preset of its module, else None.

    A preset is a public function of the vehicle's module that takes no argument and returns an
    instance (e.g. `dg1001m()` for the quadratic-polar glider).
    """
    try:
        return vehicle_type()
    except (TypeError, ValueError):
        pass
    module = sys.modules.get(vehicle_type.__module__)
    for name in getattr(module, "__all__", ()):
        obj = getattr(module, name, None)
        if not callable(obj) or isinstance(obj, type):
            continue
        try:
            sig = inspect.signature(obj)
        except (TypeError, ValueError):
            continue
        if any(p.default is inspect.Parameter.empty for p in sig.parameters.values()):
            continue
        try:
            out = obj()
        except (TypeError, ValueError):
            continue
        if isinstance(out, vehicle_type):
            return out
    return None


def _kind(value: Any, annotation: Any) -> str | None:
    text = str(annotation)
    for t in _SCALARS:
        if isinstance(value, t) or text == t.__name__:
            return t.__name__
    return None


def _construct(cls: type, values: Mapping[str, Any]) -> Any:
    """`cls(**fields)` where dotted keys build nested dataclass fields first."""
    direct: dict[str, Any] = {}
    nested: dict[str, dict[str, Any]] = {}
    for key, value in values.items():
        head, _, rest = key.partition(".")
        if rest:
            nested.setdefault(head, {})[rest] = value
        else:
            direct[key] = value
    hints = typing.get_type_hints(cls)
    for head, sub in nested.items():
        direct[head] = _construct(hints[head], sub)
    return cls(**direct)


def _vehicle_parameters(cls: type, obj: Any, prefix: str = "") -> list[Parameter]:
    """Inputs for the init fields of dataclass `cls` (nested dataclasses flattened)."""
    hints = typing.get_type_hints(cls)
    fields = [f for f in dataclasses.fields(cls) if f.init]
    names = [f.name for f in fields]
    dotted = prefix
    out: list[tuple[int, Parameter]] = []
    grouped: set[str] = set()
    order = {n: i for i, n in enumerate(names)}

    def opt_name(name: str) -> str:
        base = CLI_NAMES.get(name, name)
        return base if not prefix or base == prefix else f"{prefix}_{base}"

    for option, members, units in _GROUPS:
        if all(m in names for m in members):
            values = []
            for m, u in zip(members, units, strict=True):
                v = getattr(obj, m) if obj is not None else None
                values.append("" if v is None else _fmt(_from_si(v, u)))
            default = ",".join(values) if obj is not None else ""
            paths = tuple(f"{dotted}.{m}" if dotted else m for m in members)
            out.append(
                (
                    order[members[0]],
                    Parameter(opt_name(option), paths, default, "group", "vehicle", units),
                )
            )
            grouped.update(members)
    if "wind" in names:  # the library's (east, north) wind, entered as compass at this edge
        from glideplan.units import wind_to_compass

        w = getattr(obj, "wind", None) if obj is not None else None
        default = "" if w is None else ",".join(_fmt(v) for v in wind_to_compass(*w))
        path = f"{dotted}.wind" if dotted else "wind"
        out.append((order["wind"], Parameter(opt_name("wind"), (path,), default, "wind",
                                             "vehicle", ("m/s", "deg"))))
        grouped.add("wind")
    for f in fields:
        if f.name in grouped:
            continue
        hint = hints.get(f.name)
        value = getattr(obj, f.name) if obj is not None else None
        path = f"{dotted}.{f.name}" if dotted else f.name
        if isinstance(hint, type) and dataclasses.is_dataclass(hint):
            for p in _vehicle_parameters(hint, value, f.name):
                out.append((order[f.name], p))
            continue
        args = typing.get_args(hint)
        optional = type(None) in args
        base = next((a for a in args if a is not type(None)), hint)
        kind = _kind(value, getattr(base, "__name__", base)) or "float"
        if obj is None and f.default is not dataclasses.MISSING:
            value = f.default
        entered: tuple[str, ...] = ()
        if f.name in _DEGREE_FIELDS and isinstance(value, (int, float)):
            value, entered = round(math.degrees(value), 9), ("deg",)
        default = "" if value is None else _fmt(value)
        out.append(
            (
                order[f.name],
                Parameter(opt_name(f.name), (path,), default, kind, "vehicle", entered, optional),
            )
        )
    out.sort(key=lambda item: item[0])
    return [p for _, p in out]


def _option_parameters(spec: Any) -> list[Parameter]:
    sig = inspect.signature(spec.function)
    out: list[Parameter] = []
    for name in spec.options:
        p = sig.parameters[name]
        kind = _kind(p.default, p.annotation)
        if kind is None or p.default is inspect.Parameter.empty:
            continue  # an option the page cannot enter as text keeps its default
        out.append(Parameter(CLI_NAMES.get(name, name), (name,), _fmt(p.default), kind, "option"))
    return out


def _label(key: str, spec: Any) -> str:
    if key in LABELS:
        return LABELS[key]
    text = spec.description or spec.name
    for stop in ("(", ":"):
        text = text.split(stop)[0]
    return f"{text.strip().rstrip(',')} ({spec.method})"


def build_catalog(
    specs: tuple[Any, ...] | None = None, labels: Callable[..., str] = _label
) -> Catalog:
    """One entry per registered planner (and per objective where a name has several)."""
    if specs is None:
        from glideplan import registered_planners

        specs = registered_planners()
    by_name: dict[str, list[Any]] = {}
    for s in specs:
        name = planner_key(s.name)
        by_name.setdefault(PAGE_KEYS.get(name, name), []).append(s)
    entries: list[PlannerEntry] = []
    for name, group in by_name.items():
        for s in group:
            default_obj = getattr(s.vehicle, "default_objective", s.objective)
            key = (
                name if (len(group) == 1 or s.objective == default_obj) else f"{name}/{s.objective}"
            )
            vehicle = default_vehicle(s.vehicle)
            params = _vehicle_parameters(s.vehicle, vehicle) + _option_parameters(s)
            entries.append(PlannerEntry(key, labels(key, s), s, vehicle, tuple(params)))
    entries.sort(key=lambda e: (e.vehicle_type.__module__, e.method != "synthesis", e.key))
    return Catalog(tuple(entries))
