"""Front propagation: the reachable set's boundary as the zero level set of phi (Lolla et al.).

The set reachable at time t from the start, at speed V through the water with heading free,
in a current c(x, t), is {phi(., t) <= 0} where (Lolla, Ueckermann, Yigit, Haley & Lermusiaux
2012, eq. 3; a Hamilton-Jacobi equation)

    d phi/dt + V |grad phi| + c . grad phi = 0.

Discretisation: first-order Godunov upwinding for the convex normal-speed term (Osher-Sethian:
|grad phi|^2 ~ max(D-x, 0)^2 + min(D+x, 0)^2 + (same in y)), upwind differences for the
advection, forward Euler with dt = cfl h / (V + |cx|max + |cy|max). Land nodes hold phi = +B
(beyond the band), which the Godunov term ignores; the advection never differences across
land. phi is clipped to +-B with B = 6 h, a narrow band in value: the front only reads phi
near zero. Every step updates only the bounding box of the active band (nodes with
|phi| < B, grown by 2), so the cost follows the front, not the whole grid.

Output: the arrival-time map T(x) (first time phi(x) <= 0, linear in time between steps),
the front's arrival at the goal, and how far the reached set came to the goal.

Why this method: it is exact in its continuum limit for time-dependent, anisotropic (current-
shifted) speeds, handles land as a mask, propagates all routes at once (one run answers any
goal), and needs only array operations; an ordered-upwind (fast-marching) method for the
anisotropic, time-dependent case needs a per-node search in an interpreted loop.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.grid import CurrentSampler, RouteGrid

__all__ = ["FrontResult", "propagate_front"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class FrontResult:
    """Arrival-time map T (s since epoch, inf where never reached) and the goal's arrival."""

    arrival: FloatArray
    goal_time: float | None
    steps: int
    reached_fraction: float
    closest_distance_m: float


def _bilinear(a: FloatArray, grid: RouteGrid, x: float, y: float) -> float:
    h = grid.spacing
    fx = (x - grid.x[0]) / h
    fy = (y - grid.y[0]) / h
    j = int(np.clip(math.floor(fx), 0, grid.x.size - 2))
    i = int(np.clip(math.floor(fy), 0, grid.y.size - 2))
    wx, wy = fx - j, fy - i
    return float((1 - wy) * ((1 - wx) * a[i, j] + wx * a[i, j + 1])
                 + wy * ((1 - wx) * a[i + 1, j] + wx * a[i + 1, j + 1]))


def _minmod(a: FloatArray, b: FloatArray) -> FloatArray:
    # sign-agreeing smaller magnitude, else 0: (sign a + sign b) / 2 * min(|a|, |b|)
    return 0.5 * (np.sign(a) + np.sign(b)) * np.minimum(np.abs(a), np.abs(b))


