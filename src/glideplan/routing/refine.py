"""Local refinement of the grid route: Zermelo's navigation equation, solved by shooting.

Between obstacles a time-optimal heading theta(t) obeys Zermelo's navigation equation
(Bryson & Ho 1975, §2.7; the necessary condition of the minimum-time problem):

    theta' = sin^2(theta) dcy/dx + sin(theta) cos(theta) (dcx/dx - dcy/dy) - cos^2(theta) dcx/dy,
    x' = V cos(theta) + cx,   y' = V sin(theta) + cy.

Unknowns: the initial heading theta0 and the arrival time T; equations: x(T) = goal. Newton's
method (two trajectories integrated together with RK4 for d x(T)/d theta0; d x(T)/dT is the
velocity at T), started from the grid route's heading and arrival time. The current and its
gradient come from the routing grid (bilinear between nodes, linear in time). The caller
keeps the refined route only if it converged, stays off land and is not slower than the grid
route; it is then verified through the field itself.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.grid import CurrentSampler

__all__ = ["ShootingResult", "direct_refinement", "polyline_refinement", "zermelo_shooting"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class ShootingResult:
    """Converged (or not) shooting: heading nodes, times (s since epoch), positions (m)."""

    converged: bool
    t: FloatArray
    x: FloatArray
    y: FloatArray
    heading: FloatArray
    duration: float
    iterations: int
    message: str


def _rhs(sampler: CurrentSampler, speed: float, t: float, z: FloatArray) -> FloatArray:
    x, y, th = z
    vals = sampler.points(t, x, y, gradient=True)
    cx, cy, dcx_dx, dcx_dy, dcy_dx, dcy_dy = vals
    s, c = np.sin(th), np.cos(th)
    dth = s * s * dcy_dx + s * c * (dcx_dx - dcy_dy) - c * c * dcx_dy
    return np.stack([speed * c + cx, speed * s + cy, dth])


def _fly(sampler: CurrentSampler, speed: float, t0: float, duration: float,
         theta0: FloatArray, steps: int) -> tuple[FloatArray, FloatArray]:
    """RK4 of (x, y, theta) for each theta0 from (0, 0); returns times and states (n+1, 3, m)."""
    z = np.stack([np.zeros_like(theta0), np.zeros_like(theta0), theta0])
    dt = duration / steps
    out = [z]
    for k in range(steps):
        t = t0 + k * dt
        k1 = _rhs(sampler, speed, t, z)
        k2 = _rhs(sampler, speed, t + dt / 2, z + dt / 2 * k1)
        k3 = _rhs(sampler, speed, t + dt / 2, z + dt / 2 * k2)
        k4 = _rhs(sampler, speed, t + dt, z + dt * k3)
        z = z + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(z[:, 0])):
            break
        out.append(z)
    return np.asarray(t0 + dt * np.arange(len(out)), dtype=float), np.stack(out)


def zermelo_shooting(
    sampler: CurrentSampler,
    speed: float,
    t0: float,
    goal_xy: tuple[float, float],
    theta0: float,
    duration: float,
    steps: int = 240,
    tol_m: float = 1.0,
    max_iter: int = 25,
) -> ShootingResult:
    """Newton shooting on (theta0, T) for x(T) = goal (module docstring)."""
    goal = np.asarray(goal_xy, dtype=float)
    th, T = float(theta0), float(duration)
    delta = 1e-6
    msg = "not converged"
    empty = np.zeros(1)
    for it in range(1, max_iter + 1):
        tt, zz = _fly(sampler, speed, t0, T, np.array([th, th + delta]), steps)
        if zz.shape[0] < steps + 1:
            return ShootingResult(False, empty, empty, empty, empty, T, it,
                                  "trajectory reached land or left the grid")
        end = zz[-1]
        r = end[:2, 0] - goal
        err = math.hypot(r[0], r[1])
        if err <= tol_m:
            return ShootingResult(True, tt, zz[:, 0, 0], zz[:, 1, 0], zz[:, 2, 0], T, it,
                                  "converged")
        vel = _rhs(sampler, speed, t0 + T, end[:, :1])[:2, 0]
        jac = np.column_stack([(end[:2, 1] - end[:2, 0]) / delta, vel])
        try:
            step = np.linalg.solve(jac, -r)
        except np.linalg.LinAlgError:
            msg = "singular Jacobian"
            break
        scale = min(1.0, 0.3 / max(abs(step[0]), 1e-12), 0.2 * T / max(abs(step[1]), 1e-12))
        th += scale * step[0]
        T += scale * step[1]
        if T <= 0 or not math.isfinite(T):
            msg = "arrival time became non-positive"
            break
    return ShootingResult(False, empty, empty, empty, empty, T, max_iter, msg)


def _fly_controls(sampler: CurrentSampler, speed: float, t0: float, nodes: FloatArray,
                  durations: FloatArray, steps: int, land_as_zero: bool = False) -> tuple[
                      FloatArray, bool, FloatArray]:
    """RK4 of (x, y) for m control sets at once: heading linear between equally spaced nodes.

    nodes: (m, n) headings; durations: (m,) arrival times (s). Returns the end points (m, 2),
    whether all stayed on the grid (and off land unless `land_as_zero`: land's NaN current
    read as 0, the caller constrains the clearance instead) and the tracks (steps + 1, 2, m).
    """
    m, n = nodes.shape
    z = np.zeros((2, m))
    dt = durations / steps
    track = [z.copy()]

    def heading(f: float) -> FloatArray:
        k = min(int(f * (n - 1)), n - 2)
        w = f * (n - 1) - k
        return (1 - w) * nodes[:, k] + w * nodes[:, k + 1]

    def vel(f: float, zz: FloatArray) -> FloatArray:
        th = heading(f)
        c = _points_multi_time(sampler, t0 + f * durations, zz[0], zz[1])
        if land_as_zero:
            c = np.where(np.isnan(c) & np.isfinite(zz), 0.0, c)
        return np.stack([speed * np.cos(th) + c[0], speed * np.sin(th) + c[1]])

    for k in range(steps):
        f0, f1 = k / steps, (k + 1) / steps
        fm = 0.5 * (f0 + f1)
        k1 = vel(f0, z)
        k2 = vel(fm, z + dt / 2 * k1)
        k3 = vel(fm, z + dt / 2 * k2)
        k4 = vel(f1, z + dt * k3)
        z = z + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(z)):
            return z.T, False, np.array(track)
        track.append(z.copy())
    return z.T, True, np.array(track)


def _points_multi_time(sampler: CurrentSampler, t: FloatArray, x: FloatArray,
                       y: FloatArray) -> FloatArray:
    """Current (2, m) at points with their own times."""
    if sampler.levels.size == 1 or np.ptp(t) == 0.0:
        return sampler.points(float(t[0]), x, y)
    return sampler.points_multi(t, x, y)


def direct_refinement(
    sampler: CurrentSampler,
    speed: float,
    t0: float,
    goal_xy: tuple[float, float],
    grid_t: FloatArray,
    grid_heading: FloatArray,
    duration: float,
    nodes: int = 10,
    steps: int = 64,
    tol_m: float = 1.0,
    clearance: FloatArray | None = None,
    margin: float = 0.0,
) -> ShootingResult:
    """Minimise T over headings at `nodes` equally spaced times (linear between) s.t. x(T)=goal.

    Single shooting with SciPy SLSQP; derivatives by forward differences, all perturbed
    control sets flown together. Started from the grid route's headings and arrival time;
    the unknowns are the headings and T / T_grid. With `clearance` (distance to the nearest
    land node on the grid, m) every other track point keeps clearance >= `margin`.
    """
    from scipy.optimize import minimize

    from glideplan.routing.grid import interp_grid

    goal = np.asarray(goal_xy, dtype=float)
    frac = (grid_t - grid_t[0]) / (grid_t[-1] - grid_t[0])
    th0 = np.interp(np.linspace(0, 1, nodes), frac, np.unwrap(grid_heading))
    z0 = np.concatenate([th0, [1.0]])
    eps = 1e-6
    land = clearance is not None
    cache: dict[bytes, tuple[FloatArray, ...]] = {}
    h = sampler.grid.spacing

    def evaluate(z: FloatArray) -> tuple[FloatArray, ...]:
        key = z.tobytes()
        if key not in cache:
            m = z.size
            sets = np.repeat(z[None, :], m + 1, axis=0)
            sets[1:] += eps * np.eye(m)
            ends, ok, tracks = _fly_controls(sampler, speed, t0, sets[:, :-1],
                                             sets[:, -1] * duration, steps, land_as_zero=land)
            ends = np.where(np.isfinite(ends), ends, 1e9)
            res = ends[0] - goal
            jac = ((ends[1:] - ends[0]) / eps).T
            scale = speed * duration
            out: tuple[FloatArray, ...] = (res / scale, jac / scale)
            if clearance is not None and ok:
                pts = tracks[1:-1:2]  # (k, 2, m+1)
                cl = interp_grid(clearance[None], sampler.grid, pts[:, 0].ravel(),
                                 pts[:, 1].ravel())[0].reshape(pts.shape[0], -1)
                cl = np.where(np.isfinite(cl), cl, -h) - margin
                out += (cl[:, 0] / h, ((cl[:, 1:] - cl[:, :1]) / eps) / h)
            elif land:
                k = tracks[1:-1:2].shape[0] if tracks.shape[0] > 2 else 1
                k = max(k, (steps - 1 + 1) // 2)
                out += (np.full(k, -1.0), np.zeros((k, m)))
            cache.clear()
            cache[key] = out
        return cache[key]

    constraints: list[dict[str, Any]] = [
        {"type": "eq", "fun": lambda z: evaluate(z)[0], "jac": lambda z: evaluate(z)[1]}]
    if land:
        constraints.append({"type": "ineq", "fun": lambda z: evaluate(z)[2],
                            "jac": lambda z: evaluate(z)[3]})
    sol = minimize(
        lambda z: z[-1], z0, jac=lambda z: np.eye(z.size)[-1], method="SLSQP",
        constraints=constraints,
        bounds=[(None, None)] * nodes + [(0.2, 3.0)],
        options={"maxiter": 40, "ftol": 1e-10},
    )
    z = sol.x
    T = float(z[-1] * duration)
    tt = t0 + np.linspace(0.0, T, steps + 1)
    heading = np.interp(np.linspace(0, 1, steps + 1), np.linspace(0, 1, nodes), z[:-1])
    ends, ok, tracks = _fly_controls(sampler, speed, t0, z[None, :-1], np.array([T]), steps,
                                     land_as_zero=land)
    track = tracks[:, :, 0]
    if not ok:
        return ShootingResult(False, tt, tt * 0, tt * 0, heading, T, sol.nit,
                              "trajectory reached land or left the grid")
    err = float(np.hypot(*(ends[0] - goal)))
    if err > tol_m:
        return ShootingResult(False, tt, tt * 0, tt * 0, heading, T, sol.nit,
                              f"direct method missed the goal by {err:.1f} m")
    if clearance is not None:
        cl = interp_grid(clearance[None], sampler.grid, track[:, 0], track[:, 1])[0]
        if np.any(~np.isfinite(cl) | (cl < 0.5 * margin)):
            return ShootingResult(False, tt, tt * 0, tt * 0, heading, T, sol.nit,
                                  "direct method's track comes too close to land")
    return ShootingResult(True, tt, track[:, 0], track[:, 1], heading, T, sol.nit, "converged")


def _polyline_time(sampler: CurrentSampler, speed: float, t0: float, px: FloatArray,
                   py: FloatArray, sub: int) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Time to fly polylines (m sets of n+1 vertices: px, py (m, n+1)) holding each piece.

    Each edge is split into `sub` pieces flown with the crab angle that keeps the line: along
    speed s = sqrt(V^2 - c_n^2) + c_t at the piece's midpoint and time (c from the grid; land
    counts as still water, the clearance constraint keeps the path off it). An impossible
    piece (|c_n| >= V or s <= 0) costs as if s = V / 100. Returns total times (m,), piece
    times (m, pieces + 1) and water headings (m, pieces).
    """
    m, n1 = px.shape
    f = (np.arange(sub) + 0.5) / sub
    dx, dy = np.diff(px, axis=1), np.diff(py, axis=1)
    length = np.hypot(dx, dy) / sub
    ux = np.where(length > 0, dx / np.maximum(np.hypot(dx, dy), 1e-12), 1.0)
    uy = np.where(length > 0, dy / np.maximum(np.hypot(dx, dy), 1e-12), 0.0)
    t = np.full(m, t0)
    times = [t.copy()]
    heads = []
    for e in range(n1 - 1):
        for k in range(sub):
            mx = px[:, e] + f[k] * dx[:, e]
            my = py[:, e] + f[k] * dy[:, e]
            # Midpoint time from the previous piece's speed (predictor): t + L / (2 V).
            c = sampler.points_multi(t + 0.5 * length[:, e] / speed, mx, my)
            c = np.where(np.isfinite(c), c, 0.0)
            ct = c[0] * ux[:, e] + c[1] * uy[:, e]
            cn = -c[0] * uy[:, e] + c[1] * ux[:, e]
            root = np.sqrt(np.maximum(speed * speed - cn * cn, 0.0))
            along = np.maximum(root + ct, 0.01 * speed)
            wx, wy = along * ux[:, e] - c[0], along * uy[:, e] - c[1]
            heads.append(np.arctan2(wy, wx))
            t = t + length[:, e] / along
            times.append(t.copy())
    return t - t0, np.stack(times, axis=1), np.stack(heads, axis=1)


