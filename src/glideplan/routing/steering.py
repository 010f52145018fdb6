"""Steering a replayed vehicle: straight at the goal, a plan's headings, or a plan's track.

`crab` is the heading whose water velocity V plus the current c moves along a direction;
`_tracker` steers at the plan's point a look-ahead distance beyond its point nearest the
vehicle (the goal past its end) with that crab angle for the expected current.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M as R_EARTH  # the one Earth radius

if TYPE_CHECKING:
    from glideplan.routing.replay import Plan

__all__ = ["crab"]



def _naive(goal: tuple[float, float]) -> Callable[[float, float, float], float]:
    from glideplan.routing.sphere import gc_bearing

    def heading(t: float, lat: float, lon: float) -> float:
        return float(gc_bearing(lat, lon, goal[0], goal[1]))

    return heading


def _follow(plan: Plan, t0: float, goal: tuple[float, float]) -> Callable[[float, float, float],
                                                                          float]:
    """The plan's headings (linear in time between its samples) until its end, then at goal."""
    tt = plan.t + t0
    ch = np.unwrap(plan.chi)
    home = _naive(goal)
    end = tt[-1]

    def heading(t: float, lat: float, lon: float) -> float:
        if t > end or tt.size < 2:
            return home(t, lat, lon)
        return float(np.interp(t, tt, ch))

    return heading


def crab(east: float, north: float, cu: float, cv: float, V: float) -> float:
    """Compass heading (rad) whose water velocity V plus current c moves along (east, north):
    w = -c_perp n + sqrt(V^2 - c_perp^2) e (all of V against c_perp when |c_perp| >= V)."""
    n = math.hypot(east, north)
    if n == 0.0:
        return 0.0
    ex, ey = east / n, north / n
    if not (math.isfinite(cu) and math.isfinite(cv)):
        cu = cv = 0.0
    perp = -cu * ey + cv * ex  # component along n = (-ey, ex)
    if abs(perp) >= V:
        wx, wy = -math.copysign(V, perp) * -ey, -math.copysign(V, perp) * ex
    else:
        along = math.sqrt(V * V - perp * perp)
        wx, wy = -perp * -ey + along * ex, -perp * ex + along * ey
    return math.atan2(wx, wy)


def _tracker(plan: Plan, goal: tuple[float, float], V: float, current: Any,
             lookahead: float) -> Callable[[float, float, float], float]:
    """Steer at the plan's point `lookahead` m beyond its point nearest the vehicle (the
    goal past its end), crabbing for `current(t, lat, lon)` (None: still water)."""
    lat0 = math.radians(float(np.mean(plan.lat)))
    kx = math.radians(1.0) * R_EARTH * math.cos(lat0)
    ky = math.radians(1.0) * R_EARTH
    x, y = plan.lon * kx, plan.lat * ky
    keep = np.r_[True, np.hypot(np.diff(x), np.diff(y)) > 1.0]  # drop repeated vertices
    x, y = x[keep], y[keep]
    seg = np.hypot(np.diff(x), np.diff(y))
    cum = np.r_[0.0, np.cumsum(seg)]
    gx, gy = goal[1] * kx, goal[0] * ky
    state = {"k": 0}

    def heading(t: float, lat: float, lon: float) -> float:
        px, py = lon * kx, lat * ky
        if seg.size:  # the nearest point on the polyline's segments (from the last one on)
            k0 = state["k"]
            sl = slice(k0, min(k0 + 40, seg.size))
            ax, ay, dx, dy = x[sl], y[sl], np.diff(x)[sl], np.diff(y)[sl]
            f = np.clip(((px - ax) * dx + (py - ay) * dy) / np.maximum(seg[sl] ** 2, 1e-9),
                        0.0, 1.0)
            d2 = (ax + f * dx - px) ** 2 + (ay + f * dy - py) ** 2
            j = int(np.argmin(d2))
            state["k"] = k0 + j
            s = cum[k0 + j] + f[j] * seg[k0 + j] + lookahead
        else:
            s = math.inf
        if s >= cum[-1]:
            tx, ty = gx, gy
        else:
            tx, ty = float(np.interp(s, cum, x)), float(np.interp(s, cum, y))
        cu = cv = 0.0
        if current is not None:
            try:
                u, v = current(t, lat, lon)
                cu, cv = float(u), float(v)
            except InvalidParameterError:
                pass
        return crab(tx - px, ty - py, cu, cv, V)

    return heading
