"""One landable's answer from the native search (`reach.native`): paths flown and verified.

Candidates: the straight glide from the start; the search's node path to the best node near
the field (least loss + straight glide from that node to the field, over the nodes within
NEAR_CELLS), flown as it is and string-pulled (`reach.flight.front_candidates`). The answer
is the candidate flown with the polar through the wind that keeps the en-route clearance
all along and arrives highest; reachable when it arrives at least the arrival height above
the field. Otherwise `short_by_m`: the altitude missing -- the arrival deficit of the best
path that stays above the terrain + clearance, or else the extra start altitude the straight
glide needs to keep the clearance and the arrival height (an upper bound: a detour may need
less). A field on missing terrain (void or no tile) is `terrain_missing`, not out of reach.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.flight import FlownPath, fly, front_candidates, rhumb
from glideplan.reach.model import Glide
from glideplan.reach.native import NativeSearch, node_path
from glideplan.reach.problem import Landable
from glideplan.reach.result import ReachPoint, flown_track
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = ["NEAR_CELLS", "native_point"]

FloatArray = NDArray[np.float64]

#: Nodes within this many cells of a field are tried as the last node before it.
NEAR_CELLS = 2


def _offset_m(path: FlownPath, lat0: float, lon0: float, lat1: float, lon1: float) -> float:
    """Largest distance (m) of the path's waypoints from the straight line start -> goal."""
    c = math.cos(math.radians(lat0))
    x = EARTH_RADIUS_M * c * np.radians(path.waypoints_lon - lon0)
    y = EARTH_RADIUS_M * np.radians(path.waypoints_lat - lat0)
    gx = EARTH_RADIUS_M * c * math.radians(lon1 - lon0)
    gy = EARTH_RADIUS_M * math.radians(lat1 - lat0)
    n = math.hypot(gx, gy)
    if n == 0:
        return float(np.max(np.hypot(x, y)))
    return float(np.max(np.abs(x * gy - y * gx) / n))


def _best_node(search: NativeSearch, t: Terrain, glide: Glide, lnd: Landable
               ) -> tuple[float, int, int] | None:
    """(loss at the field, row, column) through the best reached node near the field."""
    fi = (lnd.lat - t.lat[0]) / t.dlat
    fj = (lnd.lon - t.lon[0]) / t.dlon
    ny, nx = t.shape
    i0, j0 = round(fi), round(fj)
    best = None
    for i in range(max(i0 - NEAR_CELLS, 0), min(i0 + NEAR_CELLS, ny - 1) + 1):
        for j in range(max(j0 - NEAR_CELLS, 0), min(j0 + NEAR_CELLS, nx - 1) + 1):
            v = float(search.loss[i, j])
            if not math.isfinite(v):
                continue
            d, chi = rhumb(np.array(t.lat[i]), np.array(t.lon[j]), np.array(lnd.lat),
                           np.array(lnd.lon))
            r = float(glide.ratio_fast(float(chi)))
            tot = v + (float(d) / r if float(d) > 0 else 0.0)
            if math.isfinite(tot) and (best is None or tot < best[0]):
                best = (tot, i, j)
    return best


def _straight_shortfall(path: FlownPath, lnd: Landable, clearance: float, arrival_h: float
                        ) -> float:
    """Extra start altitude (m) the straight glide needs for both safety heights."""
    need = clearance - (path.altitude - path.ground)
    need = need[np.isfinite(need)]
    en_route = float(np.max(need)) if need.size else 0.0
    return max(en_route, lnd.elevation_m + arrival_h - path.arrival_altitude, 0.0)


def native_point(terrain: Terrain, start: tuple[float, float, float], glide: Glide,
                 search: NativeSearch, lnd: Landable, clearance: float, arrival_h: float,
                 spacing_m: float, true_terrain: Terrain | None = None) -> ReachPoint:
    """The landable's answer (module docstring). `terrain`: the search's; paths are flown
    over `true_terrain` (the unpooled DEM; default `terrain`)."""
    lat0, lon0, alt = start
    grid_terrain = terrain
    terrain = grid_terrain if true_terrain is None else true_terrain

    def empty(note: str, missing: bool = False, short: float | None = None,
              front: float | None = None) -> ReachPoint:
        return ReachPoint(lnd, False, None, None, None, False, None, False, front, None, None,
                          None, note, None, short_by_m=short, terrain_missing=missing)

    if not math.isfinite(float(terrain.elevation(lnd.lat, lnd.lon))):
        return empty("outside the terrain or on no data (a void or no tile): not judged",
                     missing=True)
    near = _best_node(search, grid_terrain, glide, lnd)
    front_alt = None if near is None else alt - near[0]
    straight = fly(glide, terrain, clearance, np.array([lat0, lnd.lat]),
                   np.array([lon0, lnd.lon]), alt)
    candidates = [straight]
    if near is not None:
        pla, plo = node_path(search, grid_terrain, near[1], near[2])
        la = np.concatenate([[lat0], pla, [lnd.lat]])
        lo = np.concatenate([[lon0], plo, [lnd.lon]])
        candidates += front_candidates(glide, terrain, clearance, la, lo, alt)
    ok = [c for c in candidates if math.isfinite(c.arrival_altitude)]
    clear = [c for c in ok if c.clear]
    if clear:
        best, verified = max(clear, key=lambda c: c.arrival_altitude), True
    else:
        above = [c for c in ok if c.min_clearance_m >= 0.0]
        if not above:
            missing = not np.all(np.isfinite(straight.ground))
            short = None if missing or not math.isfinite(straight.arrival_altitude) else \
                _straight_shortfall(straight, lnd, clearance, arrival_h)
            note = ("beyond reach (the straight glide meets the terrain"
                    + (" and crosses missing terrain)" if missing else ")"))
            return empty(note, short=short, front=front_alt)
        best, verified = max(above, key=lambda c: c.arrival_altitude), False
    margin = best.arrival_altitude - lnd.elevation_m - arrival_h
    reachable = verified and margin >= -1e-6
    if reachable:
        short = None
    elif verified:
        short = -margin
    else:
        short = _straight_shortfall(straight, lnd, clearance, arrival_h)
    offset = _offset_m(best, lat0, lon0, lnd.lat, lnd.lon)
    note = "" if reachable else (
        f"arrives below the arrival height: short by {short:.0f} m" if verified else
        f"no path found keeps the terrain clearance: short by {short:.0f} m (straight glide)")
    return ReachPoint(lnd, reachable, best.arrival_altitude, margin, best.distance_m,
                      offset > spacing_m, best, verified, front_alt, best.min_clearance_m,
                      best.endpoint_error_m, offset, note, flown_track(best, lat0, lon0),
                      short_by_m=short, terrain_missing=False)
