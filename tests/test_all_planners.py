"""Every registered planner honours the contract of `plan()` (parametrised over all of them).

The parametrisation is `glideplan.registered_planners()` itself: the default and the
non-default methods (the direct ones included), and any planner registered later. A planner
with no entry in `CASES` fails `test_every_registered_planner_has_a_case` with "no test case
for planner X": add a vehicle and a simple goal for it below.

For each planner, on a simple goal: the solution is solved and verified; its controls,
integrated here with SciPy (DOP853, piecewise between the segments' breakpoints, through
the vehicle's steady wind where it has one, computed from the vehicle's own `wind` (east, north)
vector, not from the path or `glideplan.verify`), end within 1e-6 * max(1, L) of
the goal (L the vehicle's length scale: `plan()`'s documented tolerance) and cost what the
solution says; the best candidate is the cheapest feasible one; moving start and goal together
by a rigid motion changes nothing (translation only where the vehicle carries a world-fixed
wind).
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from glideplan import Pose, plan, registered_planners
from glideplan.vehicles import (
    DubinsCar,
    DubinsCarInWind,
    LoadFactorGlider,
    VariableSpeedCar,
    dg1001m,
)

RTOL, ATOL = 1e-13, 1e-13


@dataclass(frozen=True)
class Case:
    """A vehicle, a simple goal (in the start frame) and options for one planner."""

    vehicle: Callable[[], Any]
    goal: tuple[float, float, float]
    options: dict[str, Any] = field(default_factory=dict)


def _sailplane() -> Any:
    """A DG-1001M-like sailplane (the chapter 5 polar in SI) in a 3 m/s wind to 30 deg."""
    from glideplan.vehicles.sailplane import dg1001m_sailplane

    return dg1001m_sailplane(wind=(3.0 * math.cos(math.radians(30.0)),
                                   3.0 * math.sin(math.radians(30.0))))


_R_STF = dg1001m().radius_stf
# planner name -> case. One entry per registered planner; names, not vehicle types, so that a
# second planner for the same vehicle (a direct method) cannot go untested.
CASES: dict[str, Case] = {
    "dubins": Case(lambda: DubinsCar(speed=2.0, turn_radius=1.5), (2.0, 3.0, 2.5)),
    "wind": Case(
        lambda: DubinsCarInWind(speed=1.0, turn_radius=1.0,
                                wind=(0.3 * math.cos(0.5), 0.3 * math.sin(0.5))),
        (3.0, 3.0, math.pi / 2),
    ),
    "time-optimal": Case(lambda: VariableSpeedCar(0.3, 1.0, 1.0), (0.0, 2.0, 2 * math.pi / 3)),
    "time-optimal-direct": Case(
        lambda: VariableSpeedCar(0.3, 1.0, 1.0), (0.0, 2.0, 2 * math.pi / 3)
    ),
    "load-factor": Case(LoadFactorGlider, (-2.0, 4.0, 7 * math.pi / 4)),
    "load-factor-synthesis": Case(LoadFactorGlider, (1.1, 2.0, 0.0)),
    "min_altitude": Case(dg1001m, (-3.0 * _R_STF, 4.0 * _R_STF, 0.0)),
    "min_altitude_direct": Case(dg1001m, (-3.0 * _R_STF, 4.0 * _R_STF, 0.0)),
    "final_glide": Case(_sailplane, (1500.0, 800.0, math.pi / 2)),
}


def _package_specs():
    """The package's own planners (tests may register toy planners in the same process)."""
    return [s for s in registered_planners() if s.function.__module__.startswith("glideplan.")]


SPECS = _package_specs()


def _spec_id(spec) -> str:
    return f"{spec.name}-{spec.objective}-{spec.method}"


def test_every_registered_planner_has_a_case():
    names = {s.name for s in SPECS}
    missing = sorted(names - set(CASES))
    assert not missing, f"no test case for planner {', '.join(missing)}: add it to CASES"
    # the registry really holds the direct methods and the wind planner
    methods = {(s.name, s.method) for s in SPECS}
    assert {("time-optimal-direct", "direct"), ("min_altitude_direct", "direct")} <= methods
    assert {("load-factor", "direct"), ("wind", "synthesis")} <= methods


def _wind(vehicle) -> tuple[float, float]:
    """The vehicle's world-fixed steady wind (m/s), from its own parameters."""
    wx, wy = getattr(vehicle, "wind", (0.0, 0.0))
    return float(wx), float(wy)


def _rate(objective: str, vehicle) -> Callable[[float, float], float]:
    if objective == "length":
        return lambda v, u: v
    if objective == "time":
        return lambda v, u: 1.0
    assert objective == "altitude", objective
    return lambda v, u: float(vehicle.sink_rate(np.array([v]), np.array([u]))[0])


