"""Dubins leg lengths between two waypoints for all pairs of candidate headings.

The heading dynamic programme needs, for every leg, the K0 x K1 matrix of Dubins distances
from waypoint p0 with heading a_j to p1 with heading b_k (dissertation section 2.7, eq. 2.11).
Each entry is the goal (p1, b_k) seen from the start (p0, a_j): with D = (p1 - p0) / R,

    x = D . (cos a, sin a),  y = D . (-sin a, cos a),  psi = M(b - a),

(sin psi and cos psi from the angle-difference identities, so no K x K sine is taken), and the
six words' lengths come from the one Dubins kernel, `planners.dubins_kernel.word_totals`,
broadcast over a row block of the matrix (blocks stay in the CPU cache). float32 arithmetic
stays float32 (the kernel's `NUMPY32` tolerances).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.planners.dubins_kernel import ops_for, word_totals
from glideplan.pose import mod_2pi

__all__ = ["dubins_dp_step", "dubins_length_matrix"]

DP_BLOCKS = True
"""The DP step in vectorised blocks (`planners._dubins_dp`); False: the scalar bounded step
(`planners._dubins_jit.dp_leg`, the previous kernel, kept as the benchmark's baseline)."""

_BLOCK = 32768  # matrix entries per block: its ~10 temporaries stay in the L2 cache (measured:
# 200 waypoints x K = 360 take ~1.0 s at 32768 against ~1.8 s at 65536 on the CI machine)


def dubins_length_matrix(
    p0: ArrayLike,
    p1: ArrayLike,
    headings0: ArrayLike,
    headings1: ArrayLike,
    radius: float,
    dtype: type[np.floating[Any]] = np.float64,
) -> NDArray[Any]:
    """Dubins distances (m) from (p0, a_j) to (p1, b_k): a `(len(headings0), len(headings1))` array.

    `p0`, `p1`: (x, y) in m; headings in rad (CCW from +x); `radius` the minimum turn radius
    (m). In float64 equal to `planners.dubins.dubins_distance` on the broadcast poses (section
    2.7) to rounding; `dtype=np.float32` is about twice as fast, with relative errors of a few
    1e-6 (turns within 1.3e-5 rad of a multiple of 2 pi count as that multiple).
    """
    dt = np.dtype(dtype)
    o = ops_for(dt)
    p0a = np.asarray(p0, dtype=float)
    p1a = np.asarray(p1, dtype=float)
    a = np.asarray(mod_2pi(np.asarray(headings0, dtype=float).ravel())).astype(dt)
    b = np.asarray(mod_2pi(np.asarray(headings1, dtype=float).ravel())).astype(dt)
    inv = 1.0 / float(radius)
    dx = dt.type((p1a[0] - p0a[0]) * inv)
    dy = dt.type((p1a[1] - p0a[1]) * inv)
    out = np.empty((a.size, b.size), dtype=dt)
    rows = max(1, _BLOCK // max(1, b.size))
    sb, cb = np.sin(b)[None, :], np.cos(b)[None, :]
    for i in range(0, a.size, rows):
        ai = a[i : i + rows, None]
        sa, ca = np.sin(ai), np.cos(ai)
        x = ca * dx + sa * dy  # the goal in the start frame, (rows, 1)
        y = ca * dy - sa * dx
        psi = o.mod(b[None, :] - ai)
        sp = sb * ca - cb * sa  # sin(b - a), cos(b - a)
        cp = cb * ca + sb * sa
        np.minimum.reduce(word_totals(x, y, psi, sp, cp, o), out=out[i : i + rows])
    out *= dt.type(radius)
    return out


def dubins_dp_step(
    value: NDArray[np.float64],
    p0: ArrayLike,
    p1: ArrayLike,
    headings0: ArrayLike,
    headings1: ArrayLike,
    radius: float,
    scale: float = 1.0,
) -> tuple[NDArray[np.float64], NDArray[np.intp]] | None:
    """One step of the heading DP, compiled: min_j value[j] + scale * D(p0, a_j; p1, b_k).

    Returns the new values `(len(headings1),)` and the first minimising index j of each, the
    same as `argmin(value[:, None] + scale * dubins_length_matrix(..., float64), axis=0)`
    (section 2.7; the lengths to rounding) without forming the matrix: only the entries whose
    lower bounds are below the running minimum are evaluated (`planners._dubins_jit.dp_leg`).
    None when numba cannot be imported.
    """
    from glideplan.planners.dubins_kernel import _jit

    jit = _jit()
    if jit is None:  # pragma: no cover - numba is a dependency
        return None
    p0a = np.asarray(p0, dtype=float)
    p1a = np.asarray(p1, dtype=float)
    a = np.ascontiguousarray(mod_2pi(np.asarray(headings0, dtype=float).ravel()), dtype=float)
    b = np.ascontiguousarray(mod_2pi(np.asarray(headings1, dtype=float).ravel()), dtype=float)
    inv = 1.0 / float(radius)
    dx = float((p1a[0] - p0a[0]) * inv)
    dy = float((p1a[1] - p0a[1]) * inv)
    ca, sa = np.cos(a), np.sin(a)
    x = ca * dx + sa * dy  # the goal in each start frame, as in dubins_length_matrix
    y = ca * dy - sa * dx
    new = np.empty(b.size)
    arg = np.empty(b.size, dtype=np.intp)
    value = np.ascontiguousarray(value, dtype=float)
    if DP_BLOCKS:
        from glideplan.planners._dubins_dp import dp_leg

        dp_leg(value, x, y, a, b, dx, dy, float(radius), float(scale), new, arg)
    else:
        jit.dp_leg(value, x, y, a, b, dx, dy, float(radius), float(scale), new, arg)
    return new, arg