def polyline_refinement(
    sampler: CurrentSampler,
    speed: float,
    t0: float,
    goal_xy: tuple[float, float],
    grid_x: FloatArray,
    grid_y: FloatArray,
    clearance: FloatArray,
    margin: float,
    edges: int = 16,
    sub: int = 3,
) -> ShootingResult:
    """Minimise the time along a polyline start -> goal over its interior vertices (SLSQP).

    Space collocation: the route is a polyline of `edges` edges, each flown holding the line
    with a crab angle; the objective is the arrival time; every vertex and piece midpoint
    keeps a clearance >= `margin` from land nodes. Start and goal are fixed by construction,
    so there is no endpoint constraint to satisfy; derivatives by forward differences with
    all perturbed polylines flown together. Started from the grid route resampled by length.
    """
    from scipy.optimize import minimize

    from glideplan.routing.grid import interp_grid

    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(grid_x), np.diff(grid_y)))])
    sq = np.linspace(0.0, s[-1], edges + 1)
    vx, vy = np.interp(sq, s, grid_x), np.interp(sq, s, grid_y)
    vx[0], vy[0], vx[-1], vy[-1] = 0.0, 0.0, goal_xy[0], goal_xy[1]
    z0 = np.concatenate([vx[1:-1], vy[1:-1]])
    n_in = edges - 1
    scale = s[-1] / edges
    eps = 1e-4 * scale
    h = sampler.grid.spacing
    cache: dict[bytes, tuple[FloatArray, ...]] = {}

    def polylines(zs: FloatArray) -> tuple[FloatArray, FloatArray]:
        m = zs.shape[0]
        px = np.concatenate([np.zeros((m, 1)), zs[:, :n_in], np.full((m, 1), goal_xy[0])], 1)
        py = np.concatenate([np.zeros((m, 1)), zs[:, n_in:], np.full((m, 1), goal_xy[1])], 1)
        return px, py

    def evaluate(z: FloatArray) -> tuple[FloatArray, ...]:
        key = z.tobytes()
        if key not in cache:
            zs = np.repeat(z[None, :], z.size + 1, axis=0)
            zs[1:] += eps * np.eye(z.size)
            px, py = polylines(zs)
            total, _, _ = _polyline_time(sampler, speed, t0, px, py, sub)
            # Clearance at vertices and edge midpoints.
            qx = np.concatenate([px[:, 1:-1], 0.5 * (px[:, 1:] + px[:, :-1])], axis=1)
            qy = np.concatenate([py[:, 1:-1], 0.5 * (py[:, 1:] + py[:, :-1])], axis=1)
            cl = interp_grid(clearance[None], sampler.grid, qx.ravel(), qy.ravel())[0]
            cl = (np.where(np.isfinite(cl), cl, -h).reshape(qx.shape) - margin) / h
            tref = total[0]
            cache.clear()
            cache[key] = (np.array([tref]), (total[1:] - tref) / eps, cl[0],
                          ((cl[1:] - cl[:1]) / eps).T)
        return cache[key]

    t_first = float(evaluate(z0 / scale * scale)[0][0])
    sol = minimize(
        lambda z: evaluate(z * scale)[0][0] / t_first, z0 / scale,
        jac=lambda z: evaluate(z * scale)[1] * scale / t_first, method="SLSQP",
        constraints=[{"type": "ineq", "fun": lambda z: evaluate(z * scale)[2],
                      "jac": lambda z: evaluate(z * scale)[3] * scale}],
        options={"maxiter": 60, "ftol": 1e-9},
    )
    z = sol.x * scale
    px, py = polylines(z[None, :])
    total, times, heads = _polyline_time(sampler, speed, t0, px, py, sub)
    cl = evaluate(z)[2]
    if np.any(cl < -0.5 * margin / h):
        return ShootingResult(False, times[0], px[0], py[0], heads[0], float(total[0]), sol.nit,
                              "polyline comes too close to land")
    # Track at piece ends; headings per piece, held (repeat the last at the end).
    f = np.linspace(0.0, 1.0, sub + 1)[1:]
    tx = [0.0] + [float(px[0, e] + fk * (px[0, e + 1] - px[0, e]))
                  for e in range(edges) for fk in f]
    ty = [0.0] + [float(py[0, e] + fk * (py[0, e + 1] - py[0, e]))
                  for e in range(edges) for fk in f]
    hd = np.concatenate([heads[0], heads[0, -1:]])
    return ShootingResult(True, times[0], np.array(tx), np.array(ty), hd, float(total[0]),
                          sol.nit, "converged")
