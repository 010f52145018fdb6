"""Hypothesis properties of Dubins planning over random poses."""

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan import DubinsCar, Pose, plan
from glideplan.planners.dubins import dubins_distance, dubins_path, dubins_shortest

coord = st.floats(-8.0, 8.0, allow_nan=False, allow_subnormal=False)
heading = st.floats(-2 * math.pi, 2 * math.pi, allow_nan=False, allow_subnormal=False)
pose = st.tuples(coord, coord, heading)
radius = st.floats(0.2, 4.0)

FAST = settings(max_examples=60, deadline=None)
SLOW = settings(max_examples=15, deadline=None)


def _d(a, b, r=1.0):
    return float(dubins_distance(np.asarray(a, float), np.asarray(b, float), r))


@SLOW
@given(pose, pose, radius, st.floats(0.0, 0.9), st.floats(0.5, 30.0))
def test_plan_reaches_goal_and_picks_the_cheapest(start, goal, r, eps, speed):
    sol = plan(Pose(*start), Pose(*goal), DubinsCar(speed, r), disturbance_ratio=eps)
    assert sol.ok
    assert sol.endpoint_error.max < 1e-9 * max(1.0, r)
    feasible = [c.cost for c in sol.candidates if c.feasible]
    assert sol.cost == min(feasible)
    assert 2 <= len(feasible) <= 6
    # The cost is the closed-form optimum for the feasible radius.
    r_plan = r * (1 + eps) ** 2
    assert math.isclose(sol.cost, _d(start, goal, r_plan), rel_tol=1e-12, abs_tol=1e-12)


@SLOW
@given(pose, pose, radius, st.floats(0.5, 30.0))
def test_time_objective_is_length_over_speed(start, goal, r, speed):
    car = DubinsCar(speed, r)
    t = plan(Pose(*start), Pose(*goal), car, "time")
    length = plan(Pose(*start), Pose(*goal), car, "length", verify=False)
    assert math.isclose(t.cost, length.cost / speed, rel_tol=1e-12, abs_tol=1e-12)


@FAST
@given(pose, pose, st.tuples(coord, coord, heading))
def test_invariant_under_rigid_motions(start, goal, frame):
    # Express both poses in a moved frame: translate by (fx, fy) and rotate by fh.
    fx, fy, fh = frame
    c, s = math.cos(fh), math.sin(fh)

    def move(p):
        return (fx + c * p[0] - s * p[1], fy + s * p[0] + c * p[1], p[2] + fh)

    a, b = _d(start, goal), _d(move(start), move(goal))
    assert math.isclose(a, b, rel_tol=1e-7, abs_tol=1e-7)


@FAST
@given(pose, radius)
def test_mirror_symmetry(goal, r):
    # Reflecting the goal in the x-axis (y -> -y, psi -> -psi) swaps L and R: same length.
    x, y, h = goal
    assert math.isclose(
        _d((0, 0, 0), goal, r), _d((0, 0, 0), (x, -y, -h), r), rel_tol=1e-9, abs_tol=1e-10
    )


@FAST
@given(pose, pose, pose, radius)
def test_triangle_inequality(a, b, c, r):
    assert _d(a, c, r) <= _d(a, b, r) + _d(b, c, r) + 1e-9


@FAST
@given(st.lists(st.tuples(pose, pose), min_size=1, max_size=12), radius)
def test_batch_equals_scalar(pairs, r):
    starts = np.array([p[0] for p in pairs])
    goals = np.array([p[1] for p in pairs])
    batch = dubins_shortest(starts, goals, r)
    fast = dubins_distance(starts, goals, r)
    for i, (s, g) in enumerate(pairs):
        path = dubins_path(Pose(*s), Pose(*g), r)
        assert path is not None
        assert math.isclose(path.length, batch.length[i], rel_tol=1e-12, abs_tol=1e-12)
        # The two code paths snap rounding-level turns (< 6e-11 rad) slightly differently.
        assert math.isclose(fast[i], batch.length[i], rel_tol=1e-12, abs_tol=1e-9 * r)


@FAST
@given(pose, radius)
def test_length_bounds(goal, r):
    # Never shorter than the straight-line distance; never longer than the LSL/RSR bound
    # of LSL: two turns of at most 2 pi R around a straight |C2 - C1| <= d + 2R.
    d = math.hypot(goal[0], goal[1])
    length = _d((0, 0, 0), goal, r)
    assert length >= d - 1e-9
    assert length <= d + 2 * r + 4 * math.pi * r + 1e-9
