"""Compiled (numba) Dubins lengths for flat batches: all six words, branch-free, SIMD.

The flat 10^6-query loop is bound by its trigonometry: two sine/cosine pairs and six arc
tangents per query. glibc's are scalar, and this machine's numba has no SVML, so the loop
here uses its own polynomials, written so that LLVM vectorises the whole loop (no calls, no
branches, only selects; `error_model="numpy"`):

    sin, cos: x = n pi/2 + r, |r| <= pi/4 (3-part Cody-Waite pi/2), Taylor to r^19 / r^18;
    atan(a), 0 <= a <= 1: atan a = c + atan((a - tan c)/(1 + a tan c)), c in {0, pi/8, pi/4},
        |t| <= tan(pi/16), odd Taylor series to t^25 (first term left out < 1e-17 t);
    atan2 from atan(min/max) by octant; acos c = atan2(sqrt((1 - c)(1 + c)), c).

`six_words`, `_sincos` and the small `_mod`, `_edge`, `_pick` are inlined by numba
(`inline="always"`): left as calls, LLVM does not inline the first two and the flat loop is not
vectorised (7x slower); the small ones measured ~3 % faster inlined. The arc tangents (`_atan2`,
`_atan01`, eight per query) are left to LLVM's inliner, which inlines them all the same;
inlining them in numba's IR as well made the cold compile of the Dubins and DP kernels 2.3x
longer (19.7 s -> 8.5 s CPU without it, the same speed).

Each is within a few ulp of glibc, so the words' totals agree with `dubins_kernel`'s to
~1e-15 relative. The word formulas and the 2 pi snap are `dubins_kernel`'s (eq. 2.11).

Where a few ulp could change the answer, the query is flagged and recomputed by the scalar
kernel (`_dubins_jit.min_total`, glibc, the same operations as NumPy), so those answers are
the scalar kernel's exactly: a turn of any feasible word within 1e-7 rad of 0 or 2 pi (the
snap), a straight part below 1e-7 (pure turns, coincident poses), a feasibility margin within
1e-7 of its limit, the two best words within 1e-9 relative (ties keep the first word), a
heading beyond 1e5 rad or not finite. On random queries ~1e-6 of them are flagged.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from glideplan.planners._dubins_jit import min_total

__all__ = ["flat_min_lengths"]

TWO_PI = 2.0 * math.pi
PI = math.pi
HALF_PI = 0.5 * math.pi
_INV_2PI = 1.0 / TWO_PI
_TWO_OVER_PI = 2.0 / math.pi
SNAP = 1e-11  # dubins_kernel.NUMPY64.snap
FEAS = 1e-10  # dubins_kernel.NUMPY64.feas
_NEAR = 16.0 + 8.0 * FEAS  # |V|^2 at most this: the CCC words exist
# pi/2 in three parts of 30 bits (n * part exact for |n| < 2^23)
_P1 = 1.570796325802803
_P2 = 9.920935791635221e-10
_P3 = 5.170182981794105e-19
_TAN_PI_16 = 0.19891236737965800691
_TAN_3PI_16 = 0.66817863791929891999
_TAN_PI_8 = 0.41421356237309503
_PI_8 = 0.39269908169872414
_PI_8_LO = 1.5308084989341915e-17
_PI_4 = 0.7853981633974483
_PI_4_LO = 3.061616997868383e-17
_EDGE = 1e-7  # flag turns, straights and margins this close to their limits
_TIE = 1e-9  # flag the two best totals this close (relative)
_BIG = 1e5  # flag headings beyond this (the reduction's accuracy)


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def _sincos(x: float) -> tuple[float, float]:
    """sin x, cos x (module docstring), |x| <= 1e5."""
    n = math.floor(x * _TWO_OVER_PI + 0.5)
    r = ((x - n * _P1) - n * _P2) - n * _P3
    z = r * r
    s = z * (1.0 / 121645100408832000.0) - 1.0 / 355687428096000.0  # r^19 ... r^3
    s = z * s + 1.0 / 1307674368000.0
    s = z * s - 1.0 / 6227020800.0
    s = z * s + 1.0 / 39916800.0
    s = z * s - 1.0 / 362880.0
    s = z * s + 1.0 / 5040.0
    s = z * s - 1.0 / 120.0
    s = z * s + 1.0 / 6.0
    s = r - r * z * s
    c = z * (-1.0 / 6402373705728000.0) + 1.0 / 20922789888000.0  # r^18 ... r^2
    c = z * c - 1.0 / 87178291200.0
    c = z * c + 1.0 / 479001600.0
    c = z * c - 1.0 / 3628800.0
    c = z * c + 1.0 / 40320.0
    c = z * c - 1.0 / 720.0
    c = z * c + 1.0 / 24.0
    c = z * c - 0.5
    c = 1.0 + z * c
    q = n - 4.0 * math.floor(n * 0.25)  # quadrant 0..3
    sn = s if q == 0.0 else (c if q == 1.0 else (-s if q == 2.0 else -c))
    cs = c if q == 0.0 else (-s if q == 1.0 else (-c if q == 2.0 else s))
    return sn, cs


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _atan01(a: float) -> float:
    """atan a for 0 <= a <= 1 (module docstring)."""
    mid = a > _TAN_PI_16
    top = a > _TAN_3PI_16
    tc = 1.0 if top else (_TAN_PI_8 if mid else 0.0)
    t = (a - tc) / (1.0 + a * tc)
    z = t * t
    s = z * (1.0 / 25.0) - 1.0 / 23.0
    s = z * s + 1.0 / 21.0
    s = z * s - 1.0 / 19.0
    s = z * s + 1.0 / 17.0
    s = z * s - 1.0 / 15.0
    s = z * s + 1.0 / 13.0
    s = z * s - 1.0 / 11.0
    s = z * s + 1.0 / 9.0
    s = z * s - 1.0 / 7.0
    s = z * s + 1.0 / 5.0
    s = z * s - 1.0 / 3.0
    r = t + t * z * s
    hi = _PI_4 if top else (_PI_8 if mid else 0.0)
    lo = _PI_4_LO if top else (_PI_8_LO if mid else 0.0)
    return hi + (r + lo)


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _atan2(y: float, x: float) -> float:
    """atan2(y, x) (0 at the origin)."""
    ax, ay = abs(x), abs(y)
    hi = max(ax, ay)
    a = min(ax, ay) / (hi if hi > 0.0 else 1.0)
    r = _atan01(a)
    r = HALF_PI - r if ay > ax else r
    r = PI - r if x < 0.0 else r
    return -r if y < 0.0 else r


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def _mod(a: float) -> float:
    return a - TWO_PI * math.floor(a * _INV_2PI + SNAP)


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def _edge(a: float) -> bool:
    """A snapped turn within _EDGE of 0 or 2 pi."""
    return a < _EDGE or a > TWO_PI - _EDGE


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def _pick(tot: float, k: float, best: float, bk: float, second: float
          ) -> tuple[float, float, float]:
    """Running minimum (ties: the earlier word) and the second-best total."""
    better = tot < best
    second = min(second, best if better else tot)
    return (tot if better else best), (k if better else bk), second


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def six_words(x: float, y: float, psi: float, sp: float, cp: float
              ) -> tuple[float, float, float, bool]:
    """Shortest total (unit radius), its word (as a float), the second-best total and the
    risk flag (module docstring) of the goal (x, y, psi), sp, cp = sin psi, cos psi."""
    # LSL
    lx, ly = x - sp, y + cp - 1.0
    phi_l = _atan2(ly, lx)  # also LRL's
    t, p, q = _mod(phi_l), math.sqrt(lx * lx + ly * ly), _mod(psi - phi_l)
    bad = _edge(t) | _edge(q) | (p < _EDGE)
    best, bk, second = (max(t, 0.0) + p) + max(q, 0.0), 0.0, np.inf
    # LSR
    vx, vy = x + sp, y - cp - 1.0
    p2 = vx * vx + vy * vy - 4.0
    p = math.sqrt(max(p2, 0.0))
    phi = _atan2(vy * p + 2.0 * vx, vx * p - 2.0 * vy)
    t, q = _mod(phi), _mod(phi - psi)
    ok = p2 + FEAS >= 0.0
    bad |= (abs(p2) < _EDGE) | (ok & (_edge(t) | _edge(q)))
    best, bk, second = _pick((max(t, 0.0) + p) + max(q, 0.0) if ok else np.inf,
                             1.0, best, bk, second)
    # RSL
    vx, vy = x - sp, y + cp + 1.0
    p2 = vx * vx + vy * vy - 4.0
    p = math.sqrt(max(p2, 0.0))
    phi = _atan2(vy * p - 2.0 * vx, vx * p + 2.0 * vy)
    t, q = _mod(-phi), _mod(psi - phi)
    ok = p2 + FEAS >= 0.0
    bad |= (abs(p2) < _EDGE) | (ok & (_edge(t) | _edge(q)))
    best, bk, second = _pick((max(t, 0.0) + p) + max(q, 0.0) if ok else np.inf,
                             2.0, best, bk, second)
    # RSR
    rx, ry = x + sp, y - cp + 1.0
    phi_r = _atan2(ry, rx)  # also RLR's
    r2 = rx * rx + ry * ry
    t, p, q = _mod(-phi_r), math.sqrt(r2), _mod(phi_r - psi)
    bad |= _edge(t) | _edge(q) | (p < _EDGE)
    best, bk, second = _pick((max(t, 0.0) + p) + max(q, 0.0), 3.0, best, bk, second)
    # RLR (right circles), LRL (left circles): |V| <= 4
    c = min(max(1.0 - 0.125 * r2, -1.0), 1.0)
    pm = TWO_PI - _atan2(math.sqrt((1.0 - c) * (1.0 + c)), c)
    t = _mod(0.5 * pm - phi_r)
    q = _mod(pm - t - psi)
    ok = r2 <= _NEAR
    bad |= (abs(r2 - 16.0) < _EDGE) | (ok & (_edge(t) | _edge(q)))
    best, bk, second = _pick((max(t, 0.0) + pm) + max(q, 0.0) if ok else np.inf,
                             4.0, best, bk, second)
    v2 = lx * lx + ly * ly
    c = min(max(1.0 - 0.125 * v2, -1.0), 1.0)
    pm = TWO_PI - _atan2(math.sqrt((1.0 - c) * (1.0 + c)), c)
    t = _mod(phi_l + 0.5 * pm)
    q = _mod(psi - t + pm)
    ok = v2 <= _NEAR
    bad |= (abs(v2 - 16.0) < _EDGE) | (ok & (_edge(t) | _edge(q)))
    best, bk, second = _pick((max(t, 0.0) + pm) + max(q, 0.0) if ok else np.inf,
                             5.0, best, bk, second)
    return best, bk, second, bad


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _vector_pass(h0s: np.ndarray, h1s: np.ndarray, dxs: np.ndarray, dys: np.ndarray,
                 out: np.ndarray, word: np.ndarray, flag: np.ndarray) -> None:
    """Shortest total, word and risk flag of every query (branch-free; module docstring):
    start and goal headings, the goal's offset in units of R (contiguous, vectorised)."""
    for i in range(h0s.size):
        h0, h1 = h0s[i], h1s[i]
        s0, c0 = _sincos(h0)
        dx, dy = dxs[i], dys[i]
        x = c0 * dx + s0 * dy
        y = c0 * dy - s0 * dx
        psi = _mod(h1 - h0)
        sp, cp = _sincos(psi)
        bad = not (abs(h0) <= _BIG and abs(h1) <= _BIG and abs(x) < 1e300 and abs(y) < 1e300)
        best, bk, second, risky = six_words(x, y, psi, sp, cp)
        out[i] = max(best, 0.0)
        word[i] = bk
        flag[i] = bad | risky | ((second - best) <= _TIE * max(best, 1.0))


