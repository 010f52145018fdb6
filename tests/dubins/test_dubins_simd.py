"""The vectorised Dubins kernel (`planners._dubins_simd`): its polynomial trigonometry and
its fallback to the scalar kernel.

References: NumPy's (glibc's) sin, cos and arctan2, correctly rounded to within 1 ulp, so
the polynomials must agree to a few ulp (4e-16 absolute on [-1e5, 1e5]); the scalar compiled
kernel `_dubins_jit.min_total` (itself checked against the NumPy kernel in
test_dubins_compiled.py) for the lengths (1e-12 relative, the issue's tolerance) and words.
"""

import math

import numpy as np
import pytest

numba = pytest.importorskip("numba")

from glideplan.planners import _dubins_jit, _dubins_simd  # noqa: E402
from glideplan.planners.dubins_kernel import compiled_min_lengths  # noqa: E402


@numba.njit(error_model="numpy")
def _trig(x, y, out):
    for i in range(x.size):
        out[0, i], out[1, i] = _dubins_simd._sincos(x[i])
        out[2, i] = _dubins_simd._atan2(y[i], x[i])


def test_polynomial_sin_cos_atan2_within_a_few_ulp_of_glibc():
    rng = np.random.default_rng(5)
    x = np.r_[rng.uniform(-7, 7, 20000), rng.uniform(-1e5, 1e5, 20000), 0.0, -0.0,
              math.pi / 4, math.pi / 2, math.pi, 1e-300]
    y = np.r_[rng.standard_normal(40000) * 10.0 ** rng.uniform(-8, 3, 40000),
              1.0, -1.0, 0.0, 1e-300, -2.0, 0.5]
    out = np.empty((3, x.size))
    _trig(x, y, out)
    np.testing.assert_allclose(out[0], np.sin(x), rtol=0, atol=4e-16)
    np.testing.assert_allclose(out[1], np.cos(x), rtol=0, atol=4e-16)
    ref = np.arctan2(y, x)
    np.testing.assert_allclose(out[2], ref, rtol=4e-16, atol=1e-300)


def _scalar(s, g, r):
    out, idx = np.empty(len(s)), np.empty(len(s), dtype=np.intp)
    _dubins_jit.min_lengths(s, g, np.array([1.0 / r]), out, idx)
    return out, idx


def test_lengths_and_words_equal_the_scalar_kernel_on_random_and_flagged_queries():
    rng = np.random.default_rng(11)
    n = 20000
    s = np.c_[rng.uniform(-8, 8, (n, 2)), rng.uniform(-9, 9, n)]
    g = np.c_[rng.uniform(-8, 8, (n, 2)), rng.uniform(-9, 9, n)]
    # queries that must take the scalar path: coincident, straight ahead (LSL = RSR tie),
    # a full turn on the spot, headings beyond 1e5 rad, a pure left quarter turn
    g[:50] = s[:50]
    g[50:100, :2] = s[50:100, :2] + 3.0 * np.c_[np.cos(s[50:100, 2]), np.sin(s[50:100, 2])]
    g[50:100, 2] = s[50:100, 2]
    g[100:150] = s[100:150] + np.array([0.0, 0.0, 2 * math.pi])
    s[150:200, 2] += 3e5
    h = s[200:250, 2]
    g[200:250] = np.c_[s[200:250, 0] - np.sin(h) + np.cos(h),
                       s[200:250, 1] + np.cos(h) + np.sin(h), h + math.pi / 2]
    r = 1.7
    g[:, :2] = s[:, :2] + (g[:, :2] - s[:, :2]) * r
    ref, ref_k = _scalar(s, g, r)
    out, word = np.empty(n), np.empty(n)
    fixed = _dubins_simd.flat_min_lengths(s, g, np.array([1.0 / r]), out, word)
    assert 200 <= fixed < 400  # the crafted 250 (bar a few turns not near a snap), ~0 random
    np.testing.assert_allclose(out, ref, rtol=1e-12, atol=0)
    np.testing.assert_array_equal(word.astype(np.intp), ref_k)
    assert np.all(out[:50] == 0.0)  # coincident: exactly zero
    np.testing.assert_allclose(out[50:100], 3.0, rtol=1e-15)  # straight ahead (any S word)


def test_per_query_radii_and_non_finite_input():
    s = np.array([[0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.0, 0.0, np.nan], [0.0, 0.0, 0.0]])
    g = np.array([[4.0, 0.0, 0.0], [1.0, 5.0, 1.0], [1.0, 0.0, 0.0], [np.inf, 0.0, 0.0]])
    radii = np.array([2.0, 4.0, 1.0, 1.0])
    length, k = compiled_min_lengths(s, g, radii)
    assert length[0] == 2.0 and k[0] == 0  # 4 m straight ahead at R = 2 m: 2 R, LSL
    out, idx = np.empty(4), np.empty(4, dtype=np.intp)
    _dubins_jit.min_lengths(s, g, 1.0 / radii, out, idx)  # the scalar kernel
    np.testing.assert_allclose(length, out, rtol=1e-12)
    np.testing.assert_array_equal(k, idx)