def _rate(p: FloatArray, lb: NDArray[np.bool_], ux: FloatArray, uy: FloatArray, speed: float,
          h: float) -> FloatArray:
    """d phi/dt = -(V |grad phi| + c . grad phi): ENO2 one-sided differences, Godunov, upwind.

    D-x = D- phi_i + (h/2) minmod(D+D- phi_(i-1), D+D- phi_i) and its mirror (Osher & Fedkiw
    2003, §3.3); second differences that touch land are dropped (first order there).
    """
    pe = np.pad(p, 2, mode="edge")
    any_land = bool(lb.any())
    le = np.pad(lb, 2, mode="edge") if any_land else None
    out = []
    h2 = h * h
    for axis in (1, 0):
        def sh(a: NDArray[Any], k: int, axis: int = axis) -> NDArray[Any]:
            if axis == 1:
                return a[2:-2, 2 + k:a.shape[1] - 2 + k]
            return a[2 + k:a.shape[0] - 2 + k, 2:-2]

        c, m1, p1, m2, p2 = sh(pe, 0), sh(pe, -1), sh(pe, 1), sh(pe, -2), sh(pe, 2)
        d2c = (p1 - 2 * c + m1) / h2
        d2m = (c - 2 * m1 + m2) / h2
        d2p = (p2 - 2 * p1 + c) / h2
        if le is not None:
            lc, lm1, lp1, lm2, lp2 = sh(le, 0), sh(le, -1), sh(le, 1), sh(le, -2), sh(le, 2)
            d2c = np.where(lm1 | lc | lp1, 0.0, d2c)
            d2m = np.where(lm2 | lm1 | lc, 0.0, d2m)
            d2p = np.where(lc | lp1 | lp2, 0.0, d2p)
        else:
            lm1 = lp1 = None  # type: ignore[assignment]
        dm = (c - m1) / h + 0.5 * h * _minmod(d2m, d2c)
        dp = (p1 - c) / h - 0.5 * h * _minmod(d2c, d2p)
        out.append((dm, dp, lm1, lp1))
    (dxm, dxp, lw, le_), (dym, dyp, ls, ln) = out
    grad = np.sqrt(np.maximum(dxm, 0.0) ** 2 + np.minimum(dxp, 0.0) ** 2
                   + np.maximum(dym, 0.0) ** 2 + np.minimum(dyp, 0.0) ** 2)
    if lw is not None and le_ is not None and ls is not None and ln is not None:
        # Advection: upwind, never across land (fall back to the other side, else 0).
        dxm, dxp = (np.where(lw, np.where(le_, 0.0, dxp), dxm),
                    np.where(le_, np.where(lw, 0.0, dxm), dxp))
        dym, dyp = (np.where(ls, np.where(ln, 0.0, dyp), dym),
                    np.where(ln, np.where(ls, 0.0, dym), dyp))
    adv = (np.maximum(ux, 0.0) * dxm + np.minimum(ux, 0.0) * dxp
           + np.maximum(uy, 0.0) * dym + np.minimum(uy, 0.0) * dyp)
    return speed * grad + adv


def start_disk_radius(grid: RouteGrid, land: NDArray[np.bool_],
                      goal_xy: tuple[float, float]) -> float:
    """Radius of the exact start disk: 10 cells, at most 0.3 x the distance, clear of land.

    A disk of only a cell or two is under-resolved and delays the front by a fixed fraction
    of its speed (measured: ~2% at 1.5 cells, < 0.1% at 10 cells).
    """
    h = grid.spacing
    r = min(10.0 * h, 0.3 * math.hypot(*goal_xy))
    if np.any(land):
        xx, yy = np.meshgrid(grid.x, grid.y)
        r = min(r, float(np.min(np.hypot(xx[land], yy[land]))) - 2.0 * h)
    return max(r, 1.5 * h)


def _disk_time(x: FloatArray, y: FloatArray, c: FloatArray, speed: float) -> FloatArray:
    """First time tau with |p - c tau| = V tau (uniform current c, |c| < V), else |p|/V."""
    a = speed * speed - float(c @ c)
    pc = x * c[0] + y * c[1]
    pp = x * x + y * y
    if a <= 1e-12 * speed * speed:
        return np.sqrt(pp) / speed
    return (-pc + np.sqrt(pc * pc + a * pp)) / a


