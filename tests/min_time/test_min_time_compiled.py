"""The compiled synthesis (numba kernels, `synthesis.COMPILED`) against the NumPy reference.

The reference is the NumPy path that the synthesis ran before the kernels (`COMPILED =
False`: companion-matrix eigenvalues, SciPy's bounded Brent, `dubins_segment_lengths`). Both
paths evaluate the same closed forms, so every goal must give the same extremals (the same
types, compared sorted) with costs equal to rounding (1e-12 relative; measured <= 2e-14 on 4,000
random goals, benchmarks/min_time.py --compare; 414 goals of
benchmarks/min_time_vs_direct.py --reference-only). Goals: random ones over four speed ratios,
the goals of tests/min_time, and degenerate ones (pure turns, straight ahead, on the start
circles, next to the start).
"""

import math
import pickle

import numpy as np
import pytest

from glideplan import Pose, VariableSpeedCar, plan
from glideplan.path import Path
from glideplan.planners.min_time import compiled, synthesis
from glideplan.planners.min_time.fixed_turn_rate import reach_distance
from glideplan.planners.min_time.geometry import compose
from glideplan.planners.min_time.synthesis import _word_family

# `compiled` imports numba: every synthesis below runs the kernels (the first of a process
# runs the reference unless numba is loaded, see `synthesis`)
assert compiled.solve is not None

REL = 1e-12


def _both(goal, rho):
    synthesis.COMPILED = False
    try:
        ref = synthesis.synthesize(np.asarray(goal, dtype=float), rho)
    finally:
        synthesis.COMPILED = True
    new = synthesis.synthesize(np.asarray(goal, dtype=float), rho)
    return ref, new


def _flown(ext):
    out = []
    for lab, d, x in ext.moves:
        if x > 1e-6 and (not out or out[-1] != (lab, d)):
            out.append((lab, d))
    return out


def _assert_same(goal, rho, *, degenerate=False):
    """Same extremals and costs; `degenerate`: only the best cost and the flown path."""
    ref, new = _both(goal, rho)
    if degenerate:
        assert new.best.cost == pytest.approx(ref.best.cost, rel=REL, abs=1e-8)
        car = VariableSpeedCar(rho, 1.0, 1.0)
        if ref.best.cost > 1e-6:  # the same flown path, arcs below 1e-6 rad left out
            assert _word_family(new.best, car)[0] == _word_family(ref.best, car)[0]
            assert _flown(new.best) == _flown(ref.best)
        return
    a = sorted((e.ctype.name, e.cost) for e in ref.extremals)
    b = sorted((e.ctype.name, e.cost) for e in new.extremals)
    assert [n for n, _ in a] == [n for n, _ in b], (goal, rho)
    for (_, x), (_, y) in zip(a, b, strict=True):
        assert y == pytest.approx(x, rel=REL, abs=1e-14), (goal, rho)
    assert new.best.cost == pytest.approx(ref.best.cost, rel=REL)
    assert new.best.ctype.name == ref.best.ctype.name
    # the winner's moves (hence its path) agree too
    for (la, da, xa), (lb, db, xb) in zip(ref.best.moves, new.best.moves, strict=True):
        assert (la, da) == (lb, db) and xb == pytest.approx(xa, rel=1e-10, abs=1e-12)


def test_random_goals_same_extremals_and_costs():
    rng = np.random.default_rng(28)
    n = 100
    goals = np.c_[rng.uniform(-3, 3, (n, 2)), rng.uniform(-math.pi, math.pi, n)]
    for goal, rho in zip(goals, rng.choice([0.2, 0.3, 0.5, 0.8], n), strict=True):
        _assert_same(goal, float(rho))


SPECIAL = [
    (0.0, 2.0, 2 * math.pi / 3, 0.3),  # Table 4.3
    (0.148, 0.7861, 2.3468, 0.5),  # C B T B C, left out by (4.26)
    (0.09, 0.16, 0.22, 0.3),  # next to the start
    (0.5, 0.5, math.pi / 2, 0.3),  # a quarter turn on the B circle
    (0.3, 0.7, 2.0, 0.3),
    (0.2, -0.1, -0.3, 0.3),
    (2.5, 0.0, 0.0, 0.3),  # straight ahead
    (-2.0, 0.0, math.pi, 0.3),  # behind, reversed
    (0.6, 0.9, math.pi, 0.5),
    (0.0, 0.0, math.pi, 0.3),  # turn on the spot
    (1.0, 1.0, math.pi / 2, 0.3),  # on the left B circle
    (3.0, -3.0, -math.pi, 0.5),
    (1.0, 3.0, 2.0, 1.0),  # equal speeds: Dubins only
]
# Goals where rigid types have a double root at a = 0, the end of their range: rounding puts
# it at +-1e-9 in one solver or the other (companion eigenvalues, Aberth), so one keeps a
# zero-length face (e.g. BBCB with B^0) where the other keeps another (CBBC, BCBBC), and a
# few near-tangent roots pass the 1e-8 end check in one only (BTB RLR, a = 1e-6, 5e-6 above
# the optimum; BCBB with a = 1.3e-9, 7e-10 below C^pi: a double root is found to ~1e-8 by
# either solver). The optimum's cost (to 1e-8) and flown path (arcs > 1e-6) agree.
DEGENERATE = [
    (0.0, 0.0, 1e-9, 0.3),  # the start turned by 1e-9: the optimum has length ~0
    (0.0, 0.6, math.pi, 0.3),  # half the left C circle (rho = 0.3): C^pi
]


