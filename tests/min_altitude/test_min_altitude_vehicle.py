"""`QuadraticPolarGlider`: the DG-1001M preset (Table 5.2) and Assumptions 5.2.1-5.2.4."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError
from glideplan.units import kmh_to_ms
from glideplan.vehicles import QuadraticPolarGlider, dg1001m

SI = {"a": 0.0027, "b": -0.137, "c": 2.31, "v_stall": 21.0, "v_max": 44.0, "u_max": 0.2}


def test_dg1001m_matches_table_5_2():
    g = dg1001m()
    assert g.v_stall * 3.6 == pytest.approx(75.6)
    assert g.u_max == pytest.approx(math.pi / 15)
    assert g.v_ms * 3.6 == pytest.approx(91.02, abs=0.01)  # Table 5.2: 91.1 (approx.)
    assert g.v_stf * 3.6 == pytest.approx(105.2, abs=0.05)
    assert g.w_stall == pytest.approx(0.63, abs=0.005)
    assert g.w_ms == pytest.approx(0.58, abs=0.005)
    assert g.w_stf == pytest.approx(0.62, abs=0.005)
    assert g.radius_stf == pytest.approx(139.0, abs=0.6)
    assert g.radius_stall == pytest.approx(100.0, abs=0.5)
    assert g.length_scale == g.radius_stf
    assert g.default_objective == "altitude"


def test_polar_in_kmh_is_converted_explicitly():
    g = dg1001m()
    v_kmh = np.array([75.6, 91.0, 105.2, 140.0])
    w_printed = 0.0002093 * v_kmh**2 - 0.0381 * v_kmh + 2.3146  # (5.26): w m/s, v km/h
    np.testing.assert_allclose(g.sink_rate(kmh_to_ms(v_kmh), 0.0), w_printed, rtol=1e-12)


def test_derived_quantities():
    g = QuadraticPolarGlider(**SI)
    assert g.v_ms == pytest.approx(-SI["b"] / (2 * SI["a"]))
    assert g.v_stf == pytest.approx(math.sqrt(SI["c"] / SI["a"]))
    # the speed to fly is where the tangent to the polar passes through the origin
    slope = 2 * g.a * g.v_stf + g.b
    assert slope == pytest.approx(g.w_stf / g.v_stf)
    assert g.w_ms == pytest.approx(min(g.sink_rate(np.linspace(21, 44, 2001), 0.0)), abs=1e-6)
    assert g.glide_ratio == pytest.approx(g.v_stf / g.w_stf)
    assert g.radius_ms == pytest.approx(g.v_ms / g.u_max)
    # sink rate independent of the turn rate (Remark 5.2.1)
    assert g.sink_rate(25.0, 0.3) == g.sink_rate(25.0, 0.0)
    d = g.to_dict()
    assert d["model"] == "quadratic_polar_glider" and d["v_stf"] == pytest.approx(g.v_stf)


@pytest.mark.parametrize(
    ("change", "assumption", "name"),
    [
        ({"a": -0.001}, "5.2.1", "a"),
        ({"v_max": 20.0}, "5.2.1", "v_max"),
        ({"c": 1.6}, "5.2.1", "c"),  # w(v_ms) < 0
        ({"b": -0.09}, "5.2.2", "b"),  # v_ms = 16.7 below the stall speed
        ({"v_max": 24.0}, "5.2.2", "b"),  # v_ms = 25.4 above v_max
        ({"v_max": 27.0}, "5.2.3", "c"),  # v_stf = 29.2 above v_max
        ({"v_stall": 24.5}, "5.2.4", "b"),  # v_ms 25.4 < (24.5 + 29.2)/2
    ],
)
def test_assumption_violations_name_the_assumption(change, assumption, name):
    params = {**SI, **change}
    with pytest.raises(InvalidParameterError) as err:
        QuadraticPolarGlider(**params)
    msg = str(err.value)
    assert f"Assumption {assumption}" in msg and err.value.name == name
    assert any(ch.isdigit() for ch in msg.split("Assumption")[1][6:])  # the numbers are shown


@pytest.mark.parametrize("field", ["a", "b", "c", "v_stall", "v_max", "u_max"])
def test_non_finite_fields_are_rejected(field):
    with pytest.raises(InvalidParameterError):
        QuadraticPolarGlider(**{**SI, field: float("nan")})


@pytest.mark.parametrize("field", ["v_stall", "u_max"])
def test_non_positive_limits_are_rejected(field):
    with pytest.raises(InvalidParameterError):
        QuadraticPolarGlider(**{**SI, field: 0.0})


def test_dissertation_range_of_v_max_is_free_above_v_stf():
    assert dg1001m(120.0).v_max == pytest.approx(120 / 3.6)
    with pytest.raises(InvalidParameterError, match=r"5\.2\.3"):
        dg1001m(100.0)  # below v_stf = 105.2 km/h
