"""The current in a route's local plane, sampled once on a fine grid for a closed-loop
follower that asks for it one point at a time.

`follow_route` evaluates the field at the vehicle's position every step: an aeqd inverse
(pyproj), SciPy's interpolator and the rotation of north into the plane's axes, ~1-2 ms a
step, hundreds of steps a leg. `sampled_velocity` evaluates those same functions once on a
grid of spacing h over the leg's box and the field's time levels in the leg's time span
(one vectorised call), then answers each step by trilinear interpolation of the samples
(microseconds). Between samples the field's own piecewise-linear interpolation (kinks at
its cell edges, ~km apart) is replaced by the samples' linear interpolation: the difference
is at most h |jump of grad c| / 2 (about 2e-5 m/s for a 1/12 deg forecast at h = 100 m).
Outside the box or the span, or where a sample is NaN (land), the exact function answers.
"""

from __future__ import annotations

import math
from bisect import bisect_right
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

__all__ = ["sampled_velocity"]

FloatArray = NDArray[np.float64]
Velocity = Callable[[float, FloatArray, FloatArray], tuple[FloatArray, FloatArray]]


#: (times (nt,), x (n,), y (n,)) -> (u, v) each (nt, n): the exact current at many points.
Levels = Callable[[FloatArray, FloatArray, FloatArray], tuple[FloatArray, FloatArray]]


def sampled_velocity(exact: Velocity, box: tuple[float, float, float, float],
                     times: FloatArray, spacing: float, sample: Levels) -> Velocity:
    """`exact(t, x, y)` (local axes, m/s) sampled on `box` = (x0, x1, y0, y1) (m) every
    `spacing` m at `times` (s, ascending) by `sample` (the same function at all the points
    and times at once; it may raise, e.g. off the field); the returned function
    interpolates (module docstring)."""
    x0, x1, y0, y1 = box
    nx = max(math.ceil((x1 - x0) / spacing) + 1, 2)
    ny = max(math.ceil((y1 - y0) / spacing) + 1, 2)
    xs, ys = np.linspace(x0, x1, nx), np.linspace(y0, y1, ny)
    X, Y = np.meshgrid(xs, ys, indexing="ij")
    u, v = sample(np.asarray(times, dtype=float), X.ravel(), Y.ravel())
    U = np.asarray(u, dtype=float).reshape(len(times), nx, ny)
    W = np.asarray(v, dtype=float).reshape(len(times), nx, ny)
    if not (np.all(np.isfinite(U)) and np.all(np.isfinite(W))):
        return exact
    ul, wl, tl = U.tolist(), W.tolist(), [float(t) for t in times]
    dx, dy = float(xs[1] - xs[0]), float(ys[1] - ys[0])

    def velocity(t: float, x: FloatArray, y: FloatArray) -> tuple[FloatArray, FloatArray]:
        if np.size(x) != 1:
            return exact(t, x, y)
        px, py = float(np.ravel(x)[0]), float(np.ravel(y)[0])
        if not (x0 <= px <= x1 and y0 <= py <= y1 and tl[0] <= t <= tl[-1]):
            return exact(t, x, y)
        i = min(int((px - x0) / dx), nx - 2)
        j = min(int((py - y0) / dy), ny - 2)
        wx, wy = (px - x0) / dx - i, (py - y0) / dy - j
        if len(tl) == 1:
            k, wt = 0, 0.0
        else:
            k = min(max(bisect_right(tl, t) - 1, 0), len(tl) - 2)
            wt = (t - tl[k]) / (tl[k + 1] - tl[k])
        out = []
        for f in (ul, wl):
            vals = []
            for kk in ((k,) if wt == 0.0 else (k, k + 1)):
                a, b = f[kk][i], f[kk][i + 1]
                vals.append((1 - wx) * ((1 - wy) * a[j] + wy * a[j + 1])
                            + wx * ((1 - wy) * b[j] + wy * b[j + 1]))
            out.append(vals[0] if wt == 0.0 else (1 - wt) * vals[0] + wt * vals[1])
        return np.array([out[0]]), np.array([out[1]])

    return velocity
