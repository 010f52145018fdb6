"""Backtracking: the time-optimal route from the arrival-time map T(x).

On the optimal route the vehicle heads along the front's outward normal, n = grad T / |grad T|
(Lolla et al. 2012, eq. 6), so the route solves, backwards from the goal at T(goal),

    dx/dt = V n(x) + c(x, t),   t from T(goal) down to the departure time,

integrated with Heun's method (RK2) at steps of half a cell. grad T uses central differences,
one-sided next to land or unreached nodes. The last piece joins the start disk to the start.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.grid import CurrentSampler, RouteGrid, interp_grid

__all__ = ["GridRoute", "arrival_gradient", "backtrack"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class GridRoute:
    """The backtracked route: times (s since epoch), local positions (m), headings (rad)."""

    t: FloatArray
    x: FloatArray
    y: FloatArray
    heading: FloatArray
    complete: bool


def arrival_gradient(arrival: FloatArray, h: float) -> tuple[FloatArray, FloatArray]:
    """grad T with central differences, one-sided where a neighbour is unreached (inf)."""
    ok = np.isfinite(arrival)
    a = np.where(ok, arrival, 0.0)
    out = []
    for axis in (1, 0):
        p = np.pad(a, 1, mode="edge")
        okp = np.pad(ok, 1, mode="constant", constant_values=False)
        if axis == 1:
            prev, nxt = p[1:-1, :-2], p[1:-1, 2:]
            okm, okn = okp[1:-1, :-2], okp[1:-1, 2:]
        else:
            prev, nxt = p[:-2, 1:-1], p[2:, 1:-1]
            okm, okn = okp[:-2, 1:-1], okp[2:, 1:-1]
        central = (nxt - prev) / (2 * h)
        fwd = (nxt - a) / h
        bwd = (a - prev) / h
        g = np.where(okm & okn, central, np.where(okn, fwd, np.where(okm, bwd, 0.0)))
        out.append(np.where(ok, g, 0.0))
    return out[0], out[1]


def backtrack(
    grid: RouteGrid,
    sampler: CurrentSampler,
    arrival: FloatArray,
    speed: float,
    t0: float,
    goal_xy: tuple[float, float],
    goal_time: float,
    start_radius: float,
) -> GridRoute:
    """Integrate the optimal-heading ODE backwards from the goal (module docstring)."""
    h = grid.spacing
    gx_, gy_ = arrival_gradient(arrival, h)
    grads = np.stack([gx_, gy_])
    cmax = 0.0
    for k in range(sampler.levels.size):
        if k in sampler._cache:
            cx, cy = sampler._cache[k]
            cmax = max(cmax, float(np.nanmax(np.hypot(cx, cy))))
    ds = 0.5 * h / (speed + cmax)

    def velocity(px: float, py: float, t: float) -> tuple[float, float, float]:
        g = interp_grid(grads, grid, np.array([px]), np.array([py]))[:, 0]
        norm = math.hypot(g[0], g[1])
        c = sampler.points(t, np.array([px]), np.array([py]))[:, 0]
        if not np.all(np.isfinite(c)):
            c = np.zeros(2)
        if norm == 0.0 or not np.isfinite(norm):
            hd = math.atan2(-py, -px) + math.pi  # fall back: radially outward from the start
        else:
            hd = math.atan2(g[1], g[0])
        return speed * math.cos(hd) + c[0], speed * math.sin(hd) + c[1], hd

    ts, xs, ys, hs = [goal_time], [goal_xy[0]], [goal_xy[1]], []
    px, py, t = goal_xy[0], goal_xy[1], goal_time
    complete = False
    max_steps = int(10 * (goal_time - t0) / ds) + 100
    for _ in range(max_steps):
        vx, vy, hd = velocity(px, py, t)
        hs.append(hd)
        step = min(ds, t - t0)
        if math.hypot(px, py) <= start_radius or step <= 0.0:
            complete = True
            break
        qx, qy = px - step * vx, py - step * vy
        wx, wy, _ = velocity(qx, qy, t - step)
        px, py, t = px - 0.5 * step * (vx + wx), py - 0.5 * step * (vy + wy), t - step
        ts.append(t)
        xs.append(px)
        ys.append(py)
    # Close the route at the start: a straight crab from the start to the first point.
    while len(hs) < len(ts):
        hs.append(hs[-1] if hs else 0.0)
    t_arr = np.array(ts[::-1])
    x_arr = np.array(xs[::-1])
    y_arr = np.array(ys[::-1])
    h_arr = np.array(hs[: len(ts)][::-1])
    if complete and math.hypot(x_arr[0], y_arr[0]) > 1e-9 and t_arr[0] > t0:
        c = sampler.points(t0, np.array([0.0]), np.array([0.0]))[:, 0]
        c = np.nan_to_num(c)
        dur = t_arr[0] - t0
        wv = np.array([x_arr[0], y_arr[0]]) / dur - c  # water-relative velocity needed
        h0 = math.atan2(wv[1], wv[0])
        t_arr = np.concatenate([[t0], t_arr])
        x_arr = np.concatenate([[0.0], x_arr])
        y_arr = np.concatenate([[0.0], y_arr])
        h_arr = np.concatenate([[h0], h_arr])
    return GridRoute(t_arr, x_arr, y_arr, np.unwrap(h_arr), complete)