def propagate_front(
    grid: RouteGrid,
    sampler: CurrentSampler,
    speed: float,
    t0: float,
    t_max: float,
    goal_xy: tuple[float, float],
    cfl: float = 0.5,
    start_radius: float | None = None,
) -> FrontResult:
    """Propagate the reachable front from the start (x, y = 0) at t0 until it passes the goal."""
    h = grid.spacing
    ny, nx = grid.shape
    xx, yy = np.meshgrid(grid.x, grid.y)
    band = 6.0 * h
    cx0, _cy0 = sampler.at(t0)
    land0 = ~np.isfinite(cx0)
    gx, gy = goal_xy
    if start_radius is None:
        start_radius = start_disk_radius(grid, land0, goal_xy)
    r0 = start_radius
    tau0 = r0 / speed
    # The start disk: at tau0 the reachable set is the disk of radius V tau0 about the drift
    # c tau0 (the current at the start, averaged over [t0, t0 + tau0], taken as uniform).
    c_a = sampler.points(t0, np.zeros(1), np.zeros(1))[:, 0]
    c_b = sampler.points(t0 + tau0, np.zeros(1), np.zeros(1))[:, 0]
    c = 0.5 * (np.nan_to_num(c_a) + np.nan_to_num(c_b))
    dist0 = np.hypot(xx - c[0] * tau0, yy - c[1] * tau0)
    phi = np.clip(dist0 - r0, -band, band)
    phi[land0] = band
    arrival = np.full((ny, nx), np.inf)
    inside0 = (phi <= 0) & ~land0
    arrival[inside0] = t0 + _disk_time(xx[inside0], yy[inside0], c, speed)
    t = t0 + tau0
    goal_time: float | None = None
    steps = 0
    gj = int(np.clip(round((gx - grid.x[0]) / h), 1, nx - 2))
    gi = int(np.clip(round((gy - grid.y[0]) / h), 1, ny - 2))
    extra_after = -1  # steps to run after the goal is reached (fills T around it)
    stall, last_reached, steady = 0, int(inside0.sum()), sampler.levels.size == 1
    stall_limit = math.ceil(20.0 / cfl)
    phi_goal_old = _bilinear(phi, grid, gx, gy)
    while t < t_max:
        # Active box: the band plus a margin of 3 nodes.
        rows = np.nonzero(np.any(np.abs(phi) < band, axis=1))[0]
        cols = np.nonzero(np.any(np.abs(phi) < band, axis=0))[0]
        if rows.size == 0:
            break
        i0, i1 = max(rows[0] - 3, 0), min(rows[-1] + 4, ny)
        j0, j1 = max(cols[0] - 3, 0), min(cols[-1] + 4, nx)
        p = phi[i0:i1, j0:j1]
        cx, cy = sampler.box_at(t, i0, i1, j0, j1)
        lb = ~np.isfinite(cx)
        ux = np.where(lb, 0.0, cx)
        uy = np.where(lb, 0.0, cy)
        cmax = float(np.max(np.abs(ux)) + np.max(np.abs(uy))) if ux.size else 0.0
        dt = cfl * h / (speed + cmax)
        rate = _rate(p, lb, ux, uy, speed, h)
        mid = np.clip(p - dt * rate, -band, band)
        mid[lb] = band
        rate2 = _rate(mid, lb, ux, uy, speed, h)
        # TVD Runge-Kutta 2 (Heun): phi_new = (phi + (mid - dt L(mid))) / 2
        new = np.clip(0.5 * (p + mid - dt * rate2), -band, band)
        new[lb] = band
        a = arrival[i0:i1, j0:j1]
        crossed = (p > 0.0) & (new <= 0.0) & np.isinf(a)
        if np.any(crossed):
            frac = p[crossed] / (p[crossed] - new[crossed])
            a[crossed] = t + dt * frac
        phi[i0:i1, j0:j1] = new
        t += dt
        steps += 1
        if goal_time is None:
            phi_goal = _bilinear(phi, grid, gx, gy)
            if phi_goal <= 0.0:
                goal_time = t - dt + dt * phi_goal_old / (phi_goal_old - phi_goal) \
                    if phi_goal_old > 0 else t
                extra_after = math.ceil(4.0 / cfl)
            phi_goal_old = phi_goal
        else:
            extra_after -= 1
            around = arrival[gi - 1:gi + 2, gj - 1:gj + 2]
            near_land = land0[gi - 1:gi + 2, gj - 1:gj + 2]
            if extra_after <= 0 and np.all(np.isfinite(around) | near_land):
                break
            if extra_after < -math.ceil(40.0 / cfl):
                break
        if steady and goal_time is None:
            reached = int(np.count_nonzero(np.isfinite(arrival)))
            stall = stall + 1 if reached == last_reached else 0
            last_reached = reached
            if stall > stall_limit:
                break
    reached_mask = np.isfinite(arrival)
    if np.any(reached_mask):
        closest = float(np.min(np.hypot(xx[reached_mask] - gx, yy[reached_mask] - gy)))
    else:
        closest = math.hypot(gx, gy)
    closest = min(closest, math.hypot(gx, gy))  # at the start, t0, it is this far
    if goal_time is not None:
        closest = 0.0
    return FrontResult(arrival, goal_time, steps, float(reached_mask.mean()), closest)