@pytest.mark.parametrize("goal", SPECIAL, ids=lambda g: f"{g[0]},{g[1]},{g[2]:.3f},r{g[3]}")
def test_special_goals(goal):
    _assert_same(goal[:3], goal[3])


@pytest.mark.parametrize("goal", DEGENERATE, ids=lambda g: f"{g[0]},{g[1]},{g[2]:.3g}")
def test_degenerate_goals_same_optimum(goal):
    _assert_same(goal[:3], goal[3], degenerate=True)


def test_bcb_turn_goal_same():
    p, h = compose([("B", 1, 0.4), ("C", 1, 1.1), ("B", 1, 0.7)], 0.3, ())
    _assert_same((float(p[0]), float(p[1]), float(h)), 0.3)


def test_compiled_reach_matches_scipy_brent():
    from glideplan.planners.min_time.compiled import reach_distance as compiled_reach

    rng = np.random.default_rng(5)
    for _ in range(200):
        gp = rng.uniform(-6, 6, 2)
        delta = float(rng.uniform(0, 2 * math.pi))
        d0, w0 = reach_distance(gp, delta)
        d1, w1 = compiled_reach(gp, delta)
        assert d1 == pytest.approx(d0, rel=1e-12, abs=1e-12)
        assert w1 == pytest.approx(w0, abs=1e-9)


def test_roots_include_the_unit_circle_roots_of_numpy():
    from glideplan.planners.min_time import _jit

    rng = np.random.default_rng(9)
    for _ in range(300):
        c = rng.normal(size=3) + 1j * rng.normal(size=3)
        c[0] = c[0].real
        poly = np.concatenate([c[::-1], np.conj(c[1:])])
        z = np.empty(4, dtype=complex)
        _jit._poly_roots(poly, z)
        ref = np.roots(poly)
        for r in ref:
            assert np.min(np.abs(z - r)) < 1e-7 * max(1.0, abs(r))


def test_candidates_build_their_paths_on_demand():
    car = VariableSpeedCar(0.3, 1.0, 1.0)
    goal = Pose(0.0, 2.0, 2 * math.pi / 3)
    sol = plan(Pose(), goal, car)
    lazy = [c.path for c in sol.candidates[1:]]
    assert all("segments" not in p.__dict__ for p in lazy)  # only the winner was built
    for c in sol.candidates:
        assert c.path.word == c.word and c.path.family == c.family
        assert c.path.duration == pytest.approx(c.cost, rel=1e-12)
        assert c.path.endpoint_gap(goal)[0] < 1e-7
    copy = pickle.loads(pickle.dumps(sol.candidates[3].path))
    assert type(copy) is Path and copy.word == sol.candidates[3].word
    start = Pose(3.0, -1.0, 0.7)
    moved = plan(start, goal.from_frame(start), car)
    for c in moved.candidates:
        assert c.path.endpoint_gap(goal.from_frame(start))[0] < 1e-6


@pytest.mark.parametrize("heading", [0.0, 2 * math.pi / 3, -1.0])
def test_grid_rows_match_the_reference(heading):
    from glideplan.planners.min_time.grid import time_optimal_grid

    car = VariableSpeedCar(0.3, 1.0, 1.0)
    xs = np.linspace(-2.9, 2.9, 9)  # (the start itself is not on this grid)
    new = time_optimal_grid(car, xs, xs, heading, processes=1)
    synthesis.COMPILED = False
    try:
        ref = time_optimal_grid(car, xs, xs, heading, processes=1)
    finally:
        synthesis.COMPILED = True
    np.testing.assert_allclose(new.time, ref.time, rtol=REL)
    assert (new.family == ref.family).all() and (new.word == ref.word).all()
