"""One step of every vehicle `follow_paths` flies: the lookahead guidance's course error, the
saturated turn-rate law with its feedforward, and the exact motion for constant u and drift
(`glideplan.simulation.closed_loop` states the model)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from glideplan.simulation.closed_loop import FollowerSettings, _Fleet, _PathPoint


def _guidance(
    fleet: _Fleet, point: _PathPoint, gx: np.ndarray, gy: np.ndarray, cfg: FollowerSettings
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lookahead guidance (guidance.lookahead_guidance): the course error (rad) of the ground
    velocity (gx, gy) against the commanded course, the tangent turned by -atan(e / Delta),
    the rate of the path parameter (m/s) and the cross-track error e (m)."""
    c, s = point.cos, point.sin
    delta = cfg.lookahead_distance
    ex, ey = fleet.x - point.x, fleet.y - point.y
    cross = ey * c - ex * s
    rate = gx * c + gy * s + cfg.gamma * (ex * c + ey * s)
    inv = 1.0 / np.sqrt(delta * delta + cross * cross)
    dirx = (c * delta + s * cross) * inv
    diry = (s * delta - c * cross) * inv
    return np.arctan2(gx * diry - gy * dirx, gx * dirx + gy * diry), rate, cross


def _turn_rate(
    err: np.ndarray, rate: np.ndarray, point: _PathPoint, cfg: FollowerSettings
) -> np.ndarray:
    """Saturated bang-bang course control plus the path's turn rate as a feedforward."""
    umax, phi_b = cfg.max_turn_rate, cfg.boundary_layer
    if phi_b > 0.0:
        u = umax * np.clip(err / phi_b, -1.0, 1.0)
    else:
        u = umax * np.sign(err)
    if cfg.feedforward:
        kap = np.where(point.beyond == 0.0, point.kappa, 0.0)
        u = np.clip(u + kap * rate, -umax, umax)
    return u


def _move(
    fleet: _Fleet, u: np.ndarray, drift: np.ndarray, cfg: FollowerSettings
) -> tuple[np.ndarray, np.ndarray]:
    """New positions after one step, and the fleet's heading turned, for constant u and drift.

    Exact motion: the heading turns by u dt, the air-relative displacement is the chord
    v dt sinc(u dt / 2) at heading psi + u dt / 2 (half-angle series where u_max dt <= 0.2,
    exact to ~1e-13 there).
    """
    dt, v = cfg.dt, cfg.speed
    half = 0.5 * dt * u
    if cfg.max_turn_rate * dt <= 0.2:
        h2 = half * half
        sh = half * (1.0 - h2 / 6.0 * (1.0 - h2 / 20.0))
        chh = 1.0 - 0.5 * h2 * (1.0 - h2 / 12.0)
        sinc = 1.0 - h2 / 6.0 * (1.0 - h2 / 20.0)
    else:
        sh, chh = np.sin(half), np.cos(half)
        sinc = np.sinc(half / math.pi)
    cp, sp = fleet.cp, fleet.sp
    cm = cp * chh - sp * sh
    sm = sp * chh + cp * sh
    chord = v * dt * sinc
    x_new = fleet.x + chord * cm + drift[:, 0] * dt
    y_new = fleet.y + chord * sm + drift[:, 1] * dt
    fleet.cp, fleet.sp = cm * chh - sm * sh, sm * chh + cm * sh
    return x_new, y_new
