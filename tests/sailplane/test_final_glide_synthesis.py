"""Chapter 5's BSB family with drift (small-bank model in steady wind), checked against the
chapter 5 synthesis in still air, the direct method in wind, and integration."""

import math

import numpy as np
import pytest

from glideplan.planners.final_glide import bsb_with_drift
from glideplan.planners.final_glide.synthesis import straight_speed
from glideplan.planning import plan
from glideplan.pose import Pose
from glideplan.sailplane import SailplanePolar
from glideplan.vehicles.quadratic_polar_glider import dg1001m
from glideplan.vehicles.sailplane import Sailplane
from glideplan.verify import integrate_path

G = dg1001m()
R = G.radius_stf


def _vehicle(wind=(0.0, 0.0)) -> Sailplane:
    polar = SailplanePolar(G.a, G.b, G.c, G.v_stall, G.v_max, 614.0, 614.0, name="DG-1001M")
    return Sailplane(
        polar,
        bank_max=math.radians(60.0),
        turn_rate_max=G.u_max,
        turning_polar=False,
        wind=wind,
    )


def test_straight_speed_is_maccready_in_a_headwind():
    """v_S solves a v^2 - 2 a W v - (c + b W) = 0: the speed minimising w(v) / (v - W)."""
    W = np.array([-5.0, 0.0, 7.0])
    v = straight_speed(G, W)
    np.testing.assert_allclose(G.a * v**2 - 2 * G.a * W * v - (G.c + G.b * W), 0.0, atol=1e-12)
    assert v[1] == pytest.approx(G.v_stf)


@pytest.mark.parametrize("goal_r", [(-3.0, 4.0, 0.0), (0.0, 2.0, 7 * math.pi / 4)])
def test_still_air_equals_the_chapter_5_synthesis(goal_r):
    """With no wind the family is chapter 5's BSB: same cost as `plan min-altitude` (whose
    BSB is an independent root finding, appendix C.2) to 1e-9."""
    goal = Pose(goal_r[0] * R, goal_r[1] * R, goal_r[2])
    ref = plan(Pose(), goal, G, "altitude")
    best = bsb_with_drift(goal, G, (0.0, 0.0))[0]
    assert best.word == ref.word
    assert best.cost == pytest.approx(ref.cost, rel=1e-9)


@pytest.mark.parametrize("wind", [(5.0, -3.0), (-6.0, 2.0)])
def test_in_wind_verified_and_checked_by_the_direct_method(wind):
    """The synthesised path, integrated through the wind, ends at the goal (1e-8 m) and
    loses what it says; `plan()` returns the cheapest verified of synthesis and direct
    method. Where the direct method converges to the same family its cost agrees (0.1 %);
    it never beats the synthesis by more than its discretisation error (0.01 %)."""
    v = _vehicle(wind)
    goal = Pose(-3.0 * R, 4.0 * R, 0.0)
    cands = bsb_with_drift(goal, G, wind)
    best = cands[0]
    flown = integrate_path(best.path.with_vehicle(v), "altitude")
    assert flown.end.distance_to(goal) < 1e-8
    assert flown.cost == pytest.approx(best.cost, rel=1e-9)
    sol = plan(Pose(), goal, v, "altitude")
    assert sol.ok and sol.cost <= best.cost * (1 + 1e-9)
    direct = sol.extras["direct_cost"]
    assert direct >= best.cost * (1 - 1e-4)
    if direct <= best.cost * 1.05:  # the same local optimum
        assert direct == pytest.approx(best.cost, rel=1e-3)
