"""The explorer's input widgets (issue 27): the widget a user expects for each input, the
physical range enforced, values rounded for display but exact in the URL, turn rates in
deg/s, and one wind convention (compass FROM, speed in m/s, km/h or kt).

References: `PHYSICAL_RANGES` (the one range table), the planners' own name tables
(SCHEMES, FORMULATIONS, SEEDS), exact unit definitions (1 kt = 1852/3600 m/s, 1 km/h =
1/3.6 m/s) and the compass by hand: a wind FROM the north blows towards -y (south), FROM
270 deg (west) towards +x (east).
"""

from __future__ import annotations

import math
import re

import panel as pn
import pytest

from glideplan.explore.catalog import build_catalog
from glideplan.explore.inputs import build_input, display_format, number_text
from glideplan.explore.state import request, state_from_query, state_to_query
from glideplan.validation import PHYSICAL_RANGES


@pytest.fixture(scope="module")
def catalog():
    return build_catalog()


def _controls(catalog, key, texts=None, unit="m/s"):
    """Every input of planner `key` built as the page builds it; the texts it reports."""
    entry = catalog.get(key)
    seen: dict[str, list[str]] = {}
    out = {}
    for p in entry.parameters:
        text = (texts or {}).get(p.name, p.default)
        out[p.name] = build_input(
            p, text, entry.nondimensional, lambda t, n=p.name: seen.setdefault(n, []).append(t),
            wind_unit=unit,
        )
    return out, seen


def _widgets(control):
    """The widgets of a control, rows opened."""
    out, stack = [], list(control.widgets)
    while stack:
        w = stack.pop(0)
        if isinstance(w, pn.widgets.Widget):
            out.append(w)
        elif hasattr(w, "objects"):
            stack[:0] = list(w.objects)
    return out


def _label(w) -> str:
    return str(w.label)


def test_widget_kinds(catalog):
    """true/false: a checkbox; the planners' names: a dropdown of exactly those names; a
    number: a spinner; no input is a free text box except the polar's name."""
    from glideplan.planners.direct.collocation import SCHEMES
    from glideplan.planners.load_factor import FORMULATIONS
    from glideplan.planners.min_altitude.direct import SEEDS

    glide, _ = _controls(catalog, "final-glide")
    assert isinstance(_widgets(glide["turning_polar"])[0], pn.widgets.Checkbox)
    assert _widgets(glide["turning_polar"])[0].value is True
    assert isinstance(_widgets(glide["approach"])[0], pn.widgets.Checkbox)
    lf, _ = _controls(catalog, "load-factor-direct")
    assert list(_widgets(lf["scheme"])[0].options) == list(SCHEMES)
    assert list(_widgets(lf["formulation"])[0].options) == list(FORMULATIONS)
    direct, _ = _controls(catalog, "min-altitude-direct")
    assert list(_widgets(direct["seeds"])[0].options) == list(SEEDS)
    assert isinstance(_widgets(direct["n_intervals"])[0], pn.widgets.IntInput)
    for entry in catalog.entries:
        if not entry.spec.function.__module__.startswith("glideplan."):
            continue  # a planner some test registered
        controls, _ = _controls(catalog, entry.key)
        for name, c in controls.items():
            for w in _widgets(c):
                if isinstance(w, pn.widgets.TextInput):
                    assert name == "polar_name", (entry.key, name)


def test_spinners_carry_the_physical_range(catalog):
    """Each physical quantity's spinner is limited to its PHYSICAL_RANGES row (the browser
    clamps a typed value into it); turn rates in deg/s with a lower limit of 0."""
    dubins, _ = _controls(catalog, "dubins")
    speed, radius = _widgets(dubins["speed"])[0], _widgets(dubins["radius"])[0]
    for w, kind in ((speed, "speed"), (radius, "turn_radius")):
        r = PHYSICAL_RANGES[kind]
        assert (w.start, w.end) == (r.low, r.high)
    assert (_widgets(dubins["eps"])[0].start, _widgets(dubins["eps"])[0].end) == (0.0, 0.99)
    glide, _ = _controls(catalog, "final-glide")
    bank = _widgets(glide["bank_max"])[0]
    assert (bank.start, bank.end) == (PHYSICAL_RANGES["bank"].low, PHYSICAL_RANGES["bank"].high)
    mc = _widgets(glide["mc"])[0]
    assert (mc.start, mc.end) == (0.0, 10.0)
    wind = _widgets(glide["wind"])[0]
    assert (wind.start, wind.end) == (0.0, PHYSICAL_RANGES["wind_speed"].high)
    ma, _ = _controls(catalog, "min-altitude")
    u = _widgets(ma["u_max"])[0]
    assert u.start == 0.0 and "deg/s" in _label(u)


