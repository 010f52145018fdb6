"""The direct-method engine on cases with known answers (engine trust for chapters 4-6).

Tolerances: a collocation cost is accurate to about the change of cost between the last two
meshes of the refinement (`mesh_error`, the engine's own error estimate; measured errors are
0.03-0.1 of it here); the answers are exact closed forms (the LSL length).
"""

from __future__ import annotations

import doctest
import math

import numpy as np
import pytest

import glideplan.planners.direct as direct
from glideplan import Arc, Path, Pose, Straight
from glideplan.errors import InvalidParameterError
from glideplan.planners.direct import ControlSystem, fly_controls, retime, solve_direct
from glideplan.verify import endpoint_error, integrate_path

GOAL = Pose(4.0, 3.0, math.pi / 2)


def dubins_time_system(u_max: float = 1.0) -> ControlSystem:
    """Unit-speed car, |u| <= u_max, cost = time (the Dubins problem, eq. 2.1)."""
    return ControlSystem(
        name="dubins-time",
        control_names=("u",),
        lower=(-u_max,),
        upper=(u_max,),
        kinematics=lambda c: (1.0 + 0.0 * c[0], c[0]),
        cost_rate=lambda c: 1.0 + 0.0 * c[0],
        controls_from=lambda v, u: u[:, None],
    )


def lsl_length(goal: Pose) -> float:
    """LSL length with R = 1 (Shkel & Lumelsky form): independent of the engine."""
    a, b = 0.0, goal.heading
    d = math.hypot(goal.x, goal.y)
    th = math.atan2(goal.y, goal.x)
    a, b = a - th, b - th
    p2 = 2 + d * d - 2 * math.cos(a - b) + 2 * d * (math.sin(a) - math.sin(b))
    tmp = math.atan2(math.cos(b) - math.cos(a), d + math.sin(a) - math.sin(b))
    t = (-a + tmp) % (2 * math.pi)
    q = (b - tmp) % (2 * math.pi)
    return t + math.sqrt(p2) + q


def mesh_error(res) -> float:
    """The engine's error estimate: |cost on the last mesh - cost on the one before|."""
    costs = res.stats["mesh_costs"]
    assert len(costs) >= 2, costs
    return abs(costs[-1] - costs[-2])


SYSTEM = dubins_time_system()
GUESS = Path((Straight(Pose(), 4.0), Arc(Pose(4.0, 0.0, 0.0), math.pi / 2, 3.0, 1)))


@pytest.fixture(scope="module")
def hs_result():
    return solve_direct(GOAL, SYSTEM, guesses=[GUESS])


@pytest.fixture(scope="module")
def radau_result():
    return solve_direct(GOAL, SYSTEM, guesses=[GUESS], scheme="radau")


def test_lsl_reference_value():
    assert lsl_length(GOAL) == pytest.approx(5.17635, abs=5e-6)


@pytest.mark.parametrize("fixture", ["hs_result", "radau_result"])
def test_minimum_time_dubins_car_matches_lsl(fixture, request):
    res = request.getfixturevalue(fixture)
    assert res.status == "solved" and res.ok
    assert abs(res.cost - lsl_length(GOAL)) <= mesh_error(res)
    # the re-timed path flies the same controls slightly stretched (retime_stretch < 1 %):
    # its time is the collocation cost plus the stretch of the pieces, measured 6e-7
    assert res.path.duration == pytest.approx(lsl_length(GOAL), abs=5e-5)
    # L (turn at u = +1), S (u ~ 0), L: judged away from the switches (which smear)
    t, u = res.controls["t"], res.controls["u"]
    assert np.all(u[t < 0.5] > 0.999) and np.all(u[t > res.path.duration - 0.5] > 0.999)
    straight = (t > 1.5) & (t < 3.0)
    assert np.mean(np.abs(u[straight])) < 0.05
    assert res.stats["mesh_converged"]
    costs = res.stats["mesh_costs"]
    assert abs(costs[-1] - costs[-2]) / costs[-1] < 1e-4


@pytest.mark.parametrize("fixture", ["hs_result", "radau_result"])
def test_returned_path_passes_independent_integration(fixture, request):
    res = request.getfixturevalue(fixture)
    err = endpoint_error(res.path, GOAL)
    assert err.max < 1e-7
    assert res.stats["endpoint_error"]["position"] < 1e-9
    assert res.stats["retime_stretch"] < 0.01
    # every output control value is admissible
    assert np.all(np.abs(res.controls["u"]) <= 1.0 + 1e-12)
    # the Sampled states agree with an integration of its own controls
    end = integrate_path(res.path).end
    assert end.distance_to(res.path.end) < 1e-7


def test_heading_branch_comes_from_the_guess():
    # a right turn guess reaches pi/2 - 2 pi: the engine keeps that branch (RSR-like answer)
    right = Path((Straight(Pose(), 1.0), Arc(Pose(1.0, 0.0, 0.0), 3 * math.pi / 2, 1.0, -1)))
    res = solve_direct(GOAL, SYSTEM, guesses=[right])
    assert res.ok
    assert res.stats["heading_turns"] == -1
    assert res.path.end.heading == pytest.approx(GOAL.heading - 2 * math.pi, abs=1e-6)
    assert res.cost > lsl_length(GOAL)


