"""The registered Dubins planner through `plan()`: candidates, eps option, world frames."""

import math

import pytest

from glideplan import DubinsCar, InvalidParameterError, Pose, plan
from glideplan.planning import find_planner

PI = math.pi


def test_registered_for_length_and_time():
    car = DubinsCar()
    assert find_planner(car, "length").name == "dubins"
    assert find_planner(car, "time").name == "dubins"
    assert find_planner(car, "length").options == ("disturbance_ratio",)


def test_all_six_candidates_reported_with_hand_costs():
    # Goal (0, 4, pi), R = 1 (see test_dubins_words): LSL 2 + pi, LSR = RSL 2 sqrt3 + 7pi/3,
    # RSR 6 + 3pi, LRL 13pi/3, RLR infeasible.
    sol = plan(Pose(), Pose(0, 4, PI), DubinsCar())
    assert sol.ok and sol.word == "LSL" and sol.family == "BSB"
    costs = {c.word: c.cost for c in sol.candidates}
    s3 = 2 * math.sqrt(3)
    assert costs["LSL"] == pytest.approx(2 + PI)
    assert costs["LSR"] == pytest.approx(s3 + 7 * PI / 3)
    assert costs["RSL"] == pytest.approx(s3 + 7 * PI / 3)
    assert costs["RSR"] == pytest.approx(6 + 3 * PI)
    assert costs["LRL"] == pytest.approx(13 * PI / 3)
    rlr = next(c for c in sol.candidates if c.word == "RLR")
    assert not rlr.feasible and rlr.status == "infeasible" and rlr.path is None
    best = sol.candidates[0]
    assert best.info["segment_lengths"] == pytest.approx([PI / 2, 2.0, PI / 2])
    assert best.info["radius"] == 1.0


def test_any_start_pose_and_speed():
    # The same relative problem placed anywhere costs the same; time = length / speed.
    start = Pose(10.0, -3.0, 2.0)
    rel = Pose(0, 8, PI)  # (0, 4, pi) in units of R = 2
    goal = rel.from_frame(start)
    car = DubinsCar(speed=4.0, turn_radius=2.0)
    sol = plan(start, goal, car)
    # Radius 2 doubles every length: 2 (2 + pi).
    assert sol.cost == pytest.approx(2 * (2 + PI))
    assert sol.path.start.distance_to(start) < 1e-12
    assert sol.endpoint_error.max < 1e-9
    t = plan(start, goal, car, "time")
    assert t.cost == pytest.approx(2 * (2 + PI) / 4.0)
    assert t.path.duration == pytest.approx(t.cost)


def test_disturbance_ratio_plans_with_feasible_radius():
    # eps = 0.25 -> R0' = 1.5625 R0; straight-ahead goals are unaffected, turns grow.
    car = DubinsCar(speed=20.0, turn_radius=3.0)
    sol = plan(Pose(), Pose(0, 4, PI), car, disturbance_ratio=0.25)
    r = car.turn_radius * 1.5625
    assert sol.extras["radius"] == pytest.approx(r)
    assert sol.extras["disturbance_ratio"] == 0.25
    assert all(getattr(s, "radius", r) == pytest.approx(r) for s in sol.path.segments)
    ahead = plan(Pose(), Pose(50, 0, 0), car, disturbance_ratio=0.5)
    assert ahead.cost == pytest.approx(50.0)


def test_feasible_radius_worked_example():
    # v = 20 m/s, |u| <= 0.3 rad/s (chapter 3): R0 = 66.67 m; eps = 0.25 -> R0' = 104.17 m.
    # Goal (0, 4 R0', pi) in the feasible frame is the (0, 4, pi) case scaled: (2 + pi) R0'.
    r0 = 20.0 / 0.3
    car = DubinsCar(speed=20.0, turn_radius=r0)
    r1 = r0 * 1.25**2
    sol = plan(Pose(), Pose(0, 4 * r1, PI), car, disturbance_ratio=0.25)
    assert sol.cost == pytest.approx((2 + PI) * r1)
    assert sol.word == "LSL"


@pytest.mark.parametrize("eps", [1.0, 1.01, -0.01, math.nan, math.inf])
def test_bad_disturbance_ratio(eps):
    with pytest.raises(InvalidParameterError, match="disturbance_ratio"):
        plan(Pose(), Pose(3, 3, 0), DubinsCar(), disturbance_ratio=eps)


def test_unknown_option_and_bad_vehicle():
    with pytest.raises(InvalidParameterError, match="eps"):
        plan(Pose(), Pose(3, 3, 0), DubinsCar(), eps=0.1)
    with pytest.raises(InvalidParameterError, match="turn_radius"):
        DubinsCar(turn_radius=-1.0)
    with pytest.raises(InvalidParameterError, match="goal"):
        plan(Pose(), (1.0, 2.0), DubinsCar())
