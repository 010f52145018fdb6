"""Zermelo's navigation problem on the sphere, solved by shooting (the refinement phase).

State (phi, lam) (latitude, longitude in radians), compass heading chi of the through-water
velocity, current (u east, v north):

    phi' = (V cos chi + v) / R,    lam' = (V sin chi + u) / (R cos phi).

Minimum time (Pontryagin; costate p, H = 1 + p . f): with q = -p the optimal heading is
chi = atan2(q_lam / cos phi, q_phi), and q obeys the costate equations (q is homogeneous, so
its magnitude is free and only the initial heading chi0 is unknown):

    q_phi' = -[q_phi v_phi / R + q_lam u_phi / (R cos phi)
               + q_lam (V sin chi + u) sin phi / (R cos^2 phi)],
    q_lam' = -[q_phi v_lam / R + q_lam u_lam / (R cos phi)]

(subscripts: partial derivatives per radian). In still water q_lam is constant and |q| = R / V,
so cos phi sin chi is constant: Clairaut's relation, the great circle. Shooting: Newton on
(chi0, T) for position(T) = goal, two trajectories integrated together (RK4, fixed steps) for
the derivative in chi0; d position / dT is the velocity at T. The current and its gradient
come from the routing window (bilinear in space, linear in time).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.sphere import EARTH_RADIUS_M
from glideplan.routing.window import WindowCurrents

__all__ = ["Shot", "zermelo_shooting"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Shot:
    """A converged (or not) shooting: times (s since epoch), lat/lon (deg), compass headings
    (rad) at the RK4 nodes; the arrival time T (s after departure)."""

    converged: bool
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    chi: FloatArray
    duration: float
    iterations: int
    message: str


def _rhs(cur: WindowCurrents, speed: float, t: float, z: FloatArray) -> FloatArray:
    """z = (phi, lam, q_phi, q_lam) rows, columns trajectories."""
    R = EARTH_RADIUS_M
    phi, lam, qp, ql = z
    vals = cur.points(t, np.degrees(phi), np.degrees(lam), gradient=True)
    u, u_phi, u_lam, v, v_phi, v_lam = vals
    c = np.cos(phi)
    chi = np.arctan2(ql / c, qp)
    sc, cc = np.sin(chi), np.cos(chi)
    dphi = (speed * cc + v) / R
    dlam = (speed * sc + u) / (R * c)
    dqp = -(qp * v_phi / R + ql * u_phi / (R * c) + ql * (speed * sc + u) * np.sin(phi)
            / (R * c * c))
    dql = -(qp * v_lam / R + ql * u_lam / (R * c))
    return np.stack([dphi, dlam, dqp, dql])


def _fly(cur: WindowCurrents, speed: float, t0: float, duration: float, phi0: float,
         lam0: float, chi0: FloatArray, steps: int) -> FloatArray:
    """RK4 states (steps + 1, 4, m) for each initial heading (shorter if it meets NaN);
    compiled (`_fly_compiled`) when the levels it needs fit in memory, else NumPy."""
    fast = _fly_compiled(cur, speed, t0, duration, phi0, lam0, chi0, steps)
    if fast is not None:
        return fast
    return _fly_numpy(cur, speed, t0, duration, phi0, lam0, chi0, steps)


#: Largest number of float64 values (levels x 2 x nodes) the compiled shooting copies.
_MAX_COMPILED_VALUES = 20_000_000


def _fly_compiled(cur: WindowCurrents, speed: float, t0: float, duration: float, phi0: float,
                  lam0: float, chi0: FloatArray, steps: int) -> FloatArray | None:
    """The same RK4 as `_fly_numpy`, compiled with numba over the levels spanning the flight."""
    win = cur.window
    ny, nx = win.shape
    k0, _ = cur.bracket(t0)
    k1, w1 = cur.bracket(t0 + duration)
    ks = list(range(k0, k1 + (2 if (w1 > 0 and not cur.steady) else 1)))
    if cur.steady:
        ks = [0]
    if len(ks) * 2 * ny * nx > _MAX_COMPILED_VALUES:
        return None
    levels = np.stack([cur._flat(k) for k in ks])  # (L, 2, N)
    times = np.array([cur.level_time(k) for k in ks], dtype=float)
    L = win.lattice
    from glideplan.routing._zermelo_kernel import fly

    centre = L.lon0 + 0.5 * (win.j0 + win.j1 - 1) * L.dlon
    out = fly(levels, times, bool(cur.steady), float(L.lat0 + win.i0 * L.dlat),
              float(L.lon0 + win.j0 * L.dlon), math.radians(L.dlat), math.radians(L.dlon),
              ny, nx, bool(win.periodic), float(centre), float(speed), float(t0),
              float(duration), float(phi0), float(lam0), np.ascontiguousarray(chi0, dtype=float),
              int(steps), EARTH_RADIUS_M)
    n = int(out[1])
    return np.asarray(out[0][:n])


def _fly_numpy(cur: WindowCurrents, speed: float, t0: float, duration: float, phi0: float,
               lam0: float, chi0: FloatArray, steps: int) -> FloatArray:
    """RK4 states (steps + 1, 4, m) for each initial heading (shorter if it meets NaN)."""
    z = np.stack([np.full(chi0.size, phi0), np.full(chi0.size, lam0), np.cos(chi0),
                  np.sin(chi0) * math.cos(phi0)])
    dt = duration / steps
    out = [z]
    for k in range(steps):
        t = t0 + k * dt
        k1 = _rhs(cur, speed, t, z)
        k2 = _rhs(cur, speed, t + dt / 2, z + dt / 2 * k1)
        k3 = _rhs(cur, speed, t + dt / 2, z + dt / 2 * k2)
        k4 = _rhs(cur, speed, t + dt, z + dt * k3)
        z = z + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        if not np.all(np.isfinite(z[:, 0])):
            break
        # keep |q| near 1 (homogeneous): no overflow over long routes
        z[2:] /= np.hypot(z[2], z[3] / np.cos(z[0]))
        out.append(z)
    return np.stack(out)


def zermelo_shooting(
    cur: WindowCurrents,
    speed: float,
    t0: float,
    start: tuple[float, float],
    goal: tuple[float, float],
    chi0: float,
    duration: float,
    steps: int = 100,
    tol_m: float = 1.0,
    max_iter: int = 15,
) -> Shot:
    """Newton shooting on (chi0, T) for position(T) = goal (module docstring); start, goal
    (lat, lon deg; goal lon continuous with the start's), chi0 compass (rad), duration (s).

    The derivative in chi0 is a difference over 1e-5 rad (the grid's bilinear current has
    kinks at cell edges a smaller step would resolve as noise); a Newton step that does not
    reduce the miss is halved (up to 4 times); the shooting stops when 4 iterations in a row
    do not improve the best miss."""
    sh = _Shooter(cur, speed, t0, steps, math.radians(start[0]), math.radians(start[1]),
                  math.radians(goal[0]), math.radians(goal[1]))
    empty = np.zeros(1)
    ch, T = float(chi0), float(duration)
    got = sh.shoot(ch, T)
    if got is None:
        return Shot(False, empty, empty, empty, empty, T, 1,
                    "trajectory reached land or left the routing window")
    zz, r, err = got
    best, stale, msg = err, 0, "not converged"
    for it in range(1, max_iter + 1):
        if err <= tol_m:
            return sh.converged(zz, T, it)
        step = sh.newton_step(zz, r, T)
        if step is None:
            msg = "singular Jacobian"
            break
        found = sh.line_search(ch, T, step, err)
        if found is None:
            msg = "no Newton step reduces the miss"
            break
        ch, T, (zz, r, err) = found
        if err < 0.999 * best:
            best, stale = err, 0
        else:
            stale += 1
            if stale >= 4:
                msg = "the miss stopped decreasing"
                break
    if err <= tol_m:
        return sh.converged(zz, T, max_iter)
    return Shot(False, empty, empty, empty, empty, T, max_iter,
                f"{msg} (miss {err:.3g} m > {tol_m:.3g} m)")


#: The difference (rad) in chi0 for the derivative (module docstring of `zermelo_shooting`).
_DELTA = 1e-5


@dataclass(frozen=True)
class _Shooter:
    """One shooting problem: the flow on the window, speed (m/s), departure (s), RK4 steps,
    start and goal (rad)."""

    cur: WindowCurrents
    speed: float
    t0: float
    steps: int
    phi0: float
    lam0: float
    gphi: float
    glam: float

    def shoot(self, ch: float, T: float) -> tuple[FloatArray, FloatArray, float] | None:
        """The trajectories from chi0 = ch and ch + delta over T; the miss (north, east m)
        and its length; None when it meets land or leaves the window."""
        R = EARTH_RADIUS_M
        zz = _fly(self.cur, self.speed, self.t0, T, self.phi0, self.lam0,
                  np.array([ch, ch + _DELTA]), self.steps)
        if zz.shape[0] < self.steps + 1:
            return None
        end = zz[-1]
        r = np.array([(end[0, 0] - self.gphi) * R,
                      (end[1, 0] - self.glam) * R * math.cos(self.gphi)])
        return zz, r, math.hypot(r[0], r[1])

    def newton_step(self, zz: FloatArray, r: FloatArray, T: float) -> FloatArray | None:
        """The Newton step in (chi0, T) from the end's derivatives; None if singular."""
        R = EARTH_RADIUS_M
        end = zz[-1]
        d_end = np.array([(end[0, 1] - end[0, 0]) * R,
                          (end[1, 1] - end[1, 0]) * R * math.cos(self.gphi)]) / _DELTA
        vel = _rhs(self.cur, self.speed, self.t0 + T, end[:, :1])[:2, 0]
        vel = np.array([vel[0] * R, vel[1] * R * math.cos(self.gphi)])
        try:
            return np.asarray(np.linalg.solve(np.column_stack([d_end, vel]), -r))
        except np.linalg.LinAlgError:
            return None

    def line_search(self, ch: float, T: float, step: FloatArray, err: float) -> tuple[
            float, float, tuple[FloatArray, FloatArray, float]] | None:
        """The step (capped at 0.3 rad and 0.2 T), halved up to 4 times until it reduces the
        miss: (chi0, T, shot); None if none does."""
        scale = min(1.0, 0.3 / max(abs(step[0]), 1e-12), 0.2 * T / max(abs(step[1]), 1e-12))
        for _ in range(5):
            ch_n, T_n = ch + scale * step[0], T + scale * step[1]
            trial = self.shoot(ch_n, T_n) if T_n > 0 else None
            if trial is not None and trial[2] < err:
                return ch_n, T_n, trial
            scale *= 0.5
        return None

    def converged(self, zz: FloatArray, T: float, iterations: int) -> Shot:
        """The converged shot: times, lat/lon (deg) and compass headings (rad)."""
        tt = self.t0 + np.linspace(0.0, T, self.steps + 1)
        phi, lam, qp, ql = zz[:, 0, 0], zz[:, 1, 0], zz[:, 2, 0], zz[:, 3, 0]
        chi = np.arctan2(ql / np.cos(phi), qp)
        return Shot(True, tt, np.degrees(phi), np.degrees(lam), chi, T, iterations,
                    "converged")
