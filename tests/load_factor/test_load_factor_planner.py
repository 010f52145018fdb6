"""The chapter 6 planner on the dissertation's three examples (section 6.8, Figs 6.11-6.13).

Reference costs: an independent multi-start collocation found 0.36138 (one 315 deg left
turn), 0.26256 (L-R-L) and 0.20926 (L-R, 84% at the corner); we must match them within
1e-4 or find lower (then verified by integration, as every `plan()` result is).

Tolerances: the references are printed to 5 decimals (+-5e-6) from collocations converged to
about 1e-4 in cost, hence "within 1e-4"; our own collocation costs are accurate to about the
change between the last two meshes (`mesh_error`, the engine's estimate).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan import LoadFactorGlider, Pose, Status, plan
from glideplan.errors import InvalidParameterError
from glideplan.planners.direct import solve_direct
from glideplan.planners.load_factor import control_system, initial_guesses, solve_load_factor
from glideplan.verify import integrate_path

G = LoadFactorGlider()


def mesh_error(stats) -> float:
    """The engine's error estimate: |cost on the last mesh - cost on the one before|."""
    costs = stats["mesh_costs"]
    assert len(costs) >= 2, costs
    return abs(costs[-1] - costs[-2])

EXAMPLES = {
    "fig6.11": ((-2.0, 4.0, 7 * math.pi / 4), 0.36138, "L", False),
    "fig6.12": ((0.0, -0.5, math.pi), 0.26256, "LRL", False),
    "fig6.13": ((1.1, 2.0, 0.0), 0.20926, "LR", True),
}


@pytest.fixture(scope="module")
def solutions():
    return {k: plan(Pose(), Pose(*ex[0]), G) for k, ex in EXAMPLES.items()}


@pytest.mark.parametrize("key", list(EXAMPLES))
def test_examples_solve_and_match_the_independent_costs(solutions, key):
    goal, ref, word, _ = EXAMPLES[key]
    sol = solutions[key]
    assert sol.status is Status.SOLVED, sol.message
    assert sol.planner == "load-factor" and sol.objective == "altitude"
    assert sol.cost <= ref + 1e-4
    assert sol.cost >= ref - 1e-3  # a much lower cost would be suspicious (see below)
    assert sol.word == word
    # verified by integration with plan()'s default tolerance (1e-6); typically ~1e-8
    assert sol.endpoint_error.max < 1e-6
    # the cost is the altitude loss of the returned path, integrated independently: the
    # core's DOP853 at rtol 1e-11 across the sampled controls' kinks (<= ~10^4 steps) is
    # accurate to ~2e-7 relative, 1e-6 allowed
    integ = integrate_path(sol.path, "altitude")
    assert integ.cost == pytest.approx(sol.cost, rel=1e-6)
    assert integ.end.distance_to(Pose(*goal)) < 1e-6


@pytest.mark.parametrize("key", list(EXAMPLES))
def test_controls_follow_the_extremals(solutions, key):
    sol = solutions[key]
    fr = sol.extras["arcs"]["fractions"]
    # the control history lies on the extremal locus, stall boundary, corner or wings level
    assert fr["other"] < 0.02
    assert fr["locus"] + fr["stall"] > 0.1
    # every output control is admissible (6.20)
    c = sol.extras["controls"]
    assert np.all(G.admissible(np.asarray(c["v"]), np.asarray(c["n"]), tol=1e-9))


def test_only_the_third_example_reaches_the_corner(solutions):
    reached = {k: s.extras["arcs"]["reaches_corner"] for k, s in solutions.items()}
    assert reached == {k: ex[3] for k, ex in EXAMPLES.items()}
    corner = solutions["fig6.13"].extras["arcs"]["fractions"]["corner"]
    assert corner == pytest.approx(0.84, abs=0.02)


def test_cost_is_mesh_converged(solutions):
    """The cost changes by < 1e-5 (relative) between the final mesh and one twice as fine.

    Checked here for the example that reaches the corner (the hardest to resolve);
    benchmarks/validate_load_factor_mesh.py (`make validate`) checks all three."""
    key = "fig6.13"
    sol = solutions[key]
    sizes = sol.stats["mesh_sizes"]
    goal = Pose(*EXAMPLES[key][0])
    fine = solve_direct(
        goal,
        control_system(G),
        guesses=[sol.path],
        n_intervals=2 * sizes[-1],
        max_refinements=0,
    )
    assert fine.ok
    final = sol.extras["collocation_cost"]
    # refinement stopped at a change < mesh_tol = 1e-5: one more doubling stays below it
    # (measured 1.5e-6 here, 1e-7 and 9.5e-7 for the other two examples)
    assert abs(fine.cost - final) / final < 1e-5


def test_independent_formulation_agrees():
    # (v, psi_dot) controls with the nonlinear constraints n <= n_max, n <= p2 v^2 (6.17, 6.18)
    goal = Pose(*EXAMPLES["fig6.12"][0])
    res = solve_load_factor(G, goal, formulation="load-factor", scheme="radau")
    assert res.ok
    # the reference (5 decimals, converged to ~1e-4) within our collocation's own accuracy
    assert abs(res.cost - 0.26256) <= 1e-4 + mesh_error(res.stats)


def test_guesses_come_cheapest_first_and_are_deterministic():
    goal = Pose(*EXAMPLES["fig6.11"][0])
    a = initial_guesses(G, goal, max_starts=4)
    b = initial_guesses(G, goal, max_starts=4)
    assert [p.word for p in a] == [p.word for p in b]
    costs = [p.with_vehicle(G).cost("altitude") for p in initial_guesses(G, goal)]
    assert costs == sorted(costs)
    assert len(a) == 4


def test_failed_solve_is_reported():
    sol = plan(Pose(), Pose(1.1, 2.0, 0.0), G, max_iterations=1, max_starts=1)
    assert sol.status is Status.SOLVER_FAILED
    assert sol.path is None and "direct method failed" in sol.message


def test_goal_at_start_is_the_zero_length_path():
    """plan()'s one behaviour for every planner (tests/test_all_planners.py)."""
    sol = plan(Pose(), Pose(), G)
    assert sol.status is Status.SOLVED and sol.cost == 0.0 and sol.path.length == 0.0


def test_bad_options():
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1.0, 1.0, 0.0), G, max_starts=0)
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1.0, 1.0, 0.0), G, scheme="euler")
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1.0, 1.0, 0.0), G, formulation="magic")
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(float("nan"), 1.0, 0.0), G)


def test_world_frame_start():
    # a rotated and shifted start gives the same cost (the planner works in the start frame)
    start = Pose(3.0, -1.0, 0.7)
    goal = Pose(1.1, 2.0, 0.0).from_frame(start)
    sol = plan(start, goal, G)
    assert sol.ok
    assert sol.cost == pytest.approx(0.20926, abs=1e-4)
    assert sol.path.start.distance_to(start) < 1e-12
