"""Compiled (numba) step of the heading DP: vectorised blocks of exact Dubins totals, pruned.

new[j] = min_i value[i] + c(a_i, b_j) (missions.headings), arg[j] the first minimiser.
Start headings are sorted by value[i] + a lower bound of every leg from a_i
(`_dubins_jit._to_point`). For each goal heading b_j the best so far starts at the previous
goal heading's minimiser (exact), then blocks of start headings in that order get all six
words' totals at once (`_dubins_simd.six_words`: polynomial trigonometry, vectorised, with
sin/cos of b_j - a_i from those of a_i and b_j), until a block starts beyond the best. The
entries within 1e-9 relative of the block minimum (and the rare flagged ones) are evaluated
again by the scalar kernel (`_dubins_jit.min_total`, glibc, the operations of
`dubins_kernel`), so new and arg are the scalar kernel's: the polynomial totals agree with
it to ~1e-15, far inside that margin, and only choose which entries to evaluate exactly.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from glideplan.planners._dubins_jit import _to_point, min_total
from glideplan.planners._dubins_simd import SNAP, TWO_PI, six_words

__all__ = ["dp_leg"]

_INV_2PI = 1.0 / TWO_PI
_BLOCK = 32  # start headings per vectorised block (16 and 64 measured slower)
_NEAR = 1e-9  # re-evaluate exactly the entries this close (relative) to the block minimum


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _block(lo: np.uint64, hi: np.uint64, bj: float, sbj: float, cbj: float, a: np.ndarray,
           x: np.ndarray, y: np.ndarray, sa: np.ndarray, ca: np.ndarray, v: np.ndarray,
           rs: float, tot: np.ndarray, flag: np.ndarray) -> None:
    """tot[r] = v[r] + rs * Dubins total (polynomial), flag[r] the risk, for r in [lo, hi)
    (unsigned: the indices need no wrap-around selects, so the loop vectorises)."""
    for r in range(lo, hi):
        d = bj - a[r]
        psi = d - TWO_PI * math.floor(d * _INV_2PI + SNAP)
        sp = sbj * ca[r] - cbj * sa[r]  # sin(b - a), cos(b - a) as in leg_costs
        cp = cbj * ca[r] + sbj * sa[r]
        best, _, _, bad = six_words(x[r], y[r], psi, sp, cp)
        tot[r] = v[r] + max(best, 0.0) * rs
        flag[r] = bad


@njit(cache=True)
def _exact(i: int, bj: float, sbj: float, cbj: float, a: np.ndarray, x: np.ndarray,
           y: np.ndarray, sa: np.ndarray, ca: np.ndarray, value: np.ndarray, radius: float,
           scale: float) -> float:
    """value[i] + c(a_i, b_j) by the scalar kernel, as `_dubins_jit.dp_leg` forms it."""
    sp = sbj * ca[i] - cbj * sa[i]
    cp = cbj * ca[i] + sbj * sa[i]
    d = bj - a[i]
    psi = d - TWO_PI * math.floor(d * _INV_2PI + SNAP)
    t, _ = min_total(x[i], y[i], psi, sp, cp, np.inf)
    if t == np.inf:
        return np.inf
    c = t * radius
    if scale != 1.0:
        c = c * scale
    return value[i] + c


@njit(cache=True)
def dp_leg(value: np.ndarray, x: np.ndarray, y: np.ndarray, a: np.ndarray, b: np.ndarray,
           dx: float, dy: float, radius: float, scale: float, new: np.ndarray,
           arg: np.ndarray) -> None:
    """new[j] = min_i value[i] + c(a_i, b_j), arg[j] its first minimiser (module docstring);
    (x[i], y[i]) the goal in start frame i, (dx, dy) the leg (units of R), c = scale * R *
    Dubins total. A block is skipped when its least value plus a lower bound of every leg
    into b_j (the reversed path from the goal to the start point, `_to_point`) is above the
    best."""
    rs = radius * scale
    k = a.size
    key = np.empty(k)
    for i in range(k):
        key[i] = value[i] + _to_point(x[i], y[i]) * rs
    order = np.argsort(key, kind="mergesort")
    ks, as_, xs, ys, vs = key[order], a[order], x[order], y[order], value[order]
    sa_, ca_ = np.sin(a), np.cos(a)
    sas, cas = sa_[order], ca_[order]
    tot = np.empty(k)
    flag = np.empty(k, dtype=np.bool_)
    sb, cb = np.sin(b), np.cos(b)
    nblk = (k + _BLOCK - 1) // _BLOCK
    vmin = np.full(nblk, np.inf)
    for r in range(k):
        vmin[r // _BLOCK] = min(vmin[r // _BLOCK], vs[r])
    prev = -1
    for j in range(b.size):
        bj, sbj, cbj = b[j], sb[j], cb[j]
        warm = np.inf
        if prev >= 0:
            warm = _exact(prev, bj, sbj, cbj, a, x, y, sa_, ca_, value, radius, scale)
        cut = warm * (1.0 + _NEAR) + _NEAR
        low_b = _to_point(cbj * dx + sbj * dy, cbj * dy - sbj * dx) * rs  # from (p1, b + pi)
        pos = 0
        low = np.inf
        while pos < k and ks[pos] <= cut:
            hi = min(pos + _BLOCK, k)
            if vmin[pos // _BLOCK] + low_b > cut:
                for r in range(pos, hi):
                    tot[r] = np.inf
                pos = hi
                continue
            _block(np.uint64(pos), np.uint64(hi), bj, sbj, cbj, as_, xs, ys, sas, cas, vs, rs,
                   tot, flag)
            for r in range(pos, hi):
                if flag[r]:
                    tot[r] = _exact(order[r], bj, sbj, cbj, a, x, y, sa_, ca_, value, radius,
                                    scale)
                low = min(low, tot[r])
            cut = min(cut, low * (1.0 + _NEAR) + _NEAR)
            pos = hi
        bi = -1
        best = np.inf
        for r in range(pos):  # the near-minimal entries, exactly; ties to the first index
            if tot[r] <= cut:
                i = order[r]
                t = warm if i == prev else _exact(i, bj, sbj, cbj, a, x, y, sa_, ca_, value,
                                                  radius, scale)
                if t < best or (t == best and i < bi):
                    best, bi = t, i
        if bi < 0 and prev >= 0:  # nothing evaluated beat the warm start
            best, bi = warm, prev
        new[j] = best
        arg[j] = bi
        prev = bi
