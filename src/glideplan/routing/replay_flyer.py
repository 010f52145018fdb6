"""Flying a replayed vehicle through the truth, and what it measures on the way.

`_Flyer` integrates the vehicle's motion through the truth (RK4, module docstring of
`glideplan.routing.replay`), records its track and through-water displacement, and gives the
depth-averaged current it measured between fixes; `_Expected` is the current the vehicle
expects when it crabs (its field corrected by that measurement); `_lateness` how far it is
behind its plan's schedule.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.geodesy import EARTH_RADIUS_M as R_EARTH  # the one Earth radius
from glideplan.routing.forecasts import mean_current

if TYPE_CHECKING:
    from glideplan.routing.replay import Flight, Mission, Plan, ReplaySettings

FloatArray = NDArray[np.float64]


class _Flyer:
    """RK4 through the truth in the truth's clock (s since its epoch), recording the track."""

    def __init__(self, truth: FlowField, mission: Mission, t0: float, t_end: float,
                 step_s: float) -> None:
        self.truth, self.m, self.t0, self.t_end = truth, mission, t0, t_end
        self.step = min(step_s, 900.0)
        self.t, self.lat, self.lon = [t0], [mission.start[0]], [mission.start[1]]
        self.wx, self.wy = [0.0], [0.0]  # through-water displacement (m, east/north)
        self.status: str | None = None
        self.reason: str | None = None
        self.t_arrive: float | None = None

    def _rhs(self, t: float, y: FloatArray, chi: float) -> FloatArray:
        ua, va = self.truth.velocity(t, y[0], y[1])
        u, v = float(ua), float(va)
        if not (math.isfinite(u) and math.isfinite(v)):
            raise _Aground
        V = self.m.speed
        cl = max(math.cos(math.radians(y[0])), 1e-9)
        return np.degrees([(V * math.cos(chi) + v) / R_EARTH,
                           (V * math.sin(chi) + u) / (R_EARTH * cl)])

    def goal_distance(self, lat: float, lon: float) -> float:
        from glideplan.routing.sphere import gc_distance

        return float(gc_distance(lat, lon, *self.m.goal))

    def fly(self, t_stop: float, heading: Callable[[float, float, float], float],
            nodes: FloatArray | None = None) -> bool:
        """Fly until t_stop (or arrival / failure: then False) with heading(t, lat, lon)."""
        t = self.t[-1]
        t_stop = min(t_stop, self.t_end)
        marks = [] if nodes is None else [n for n in nodes if t < n < t_stop]
        bounds = [*marks, t_stop]
        for b in bounds:
            while t < b - 1e-9:
                h = min(self.step, b - t)
                if not self._step(t, h, heading):
                    return False
                t = self.t[-1]
        if self.t[-1] >= self.t_end - 1e-9:
            self.status, self.reason = "unreachable", "max_duration"
            return False
        return True

    def _step(self, t: float, h: float, heading: Callable[[float, float, float], float]) -> bool:
        y = np.array([self.lat[-1], self.lon[-1]])
        try:
            chi1 = heading(t, *y)
            k1 = self._rhs(t, y, chi1)
            chi2 = heading(t + h / 2, *(y + h / 2 * k1))
            k2 = self._rhs(t + h / 2, y + h / 2 * k1, chi2)
            k3 = self._rhs(t + h / 2, y + h / 2 * k2, chi2)
            chi4 = heading(t + h, *(y + h * k3))
            k4 = self._rhs(t + h, y + h * k3, chi4)
        except _Aground:
            self.status, self.reason = "unreachable", "aground"
            return False
        except InvalidParameterError:
            self.status, self.reason = "unreachable", "field_extent"
            return False
        y1 = y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        chis = np.array([chi1, chi2, chi2, chi4])
        wts = np.array([1, 2, 2, 1]) / 6.0
        V = self.m.speed
        dwx = h * V * float(np.sum(wts * np.sin(chis)))
        dwy = h * V * float(np.sum(wts * np.cos(chis)))
        d0 = self.goal_distance(*y)
        d1 = self.goal_distance(*y1)
        r = self.m.goal_radius_m
        if d1 <= r:  # arrival within this step: interpolate the crossing
            f = 1.0 if d0 <= d1 else float(np.clip((d0 - r) / (d0 - d1), 0.0, 1.0))
            y1 = y + f * (y1 - y)
            h, dwx, dwy = f * h, f * dwx, f * dwy
            self.status, self.t_arrive = "solved", t + h
        self.t.append(t + h)
        self.lat.append(float(y1[0]))
        self.lon.append(float(y1[1]))
        self.wx.append(self.wx[-1] + dwx)
        self.wy.append(self.wy[-1] + dwy)
        return self.status is None

    def measured_current(self, span: float) -> tuple[float, float, FloatArray, FloatArray,
                                                     FloatArray] | None:
        """The depth-averaged current the vehicle measured over its last `span` seconds:
        (ground - through-water displacement) / time; with the segment's track points."""
        t = np.asarray(self.t)
        if t[-1] - t[0] < 60.0:
            return None
        ta = max(t[0], t[-1] - span)
        k = int(np.searchsorted(t, ta))
        k = min(k, t.size - 2)
        lat, lon = np.asarray(self.lat), np.asarray(self.lon)
        dt = t[-1] - t[k]
        mid = math.radians(0.5 * (lat[k] + lat[-1]))
        gx = math.radians(lon[-1] - lon[k]) * R_EARTH * math.cos(mid)
        gy = math.radians(lat[-1] - lat[k]) * R_EARTH
        cu = (gx - (self.wx[-1] - self.wx[k])) / dt
        cv = (gy - (self.wy[-1] - self.wy[k])) / dt
        return cu, cv, t[k:], lat[k:], lon[k:]

    def flight(self, plans: tuple[Plan, ...] = ()) -> Flight:
        from glideplan.routing.replay import Flight

        t = np.asarray(self.t) - self.t0
        keep = np.r_[True, np.diff(t) > 1.0]  # drop the millisecond heading switches
        keep[-1] = True
        dur = None if self.t_arrive is None else float(self.t_arrive - self.t0)
        return Flight(self.status or "unreachable", dur,
                      None if self.status == "solved" else (self.reason or "max_duration"),
                      t[keep], np.asarray(self.lat)[keep], np.asarray(self.lon)[keep], plans)


