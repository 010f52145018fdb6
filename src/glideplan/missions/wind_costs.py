"""Minimum arrival times of convected Dubins paths, vectorised over many leg queries.

The known-wind planner (`glideplan.planners.wind`, dissertation section 3.2 and appendix A)
solves one query at a time. The heading optimisation needs thousands: this module finds, for
arrays of (start, goal) poses at once, the smallest root of

    F_W(tau) = L_W(start -> g(tau)) - tau,   g(tau) = (goal - w tau, psi_goal)

in units where R = 1 and v = 1 (REFERENCE_NOTES 3.4), for the six words W, by scanning tau
from the lower bound |goal - start| / (1 + |w|) (ground speed <= v + |w|) in steps of
`step` and bisecting the first cell where any word's F_W (on the branch through the cell's
left end: L_W jumps by 2 pi where an arc wraps) changes sign. A root closer than `step` to
another may be missed, which only overestimates the time; the final legs are planned with the
planner itself.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.planners.dubins import dubins_word_lengths

__all__ = ["convected_times"]

TWO_PI = 2.0 * math.pi


def _f(s: NDArray[np.float64], g: NDArray[np.float64], w: NDArray[np.float64],
       tau: NDArray[np.float64]) -> NDArray[np.float64]:
    """F_W(tau) for all six words: `(m, 6)` (NaN where a word does not exist)."""
    goal = g.copy()
    goal[:, 0] -= w[0] * tau
    goal[:, 1] -= w[1] * tau
    return dubins_word_lengths(s, goal, 1.0) - tau[:, None]


def convected_times(
    start: ArrayLike,
    goal: ArrayLike,
    *,
    speed: float,
    radius: float,
    wind: tuple[float, float],
    step: float = 0.25,
) -> NDArray[np.float64]:
    """Minimum arrival time (s) over ground for `(m, 3)` start/goal poses (m, rad) in a wind.

    `speed` the air-relative speed v (m/s), `radius` R (m), `wind` (wx, wy) in m/s with
    |w| < v. Returns `(m,)` times (inf when no root was found below the upper bound
    (|goal| + 2 R + 4 pi R) / (v - |w|)).
    """
    s = np.array(start, dtype=float).reshape(-1, 3)
    g = np.array(goal, dtype=float).reshape(-1, 3)
    s[:, :2] /= radius
    g[:, :2] /= radius
    w = np.asarray(wind, dtype=float) / speed
    wm = float(np.hypot(w[0], w[1]))
    m = s.shape[0]
    dist = np.hypot(g[:, 0] - s[:, 0], g[:, 1] - s[:, 1])
    # |goal - start - w tau| = tau: no path arrives earlier (L_W >= the straight distance)
    dx = g[:, 0] - s[:, 0]
    dy = g[:, 1] - s[:, 1]
    dw = dx * w[0] + dy * w[1]
    lo = (np.sqrt(dw * dw + (1.0 - wm * wm) * dist * dist) - dw) / (1.0 - wm * wm)
    lo *= 1.0 - 1e-12
    hi = (dist + 2.0 + 2.0 * TWO_PI) / (1.0 - wm)
    out = np.full(m, np.inf)
    active = np.arange(m)
    tau = lo.copy()
    f_prev = _f(s, g, w, tau)
    done0 = np.any(f_prev <= 1e-12, axis=1)  # arrival at the lower bound (straight downwind)
    out[done0] = lo[done0]
    keep = ~done0
    active, tau, f_prev = active[keep], tau[keep], f_prev[keep]
    # the cell [a, b] where each query first crosses zero, bisected all together at the end
    cell_a = np.full(m, np.nan)
    cell_b = np.full(m, np.nan)
    cell_f = np.full((m, 6), np.nan)
    cell_x = np.zeros((m, 6), dtype=bool)
    while active.size:
        t_next = np.minimum(tau + step, hi[active])
        f_next = _f(s[active], g[active], w, t_next)
        with np.errstate(invalid="ignore"):
            jumps = np.round((f_next - f_prev) / TWO_PI)
            cross = (f_prev > 0.0) & ((f_next - TWO_PI * jumps <= 0.0) | (f_next <= 0.0))
        hit = np.any(cross, axis=1)
        rows = active[hit]
        cell_a[rows], cell_b[rows] = tau[hit], t_next[hit]
        cell_f[rows], cell_x[rows] = f_prev[hit], cross[hit]
        keep = ~(hit | (t_next >= hi[active]))
        active, tau, f_prev = active[keep], t_next[keep], f_next[keep]
    found = np.nonzero(np.any(cell_x, axis=1))[0]
    if found.size:
        out[found] = _bisect(s[found], g[found], w, cell_a[found], cell_b[found],
                             cell_f[found], cell_x[found])
    return out * radius / speed


def _bisect(
    s: NDArray[np.float64],
    g: NDArray[np.float64],
    w: NDArray[np.float64],
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    fa: NDArray[np.float64],
    words: NDArray[np.bool_],
    iterations: int = 36,
) -> NDArray[np.float64]:
    """Smallest root in [a, b] over the crossing words (bisection on each word's branch, all
    (query, word) pairs in one vectorised evaluation per step)."""
    rows, ks = np.nonzero(words)
    lo, hi, f0 = a[rows].copy(), b[rows].copy(), fa[rows, ks]
    sr, gr = s[rows], g[rows]
    pick = np.arange(rows.size)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        f = _f(sr, gr, w, mid)[pick, ks]
        with np.errstate(invalid="ignore"):
            branch = f - TWO_PI * np.round((f - f0) / TWO_PI)
            right = (branch <= 0.0) | ~np.isfinite(f)
        hi = np.where(right, mid, hi)
        lo = np.where(right, lo, mid)
    best = np.full(s.shape[0], np.inf)
    np.minimum.at(best, rows, hi)
    return best