def test_values_rounded_for_display_exact_in_the_url(catalog):
    """v max 44.44444444 m/s is shown 44.44 (4 digits), u max 0.2094395102 rad/s as 12 deg/s;
    an untouched input keeps its exact text; a changed one writes the SI value to 10 digits."""
    assert display_format(44.44444444) == "0,0.[00]"
    assert display_format(0.2094395102 * 180 / math.pi) == "0,0.[00]"
    assert display_format(0.002712528) == "0,0.[000000]"
    assert display_format(1e-5) == "0,0.[00000000]"
    controls, seen = _controls(catalog, "min-altitude")
    vmax, umax = _widgets(controls["v_max"])[0], _widgets(controls["u_max"])[0]
    assert vmax.value == 44.44444444 and vmax.format == "0,0.[00]"
    assert umax.value == pytest.approx(12.0, rel=1e-9)  # 0.2094395102 rad/s = 12 deg/s
    assert controls["u_max"].get_text() == "0.2094395102"  # untouched: exact
    umax.value = 15.0
    assert seen["u_max"] == [number_text(math.radians(15.0))] == ["0.2617993878"]
    vmax.value = 50.0
    assert seen["v_max"] == ["50"]
    controls["v_max"].set_text("44.44444444")
    assert controls["v_max"].get_text() == "44.44444444"


def test_labels_have_no_radians_in_degree_fields_nor_doubled_words(catalog):
    """No label says 'rad' (turn rates are deg/s, angles deg); no word twice in a row."""
    for entry in catalog.entries:
        if not entry.spec.function.__module__.startswith("glideplan."):
            continue
        controls, _ = _controls(catalog, entry.key)
        for c in controls.values():
            for w in _widgets(c):
                label = _label(w)
                assert not re.search(r"\brad\b", label), (entry.key, label)
                assert not re.search(r"\b(\w+) \1\b", label), (entry.key, label)


@pytest.mark.parametrize(
    ("frm", "east", "north"), [(0.0, 0.0, -1.0), (90.0, -1.0, 0.0), (270.0, 1.0, 0.0)]
)
def test_wind_is_compass_from(catalog, frm, east, north):
    """`wind=SPEED,FROM_DEG` (as every --wind): 3 m/s FROM the north blows towards -y."""
    state = state_from_query(catalog, f"planner=wind&goal=4,3,90&speed=5&wind=3,{frm:g}")
    req, errors = request(catalog, state)
    assert req is not None, errors
    wx, wy = req.vehicle.wind
    assert (wx, wy) == pytest.approx((3.0 * east, 3.0 * north), abs=1e-12)


def test_wind_speed_in_the_chosen_unit(catalog):
    """The wind's speed is shown in kt (or km/h) while the URL keeps m/s: 10 kt =
    5.144444444 m/s; typing 20 kt writes 10.28888889 m/s; another unit shows the same wind
    (37.04 km/h) without a new state; the unit is kept in the link."""
    controls, seen = _controls(catalog, "wind", {"wind": "5.144444444,90"}, unit="kt")
    speed, unit, frm = _widgets(controls["wind"])
    assert speed.value == pytest.approx(10.0, rel=1e-9) and unit.value == "kt"
    assert frm.value == 90.0 and (frm.start, frm.end) == (0.0, 360.0)
    speed.value = 20.0
    assert seen["wind"] == [number_text(20.0 * 1852.0 / 3600.0) + ",90"] == ["10.28888889,90"]
    unit.value = "km/h"
    assert speed.value == pytest.approx(20.0 * 1852.0 / 3600.0 * 3.6, rel=1e-9)  # 37.04
    assert seen["wind"] == ["10.28888889,90"]  # no new wind
    assert speed.end == pytest.approx(PHYSICAL_RANGES["wind_speed"].high * 3.6)
    state = state_from_query(catalog, "planner=wind&wind=3,40&wind_unit=kt")
    assert state.wind_unit == "kt"
    assert "wind_unit=kt" in state_to_query(catalog, state)
    assert state_from_query(catalog, state_to_query(catalog, state)) == state
