"""LoadFactorGlider: validation, the model in time vs arc length (6.8-6.22), unit helpers."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from glideplan import LoadFactorGlider
from glideplan.errors import InvalidParameterError

G = LoadFactorGlider()


def test_defaults_are_the_dissertation_example():
    assert (G.l_over_d_max, G.v_min, G.v_max, G.n_max) == (30.0, 0.75, 2.0, 2.0)
    assert G.p1 == pytest.approx(1 / 60)
    assert G.p2 == pytest.approx(1.7777778)
    assert math.degrees(G.max_bank) == pytest.approx(60.0)
    assert G.corner_speed == pytest.approx(math.sqrt(2 * 0.75**2))
    assert G.default_objective == "altitude"


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"n_max": 1.0}, "n_max"),
        ({"n_max": 0.5}, "n_max"),
        ({"v_min": 2.0}, "v_min"),
        ({"v_min": 2.5}, "v_min"),
        ({"l_over_d_max": float("nan")}, "l_over_d_max"),
        ({"v_max": float("inf")}, "v_max"),
        ({"v_min": -0.1}, "v_min"),
        ({"l_over_d_max": "thirty"}, "l_over_d_max"),
    ],
)
def test_bad_parameters_name_the_parameter(kwargs, name):
    with pytest.raises(InvalidParameterError) as info:
        LoadFactorGlider(**kwargs)
    assert info.value.name == name


@given(
    v=st.floats(0.75, 2.0),
    n=st.floats(1.0, 2.0),
    direction=st.sampled_from([-1.0, 1.0]),
)
def test_time_and_arc_length_forms_agree(v, n, direction):
    # psi_dot = sqrt(n^2-1)/v (6.9) and psi' = psi_dot / v (6.15); z_dot = z' v (6.8, 6.22)
    u = G.turn_rate(v, n, direction)
    assert G.load_factor(v, u) == pytest.approx(n, rel=1e-12)
    assert float(G.sink_rate(v, u)) == pytest.approx(float(G.sink_per_length(v, n)) * v, rel=1e-12)
    assert abs(float(u)) / v == pytest.approx(math.sqrt(n * n - 1) / v**2, rel=1e-12, abs=1e-15)
    assert float(np.tan(G.bank_angle(v, u))) == pytest.approx(
        direction * math.sqrt(n * n - 1), rel=1e-9, abs=1e-12
    )


def test_admissible_set():
    assert G.admissible(1.0, 1.0)
    assert G.admissible(G.corner_speed, 2.0)
    assert not G.admissible(0.74, 1.0)  # below stall
    assert not G.admissible(1.0, 1.9)  # n > p2 v^2
    assert not G.admissible(2.1, 1.0)  # too fast
    assert not G.admissible(1.5, 2.1)  # n > n_max


def test_dimensional_scales():
    sc = G.scales(stall_speed=15.0)  # 15 m/s wings-level stall
    assert sc.speed == pytest.approx(20.0)
    assert sc.time == pytest.approx(20.0 / 9.80665)
    assert sc.length == pytest.approx(400.0 / 9.80665)
    speed, length, time = sc.to_dimensional(speed=1.0, length=2.0, time=3.0)
    back = sc.to_nondimensional(speed=speed, length=length, time=time)
    assert np.allclose(back, (1.0, 2.0, 3.0))
    # V_ref = sqrt(2 (W/S) / (rho C_L,md)): 350 N/m^2, sea level, C_L,md = 0.8
    ref = G.scales(wing_loading=350.0, density=1.225, cl_md=0.8)
    assert ref.speed == pytest.approx(math.sqrt(2 * 350 / (1.225 * 0.8)))
    with pytest.raises(InvalidParameterError):
        G.scales(wing_loading=350.0)
    with pytest.raises(InvalidParameterError):
        G.scales(stall_speed=-1.0)


def test_corner_limited_by_max_speed():
    # with v_max below the corner speed the largest load factor is p2 v_max^2
    g = LoadFactorGlider(v_min=0.75, v_max=0.9, n_max=2.0)
    assert g.n_limit == pytest.approx(0.9**2 / 0.75**2)
    assert g.corner_speed == pytest.approx(0.9)
