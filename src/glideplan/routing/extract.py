"""Routes where the current may be stronger than the vehicle: the drift cone and the
characteristic's own controls.

The drift cone (checked before any front is built). Whatever its heading, a vehicle of water
speed V in a current c(x, t) moves with dx/dt = V e + c, |e| = 1, so in a local plane
about the start

    x(t) - x0 = V * integral(e) + integral(c) dt.

- Spatially uniform current c(t) (a `UniformField`, or a gridded field whose every time level
  is one vector): x(t) lies in the drift disk |x - x0 - D(t)| <= V t, D(t) = integral_0^t c,
  and every point of that disk is reached at t (hold the one heading e = (g - x0 - D(t)) /
  |...|). The minimum time to the goal g is the first t with |g - x0 - D(t)| <= V t: the
  goal is unreachable exactly when that never holds before the field's (or the duration's)
  limit.
- Any gridded field: c(x, t) lies in the box B = [u_min, u_max] x [v_min, v_max] of the
  field's own nodes (linear interpolation stays in the nodes' hull), so x(t) - x0 lies in
  t (B + disk(V)), a convex set with support function h(n) = V + max_{c in B} c.n. If for a
  direction n the goal lies ahead, n.(g - x0) > 0, while h(n) < 0 (the current everywhere
  carries the vehicle away along n faster than it can swim), or n.(g - x0) > T h(n) within
  the time limit T, no heading ever reaches the goal: it lies outside the drift cone at any
  resolution.

Either case answers `unreachable` at once (no front): reason "outside_drift_cone" when no
duration would do (the current is faster than the vehicle and sets it away from the goal),
else the limit that comes first ("time_span" / "max_duration"), with the sentence saying the
drift envelope proved it. On the
sphere the local plane (azimuthal equidistant about the start) and the compass components of
the current differ by the rotation of north across the route (<= |dlon| sin(lat)); the test
only claims unreachable beyond a margin of CONE_MARGIN of the distance plus two grid
spacings and with h(n) below -CONE_SLACK x (V + |c|max), and only for routes shorter than
CONE_MAX_DISTANCE_M.

The characteristic's controls. The front's backtracked characteristic (`fronts.backtrack`,
the optimal heading n = grad T / |grad T| integrated backwards from the goal on the front's
own time levels) carries its times and headings; flown as they are (heading linear in time
between its samples) they reproduce the optimal path also where the vehicle is swept along.
The polyline route (`phases.backtrack`: the path thinned to a cell and each leg held with a
crab angle) cannot: where the current is stronger than the vehicle a leg's direction need
not be one the vehicle can hold, and a path swept back and forth over itself is not a
function of position. When that characteristic route misses (a divergent flow amplifies its
heading errors), `tracking_candidate` flies the route closed-loop through the field: the
heading that holds the characteristic's position at each time (its own heading plus a
correction towards the reference point, within the vehicle's speed), and its flown headings
become the controls that the verification flies again.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.routing.sphere import EARTH_RADIUS_M, gc_distance, unwrap_lon

__all__ = [
    "CONE_MARGIN",
    "CONE_MAX_DISTANCE_M",
    "CONE_SLACK",
    "DriftCone",
    "characteristic_candidate",
    "drift_cone",
    "drift_disk_time",
    "peak_current",
    "rescue",
    "swept",
    "tracking_candidate",
]

FloatArray = NDArray[np.float64]

_LIMIT = {"time_span": "field's time span", "max_duration": "duration limit"}

#: The cone test claims unreachable only beyond this fraction of the start-goal distance.
CONE_MARGIN = 0.02
#: ... and with the support function below -CONE_SLACK x (V + largest current).
CONE_SLACK = 0.05
#: ... and only for routes shorter than this (m; the local plane's rotation of north).
CONE_MAX_DISTANCE_M = 500_000.0


@dataclass(frozen=True)
class DriftCone:
    """Why no heading reaches the goal, found without a front: `message` (one sentence),
    `kind` ("disk" for a spatially uniform current, "box" for the field's velocity bounds),
    `reason` ("outside_drift_cone" at any duration, else the time limit's reason:
    "time_span" / "max_duration")."""

    message: str
    kind: str
    reason: str = "outside_drift_cone"


def _local(start: tuple[float, float], goal: tuple[float, float]) -> FloatArray:
    """The goal (m east, north) in the azimuthal-equidistant plane about the start."""
    from glideplan.routing.sphere import gc_bearing

    d = float(gc_distance(start[0], start[1], goal[0], goal[1]))
    b = float(gc_bearing(start[0], start[1], goal[0], goal[1]))
    return np.array([d * math.sin(b), d * math.cos(b)])


def _uniform_series(fld: Any, t0: float, t_max: float, start: tuple[float, float]) -> tuple[
        FloatArray, FloatArray, FloatArray] | None:
    """(t, u, v) samples of a spatially uniform current from t0 to t_max (linear between
    them, exact for a gridded field's levels), or None when the field is not uniform."""
    from glideplan.fields.field import GriddedField, UniformField

    if isinstance(fld, UniformField):
        return (np.array([t0, t_max]), np.full(2, float(fld.u)), np.full(2, float(fld.v)))
    if not isinstance(fld, GriddedField):
        return None
    u, v = np.asarray(fld.u, dtype=float), np.asarray(fld.v, dtype=float)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        return None
    uu, vv = u.reshape(u.shape[0], -1), v.reshape(v.shape[0], -1)
    if np.any(np.ptp(uu, axis=1) > 1e-9) or np.any(np.ptp(vv, axis=1) > 1e-9):
        return None
    tl = np.asarray(fld.times, dtype=float)
    if tl.size == 1:
        return (np.array([t0, t_max]), np.full(2, uu[0, 0]), np.full(2, vv[0, 0]))
    inner = tl[(tl > t0) & (tl < t_max)]
    ts = np.concatenate([[t0], inner, [t_max]])
    return ts, np.interp(ts, tl, uu[:, 0]), np.interp(ts, tl, vv[:, 0])


def drift_disk_time(t: FloatArray, u: FloatArray, v: FloatArray, goal_xy: FloatArray,
                    speed: float, substeps: int = 64) -> tuple[float | None, float]:
    """The first time after t[0] (s) with |g - D(t)| <= V (t - t[0]) for a uniform current
    linear between samples (t, u, v); D(t) = integral of the current (trapezoids on each
    sample interval cut into `substeps`, exact for a current linear in time). Returns
    (time or None, the smallest |g - D| - V (t - t0) over the span, m)."""
    tt = np.unique(np.concatenate([np.linspace(a, b, substeps + 1)
                                   for a, b in itertools.pairwise(t)]))
    uu, vv = np.interp(tt, t, u), np.interp(tt, t, v)
    dt = np.diff(tt)
    dx = np.concatenate([[0.0], np.cumsum(0.5 * (uu[1:] + uu[:-1]) * dt)])
    dy = np.concatenate([[0.0], np.cumsum(0.5 * (vv[1:] + vv[:-1]) * dt)])
    gap = np.hypot(goal_xy[0] - dx, goal_xy[1] - dy) - speed * (tt - tt[0])
    inside = np.flatnonzero(gap <= 0.0)
    if inside.size == 0:
        return None, float(np.min(gap))
    k = int(inside[0])
    if k == 0:
        return float(tt[0]), float(np.min(gap))
    # the crossing inside [tt[k-1], tt[k]]: gap linear there to within the substep
    a, b = gap[k - 1], gap[k]
    return float(tt[k - 1] + (tt[k] - tt[k - 1]) * a / (a - b)), float(np.min(gap))


def _box_cone(fld: Any, goal_xy: FloatArray, speed: float, horizon: float,
              margin: float, limit: str) -> DriftCone | None:
    """The box test of the module docstring on a gridded field's node velocities."""
    from glideplan.fields.field import GriddedField

    if not isinstance(fld, GriddedField):
        return None
    u, v = np.asarray(fld.u, dtype=float), np.asarray(fld.v, dtype=float)
    if not (np.any(np.isfinite(u)) and np.any(np.isfinite(v))):
        return None
    umin, umax = float(np.nanmin(u)), float(np.nanmax(u))
    vmin, vmax = float(np.nanmin(v)), float(np.nanmax(v))
    cmax = float(np.nanmax(np.hypot(u, v)))
    ang = np.linspace(0.0, 2 * math.pi, 720, endpoint=False)
    nx, ny = np.cos(ang), np.sin(ang)
    h = speed + np.maximum(nx * umin, nx * umax) + np.maximum(ny * vmin, ny * vmax)
    ahead = nx * goal_xy[0] + ny * goal_xy[1]
    slack = CONE_SLACK * (speed + cmax)
    cone = (ahead > margin) & (h < -slack)
    if cone.any():
        k = int(np.argmax(np.where(cone, ahead, -np.inf)))
        brg = (90.0 - math.degrees(ang[k])) % 360.0
        return DriftCone(
            f"the goal lies outside the drift cone: along bearing {brg:.0f} deg (towards the "
            f"goal) every current in the field sets the vehicle back by more than its speed "
            f"{speed:g} m/s makes good (net at least {-h[k]:.2g} m/s away), so no heading "
            "reaches it at any resolution or duration", "box")
    within = (ahead > horizon * np.maximum(h + slack, 0.0) + margin) & (h + slack > 0)
    if within.any():
        return DriftCone(
            f"the goal lies outside the drift cone within the "
            f"{_LIMIT.get(limit, 'time limit')} ({horizon / 3600:.4g} h): even the field's "
            f"most favourable current (u {umin:.2g}..{umax:.2g}, v {vmin:.2g}..{vmax:.2g} "
            f"m/s) added to the vehicle's "
            f"{speed:g} m/s cannot carry it there in time, at any resolution", "box", limit)
    return None


def drift_cone(problem: Any, spacing_m: float) -> DriftCone | None:
    """Why the goal lies outside the drift cone (module docstring), or None when it may not."""
    if problem.distance_m <= 0 or problem.distance_m > CONE_MAX_DISTANCE_M:
        return None
    g = _local(problem.start, problem.goal)
    margin = CONE_MARGIN * problem.distance_m + 2.0 * spacing_m
    horizon = problem.t_max - problem.t0
    series = _uniform_series(problem.field_, problem.t0, problem.t_max, problem.start)
    if series is not None:
        t, u, v = series
        first, gap = drift_disk_time(t, u, v, g, problem.speed)
        cmax = float(np.max(np.hypot(u, v)))
        if first is None and gap > margin:
            limit = _LIMIT.get(problem.limit_reason, "time limit")
            steady = bool(np.all(u == u[0]) and np.all(v == v[0]))
            c = np.array([u[0], v[0]])
            along = float(g @ c) / max(float(np.linalg.norm(c)), 1e-300)
            across = math.sqrt(max(float(g @ g) - along * along, 0.0))
            # the cone {t (c + V e)}: |c| > V and the goal beyond its half-angle asin(V/|c|)
            if steady and cmax > problem.speed * (1 + CONE_SLACK) and (
                    along <= 0 or across > along * problem.speed / math.sqrt(
                        cmax**2 - problem.speed**2) + margin):
                return DriftCone(
                    f"the goal lies outside the drift cone: the uniform current "
                    f"({cmax:.3g} m/s) is faster than the vehicle ({problem.speed:g} m/s) "
                    f"and the goal is not within the cone it sweeps (the drift disk "
                    f"|goal - start - c t| <= V t never holds), so no heading reaches it at "
                    f"any resolution or duration", "disk")
            return DriftCone(
                f"the goal lies outside the drift cone within the {limit} "
                f"({horizon / 3600:.4g} h): in this spatially uniform current the drift disk "
                f"|goal - start - integral(c dt)| <= V t never contains the goal (it stays "
                f"{gap / 1000:.3g} km short), so no heading reaches it at any resolution", "disk",
                problem.limit_reason)
        return None
    return _box_cone(problem.field_, g, problem.speed, horizon, margin,
                     problem.limit_reason)


# ------------------------------------------------------------------- the characteristic


def swept(problem: Any, rg: Any, t_end: float) -> bool:
    """Whether the current reaches the vehicle's speed somewhere on the routing window
    between departure and `t_end` (s since epoch), sampled on a 9 x 9 sub-grid of the window
    at 33 times."""
    return peak_current(problem, rg, t_end) >= problem.speed


def peak_current(problem: Any, rg: Any, t_end: float) -> float:
    """The largest current speed (m/s) on the routing window between departure and `t_end`
    (s since epoch), sampled on a 9 x 9 sub-grid of the window at 33 times (0 where the
    field refuses a point or has no data)."""
    win = rg.window
    la = win.lat[np.linspace(0, win.lat.size - 1, 9).astype(int)]
    lo = win.lon[np.linspace(0, win.lon.size - 1, 9).astype(int)]
    ext = problem.field_.extent
    if ext is not None:  # the window may reach past the field's edge
        la = np.clip(la, ext.lat_min, ext.lat_max)
        if not ext.periodic:
            lo = np.clip(lo, ext.lon_min, ext.lon_max)
    tt = np.linspace(problem.t0, max(t_end, problem.t0), 33)
    T, LA, LO = np.meshgrid(tt, la, lo, indexing="ij")
    try:
        with np.errstate(invalid="ignore"):
            u, v = problem.field_.velocity(T.ravel(), LA.ravel(), LO.ravel())
    except InvalidParameterError:
        return 0.0
    s = np.hypot(u, v)
    return float(np.nanmax(s)) if np.any(np.isfinite(s)) else 0.0


def rescue(problem: Any, rg: Any, fo: Any, tolerance: float, tried: bool,
           track: bool = True, home: bool = False) -> tuple[Any, Any] | None:
    """A verified route from the characteristic when the other routes failed: its own
    controls (unless `tried`), then (with `track`, a refinement) flown closed-loop
    (`tracking_candidate`), then (with `home`: routes without refinement) flown closed-loop
    and homing on the goal past the reference's end; (candidate, flown) or None."""
    from glideplan.routing.phases import flown_ok, verify

    ref = characteristic_candidate(problem, rg, fo)
    if ref is None:
        return None
    if not tried:
        flown = verify(problem, rg, ref)
        if flown_ok(flown, tolerance):
            return ref, flown
    if not track:
        return None
    for goal_m in (None, 0.5 * tolerance) if home else (None,):
        tracked = tracking_candidate(problem, rg, ref, goal_m=goal_m)
        if tracked is None:
            return None
        flown = verify(problem, rg, tracked)
        if flown_ok(flown, tolerance):
            return tracked, flown
    return None


def characteristic_candidate(problem: Any, rg: Any, fo: Any) -> Any:
    """The backtracked characteristic with its own times and headings (module docstring), or
    None when it did not reach the start."""
    from glideplan.fronts import backtrack as kernel_backtrack
    from glideplan.routing.phases import Candidate

    assert fo.goal_time is not None
    tr = kernel_backtrack(fo.problem, fo.arrival, goal=problem.goal, t_goal=fo.goal_time,
                          t0=problem.t0, source=problem.start,
                          start_radius_m=fo.state.start_radius_m)
    if not tr.complete or tr.t.size < 2:
        return None
    t = np.asarray(tr.t, dtype=float)
    keep = np.concatenate([[True], np.diff(t) > 1e-9])
    t = t[keep]
    lat = np.asarray(tr.lat, dtype=float)[keep]
    lon = unwrap_lon(np.asarray(tr.lon, dtype=float)[keep], problem.start[1])
    lon = np.degrees(np.unwrap(np.radians(lon)))
    chi = np.unwrap(0.5 * math.pi - np.asarray(tr.heading, dtype=float)[keep])
    lat[0], lon[0] = problem.start
    lat[-1], lon[-1] = problem.goal
    return Candidate("characteristic", t, lat, lon, chi, False, float(t[-1] - problem.t0))


def tracking_candidate(problem: Any, rg: Any, ref: Any, gain_s: float | None = None,
                       goal_m: float | None = None) -> Any:
    """The reference route flown closed-loop through the field (RK4 at the reference's own
    samples): water heading along V n_ref + (x_ref(t) - x) / tau, scaled to the speed V
    (tau = `gain_s`, default one cell's crossing at V); its flown headings and track as a
    Candidate ("characteristic-tracked"), or None where the field is NaN. With `goal_m`, a
    flight that ends farther than `goal_m` from the goal (the front's arrival is a little
    early: the vehicle lags its reference) goes on, heading at the goal with the crab angle
    for the field's current (`_home`), for at most a quarter of the reference's duration."""
    from glideplan.routing.phases import _held

    R = EARTH_RADIUS_M
    V = problem.speed
    tau = gain_s if gain_s is not None else max(rg.spacing_m / V, 1.0)
    t = np.asarray(ref.t, dtype=float)
    sub = np.unique(np.concatenate([t, 0.5 * (t[:-1] + t[1:])]))
    ref_la = np.radians(np.interp(sub, t, ref.lat))
    ref_lo = np.radians(np.interp(sub, t, ref.lon))
    ref_chi = np.interp(sub, t, np.unwrap(ref.chi))
    fld = problem.field_

    def heading(k: float, la: float, lo: float) -> float:
        rla = float(np.interp(k, sub, ref_la))
        rlo = float(np.interp(k, sub, ref_lo))
        ch = float(np.interp(k, sub, ref_chi))
        ex = R * math.cos(la) * (rlo - lo)
        ey = R * (rla - la)
        we = V * math.sin(ch) + ex / tau
        wn = V * math.cos(ch) + ey / tau
        return math.atan2(we, wn) if (we or wn) else ch

    def rhs(s: float, la: float, lo: float, ch: float) -> tuple[float, float] | None:
        uu, vv = fld.velocity_at(s, math.degrees(la), math.degrees(lo))
        if not (math.isfinite(uu) and math.isfinite(vv)):
            return None
        return (V * math.cos(ch) + vv) / R, (V * math.sin(ch) + uu) / (R * max(math.cos(la),
                                                                           1e-9))

    la, lo = float(ref_la[0]), float(ref_lo[0])
    las, los, chis = [la], [lo], []
    try:
        for k in range(sub.size - 1):
            s0, dt = float(sub[k]), float(sub[k + 1] - sub[k])
            ch = heading(s0, la, lo)
            chis.append(ch)
            k1 = rhs(s0, la, lo, ch)
            k2 = None if k1 is None else rhs(s0 + dt / 2, la + dt / 2 * k1[0],
                                             lo + dt / 2 * k1[1], ch)
            k3 = None if k2 is None else rhs(s0 + dt / 2, la + dt / 2 * k2[0],
                                             lo + dt / 2 * k2[1], ch)
            k4 = None if k3 is None else rhs(s0 + dt, la + dt * k3[0], lo + dt * k3[1], ch)
            if k1 is None or k2 is None or k3 is None or k4 is None:
                return None
            la += dt / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0])
            lo += dt / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])
            las.append(la)
            los.append(lo)
    except InvalidParameterError:  # the field refused a point (off its extent or time)
        return None
    times = list(sub)
    if goal_m is not None:
        _home(problem, rhs, times, las, los, chis, goal_m, 0.25 * float(sub[-1] - sub[0]),
              max(float(np.median(np.diff(sub))), 60.0))
    chis.append(chis[-1])
    # each step's heading held: published as controls linear in time between samples with
    # a millisecond switch at each sample (phases._held), so that the route's track, flown
    # as published, is the flight that was verified
    return _held("characteristic-tracked", np.asarray(times), np.degrees(las),
                 np.degrees(los), np.unwrap(np.array(chis)), problem.t0)


