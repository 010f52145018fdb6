"""Kinematics on the sphere: distances, the flown controls, and holding a line with a crab angle.

The router's Earth is the front kernel's sphere of radius R = 6,371,008.8 m (the IUGG mean
radius): a vehicle at water speed V with compass heading chi (of its through-water velocity) in
a current (u east, v north) moves as

    dlat/dt = (V cos chi + v) / R,    dlon/dt = (V sin chi + u) / (R cos lat)      (radians).

On this sphere the geodesic is the great circle and still water gives duration = great-circle
distance / V. WGS84 geodesics differ from the sphere's great circles by at most ~0.5 % of the
distance (flattening 1/298; e.g. +0.17 % for an east-west transect at 45 deg N); every routing
time and distance is on the sphere, the model the front, the backtracking and the verification
share. Endpoint errors are great-circle distances (m).

`fly_headings` integrates the heading controls through the field itself with SciPy's
`solve_ivp` (RK45, rtol 1e-7, atol 1 cm); `crab_controls` gives the headings that hold
each leg of a polyline (the great circle between consecutive points) at water speed V:
along-leg ground speed s = sqrt(V^2 - c_n^2) + c_t (c_t, c_n the current along/across the leg
at its midpoint), leg time = length / s.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.geodesy import EARTH_RADIUS_M, destination  # one place each: re-exported here

__all__ = [
    "EARTH_RADIUS_M",
    "FlownRoute",
    "crab_controls",
    "destination",
    "fly_headings",
    "gc_bearing",
    "gc_distance",
    "straight_line_duration",
    "unwrap_lon",
]

FloatArray = NDArray[np.float64]


#: (t, lat, lon) -> (u, v): the current where the field's interpolation stencil touches land
#: (nearest water value), used by the verification only (FlownRoute.filled counts its uses).
Fill = Callable[[float, float, float], tuple[float, float]]


def unwrap_lon(lon: ArrayLike, ref: ArrayLike) -> FloatArray:
    """The representative of each longitude (deg) within (-180, 180] of `ref`."""
    lo = np.asarray(lon, dtype=float)
    r = np.asarray(ref, dtype=float)
    return np.asarray(r - np.mod(r - lo + 180.0, 360.0) + 180.0, dtype=float)


def gc_distance(lat1: ArrayLike, lon1: ArrayLike, lat2: ArrayLike, lon2: ArrayLike) -> FloatArray:
    """Great-circle distance (m) on the sphere of radius R (haversine), vectorised (deg in)."""
    p1, p2 = np.radians(lat1), np.radians(lat2)
    dl = np.radians(np.asarray(lon2, dtype=float) - np.asarray(lon1, dtype=float))
    a = np.sin((p2 - p1) / 2) ** 2 + np.cos(p1) * np.cos(p2) * np.sin(dl / 2) ** 2
    return np.asarray(2 * EARTH_RADIUS_M * np.arcsin(np.sqrt(np.clip(a, 0.0, 1.0))), dtype=float)


def gc_bearing(lat1: ArrayLike, lon1: ArrayLike, lat2: ArrayLike, lon2: ArrayLike) -> FloatArray:
    """Initial compass bearing (rad, clockwise from north) of the great circle 1 -> 2."""
    p1, p2 = np.radians(lat1), np.radians(lat2)
    dl = np.radians(np.asarray(lon2, dtype=float) - np.asarray(lon1, dtype=float))
    y = np.sin(dl) * np.cos(p2)
    x = np.cos(p1) * np.sin(p2) - np.sin(p1) * np.cos(p2) * np.cos(dl)
    return np.asarray(np.arctan2(y, x), dtype=float)


@dataclass(frozen=True, eq=False)
class FlownRoute:
    """Where the heading controls take the vehicle: times (s since epoch), lat/lon (deg, lon
    continuous), whether it touched land or left the field (the reason), the great-circle
    distance from the goal at the end (m), and how often the verification filled a NaN
    stencil at the coast with the nearest water current (`filled`)."""

    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    on_land: bool
    left_field: str | None
    endpoint_error_m: float
    filled: int = 0


class _OffField(Exception):
    pass


def _current(field_: FlowField, t: float, lat: float, lon: float) -> tuple[float, float]:
    try:
        return field_.velocity_at(t, lat, lon)
    except InvalidParameterError as exc:
        raise _OffField(str(exc)) from None


def fly_headings(
    field_: FlowField,
    speed: float,
    t: FloatArray,
    chi: FloatArray,
    start: tuple[float, float],
    goal: tuple[float, float],
    *,
    hold: bool = False,
    fill: Fill | None = None,
    is_land: Callable[[float, float], bool] | None = None,
    samples: int = 400,
) -> FlownRoute:
    """Fly compass headings chi(t) (rad) from `start` (lat, lon deg) at t[0] until t[-1].

    chi is linear in time between nodes, or held from each node to the next with `hold`
    (piecewise-constant controls; the integrator restarts at every node). Where the field is
    NaN, `fill` (if given) supplies the current and `is_land(lat, lon)` decides whether the
    point is land (then `on_land`); without `fill` any NaN is land (current taken as 0).
    """
    from scipy.integrate import solve_ivp

    tt = np.asarray(t, dtype=float)
    hd = np.unwrap(np.asarray(chi, dtype=float))
    R = EARTH_RADIUS_M
    state: dict[str, Any] = {"land": False, "filled": 0}
    lon_ref = float(start[1])

    def make_rhs(h_const: float | None) -> Callable[[float, FloatArray], FloatArray]:
        def rhs(s: float, z: FloatArray) -> FloatArray:
            h = h_const if h_const is not None else float(np.interp(s, tt, hd))
            lat, lon = math.degrees(z[0]), math.degrees(z[1])
            u, v = _current(field_, s, lat, lon)
            if not (math.isfinite(u) and math.isfinite(v)):
                if fill is None:
                    state["land"] = True
                    u, v = 0.0, 0.0
                else:
                    state["filled"] += 1
                    if is_land is not None and is_land(lat, lon):
                        state["land"] = True
                    u, v = fill(s, lat, lon)
            cl = max(math.cos(z[0]), 1e-9)
            return np.array([(speed * math.cos(h) + v) / R, (speed * math.sin(h) + u) / (R * cl)])
        return rhs

    duration = float(tt[-1] - tt[0])
    if hold:
        pieces = [(tt[k], tt[k + 1], float(hd[k])) for k in range(tt.size - 1)]
    else:
        pieces = [(tt[0], tt[-1], None)]  # type: ignore[list-item]
    z = np.radians([start[0], lon_ref])
    ts_out, la_out, lo_out = [tt[:1]], [np.array([start[0]])], [np.array([lon_ref])]
    for a, b, h in pieces:
        if b <= a:
            continue
        n_eval = max(2, int(samples * (b - a) / max(duration, 1e-12)) + 1)
        try:
            sol = solve_ivp(make_rhs(h), (a, b), z, method="RK45", rtol=1e-7,
                            atol=1e-2 / R, t_eval=np.linspace(a, b, n_eval),
                            max_step=max(min(duration / 40.0, b - a), 1e-6))
        except _OffField as exc:
            return FlownRoute(tt, np.zeros(1), np.zeros(1), bool(state["land"]), str(exc),
                              math.inf, int(state["filled"]))
        if not sol.success:
            return FlownRoute(tt, np.zeros(1), np.zeros(1), bool(state["land"]), sol.message,
                              math.inf, int(state["filled"]))
        z = sol.y[:, -1]
        ts_out.append(sol.t[1:])
        la_out.append(np.degrees(sol.y[0, 1:]))
        lo_out.append(np.degrees(sol.y[1, 1:]))
    lat, lon = np.concatenate(la_out), np.concatenate(lo_out)
    err = float(gc_distance(lat[-1], lon[-1], goal[0], goal[1]))
    return FlownRoute(np.concatenate(ts_out), lat, lon, bool(state["land"]), None, err,
                      int(state["filled"]))


def crab_controls(
    field_: FlowField | Callable[[FloatArray, FloatArray, FloatArray], Any],
    speed: float,
    t0: float,
    lat: FloatArray,
    lon: FloatArray,
) -> tuple[FloatArray, FloatArray, bool]:
    """Hold the polyline (lat, lon deg) leg by leg at water speed V (module docstring).

    field_: a FlowField or a function (t, lat, lon) -> (u, v) arrays (NaN read as still water,
    the route's clearance keeps it off land). Returns the times at the vertices (s since
    epoch), the compass heading held on each leg (rad; the last repeated) and whether every
    leg could be held (|c_n| < V and s > 0; an impossible leg costs as if s = V / 100).
    Legs are timed in turn, each from the previous leg's arrival (the current at its midpoint
    at its midpoint time, one predictor-corrector pass).
    """
    la, lo = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    n = la.size
    length = gc_distance(la[:-1], lo[:-1], la[1:], lo[1:])
    # The leg's direction at its midpoint: the bearing from start to end, taken at the middle.
    mid_la = 0.5 * (la[:-1] + la[1:])
    mid_lo = 0.5 * (lo[:-1] + lo[1:])
    brg = gc_bearing(mid_la, mid_lo, la[1:], lo[1:])
    back = gc_bearing(mid_la, mid_lo, la[:-1], lo[:-1]) + math.pi
    brg = np.arctan2(np.sin(brg) + np.sin(back), np.cos(brg) + np.cos(back))
    de, dn = np.sin(brg), np.cos(brg)
    times = np.empty(n)
    times[0] = t0
    chi = np.empty(n)
    ok = True

    def current(tm: float, k: int) -> tuple[float, float]:
        if isinstance(field_, FlowField):
            u, v = field_.velocity(tm, mid_la[k], mid_lo[k])
        else:
            u, v = field_(np.array([tm]), mid_la[k:k + 1], mid_lo[k:k + 1])
        uu, vv = float(np.ravel(u)[0]), float(np.ravel(v)[0])
        return (uu if math.isfinite(uu) else 0.0), (vv if math.isfinite(vv) else 0.0)

    for k in range(n - 1):
        tm = times[k] + 0.5 * length[k] / speed
        for _ in range(2):
            u, v = current(tm, k)
            ct = u * de[k] + v * dn[k]
            cn = -u * dn[k] + v * de[k]
            root = speed * speed - cn * cn
            s = math.sqrt(max(root, 0.0)) + ct
            if root <= 0.0 or s <= 0.0:
                ok = False
                s = 0.01 * speed
            tm = times[k] + 0.5 * length[k] / s
        we, wn = s * de[k] - u, s * dn[k] - v
        chi[k] = math.atan2(we, wn)
        times[k + 1] = times[k] + length[k] / s
    chi[-1] = chi[-2] if n > 1 else 0.0
    return times, chi, ok


def straight_line_duration(
    field_: FlowField,
    speed: float,
    t0: float,
    start: tuple[float, float],
    goal: tuple[float, float],
    t_max: float,
) -> float | None:
    """Time (s) to hold the great circle start -> goal with a crab angle: ds/dt =
    sqrt(V^2 - c_n^2) + c_t along it; None if |c_n| >= V, the along speed is <= 0, the line
    crosses land or leaves the field, or it takes longer than t_max - t0."""
    held = _hold_line(field_, speed, t0, start, goal, t_max, dense=False)
    return None if held is None else held[0]


def straight_line_track(
    field_: FlowField,
    speed: float,
    t0: float,
    start: tuple[float, float],
    goal: tuple[float, float],
    t_max: float,
    samples: int = 200,
) -> tuple[float, FloatArray, FloatArray, FloatArray, FloatArray] | None:
    """The straight line with crab angle (`straight_line_duration`) as a track: (duration s,
    times s since epoch, lat, lon (deg), compass heading (rad) of the through-water velocity
    (`steering.crab` along the line's bearing) at `samples` times); None where the duration
    is None."""
    from glideplan.routing.steering import crab

    held = _hold_line(field_, speed, t0, start, goal, t_max, dense=True)
    if held is None:
        return None
    T, sol, point = held
    t = t0 + np.linspace(0.0, T, max(samples, 2))
    lat, lon, chi = (np.empty(t.size) for _ in range(3))
    for k, tk in enumerate(t):
        la, lo, b = point(float(sol.sol(tk)[0]) if sol is not None else 0.0)
        u, v = _current(field_, float(tk), la, lo)
        lat[k], lon[k], chi[k] = la, lo, crab(math.sin(b), math.cos(b), u, v, speed)
    lat[-1], lon[-1] = goal
    return T, t, lat, lon, chi


def _hold_line(
    field_: FlowField, speed: float, t0: float, start: tuple[float, float],
    goal: tuple[float, float], t_max: float, dense: bool,
) -> tuple[float, Any, Callable[[float], tuple[float, float, float]]] | None:
    """(duration s, the ODE solution of the arc length s(t) (None for a zero-length line),
    the point and bearing at s) of the line held with a crab angle; None (see
    `straight_line_duration`)."""
    from scipy.integrate import solve_ivp

    length = float(gc_distance(start[0], start[1], goal[0], goal[1]))
    b0 = float(gc_bearing(start[0], start[1], goal[0], goal[1])) if length > 0.0 else 0.0

    def point(s: float) -> tuple[float, float, float]:
        s = min(max(s, 0.0), length)
        la, lo = destination(start[0], start[1], b0, s)
        la2, lo2 = destination(start[0], start[1], b0, min(s + 1.0, length + 1.0))
        b = float(gc_bearing(la, lo, la2, lo2))
        return float(la), float(lo), b

    if length <= 0.0:
        return 0.0, None, point

    def rhs(t: float, s: FloatArray) -> FloatArray:
        la, lo, b = point(float(s[0]))
        u, v = _current(field_, t, la, lo)
        if not (math.isfinite(u) and math.isfinite(v)):
            raise _OffField("land on the line")
        ct = u * math.sin(b) + v * math.cos(b)
        cn = -u * math.cos(b) + v * math.sin(b)
        if abs(cn) >= speed:
            raise _OffField("cross current too strong")
        along = math.sqrt(speed * speed - cn * cn) + ct
        if along <= 0.0:
            raise _OffField("head current too strong")
        return np.array([along])

    def arrive(t: float, s: FloatArray) -> float:
        return float(s[0] - length)

    arrive.terminal = True  # type: ignore[attr-defined]
    try:
        sol = solve_ivp(rhs, (t0, t_max), np.zeros(1), rtol=1e-6, atol=1e-1,
                        events=arrive, max_step=max((t_max - t0) / 60.0, 1e-6),
                        dense_output=dense)
    except _OffField:
        return None
    if sol.t_events[0].size == 0:
        return None
    return float(sol.t_events[0][0] - t0), sol, point
