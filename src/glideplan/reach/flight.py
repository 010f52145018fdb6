"""Flying a path through the wind with the polar: legs, string pulling, the verified track.

A path is a chain of waypoints joined by rhumb lines (constant bearing; on the sphere of
radius R). Each leg is flown at the airspeed and air heading `Glide.along` gives for its
ground direction chi (crabbing so the ground track stays on the leg). With those constant
controls the equations of motion

    d lat/dt = v_n / R,  d lon/dt = v_e / (R cos lat),  dh/dt = -w_R(V),
    (v_e, v_n) = V (cos psi, sin psi) + W

have the closed-form solution lat(t) = lat_1 + v_n t / R, lon(t) = lon_1 + (v_e / v_n)
(Psi(lat(t)) - Psi(lat_1)) with Psi(lat) = ln tan(pi/4 + lat/2) (v_n = 0: lon_1 +
v_e t / (R cos lat_1)), h(t) = h_1 - w t, so verification integrates exactly and the
endpoint error measures only the controls. Terrain clearance h - z(lat, lon) (bilinear
terrain) is checked at samples every third of the terrain's spacing.

String pulling: from each waypoint the farthest later waypoint whose straight leg clears
terrain + safety all along (altitude carried from the start) is taken next. In a uniform
wind the cost of a leg is |leg| / r(chi) with r the gauge of a convex set, so a straight leg
never costs more than the sub-path it replaces (triangle inequality): the pulled path is
never worse than the front's. Each corner then slides towards the chord of its neighbours
and by a pattern search (8 directions, halving steps to 1 m) while its two legs stay clear
and lose less altitude: the taut string past the terrain it must avoid. Legs are checked on
straight lat/lon chords, the flight on the exact rhumb lines; next to steep terrain these
differ by a fraction of a metre, so the pulling asks for a small extra margin
(PULL_MARGINS_M, tried in turn until the flown path keeps the safety height).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.model import Glide
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = ["PULL_MARGINS_M", "FlownPath", "fly", "front_candidates", "pull_string", "rhumb"]

FloatArray = NDArray[np.float64]
R = EARTH_RADIUS_M
_TOL = 1e-6  # m: clearance round-off allowed
#: Extra clearance (m) the string pulling asks of its legs, tried in turn until the pulled
#: path, flown, keeps the safety height: the pulling samples straight lat/lon chords, the
#: flight the exact rhumb lines, and next to steep terrain they can differ by a fraction of
#: a metre.
PULL_MARGINS_M = (1.0, 10.0, 50.0)


def _psi(lat_rad: FloatArray) -> FloatArray:
    return np.log(np.tan(0.25 * np.pi + 0.5 * lat_rad))


def rhumb(lat1: FloatArray, lon1: FloatArray, lat2: FloatArray, lon2: FloatArray
          ) -> tuple[FloatArray, FloatArray]:
    """(distance m, direction chi rad CCW from east) of the rhumb lines P1 -> P2 (degrees)."""
    p1, p2 = np.radians(lat1), np.radians(lat2)
    dl = np.radians(np.asarray(lon2, float) - np.asarray(lon1, float))
    dphi = p2 - p1
    dpsi = _psi(p2) - _psi(p1)
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.where(np.abs(dpsi) > 1e-12, dphi / np.where(dpsi == 0, 1.0, dpsi), np.cos(p1))
    east, north = q * dl, dphi
    return R * np.hypot(east, north), np.arctan2(north, east)


def _leg_positions(lat1: float, lon1: float, ve: float, vn: float, t: FloatArray
                   ) -> tuple[FloatArray, FloatArray]:
    """Closed-form solution of the equations of motion (module docstring), degrees."""
    p1 = math.radians(lat1)
    lat = p1 + vn * t / R
    if abs(vn) > 1e-12 * max(abs(ve), 1.0):
        lon = math.radians(lon1) + (ve / vn) * (_psi(lat) - _psi(np.array(p1)))
    else:
        lon = math.radians(lon1) + ve * t / (R * math.cos(p1))
    return np.degrees(lat), np.degrees(lon)


@dataclass(frozen=True, eq=False)
class FlownPath:
    """A path flown and checked. Arrays along the samples: t (s), lat, lon (deg), altitude
    (m MSL), ground (terrain m), heading (air heading, rad CCW from east), leg index.
    Waypoints: lat/lon of the leg ends. distance_m along the path; endpoint_error_m between
    where the integrated flight ends and the last waypoint; min_clearance_m (altitude -
    terrain, over the samples); clear: >= safety everywhere."""

    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    altitude: FloatArray
    ground: FloatArray
    heading: FloatArray
    speed: FloatArray
    waypoints_lat: FloatArray
    waypoints_lon: FloatArray
    distance_m: float
    endpoint_error_m: float
    min_clearance_m: float
    clear: bool

    @property
    def arrival_altitude(self) -> float:
        return float(self.altitude[-1])


def _sample_step(terrain: Terrain) -> float:
    ex, ey = terrain.spacing_m
    return min(ex, ey) / 3.0


def leg_clear(glide: Glide, terrain: Terrain, safety: float, lat1: float, lon1: float,
              h1: float, lat2: float, lon2: float) -> tuple[bool, float, float]:
    """(clear, altitude at the end, min clearance) of one straight leg from altitude h1."""
    dd, chi = rhumb(np.array(lat1), np.array(lon1), np.array(lat2), np.array(lon2))
    d = float(dd)
    if d == 0.0:
        return True, h1, h1 - float(terrain.elevation(lat1, lon1))
    r = float(glide.ratio_fast(float(chi)))
    if not (math.isfinite(r) and r > 0):
        return False, -math.inf, -math.inf
    n = max(2, math.ceil(d / _sample_step(terrain)) + 1)
    f = np.linspace(0.0, 1.0, n)
    la = lat1 + f * (lat2 - lat1)  # the rhumb line, to the sampling's accuracy
    lo = lon1 + f * (lon2 - lon1)
    h = h1 - f * d / r
    clearance = h - terrain.elevation(la, lo)
    mc = float(np.min(np.where(np.isfinite(clearance), clearance, -np.inf)))
    return mc >= safety - _TOL, h1 - d / r, mc


def pull_string(glide: Glide, terrain: Terrain, safety: float, lat: FloatArray,
                lon: FloatArray, h0: float, max_points: int = 300) -> tuple[FloatArray, FloatArray]:
    """Waypoints of the pulled path (module docstring); the first and last are kept. Legs
    must keep `safety` (pass the safety height plus a margin, `front_candidates`)."""
    la, lo = np.asarray(lat, float), np.asarray(lon, float)
    if la.size > max_points:
        keep = np.unique(np.linspace(0, la.size - 1, max_points).round().astype(int))
        la, lo = la[keep], lo[keep]
    n = la.size
    out = [0]
    i, h = 0, h0
    while i < n - 1:
        j_ok, h_ok = i + 1, None
        for j in range(n - 1, i, -1):
            ok, hj, _ = leg_clear(glide, terrain, safety, la[i], lo[i], h, la[j], lo[j])
            if ok:
                j_ok, h_ok = j, hj
                break
        if h_ok is None:  # no clear leg: keep the front's next point (verification reports it)
            _, h_ok, _ = leg_clear(glide, terrain, safety, la[i], lo[i], h, la[j_ok], lo[j_ok])
        out.append(j_ok)
        i, h = j_ok, h_ok
    return _tighten(glide, terrain, safety, la[out], lo[out], h0)


def _tighten(glide: Glide, terrain: Terrain, safety: float, la: FloatArray, lo: FloatArray,
             h0: float, passes: int = 3, bisections: int = 16) -> tuple[FloatArray, FloatArray]:
    """Slide each interior waypoint towards the straight line between its neighbours as far
    as both its legs stay clear (bisection): the pulled path's corners move onto the
    terrain they go round. Shorter legs arrive higher, so later legs stay clear."""
    la, lo = la.copy(), lo.copy()
    for _ in range(passes):
        h = h0
        for k in range(1, la.size - 1):
            # target: the point of the chord P(k-1) P(k+1) nearest P(k) (in lat/lon degrees,
            # scaled by cos(lat) in longitude)
            c = math.cos(math.radians(la[k]))
            ax, ay = lo[k - 1] * c, la[k - 1]
            bx, by = lo[k + 1] * c, la[k + 1]
            px, py = lo[k] * c, la[k]
            dx, dy = bx - ax, by - ay
            t = 0.0 if dx == dy == 0 else min(max(((px - ax) * dx + (py - ay) * dy)
                                                   / (dx * dx + dy * dy), 0.0), 1.0)
            tx, ty = ax + t * dx, ay + t * dy
            lo_lam, hi_lam = 0.0, 1.0
            for _ in range(bisections):
                lam = 0.5 * (lo_lam + hi_lam)
                qx, qy = px + lam * (tx - px), py + lam * (ty - py)
                ok1, hq, _ = leg_clear(glide, terrain, safety, la[k - 1], lo[k - 1], h, qy,
                                       qx / c)
                ok2 = ok1 and leg_clear(glide, terrain, safety, qy, qx / c, hq, la[k + 1],
                                        lo[k + 1])[0]
                lo_lam, hi_lam = (lam, hi_lam) if ok2 else (lo_lam, lam)
            if lo_lam > 0:
                la[k] = py + lo_lam * (ty - py)
                lo[k] = (px + lo_lam * (tx - px)) / c
            la[k], lo[k] = _pattern_search(glide, terrain, safety, la, lo, k, h)
            h = leg_clear(glide, terrain, safety, la[k - 1], lo[k - 1], h, la[k], lo[k])[1]
    return la, lo


def _pattern_search(glide: Glide, terrain: Terrain, safety: float, la: FloatArray,
                    lo: FloatArray, k: int, h: float, min_step_m: float = 1.0
                    ) -> tuple[float, float]:
    """Move waypoint k (8 directions, steps halving from a terrain spacing x 4 to
    `min_step_m`) while the altitude lost on its two legs drops and both stay clear: the
    corner slides along the terrain it goes round to where the taut string touches it."""
    ex, ey = terrain.spacing_m
    step = 4.0 * max(ex, ey)
    c = math.cos(math.radians(la[k]))
    dirs = [(math.cos(a), math.sin(a)) for a in np.linspace(0, 2 * np.pi, 8, endpoint=False)]

    def loss(y: float, x: float) -> float:
        ok1, h1, _ = leg_clear(glide, terrain, safety, la[k - 1], lo[k - 1], h, y, x)
        if not ok1:
            return math.inf
        ok2, h2, _ = leg_clear(glide, terrain, safety, y, x, h1, la[k + 1], lo[k + 1])
        return h - h2 if ok2 else math.inf

    y0, x0 = float(la[k]), float(lo[k])
    best = loss(y0, x0)
    if not math.isfinite(best):
        return y0, x0
    while step >= min_step_m:
        moved = False
        for ux, uy in dirs:
            y = y0 + math.degrees(uy * step / EARTH_RADIUS_M)
            x = x0 + math.degrees(ux * step / (EARTH_RADIUS_M * c))
            f = loss(y, x)
            if f < best - 1e-9:
                best, y0, x0, moved = f, y, x, True
                break
        if not moved:
            step *= 0.5
    return y0, x0


def front_candidates(glide: Glide, terrain: Terrain, safety: float, lat: FloatArray,
                     lon: FloatArray, h0: float) -> list[FlownPath]:
    """The front's path flown as it is, then string-pulled (with the margins of
    PULL_MARGINS_M until one keeps the safety height) and flown."""
    out = [fly(glide, terrain, safety, lat, lon, h0)]
    for margin in PULL_MARGINS_M:
        wla, wlo = pull_string(glide, terrain, safety + margin, lat, lon, h0)
        flown = fly(glide, terrain, safety, wla, wlo, h0)
        out.append(flown)
        if flown.clear:
            break
    return out


def fly(glide: Glide, terrain: Terrain, safety: float, lat: FloatArray, lon: FloatArray,
        h0: float, t0: float = 0.0) -> FlownPath:
    """Fly the rhumb legs between waypoints (lat, lon) from altitude h0 (module docstring)."""
    la_w, lo_w = np.asarray(lat, float), np.asarray(lon, float)
    d, chi = rhumb(la_w[:-1], lo_w[:-1], la_w[1:], lo_w[1:])
    keep = np.concatenate([[True], d > 1e-9])
    la_w, lo_w = la_w[keep], lo_w[keep]
    d, chi = rhumb(la_w[:-1], lo_w[:-1], la_w[1:], lo_w[1:])
    step = _sample_step(terrain)
    ts, las, los, hs, hd, vs = [np.array([t0])], [la_w[:1]], [lo_w[:1]], [np.array([h0])], [], []
    t, h = t0, h0
    cur_lat, cur_lon = float(la_w[0]), float(lo_w[0])
    if d.size:
        gg = glide.along(chi)
    for k in range(d.size):
        v, psi = float(gg.speed[k]), float(gg.heading[k])
        if not math.isfinite(v):  # no progress possible along this leg
            return _failed(la_w, lo_w, t0, h0, terrain)
        ve = v * math.cos(psi) + glide.wind[0]
        vn = v * math.sin(psi) + glide.wind[1]
        w = float(glide.sink(v))
        duration = float(d[k]) / math.hypot(ve, vn)
        n = max(1, math.ceil(float(d[k]) / step))
        tt = np.linspace(0.0, duration, n + 1)[1:]
        a, b = _leg_positions(cur_lat, cur_lon, ve, vn, tt)
        ts.append(t + tt)
        las.append(a)
        los.append(b)
        hs.append(h - w * tt)
        hd.append(np.full(n, psi))
        vs.append(np.full(n, v))
        t, h = t + duration, h - w * duration
        cur_lat, cur_lon = float(a[-1]), float(b[-1])
    lat_s, lon_s = np.concatenate(las), np.concatenate(los)
    alt = np.concatenate(hs)
    heading = np.concatenate([hd[0][:1], *hd]) if hd else np.zeros(1)
    speed = np.concatenate([vs[0][:1], *vs]) if vs else np.zeros(1)
    ground = terrain.elevation(lat_s, lon_s)
    clearance = np.where(np.isfinite(ground), alt - ground, -np.inf)
    miss, _ = rhumb(np.array(cur_lat), np.array(cur_lon), la_w[-1:], lo_w[-1:])
    mc = float(np.min(clearance))
    return FlownPath(np.concatenate(ts), lat_s, lon_s, alt, ground, heading, speed, la_w, lo_w,
                     float(np.sum(d)), float(miss[0]), mc, mc >= safety - _TOL)


def _failed(la: FloatArray, lo: FloatArray, t0: float, h0: float, terrain: Terrain) -> FlownPath:
    one = np.array
    return FlownPath(one([t0]), la[:1], lo[:1], one([h0]), terrain.elevation(la[:1], lo[:1]),
                     one([0.0]), one([0.0]), la, lo, math.inf, math.inf, -math.inf, False)