def _home(problem: Any, rhs: Any, times: list[float], las: list[float], los: list[float],
          chis: list[float], goal_m: float, extra_s: float, dt: float) -> None:
    """Extend a flight (lists in place; radians) at the goal until within `goal_m` of it or
    `extra_s` more: compass heading = the crab angle along the bearing to the goal for the
    current there (`steering.crab`), RK4 steps of at most `dt`, the last shortened to the
    closest approach (distance d <= V h for the step)."""
    from glideplan.routing.steering import crab

    R = EARTH_RADIUS_M
    V = problem.speed
    gla, glo = math.radians(problem.goal[0]), math.radians(problem.goal[1])
    t_stop = times[-1] + extra_s
    fld = problem.field_
    try:
        while times[-1] < t_stop:
            la, lo, s0 = las[-1], los[-1], times[-1]
            east = R * math.cos(la) * (glo - lo)
            north = R * (gla - la)
            d = math.hypot(east, north)
            if d <= goal_m:
                return
            u, v = fld.velocity_at(s0, math.degrees(la), math.degrees(lo))
            ch = crab(east, north, u, v, V)
            h = min(dt, t_stop - s0, max(d / V, 1.0))
            k1 = rhs(s0, la, lo, ch)
            k2 = None if k1 is None else rhs(s0 + h / 2, la + h / 2 * k1[0],
                                             lo + h / 2 * k1[1], ch)
            k3 = None if k2 is None else rhs(s0 + h / 2, la + h / 2 * k2[0],
                                             lo + h / 2 * k2[1], ch)
            k4 = None if k3 is None else rhs(s0 + h, la + h * k3[0], lo + h * k3[1], ch)
            if k1 is None or k2 is None or k3 is None or k4 is None:
                return
            chis.append(ch)
            las.append(la + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]))
            los.append(lo + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1]))
            times.append(s0 + h)
    except InvalidParameterError:  # past the field's extent or time: stop where it was
        return
