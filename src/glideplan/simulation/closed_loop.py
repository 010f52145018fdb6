"""Closed-loop path following of the disturbed car (3.2)/(A.4), thousands of vehicles at once.

Dissertation §3.4; REFERENCE_NOTES §1. Each vehicle flies at constant air-relative speed v
with heading psi and turn rate |u| <= u_max, pushed by a disturbance velocity delta(t):

    x' = v cos psi + delta_x,  y' = v sin psi + delta_y,  psi' = u.

Breivik-Fossen lookahead guidance (`glideplan.simulation.guidance`) turns the path and the
measured position and ground velocity into a course command chi_d; a saturated bang-bang
controller tracks it, u = u_max sat((chi_d - chi) / phi_b) with chi the measured course
(pure bang-bang u = u_max sign(chi_d - chi) when phi_b = 0). Each step holds u and delta
constant and moves the vehicle exactly (circular arc plus drift).

The final cross-track error (REFERENCE_NOTES §1.5) is the distance from the path's end to the
point where the vehicle crosses the finish line — the line through the end orthogonal to
the final tangent — going forwards, interpolated between steps. The detector is armed only
once the path point has reached the path's last segment; a vehicle that has not crossed by
the time-out t_max = timeout_factor (L + 2 pi R0) / (v - delta_max) is a failure.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.simulation.disturbances import DisturbanceStream
from glideplan.simulation.guidance import PathArrays, lookahead_guidance
from glideplan.validation import check_in_range, check_nonnegative, check_positive

__all__ = ["FollowResult", "FollowerSettings", "follow_paths"]

TWO_PI = 2.0 * math.pi


@dataclass(frozen=True)
class FollowerSettings:
    """Vehicle, guidance and simulation parameters (SI units).

    speed: v (m/s); max_turn_rate: u_max (rad/s); lookahead: Delta (m), None for R0 = v/u_max;
    gamma: along-track gain (1/s); boundary_layer: phi_b (rad), 0 for pure bang-bang;
    dt: time step (s); timeout_factor: see the module docstring. The defaults are the
    dissertation's vehicle (v = 20 m/s, u_max = 0.3 rad/s) and gains chosen, as in the
    dissertation, heuristically for reasonable tracking across wind strengths and radii.
    """

    speed: float = 20.0
    max_turn_rate: float = 0.3
    lookahead: float | None = None
    gamma: float = 1.0
    boundary_layer: float = 0.2
    dt: float = 0.05
    timeout_factor: float = 2.0
    feedforward: bool = False

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", check_positive("speed", self.speed))
        object.__setattr__(self, "max_turn_rate", check_positive("umax", self.max_turn_rate))
        if self.lookahead is not None:
            object.__setattr__(self, "lookahead", check_positive("lookahead", self.lookahead))
        object.__setattr__(self, "gamma", check_nonnegative("gamma", self.gamma))
        object.__setattr__(
            self, "boundary_layer", check_nonnegative("boundary_layer", self.boundary_layer)
        )
        object.__setattr__(self, "dt", check_positive("dt", self.dt))
        object.__setattr__(
            self, "timeout_factor", check_positive("timeout_factor", self.timeout_factor)
        )

    @property
    def min_radius(self) -> float:
        """R0 = v / u_max (m)."""
        return self.speed / self.max_turn_rate

    @property
    def lookahead_distance(self) -> float:
        """Delta (m)."""
        return self.lookahead if self.lookahead is not None else self.min_radius


@dataclass(frozen=True, eq=False)
class FollowResult:
    """Per vehicle: final cross-track error (m; NaN for failures), whether it crossed the
    finish line, and the crossing (or time-out) time (s). `tracks` (steps, N, 2) when recorded."""

    error: np.ndarray
    crossed: np.ndarray
    time: np.ndarray
    tracks: np.ndarray | None = field(default=None)

    @property
    def failures(self) -> int:
        return int(np.count_nonzero(~self.crossed))


def follow_paths(
    paths: PathArrays,
    disturbance: DisturbanceStream,
    *,
    rows: np.ndarray | None = None,
    settings: FollowerSettings | None = None,
    disturbance_bound: float = 0.0,
    record: bool = False,
) -> FollowResult:
    """Fly every path of `paths` from its start pose under guidance (module docstring).

    disturbance: a stream giving (rows, 2) velocities (m/s) per step; `rows` (N,) maps each
    vehicle to a row (default: vehicle i uses row i), so several vehicles can share one
    realisation. disturbance_bound: delta_max (m/s) for the time-out. record: keep every
    vehicle's positions (for figures; memory grows with N x steps).
    """
    cfg = settings or FollowerSettings()
    n = paths.count
    v, umax, dt = cfg.speed, cfg.max_turn_rate, cfg.dt
    dmax = check_in_range("disturbance_bound", disturbance_bound, 0.0, v, high_open=True)
    row_of = np.arange(n) if rows is None else np.asarray(rows, dtype=np.intp)
    if row_of.shape != (n,) or (n and (row_of.min() < 0 or row_of.max() >= disturbance.rows)):
        raise InvalidParameterError("rows", row_of.shape, "need one valid row per path")
    delta_lookahead = cfg.lookahead_distance
    phi_b = cfg.boundary_layer
    feedforward = cfg.feedforward
    lost_margin = 2.0 * cfg.min_radius

    error = np.full(n, np.nan)
    crossed = np.zeros(n, dtype=bool)
    t_end = np.zeros(n)
    t_max = cfg.timeout_factor * (paths.length + TWO_PI * cfg.min_radius) / (v - dmax)

    ids = np.arange(n)
    p = paths
    x, y, psi = p.x0[:, 0].copy(), p.y0[:, 0].copy(), p.h0[:, 0].copy()
    varpi = np.zeros(n)
    xf, yf = p.end[:, 0].copy(), p.end[:, 1].copy()
    cf, sf = np.cos(p.end[:, 2]), np.sin(p.end[:, 2])
    tmax = t_max.copy()
    rw = row_of.copy()
    a_prev = (x - xf) * cf + (y - yf) * sf
    t = 0.0
    track_list: list[np.ndarray] = []
    if record:
        full = np.stack([x, y], axis=-1)
        track_list.append(full.copy())
    while ids.size:
        d = disturbance.next()[rw]
        dx, dy = d[:, 0], d[:, 1]
        gx = v * np.cos(psi) + dx
        gy = v * np.sin(psi) + dy
        cmd = lookahead_guidance(
            p, varpi, x, y, gx, gy, lookahead=delta_lookahead, gamma=cfg.gamma
        )
        err = cmd.course - np.arctan2(gy, gx)
        err = (err + math.pi) % TWO_PI - math.pi
        if phi_b > 0.0:
            u = umax * np.clip(err / phi_b, -1.0, 1.0)
        else:
            u = umax * np.sign(err)
        if feedforward:
            u = np.clip(u + cmd.path_turn_rate, -umax, umax)
        # exact motion over the step for constant u and delta
        half = 0.5 * u * dt
        chord = v * dt * np.sinc(half / math.pi)
        mid = psi + half
        x_new = x + chord * np.cos(mid) + dx * dt
        y_new = y + chord * np.sin(mid) + dy * dt
        psi = psi + u * dt
        varpi = varpi + cmd.varpi_rate * dt
        t += dt
        a = (x_new - xf) * cf + (y_new - yf) * sf
        hit = (varpi >= p.arm) & (a_prev < 0.0) & (a >= 0.0)
        if hit.any():
            frac = a_prev[hit] / (a_prev[hit] - a[hit])
            xc = x[hit] + frac * (x_new[hit] - x[hit])
            yc = y[hit] + frac * (y_new[hit] - y[hit])
            k = ids[hit]
            error[k] = np.hypot(xc - xf[hit], yc - yf[hit])
            crossed[k] = True
            t_end[k] = t - dt + frac * dt
        x, y, a_prev = x_new, y_new, a
        if record:
            full[ids, 0], full[ids, 1] = x, y
            track_list.append(full.copy())
        # lost: the path point is far past the end, so the vehicle went beyond the finish
        # line without crossing it forwards while armed (it will not come back)
        done = hit | (t >= tmax) | (varpi > p.length + lost_margin)
        if done.any():
            t_end[ids[done & ~hit]] = t
            keep = ~done
            ids, x, y, psi, varpi, a_prev = (arr[keep] for arr in (ids, x, y, psi, varpi, a_prev))
            xf, yf, cf, sf, tmax, rw = (arr[keep] for arr in (xf, yf, cf, sf, tmax, rw))
            p = p.take(keep)
    tracks = np.stack(track_list) if record else None
    return FollowResult(error=error, crossed=crossed, time=t_end, tracks=tracks)