class _Aground(Exception):
    pass


def _lateness(plan: Plan, fl: _Flyer) -> float:
    """How far (s) the vehicle is behind the plan's schedule: now minus the plan's time at
    the point of its track nearest the vehicle (segments in a local plane)."""
    lat, lon = fl.lat[-1], fl.lon[-1]
    ky = math.radians(1.0) * R_EARTH
    kx = ky * math.cos(math.radians(lat))
    x, y = (plan.lon - lon) * kx, (plan.lat - lat) * ky
    if x.size < 2:
        return 0.0
    dx, dy = np.diff(x), np.diff(y)
    f = np.clip(-(x[:-1] * dx + y[:-1] * dy) / np.maximum(dx * dx + dy * dy, 1e-9), 0.0, 1.0)
    d2 = (x[:-1] + f * dx) ** 2 + (y[:-1] + f * dy) ** 2
    j = int(np.argmin(d2))
    t_plan = plan.t[j] + f[j] * (plan.t[j + 1] - plan.t[j])
    return float(fl.t[-1] - fl.t0 - t_plan)


class _Expected:
    """The current the vehicle expects at (t, lat, lon): the field it steers by (t clipped
    into its span), plus the bias b it measured at its last fix (measured current minus the
    field's along the same segment), fading as at planning:
    c = c_fld + b exp(-d^2 / 2L^2) exp(-(t - t_fix) / tau)."""

    def __init__(self, fld: FlowField, s: ReplaySettings) -> None:
        self.fld, self.s = fld, s
        self.span = fld.time_span
        self.bias = (0.0, 0.0)
        self.at = (0.0, 0.0)
        self.t_fix = 0.0

    def update(self, fl: _Flyer) -> None:
        meas = fl.measured_current(self.s.fix_every_s)
        if meas is None:
            return
        fu, fv = mean_current(self.fld, meas[2], meas[3], meas[4])
        self.bias = (meas[0] - fu, meas[1] - fv)
        self.at, self.t_fix = (fl.lat[-1], fl.lon[-1]), fl.t[-1]

    def __call__(self, t: float, lat: float, lon: float) -> tuple[Any, Any]:
        span = self.span
        tt = t if span is None else min(max(t, span[0]), span[1])
        u, v = self.fld.velocity(tt, lat, lon)
        b, L = self.bias, self.s.bias_length_m
        if (b[0] or b[1]) and L > 0:
            dy = math.radians(lat - self.at[0]) * R_EARTH
            dx = math.radians(lon - self.at[1]) * R_EARTH * math.cos(math.radians(lat))
            w = math.exp(-0.5 * (dx * dx + dy * dy) / (L * L)
                         - max(t - self.t_fix, 0.0) / max(self.s.bias_time_s, 1e-9))
            return float(u) + b[0] * w, float(v) + b[1] * w
        return u, v