def fly(path, vehicle, objective):
    """Integrate x' = v cos psi + wx, y' = v sin psi + wy, psi' = u, J' = rate(v, u) along the
    path's controls (`Segment.controls`) from its start, piecewise between each segment's
    breakpoints (the controls are smooth on each piece). Returns (x, y, psi, J) and, per
    component, a bound on the integration error: a quadrature-like system (psi depends on
    t only), so the global error is at most the sum over accepted steps of the local error,
    each below 2 (ATOL + RTOL max|z|) (DOP853's RMS norm over four components)."""
    wx, wy = _wind(vehicle)
    rate = _rate(objective, vehicle)
    z = np.array([path.start.x, path.start.y, path.start.heading, 0.0])
    bound = np.zeros(4)
    for seg in path.segments:

        def rhs(t, s, seg=seg):
            v, u = (float(q[0]) for q in seg.controls(np.array([t])))
            return [v * math.cos(s[2]) + wx, v * math.sin(s[2]) + wy, u, rate(v, u)]

        for a, b in itertools.pairwise(np.asarray(seg.breakpoints(), dtype=float)):
            if b <= a:
                continue
            sol = solve_ivp(rhs, (a, b), z, method="DOP853", rtol=RTOL, atol=ATOL)
            assert sol.success, sol.message
            bound += (sol.t.size - 1) * 2.0 * (ATOL + RTOL * np.max(np.abs(sol.y), axis=1))
            z = sol.y[:, -1]
    return z, bound


@pytest.fixture(scope="module", params=SPECS, ids=_spec_id)
def solved(request):
    spec = request.param
    case = CASES.get(spec.name)
    if case is None:
        pytest.fail(f"no test case for planner {spec.name}: add it to CASES")
    vehicle = case.vehicle()
    sol = plan(Pose(), Pose(*case.goal), vehicle, spec.objective, spec.method, **case.options)
    return spec, case, vehicle, sol


def test_solution_is_verified_by_an_independent_integration(solved):
    spec, case, vehicle, sol = solved
    assert sol.planner == spec.name and sol.objective == spec.objective
    # a simple goal: each planner must solve it (a failure would have to say so clearly)
    assert sol.ok, f"{sol.status}: {sol.message}"
    tol = 1e-6 * max(1.0, vehicle.length_scale)
    assert sol.endpoint_error.position <= tol and sol.endpoint_error.heading <= 1e-6
    (x, y, psi, cost), bound = fly(sol.path, vehicle, spec.objective)
    goal = Pose(*case.goal)
    assert bound[:2].max() < 0.01 * tol  # the reference is far more accurate than the check
    assert math.hypot(x - goal.x, y - goal.y) <= tol
    assert abs(math.remainder(psi - goal.heading, 2 * math.pi)) <= 1e-6
    # the cost the solution states is the cost of its controls (plus the path's own
    # quadrature round-off, 1e-9 relative)
    assert abs(cost - sol.cost) <= bound[3] + 1e-9 * abs(sol.cost)


@pytest.mark.parametrize("spec", SPECS, ids=_spec_id)
def test_goal_equal_to_start_is_one_behaviour_for_all(spec):
    """Start equal to goal: solved, a zero-length path costing 0, for every planner."""
    case = CASES.get(spec.name)
    if case is None:
        pytest.fail(f"no test case for planner {spec.name}: add it to CASES")
    start = Pose(3.0, -2.0, 0.4)
    sol = plan(start, start, case.vehicle(), spec.objective, spec.method)
    assert sol.ok and sol.cost == 0.0
    assert sol.path.length == 0.0 and sol.path.duration == 0.0
    assert sol.path.start.distance_to(start) == 0.0


def test_failures_are_clear():
    """A planner that cannot find a path says so: the status and a message, no path."""
    sol = plan(
        Pose(),
        Pose(0.0, 2.0, 2 * math.pi / 3),
        VariableSpeedCar(0.3, 1.0, 1.0),
        method="direct",
        max_iterations=1,
        max_refinements=0,
    )
    assert not sol.ok and sol.path is None
    assert sol.status in {"solver_failed", "no_path", "not_verified"} and sol.message


def test_best_candidate_is_the_cheapest_feasible(solved):
    _, _, _, sol = solved
    feasible = [c.cost for c in sol.candidates if c.feasible]
    assert feasible and sol.cost == pytest.approx(min(feasible), rel=1e-12)
    assert feasible == sorted(feasible)


def test_rigid_motion_of_both_poses_changes_nothing(solved):
    """plan() hands every planner the problem in the start's frame: a moved request is the
    same problem. Checked for the closed-form methods only (re-solving an NLP would test the
    same frame change at ~1 s a solve)."""
    spec, case, vehicle, sol = solved
    if spec.method == "direct":
        pytest.skip("the same frame change is checked on the synthesis planners")
    rotation_invariant = _wind(vehicle) == (0.0, 0.0)
    frame = Pose(17.0, -4.0, 1.1 if rotation_invariant else 0.0)
    start = Pose().from_frame(frame)
    moved = plan(
        start, Pose(*case.goal).from_frame(frame), vehicle, spec.objective, spec.method
    )
    assert moved.ok
    # round-off of the frame change (|pose| ~ 20 length scales) through the closed forms
    assert moved.cost == pytest.approx(sol.cost, rel=1e-9)
    assert moved.path.start.distance_to(start) < 1e-9 * max(1.0, vehicle.length_scale)
