"""Feedback steering for the replay: the heading that lowers the time-to-go fastest.

At each plan the closed loop also computes, on the same field (the forecast corrected by the
vehicle's measurement), the time-to-go map tau(x): the front run backwards from the goal, in
reversed time and with the current reversed, starting at the plan's arrival time t_goal:

    c_rev(x, s) = -c(x, t_goal - s),   tau(x) = the reversed front's arrival at x,

so t_goal - tau(x) is the latest departure from x that still reaches the goal at t_goal.
Along any heading a the vehicle gains d(t_goal - tau)/dt = -grad(tau) . (c + V a) on that
schedule, largest for

    a = -grad(tau) / |grad(tau)|   (normal to the isochrones of tau: Zermelo's heading),

a feedback law: it answers from wherever the vehicle is (pushed off its plan by the truth's
currents) without tracking the plan's path, as the HJ-reachability controllers of the ocean
platform control project do with their value function (Wiggert et al. 2022). One map per plan
(reversed front only; no verification); where the map has no value (outside the front's
window, land, unreached) the caller falls back to tracking the plan.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M as R_EARTH  # the one Earth radius

__all__ = ["TimeToGo", "time_to_go"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class TimeToGo:
    """tau's gradient (s/m, east gx and north gy) on a regular lat/lon grid (deg); NaN where
    tau is unknown."""

    lat: FloatArray
    lon: FloatArray
    gx: FloatArray
    gy: FloatArray

    def heading(self, lat: float, lon: float) -> float | None:
        """Compass heading (rad) along -grad(tau), bilinear in the grid's cell; None where
        any of the cell's four nodes has no value or the gradient vanishes."""
        la, lo = self.lat, self.lon
        fi = (lat - la[0]) / (la[1] - la[0])
        fj = (lon - lo[0]) / (lo[1] - lo[0])
        i, j = math.floor(fi), math.floor(fj)
        if not (0 <= i < la.size - 1 and 0 <= j < lo.size - 1):
            return None
        a, b = fi - i, fj - j
        gx = self.gx[i:i + 2, j:j + 2]
        gy = self.gy[i:i + 2, j:j + 2]
        w = ((1 - a) * (1 - b), (1 - a) * b, a * (1 - b), a * b)
        x = w[0] * gx[0, 0] + w[1] * gx[0, 1] + w[2] * gx[1, 0] + w[3] * gx[1, 1]
        y = w[0] * gy[0, 0] + w[1] * gy[0, 1] + w[2] * gy[1, 0] + w[3] * gy[1, 1]
        if not (math.isfinite(x) and math.isfinite(y)) or math.hypot(x, y) < 1e-9:
            return None
        return math.atan2(-x, -y)


def _reversed(fld: Any, t_goal: float, hold_s: float) -> Any:
    """The field in reversed time s = t_goal - t with the current reversed; the earliest
    field held for `hold_s` more (the reversed front may run past the field's start)."""
    from glideplan.fields.scalar import ScalarGridded

    times = np.asarray(fld.times, dtype=float)
    s = (t_goal - times)[::-1]
    u = -np.asarray(fld.u, dtype=float)[::-1]
    v = -np.asarray(fld.v, dtype=float)[::-1]
    s = np.r_[s, s[-1] + hold_s]
    u, v = np.concatenate([u, u[-1:]]), np.concatenate([v, v[-1:]])
    return ScalarGridded(times=s, lat=fld.lat, lon=fld.lon, u=u, v=v, epoch=fld.epoch,
                         info=dict(getattr(fld, "info", {}) or {}), warnings=())


def time_to_go(fld: Any, goal: tuple[float, float], pos: tuple[float, float], speed: float,
               t_goal: float, t_now: float, resolution: float) -> TimeToGo | None:
    """The time-to-go map on `fld` (a gridded field with times/u/v in the truth's clock) for
    arriving at `goal` at t_goal, covering the vehicle at `pos` at t_now and ~20 % beyond
    it (module docstring); None when the front cannot be run or does not reach the vehicle."""
    from glideplan.routing import phases
    from glideplan.routing.settings import RouteSettings
    from glideplan.routing.sphere import gc_distance

    togo = max(t_goal - t_now, 3600.0)
    rev = _reversed(fld, t_goal, 2 * togo + 86400.0)
    dist = float(gc_distance(*pos, *goal))
    # the front stops at a point beyond the vehicle (seen from the goal): the map covers
    # where the truth may push it back
    k = 1.0 + max(0.2, 10e3 / max(dist, 1.0))
    far = (goal[0] + k * (pos[0] - goal[0]), goal[1] + k * (pos[1] - goal[1]))
    settings = RouteSettings(resolution=resolution, max_duration=1.5 * togo + 6 * 3600.0,
                             refine=False, progress=False)
    fo = rg = None
    for stop in (far, pos):
        try:
            problem = phases.setup(rev, goal, stop, speed, 0.0, None, settings)
            rg = phases.grid(problem)
            fo, rg = phases.front(problem, rg)
            break
        except InvalidParameterError:
            continue
    if fo is None or rg is None:
        return None
    tau = np.where(np.isfinite(fo.arrival), fo.arrival, np.nan)
    lat, lon = rg.window.lat, rg.window.lon
    if lat.size < 3 or lon.size < 3:
        return None
    dy = math.radians(lat[1] - lat[0]) * R_EARTH
    dx = math.radians(lon[1] - lon[0]) * R_EARTH * np.cos(np.radians(lat))[:, None]
    with np.errstate(invalid="ignore"):
        gy = np.gradient(tau, axis=0) / dy
        gx = np.gradient(tau, axis=1) / dx
    return TimeToGo(np.asarray(lat, float), np.asarray(lon, float), gx, gy)