def test_multistart_keeps_the_best_and_reports_every_start():
    right = Path((Straight(Pose(), 1.0), Arc(Pose(1.0, 0.0, 0.0), 3 * math.pi / 2, 1.0, -1)))
    res = solve_direct(GOAL, SYSTEM, guesses=[right, GUESS], n_intervals=40)
    assert len(res.starts) == 2
    costs = [c for c, _ in res.starts]
    assert res.stats["starts_tried"] == 2 and res.stats["starts_succeeded"] == 2
    # the starts' costs are on the first mesh (40 intervals, before refinement)
    assert min(costs) == pytest.approx(lsl_length(GOAL), abs=1e-3)
    assert res.stats["best_start"] == 1
    assert abs(res.cost - lsl_length(GOAL)) <= mesh_error(res)


@pytest.mark.parametrize("scheme", ["hermite-simpson", "radau"])
def test_nonlinear_path_constraint_is_respected(scheme):
    # (v, u) controls, v in [0.5, 1], curvature |u / v| <= 1 as a nonlinear constraint:
    # the fastest path is the unit-speed Dubins LSL (slowing down does not tighten turns)
    sys2 = ControlSystem(
        name="curvature",
        control_names=("v", "u"),
        lower=(0.5, -2.0),
        upper=(1.0, 2.0),
        kinematics=lambda c: (c[0], c[1]),
        cost_rate=lambda c: 1.0 + 0.0 * c[0],
        path_constraints=lambda c: [(c[1] / c[0], -1.0, 1.0)],
    )
    slow = Path((Straight(Pose(), 4.0, 0.7), Arc(Pose(4.0, 0.0, 0.0), math.pi / 2, 3.0, 1, 0.7)))
    res = solve_direct(GOAL, sys2, guesses=[slow], scheme=scheme)
    assert res.ok
    assert abs(res.cost - lsl_length(GOAL)) <= mesh_error(res)
    curvature = res.controls["u"] / res.controls["v"]
    assert np.max(np.abs(curvature)) < 1.0 + 1e-7  # at every output node
    assert endpoint_error(res.path, GOAL).max < 1e-7


def test_failure_is_reported_not_returned():
    res = solve_direct(
        GOAL,
        SYSTEM,
        guesses=[GUESS],
        n_intervals=10,
        ipopt_options={"max_iter": 2},
        max_refinements=0,
    )
    assert res.status == "failed"
    assert res.path is None and not res.ok
    assert math.isinf(res.cost)
    assert res.starts[0].status == "Maximum_Iterations_Exceeded"
    assert "no start converged" in res.message


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"guesses": []}, "guesses"),
        ({"guesses": [GUESS], "scheme": "euler"}, "scheme"),
        ({"guesses": [GUESS], "n_intervals": 1}, "n_intervals"),
        ({"guesses": [GUESS], "mesh_tol": 0.0}, "mesh_tol"),
        ({"guesses": [GUESS], "length_scale": -1.0}, "length_scale"),
        ({"guesses": ["LSL"]}, "guesses[0]"),
    ],
)
def test_bad_arguments_are_named(kwargs, name):
    with pytest.raises(InvalidParameterError) as info:
        solve_direct(GOAL, SYSTEM, **kwargs)
    assert info.value.name == name


def test_non_scalar_rates_are_rejected():
    bad = ControlSystem(
        "vector-cost",
        ("v", "u"),
        (0.5, -1.0),
        (1.0, 1.0),
        kinematics=lambda c: (c[0], c[1]),
        cost_rate=lambda c: c,
    )
    with pytest.raises(InvalidParameterError, match="cost rate"):
        solve_direct(GOAL, bad, guesses=[GUESS])


def test_bad_control_system():
    with pytest.raises(InvalidParameterError):
        ControlSystem("bad", ("a", "b"), (0.0,), (1.0, 1.0), lambda c: c, lambda c: c)
    with pytest.raises(InvalidParameterError):
        ControlSystem("bad", ("a",), (2.0,), (1.0,), lambda c: c, lambda c: c)


def test_fly_controls_exact_for_constant_turn():
    t = np.linspace(0.0, math.pi, 7)
    x, y, psi = fly_controls(t, np.ones(7), np.ones(7))
    assert x[-1] == pytest.approx(0.0, abs=1e-12)
    assert y[-1] == pytest.approx(2.0, abs=1e-12)
    assert psi[-1] == pytest.approx(math.pi, abs=1e-15)


def test_retime_keeps_control_values_and_hits_target():
    t = np.linspace(0.0, 4.0, 81)
    v, u = np.ones(81), np.where(t < 1.0, 1.0, np.where(t < 3.0, 0.0, -1.0))
    x, y, psi = fly_controls(t, v, u)
    target = np.array([x[-1] + 1e-3, y[-1] - 2e-3, psi[-1] + 1e-3])
    t2, stretch, ok = retime(t, v, u, target)
    assert ok and 0 < stretch < 0.05
    x2, y2, psi2 = fly_controls(t2, v, u)
    assert np.allclose([x2[-1], y2[-1], psi2[-1]], target, atol=1e-11)


def test_module_docstring_example_runs():
    result = doctest.testmod(direct, optionflags=doctest.ELLIPSIS)
    assert result.failed == 0 and result.attempted > 0