@njit(cache=True)
def _fix(start: np.ndarray, goal: np.ndarray, inv: np.ndarray, out: np.ndarray,
         word: np.ndarray, flag: np.ndarray) -> int:
    """Recompute the flagged queries with the scalar kernel (`_dubins_jit.min_lengths`' loop)."""
    scalar = inv.shape[0] == 1
    n = 0
    for i in range(start.shape[0]):
        if not flag[i]:
            continue
        n += 1
        h0 = start[i, 2]
        c0, s0 = math.cos(h0), math.sin(h0)
        dx, dy = goal[i, 0] - start[i, 0], goal[i, 1] - start[i, 1]
        r = inv[0] if scalar else inv[i]
        x = (c0 * dx + s0 * dy) * r
        y = (c0 * dy - s0 * dx) * r
        psi = goal[i, 2] - h0
        psi = psi - TWO_PI * math.floor(psi * _INV_2PI + SNAP)
        tot, k = min_total(x, y, psi, math.sin(psi), math.cos(psi), np.inf)
        out[i] = max(tot, 0.0)
        word[i] = k
    return n


_CHUNK = 1024  # queries per vectorised block (its buffers stay in the L1 cache)


@njit(cache=True)
def flat_min_lengths(start: np.ndarray, goal: np.ndarray, inv: np.ndarray, out: np.ndarray,
                     word: np.ndarray) -> int:
    """Shortest total (units of R) and word of each `(m, 3)` pair into `out`, `word` (word
    index 0..5 as a float); `inv` = 1 / R, `(m,)` or `(1,)`. Returns the number of queries
    recomputed by the scalar kernel."""
    m = start.shape[0]
    scalar = inv.shape[0] == 1
    buf = np.empty((4, _CHUNK))
    flag = np.empty(m, dtype=np.bool_)
    for lo in range(0, m, _CHUNK):
        n = min(_CHUNK, m - lo)
        for k in range(n):
            i = lo + k
            r = inv[0] if scalar else inv[i]
            buf[0, k] = start[i, 2]
            buf[1, k] = goal[i, 2]
            buf[2, k] = (goal[i, 0] - start[i, 0]) * r
            buf[3, k] = (goal[i, 1] - start[i, 1]) * r
        _vector_pass(buf[0, :n], buf[1, :n], buf[2, :n], buf[3, :n], out[lo:lo + n],
                     word[lo:lo + n], flag[lo:lo + n])
    return _fix(start, goal, inv, out, word, flag)
