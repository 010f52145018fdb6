"""The compiled (numba) kernels against the NumPy reference kernels they replace.

Reference: `dubins_kernel.flat_word_totals` / `word_totals` and `dubins_distance` with
`dubins.COMPILED = False` (the NumPy kernel, itself checked
against OMPL and the dissertation in the other Dubins tests), `leg_costs.dubins_length_matrix`
with the DP's argmin, and `Kernel.primitives` on NumPy for chapter 5. The compiled kernels
evaluate the same formulas in the same order, so lengths agree to rounding (1e-12 relative)
and the degenerate cases (coincident poses, full turns, LSL/RSR ties) give the same numbers
and the same words; the pruning bounds only decide which words are evaluated.
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan.missions.leg_costs import dubins_dp_step, dubins_length_matrix
from glideplan.planners import dubins
from glideplan.planners.dubins import dubins_distance
from glideplan.planners.dubins_kernel import (
    NUMPY64,
    compiled_min_lengths,
    flat_word_totals,
    word_totals,
)

pytest.importorskip("numba")

TWO_PI = 2 * math.pi
coord = st.floats(-6.0, 6.0, allow_nan=False, allow_subnormal=False)
heading = st.floats(-2 * TWO_PI, 2 * TWO_PI, allow_nan=False, allow_subnormal=False)
pose = st.tuples(coord, coord, heading)
# degenerate goals relative to a start: the start itself, pure turns up to and through 2 pi
# (the heading a rounding away from a multiple of 2 pi), straight ahead (LSL = RSR tie),
# straight behind, on the turning circles
special = st.sampled_from(["same", "turn", "ahead", "behind", "circle", "full"])


def _degenerate(kind: str, s: tuple[float, float, float], u: float) -> tuple[float, ...]:
    x, y, h = s
    if kind == "same":
        return (x, y, h + TWO_PI * round(u * 3))
    if kind == "turn":  # a left or right turn of u * 2 pi (unit radius)
        a = TWO_PI * u
        sgn = 1.0 if u > 0.5 else -1.0
        lx, ly = math.sin(a), sgn * (1.0 - math.cos(a))
        return (x + lx * math.cos(h) - ly * math.sin(h), y + lx * math.sin(h) + ly * math.cos(h),
                h + sgn * a)
    if kind == "ahead":
        return (x + 5 * u * math.cos(h), y + 5 * u * math.sin(h), h)
    if kind == "behind":
        return (x - 5 * u * math.cos(h), y - 5 * u * math.sin(h), h)
    if kind == "circle":  # on the left circle, heading the other way
        return (x - math.sin(h) + math.cos(h + u), y + math.cos(h) + math.sin(h + u), h + math.pi)
    return (x, y, h + TWO_PI - 1e-13 * u)  # a rounding short of a full turn


def _reference(s: np.ndarray, g: np.ndarray, r: float) -> tuple[np.ndarray, np.ndarray]:
    tot = flat_word_totals(s, g, np.float64(r))
    return np.maximum(tot.min(axis=0), 0.0), np.argmin(tot, axis=0)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(pose, pose, special, st.floats(0.0, 1.0), st.booleans()),
                min_size=1, max_size=40), st.floats(0.3, 3.0))
def test_compiled_lengths_and_words_equal_the_numpy_kernel(rows, r):
    starts, goals = [], []
    for s, g, kind, u, degenerate in rows:
        starts.append(s)
        goals.append(_degenerate(kind, s, u) if degenerate else g)
    s = np.array(starts)
    g = np.array(goals)
    g[:, :2] = s[:, :2] + (g[:, :2] - s[:, :2]) * r  # scale the degenerate cases with R
    ref, ref_k = _reference(s, g, r)
    got, got_k = compiled_min_lengths(s, g, np.float64(r))
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12)
    exact = ref == 0.0  # coincident poses: zero exactly, as the NumPy kernel gives
    assert np.all(got[exact] == 0.0)
    # the same word, except where two words tie to rounding (then either is optimal)
    tot = flat_word_totals(s, g, np.float64(r))
    picked = tot[got_k, np.arange(len(s))]
    np.testing.assert_allclose(picked, tot[ref_k, np.arange(len(s))], rtol=1e-12, atol=1e-12)


def test_ties_go_to_the_first_word_as_in_numpy():
    # straight ahead: LSL and RSR have the same length (a straight), LSL comes first
    s = np.array([[0.0, 0.0, 0.3], [1.0, 2.0, -1.0]])
    g = s.copy()
    g[:, 0] += 4.0 * np.cos(s[:, 2])
    g[:, 1] += 4.0 * np.sin(s[:, 2])
    length, k = compiled_min_lengths(s, g, np.float64(1.0))
    _, ref_k = _reference(s, g, 1.0)
    np.testing.assert_allclose(length, 4.0, rtol=1e-15)
    np.testing.assert_array_equal(k, ref_k)


def _numpy_distance(*args, **kw):
    """`dubins_distance` on the NumPy kernel (`dubins.COMPILED = False`)."""
    dubins.COMPILED = False
    try:
        return dubins_distance(*args, **kw)
    finally:
        dubins.COMPILED = True


def test_dubins_distance_runs_the_compiled_kernel_on_a_batch():
    # 5,000 random queries: `dubins_distance` takes the compiled kernel once numba is loaded
    # (it is, here) and equals the NumPy kernel's answers to 1e-12 relative (issue 28)
    rng = np.random.default_rng(3)
    n = 5000
    s = np.c_[rng.uniform(-5, 5, (n, 2)), rng.uniform(-4, 4, n)]
    g = np.c_[rng.uniform(-5, 5, (n, 2)), rng.uniform(-4, 4, n)]
    assert dubins._use_compiled(n)
    d, k = _numpy_distance(s, g, 1.5, return_index=True)
    got, got_k = dubins_distance(s, g, 1.5, return_index=True)
    np.testing.assert_allclose(got, d, rtol=1e-12)
    assert np.mean(got_k == k) > 0.999
    raw, raw_k = compiled_min_lengths(s, g, np.float64(1.5))
    np.testing.assert_array_equal(got, raw * 1.5)
    np.testing.assert_array_equal(got_k, raw_k)


@settings(max_examples=30, deadline=None)
@given(st.lists(st.tuples(pose, special, st.floats(0.0, 1.0)), min_size=1, max_size=40),
       st.floats(0.3, 3.0))
def test_dubins_distance_degenerate_cases_as_the_numpy_kernel(rows, r):
    # coincident poses, pure and full turns, straight ahead/behind (LSL = RSR ties): the
    # compiled `dubins_distance` gives the NumPy kernel's lengths (1e-12; zero exactly)
    s = np.array([row[0] for row in rows])
    g = np.array([_degenerate(kind, p, u) for p, kind, u in rows])
    g[:, :2] = s[:, :2] + (g[:, :2] - s[:, :2]) * r
    ref = _numpy_distance(s, g, r)
    got = dubins_distance(s, g, r)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12 * r)
    assert np.all(got[ref == 0.0] == 0.0)


def test_dubins_distance_small_batches_do_not_import_numba():
    # CLI start-up: without numba loaded, a small batch stays on NumPy; a large one compiles
    import subprocess
    import sys

    code = ("import sys, numpy as np\n"
            "from glideplan.planners.dubins import dubins_distance\n"
            "dubins_distance(np.zeros(3), np.ones((100, 3)))\n"
            "print('numba' in sys.modules)")  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True)  # fmt: skip
    assert out.stdout.strip() == "False"
    assert dubins._COMPILED_FROM > 100


@settings(max_examples=15, deadline=None)
@given(st.floats(0.3, 6.0), st.floats(-math.pi, math.pi), st.integers(8, 60),
       st.floats(0.5, 2.0), st.floats(0.0, 3.0), st.integers(0, 2**31))
def test_dp_step_equals_the_matrix_minimum(dist, bearing, k, r, spread, seed):
    # reference: argmin over the full float64 matrix, the DP's own step
    rng = np.random.default_rng(seed)
    a = np.sort(rng.uniform(0, TWO_PI, k))
    b = np.concatenate([np.arange(k) * TWO_PI / k, [bearing % TWO_PI]])
    value = rng.uniform(0, spread, k)
    p0 = np.array([0.3, -0.2])
    p1 = p0 + dist * r * np.array([math.cos(bearing), math.sin(bearing)])
    m = dubins_length_matrix(p0, p1, a, b, r, np.float64) * 1.25
    total = value[:, None] + m
    arg = np.argmin(total, axis=0)
    out = dubins_dp_step(value, p0, p1, a, b, r, 1.25)
    assert out is not None
    new, got = out
    np.testing.assert_allclose(new, total[arg, np.arange(b.size)], rtol=1e-12)
    ok = got == arg  # a different index only where two entries tie to rounding
    np.testing.assert_allclose(total[got[~ok], np.arange(b.size)[~ok]],
                               total[arg[~ok], np.arange(b.size)[~ok]], rtol=1e-12)


def test_word_totals_numpy_agrees_with_each_compiled_word():
    from glideplan.planners._dubins_jit import word_total

    rng = np.random.default_rng(5)
    x, y = rng.uniform(-4, 4, 300), rng.uniform(-4, 4, 300)
    psi = np.asarray(NUMPY64.mod(rng.uniform(-7, 7, 300)))
    ref = word_totals(x, y, psi, np.sin(psi), np.cos(psi), NUMPY64)
    for w in range(6):
        got = np.array([word_total(w, x[i], y[i], psi[i], math.sin(psi[i]), math.cos(psi[i]))
                        for i in range(300)])
        np.testing.assert_allclose(got, ref[w], rtol=1e-12, atol=1e-12)
