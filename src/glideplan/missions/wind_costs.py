"""Minimum arrival times of convected Dubins paths, vectorised over many leg queries.

The known-wind planner (`glideplan.planners.wind`, dissertation section 3.2 and appendix A)
solves one query at a time. The heading optimisation needs thousands: this module finds, for
arrays of (start, goal) poses at once, the smallest root of

    F_W(tau) = L_W(start -> g(tau)) - tau,   g(tau) = (goal - w tau, psi_goal)

in units where R = 1 and v = 1 (REFERENCE_NOTES 3.4), for the six words W, by scanning tau
from the lower bound where |goal - start - w tau| = tau (no path is shorter than the straight
line to the virtual target) in steps of
`step` and bisecting the first cell where any word's F_W (on the branch through the cell's
left end: L_W jumps by 2 pi where an arc wraps) changes sign; as in the planner, a root must
make F_W itself vanish (a jump of L_W across zero is not an arrival), else the scan goes on.
A root closer than `step` to another may be missed, which only overestimates the time; the
final legs are planned (and verified) with the planner itself. F_W and the crossing test are
the planner's own (`glideplan.planners.wind_kernel`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.planners.wind_kernel import crossing_cells, word_residuals
from glideplan.pose import TWO_PI

__all__ = ["convected_times"]


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
    f_lo = word_residuals(s, g, w, lo)
    done0 = np.any(f_lo <= 1e-12, axis=1)  # arrival at the lower bound (straight downwind)
    out[done0] = lo[done0]
    active = np.nonzero(~done0)[0]
    tau, f_prev = lo[active], f_lo[active]
    # Rounds: scan every open query to its first cell where some F_W changes sign, bisect
    # all those cells together, keep valid roots; the others resume scanning after the cell.
    while active.size:
        cells = _scan(s, g, w, active, tau, f_prev, hi[active], step)
        rows, cell_a, cell_b, cell_f, cell_x, f_b = cells
        if rows.size == 0:
            break
        roots = _roots(s[rows], g[rows], w, cell_a, cell_b, cell_f, cell_x)
        ok = np.isfinite(roots)
        out[rows[ok]] = roots[ok]
        again = ~ok & (cell_b < hi[rows])
        active, tau, f_prev = rows[again], cell_b[again], f_b[again]
    return out * radius / speed


def _scan(
    s: NDArray[np.float64],
    g: NDArray[np.float64],
    w: NDArray[np.float64],
    active: NDArray[np.intp],
    tau: NDArray[np.float64],
    f_prev: NDArray[np.float64],
    hi: NDArray[np.float64],
    step: float,
) -> tuple[NDArray[Any], ...]:
    """March each open query in steps of `step` to the first cell where a word's F_W (or its
    branch through the cell's left end) becomes <= 0: (rows, a, b, F(a), crossing words,
    F(b))."""
    out_rows, out_a, out_b, out_fa, out_x, out_fb = [], [], [], [], [], []
    while active.size:
        t_next = np.minimum(tau + step, hi)
        f_next = word_residuals(s[active], g[active], w, t_next)
        cross = crossing_cells(f_prev, f_next)
        hit = np.any(cross, axis=1)
        out_rows.append(active[hit])
        out_a.append(tau[hit])
        out_b.append(t_next[hit])
        out_fa.append(f_prev[hit])
        out_x.append(cross[hit])
        out_fb.append(f_next[hit])
        keep = ~hit & (t_next < hi)
        active, tau, f_prev, hi = active[keep], t_next[keep], f_next[keep], hi[keep]
    return (
        np.concatenate(out_rows),
        np.concatenate(out_a),
        np.concatenate(out_b),
        np.concatenate(out_fa),
        np.concatenate(out_x),
        np.concatenate(out_fb),
    )


def _roots(
    s: NDArray[np.float64],
    g: NDArray[np.float64],
    w: NDArray[np.float64],
    a: NDArray[np.float64],
    b: NDArray[np.float64],
    fa: NDArray[np.float64],
    words: NDArray[np.bool_],
    iterations: int = 36,
) -> NDArray[np.float64]:
    """Smallest valid root in each cell [a, b] over the crossing words, else inf.

    Bisection on two branches of each word's F_W (as the wind planner's `_polish`): unwrapped
    relative to F(a) (a root just before an arc wraps) and F_W itself (a root after a wrap);
    where the word does not exist at one end, the root is sought between its boundary and the
    other end;
    a root is valid only if F_W itself vanishes there (|F| <= 1e-7 max(1, tau)), so a jump of
    L_W by 2 pi across zero is not taken for an arrival.
    """
    rows, ks = np.nonzero(words)
    rows = np.concatenate([rows, rows])
    ks = np.concatenate([ks, ks])
    unwrap = np.arange(rows.size) < rows.size // 2
    lo, hi, f0 = a[rows].copy(), b[rows].copy(), fa[rows, ks]
    nan_left = np.isnan(f0)  # the word appears inside the cell: missing counts as "before"
    unwrap &= ~nan_left
    sr, gr = s[rows], g[rows]
    pick = np.arange(rows.size)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        f = word_residuals(sr, gr, w, mid)[pick, ks]
        with np.errstate(invalid="ignore"):
            branch = np.where(unwrap, f - TWO_PI * np.round((f - f0) / TWO_PI), f)
            missing = ~np.isfinite(f)
            right = np.where(nan_left, (branch <= 0.0) & ~missing, (branch <= 0.0) | missing)
        hi = np.where(right, mid, hi)
        lo = np.where(right, lo, mid)
    f_end = word_residuals(sr, gr, w, hi)[pick, ks]
    with np.errstate(invalid="ignore"):
        valid = np.abs(f_end) <= 1e-7 * np.maximum(1.0, hi)
    best = np.full(s.shape[0], np.inf)
    np.minimum.at(best, rows[valid], hi[valid])
    return best
