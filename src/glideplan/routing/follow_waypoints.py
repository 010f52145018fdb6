"""Fly routes' tracks as waypoints through other fields in closed loop (the ensemble's choice).

Vehicle k flies at water speed V through field F_m(k) (an ensemble member), steering at the
next waypoint of its own track with the crab angle that cancels the cross component of the
current c measured where it is (what a glider's depth-averaged current estimate gives):

    e = unit vector to the waypoint, n = e turned 90 deg left,
    h_n = -clip(c.n / V, -1, 1),  h_e = sqrt(1 - h_n^2),  heading = h_e e + h_n n,
    ground velocity g = V heading + c   (full speed, never slowed).

Waypoint j is passed when the vehicle is within r of it or beyond the line through it normal
to the leg (j-1, j). The last waypoint is the goal: the vehicle arrives at its closest
approach inside a step once that approach is within r (the route's endpoint tolerance, one
routing-grid spacing), so arrival times compare with the route's own duration. Integration:
explicit midpoint (heading held over the step, current at the midpoint), the step chosen so
that no vehicle moves more than r/2 over the ground. A vehicle stops as "left the field"
(off the field, or off the box the stacked fields were cropped to), "ran aground" (NaN
current) or "time ran out" (t_end).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, GriddedField
from glideplan.routing.sphere import EARTH_RADIUS_M, gc_distance

__all__ = ["FollowOutcome", "follow_waypoints"]

FloatArray = NDArray[np.float64]
REASONS = ("arrived", "time ran out", "left the field", "ran aground")


@dataclass(frozen=True, eq=False)
class FollowOutcome:
    """Per vehicle: arrived (bool), duration_s (s after departure, NaN unless arrived),
    reason (an index into REASONS), miss_m (closest approach to the goal, m)."""

    arrived: NDArray[np.bool_]
    duration_s: FloatArray
    reason: NDArray[np.int_]
    miss_m: FloatArray

    def reasons(self) -> list[str]:
        return [REASONS[int(k)] for k in self.reason]


class _Stacked:
    """Members on one (time, lat, lon) grid, cropped to a box, as one interpolator over
    (member, time, lat, lon): one call per step for every vehicle (exact at integer member)."""

    def __init__(self, fields: Sequence[GriddedField], box: tuple[float, float, float, float]):
        from scipy.interpolate import RegularGridInterpolator

        f0 = fields[0]
        la0, la1, lo0, lo1 = box
        iy = np.flatnonzero((f0.lat >= la0) & (f0.lat <= la1))
        ix = np.flatnonzero((f0.lon >= lo0) & (f0.lon <= lo1))
        ys = slice(max(int(iy[0]) - 2, 0), min(int(iy[-1]) + 3, f0.lat.size)) if iy.size else \
            slice(0, f0.lat.size)
        xs = slice(max(int(ix[0]) - 2, 0), min(int(ix[-1]) + 3, f0.lon.size)) if ix.size else \
            slice(0, f0.lon.size)
        vals = np.stack([np.stack([f.u[:, ys, xs], f.v[:, ys, xs]], axis=-1) for f in fields])
        self.lat, self.lon = f0.lat[ys], f0.lon[xs]
        self.steady = f0.times.size == 1
        axes: tuple[Any, ...] = (np.arange(len(fields), dtype=float),)
        if self.steady:
            vals = vals[:, 0]
        else:
            axes += (f0.times,)
        if len(fields) == 1:  # an interpolator axis needs two points: repeat the member
            vals = np.concatenate([vals, vals])
            axes = (np.array([0.0, 1.0]), *axes[1:])
        self.interp = RegularGridInterpolator((*axes, self.lat, self.lon), vals,
                                              bounds_error=False, fill_value=np.nan)
        self.centre = 0.5 * (float(f0.lon[0]) + float(f0.lon[-1]))

    def __call__(self, t: float, member: NDArray[np.int_], lat: FloatArray, lon: FloatArray
                 ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
        lo = self.centre + np.mod(lon - self.centre + 180.0, 360.0) - 180.0
        inside = ((lat >= self.lat[0]) & (lat <= self.lat[-1]) & (lo >= self.lon[0])
                  & (lo <= self.lon[-1]))
        cols: list[Any] = [member.astype(float)]
        if not self.steady:
            cols.append(np.full(lat.shape, t))
        uv = self.interp(np.stack([*cols, lat, lo], axis=-1))
        return uv[:, 0], uv[:, 1], inside


class _PerField:
    """Any fields: one `velocity` call per field and step (off the field -> outside)."""

    def __init__(self, fields: Sequence[FlowField]):
        self.fields = list(fields)

    def __call__(self, t: float, member: NDArray[np.int_], lat: FloatArray, lon: FloatArray
                 ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
        u, v = np.full(lat.shape, np.nan), np.full(lat.shape, np.nan)
        inside = np.ones(lat.shape, dtype=bool)
        for m in np.unique(member):
            sel = np.flatnonzero(member == m)
            fld = self.fields[int(m)]
            ext = fld.extent
            if ext is not None:
                ok = ((lat[sel] >= ext.lat_min) & (lat[sel] <= ext.lat_max)
                      & ext.contains_lon(lon[sel]))
                inside[sel[~ok]] = False
                sel = sel[ok]
            if sel.size:
                u[sel], v[sel] = fld.velocity(t, lat[sel], lon[sel])
        return u, v, inside


def _same_grid(fields: Sequence[FlowField]) -> bool:
    grids = [f for f in fields if isinstance(f, GriddedField) and not f.periodic_lon]
    if len(grids) != len(fields):
        return False
    f0 = grids[0]
    return all(f.u.shape == f0.u.shape and np.array_equal(f.lat, f0.lat)
               and np.array_equal(f.lon, f0.lon) and np.array_equal(f.times, f0.times)
               for f in grids)


def sampler(fields: Sequence[FlowField], tracks: Sequence[tuple[FloatArray, FloatArray]]) -> Any:
    """The fastest velocity sampler for these fields: stacked when they share a grid (cropped
    to the tracks' box grown by a quarter of its size and 0.5 deg), else per field."""
    if not _same_grid(fields):
        return _PerField(fields)
    f0 = fields[0]
    assert isinstance(f0, GriddedField)
    la = np.concatenate([t[0] for t in tracks])
    centre = 0.5 * (float(f0.lon[0]) + float(f0.lon[-1]))
    lo = centre + np.mod(np.concatenate([t[1] for t in tracks]) - centre + 180.0, 360.0) - 180.0
    pad_la = 0.25 * float(np.ptp(la)) + 0.5
    pad_lo = 0.25 * float(np.ptp(lo)) + 0.5
    box = (float(la.min()) - pad_la, float(la.max()) + pad_la, float(lo.min()) - pad_lo,
           float(lo.max()) + pad_lo)
    return _Stacked([f for f in fields if isinstance(f, GriddedField)], box)


def _local(lat: FloatArray, lon: FloatArray, lat2: FloatArray, lon2: FloatArray
           ) -> tuple[FloatArray, FloatArray]:
    """East, north (m) of point 2 from point 1 (equirectangular about 1: short distances)."""
    de = np.radians((lon2 - lon + 180.0) % 360.0 - 180.0) * EARTH_RADIUS_M * np.cos(
        np.radians(lat))
    return de, np.radians(lat2 - lat) * EARTH_RADIUS_M


def _heading(de: FloatArray, dn: FloatArray, u: FloatArray, v: FloatArray, speed: float
             ) -> tuple[FloatArray, FloatArray]:
    """Water-velocity (east, north) at full speed towards (de, dn) with the crab angle."""
    d = np.maximum(np.hypot(de, dn), 1e-9)
    ee, en = de / d, dn / d
    ne, nn = -en, ee
    hn = -np.clip((u * ne + v * nn) / speed, -1.0, 1.0)
    he = np.sqrt(1.0 - hn * hn)
    return speed * (he * ee + hn * ne), speed * (he * en + hn * nn)


def _padded(tracks: Sequence[tuple[FloatArray, FloatArray]], goal: tuple[float, float]
            ) -> tuple[FloatArray, FloatArray, NDArray[np.int_]]:
    """Waypoints (n, K) lat/lon, each track ending exactly at the goal; last index per row."""
    rows = [(np.append(np.asarray(a, float)[:-1], goal[0]),
             np.append(np.asarray(b, float)[:-1], goal[1])) for a, b in tracks]
    k = max(r[0].size for r in rows)
    wlat = np.array([np.pad(a, (0, k - a.size), mode="edge") for a, _ in rows])
    wlon = np.array([np.pad(b, (0, k - b.size), mode="edge") for _, b in rows])
    return wlat, wlon, np.array([a.size - 1 for a, _ in rows])


def _advance(k: NDArray[np.int_], last: NDArray[np.int_], lat: FloatArray, lon: FloatArray,
             wlat: FloatArray, wlon: FloatArray, radius: float) -> NDArray[np.int_]:
    """Move each vehicle's waypoint on while it is within r of it or past its normal line."""
    rows = np.arange(k.size)
    for _ in range(wlat.shape[1]):
        can = k < last
        if not can.any():
            break
        de, dn = _local(lat, lon, wlat[rows, k], wlon[rows, k])
        km = np.maximum(k - 1, 0)
        ae, an = _local(wlat[rows, km], wlon[rows, km], wlat[rows, k], wlon[rows, k])
        passed = (np.hypot(de, dn) < radius) | ((k > 0) & (-(ae * de + an * dn) > 0))
        step = can & passed
        if not step.any():
            break
        k = k + step
    return k


def follow_waypoints(
    fields: Sequence[FlowField],
    member: Sequence[int],
    tracks: Sequence[tuple[FloatArray, FloatArray]],
    speed: float,
    goal: tuple[float, float],
    t0: float,
    t_end: float,
    radius_m: float,
) -> FollowOutcome:
    """Vehicle k flies track k (lat, lon arrays, deg) through fields[member[k]] from t0 (s
    since the fields' epoch) until it arrives within radius_m of the goal or t_end (module
    docstring for the law and the stops)."""
    n = len(tracks)
    if n == 0 or len(member) != n:
        raise InvalidParameterError("tracks", n, "need one member index per track (>= 1)")
    if not (speed > 0 and radius_m > 0 and t_end > t0):
        raise InvalidParameterError("follow", (speed, radius_m, t_end - t0),
                                    "needs speed > 0, radius > 0 and t_end > t0")
    memb = np.asarray(member, dtype=int)
    sample = sampler(fields, tracks)
    wlat, wlon, last = _padded(tracks, goal)
    lat, lon = wlat[:, 0].copy(), wlon[:, 0].copy()
    k = np.zeros(n, dtype=int)
    flying = np.ones(n, dtype=bool)
    reason = np.ones(n, dtype=int)  # time ran out unless something else happens
    dur, miss = np.full(n, np.nan), np.full(n, np.inf)
    t = t0
    while flying.any() and t < t_end - 1e-9:
        f = np.flatnonzero(flying)
        k[f] = _advance(k[f], last[f], lat[f], lon[f], wlat[f], wlon[f], radius_m)
        u, v, inside = sample(t, memb[f], lat[f], lon[f])
        bad = ~inside | ~(np.isfinite(u) & np.isfinite(v))
        if bad.any():
            reason[f[bad]] = np.where(inside[bad], 3, 2)
            flying[f[bad]] = False
            f, u, v = f[~bad], u[~bad], v[~bad]
            if not f.size:
                break
        de, dn = _local(lat[f], lon[f], wlat[f, k[f]], wlon[f, k[f]])
        we, wn = _heading(de, dn, u, v, speed)
        g_max = float(np.max(np.hypot(we + u, wn + v)))
        dt = min(0.5 * radius_m / max(g_max, 1e-3), t_end - t)
        # explicit midpoint: heading held, current at the half step
        hl = lat[f] + np.degrees(0.5 * dt * (wn + v) / EARTH_RADIUS_M)
        ho = lon[f] + np.degrees(0.5 * dt * (we + u) / (EARTH_RADIUS_M * np.cos(
            np.radians(lat[f]))))
        um, vm, _inside_m = sample(t + 0.5 * dt, memb[f], hl, ho)
        um, vm = np.where(np.isfinite(um), um, u), np.where(np.isfinite(vm), vm, v)
        ge, gn = we + um, wn + vm
        at_goal = k[f] == last[f]
        if at_goal.any():
            a = f[at_goal]
            pe, pn = _local(np.full(a.size, goal[0]), np.full(a.size, goal[1]), lat[a], lon[a])
            gge, ggn = ge[at_goal], gn[at_goal]
            ts = np.clip(-(pe * gge + pn * ggn) / np.maximum(gge ** 2 + ggn ** 2, 1e-12), 0, dt)
            dmin = np.hypot(pe + gge * ts, pn + ggn * ts)
            miss[a] = np.minimum(miss[a], dmin)
            hit = (dmin <= radius_m) & (ts < dt)
            dur[a[hit]] = t + ts[hit] - t0
            reason[a[hit]] = 0
            flying[a[hit]] = False
        lon[f] = lon[f] + np.degrees(dt * ge / (EARTH_RADIUS_M * np.cos(np.radians(hl))))
        lat[f] = lat[f] + np.degrees(dt * gn / EARTH_RADIUS_M)
        t += dt
    left = flying | (reason != 0)
    if left.any():
        d = gc_distance(lat[left], lon[left], goal[0], goal[1])
        miss[left] = np.minimum(miss[left], d)
    return FollowOutcome(reason == 0, dur, reason, miss)
