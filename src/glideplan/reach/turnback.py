"""`turnback`: how far out along a course the glider can fly and still glide home.

Outbound: from the start (lat, lon, ALT) along the compass `course` at the speed to fly for
that direction (`Glide.along`): after s metres it is at P(s) (rhumb line) at altitude
A(s) = ALT - s / r_out. The turn-back point is the largest s (the first, going out) from
which home is still reachable: from (P(s), A(s)) a path to home that keeps
A - terrain >= clearance all along and arrives >= home elevation + arrival height. Two
heights as in `glide_reach` (XCSoar/LK8000): the en-route terrain clearance (default 150 m)
for every clearance check out and back and the search's terrain floor, the arrival height
(default 300 m) only at home; the former single `safety_height` sets both (`two_heights`).

One backward search from home on the terrain's own grid (`reach.native.native_back_search`):
the least altitude need(x) at every node from which home is reached keeping the clearance
all along and arriving at home elevation + arrival height. Over a ridge the need is floored
by the terrain (need >= terrain + clearance along every edge), which a Dijkstra expresses
exactly as need_v = max(need_u + loss, floor along the edge) (non-decreasing, so the search
stays exact); a front's block times could not, which is why the former search ran one
forward front per probe and, at fine grids, stopped after 24 probes a cell apart.

Search: the straight glide home without terrain bounds s from above (terrain only adds
constraints), as does the first point where the outbound glide itself loses the clearance
over the terrain (s_hi). The course is walked in thirds of a DEM cell to the first
point where A(s) < need(P(s)) (the first crossing); the return from the last point before
it is the node path string-pulled and flown (`reach.flight`); if that flight does not
verify, bisection on s with flown probes. Then the verified return's tail is flown from
further out (bisection to 1 m) and a probe a third of a cell beyond asks whether another
way works (the graph is conservative by <= 0.76 %), until one fails. At most _MAX_PROBES
such steps: a stop there is reported as `limited_by` "search budget", the distance then a
lower bound.
Without terrain the ground is flat at the home's elevation and the straight glide home is
optimal (uniform wind, convex set of velocities): no front is run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M, check_latlon, rhumb_destination
from glideplan.reach.flight import FlownPath, fly, front_candidates, rhumb
from glideplan.reach.grid import ReachGrid, cell_nodes, reach_grid
from glideplan.reach.model import Glide
from glideplan.reach.problem import Landable, ReachProblem
from glideplan.sailplane.polar import SailplanePolar
from glideplan.solution import Status
from glideplan.terrain.grid import Terrain
from glideplan.validation import check_finite

__all__ = ["TurnbackResult", "turnback"]

FloatArray = NDArray[np.float64]
_REFINE_TOL_M = 1.0
_MAX_PROBES = 60


@dataclass(frozen=True, eq=False)
class TurnbackResult:
    """The turn-back point: status SOLVED (found, return flown and clear) or UNREACHABLE
    (home is out of reach already at the start); distance_m out along the course; the point
    and the altitude there; the return's arrival altitude at home (flown) and its margin
    above home elevation + arrival height; limited_by: "glide home" or "outbound terrain"
    (the outbound glide itself meets terrain + clearance first); outbound and return
    flights; probes: (s, reachable) of the search. safety_height: the arrival height (as
    `ReachResult`); terrain_clearance, arrival_height: the two heights (m; None: both are
    safety_height, results built before the two heights existed)."""

    status: Status
    message: str
    start: tuple[float, float, float]
    home: Landable
    course_deg: float
    safety_height: float
    glide: Glide
    distance_m: float
    lat: float
    lon: float
    altitude_m: float
    arrival_altitude_m: float | None
    arrival_margin_m: float | None
    limited_by: str
    outbound: FlownPath | None
    back: FlownPath | None
    probes: tuple[tuple[float, bool], ...]
    terrain: Terrain | None
    resolution_m: float
    warnings: tuple[str, ...] = ()
    timings: dict[str, float] = field(default_factory=dict)
    terrain_clearance: float | None = None
    arrival_height: float | None = None

    @property
    def ok(self) -> bool:
        return self.status is Status.SOLVED

    def to_dict(self) -> dict[str, Any]:
        def num(x: float | None) -> float | None:
            return None if x is None or not math.isfinite(x) else float(x)

        def profile(path: FlownPath | None, s0: float) -> dict[str, list[float]] | None:
            if path is None:
                return None
            d, _ = rhumb(path.lat[:-1], path.lon[:-1], path.lat[1:], path.lon[1:])
            return {"distance_m": (s0 + np.concatenate([[0.0], np.cumsum(d)])).tolist(),
                    "altitude_m": path.altitude.tolist(), "lat": path.lat.tolist(),
                    "lon": path.lon.tolist()}

        lat, lon, alt = self.start
        return {
            "status": self.status.value,
            "message": self.message,
            "start": {"lat": lat, "lon": lon, "altitude_m": alt},
            "home": {"name": self.home.name, "lat": self.home.lat, "lon": self.home.lon,
                     "elevation_m": self.home.elevation_m},
            "course_deg": self.course_deg,
            "safety_height_m": self.safety_height,
            "terrain_clearance_m": (self.safety_height if self.terrain_clearance is None
                                    else self.terrain_clearance),
            "arrival_height_m": (self.safety_height if self.arrival_height is None
                                 else self.arrival_height),
            "glide": self.glide.to_dict(),
            "turnback": {"distance_m": self.distance_m, "lat": self.lat, "lon": self.lon,
                         "altitude_m": self.altitude_m},
            "arrival_altitude_m": num(self.arrival_altitude_m),
            "arrival_margin_m": num(self.arrival_margin_m),
            "return_distance_m": None if self.back is None else self.back.distance_m,
            "limited_by": self.limited_by,
            "grid_resolution_m": self.resolution_m,
            "outbound": profile(self.outbound, 0.0),
            "return": profile(self.back, self.distance_m),
            "probes": [{"distance_m": s, "reachable": ok} for s, ok in self.probes],
            "timings_s": dict(self.timings),
            "warnings": list(self.warnings),
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Map (terrain, outbound, turn-back point, return) and the altitude profile."""
        from glideplan.reach.plot import plot_turnback

        return plot_turnback(self, ax=ax, **kwargs)


def _flat(home: Landable, start: tuple[float, float, float], reach_m: float) -> Terrain:
    """Ground everywhere at the home's elevation (no terrain given): a grid about start and
    home wide enough for any glide from the start."""
    lat0, lon0 = start[0], start[1]
    dlat = math.degrees(1.1 * reach_m / EARTH_RADIUS_M) + 0.01
    dlon = dlat / max(math.cos(math.radians(abs(lat0) + dlat)), 1e-3)
    s, n = min(lat0, home.lat) - dlat, max(lat0, home.lat) + dlat
    w, e = min(lon0, home.lon) - dlon, max(lon0, home.lon) + dlon
    ny = nx = 801
    return Terrain(np.linspace(s, n, ny), np.linspace(w, e, nx),
                   np.full((ny, nx), home.elevation_m, dtype=np.float32))


def turnback(
    start: tuple[float, float, float],
    course_deg: float,
    home: tuple[float, float, float] | Landable,
    polar: SailplanePolar,
    *,
    terrain: Terrain | None = None,
    mc: float = 0.0,
    wind: tuple[float, float] = (0.0, 0.0),
    safety_height: float | None = None,
    safety_glide_ratio: float | None = None,
    resolution_m: float | None = None,
    terrain_clearance: float | None = None,
    arrival_height: float | None = None,
) -> TurnbackResult:
    """The turn-back point along compass `course_deg` from `start` = (lat, lon, ALT m) for
    `home` = (lat, lon, elevation m) (module docstring). Without terrain the ground is flat
    at the home's elevation. wind: (east, north) m/s towards. terrain_clearance (m, default
    150) kept above the terrain out and back; arrival_height (m, default 300) above home on
    arrival; safety_height: the former single height, sets both (an explicit one wins)."""
    import time

    from glideplan.reach.solve import two_heights

    t_all = time.perf_counter()
    course = check_finite("course", course_deg)
    if not isinstance(home, Landable):
        if len(home) != 3:
            raise InvalidParameterError("home", home, "must be (lat, lon, elevation_m)")
        check_latlon(home[0], home[1], "home")
        home = Landable("HOME", float(home[0]), float(home[1]), float(home[2]))
    clear_h, arrive_h = two_heights(safety_height, terrain_clearance, arrival_height)
    glide = Glide(polar, mc, wind, safety_glide_ratio)
    lat0, lon0, alt = float(start[0]), float(start[1]), float(start[2])
    warnings: list[str] = []
    use_front = terrain is not None
    if terrain is None:
        reach = max(alt - home.elevation_m, 0.0) * glide.max_ratio
        terrain = _flat(home, (lat0, lon0, alt), reach + 5000.0)
    warnings += list(terrain.warnings)
    problem = ReachProblem(terrain, (lat0, lon0, alt), glide, (home,), arrive_h,
                           resolution_m)
    if not math.isfinite(float(terrain.elevation(home.lat, home.lon))):
        raise InvalidParameterError("home", (home.lat, home.lon), "lies outside the terrain")
    grid = reach_grid(problem, glide.max_ratio)
    chi = math.radians(90.0 - course)
    out = glide.along(np.array([chi]))
    r_out = float(out.ratio[0])
    if not (math.isfinite(r_out) and r_out > 0):
        raise InvalidParameterError("course", course, "the wind allows no progress along it")
    fine = problem.terrain

    def P(s: float) -> tuple[float, float, float]:
        la, lo = rhumb_destination(lat0, lon0, chi, np.array(s))
        return float(la), float(lo), alt - s / r_out

    # outbound limit: where the outbound glide loses the clearance (or leaves the data),
    # within s_max: beyond it the glider is below home elevation + arrival height already
    s_max = (alt - home.elevation_m - arrive_h) * r_out
    if s_max <= 0:
        s_max = 0.0
    step = min(fine.spacing_m) / 3.0
    ss = np.linspace(0.0, s_max, max(2, math.ceil(s_max / step) + 1))
    la_s, lo_s = rhumb_destination(lat0, lon0, chi, ss)
    ground = fine.elevation(la_s, lo_s)
    inside = np.isfinite(ground) & np.asarray(grid_contains(grid, la_s, lo_s))
    clear = np.where(inside, alt - ss / r_out - np.where(inside, ground, 0.0), -np.inf)
    bad = ~(clear >= clear_h - 1e-6)
    first_bad = int(np.argmax(bad))
    s_hit = float(ss[max(first_bad - 1, 0)]) if np.any(bad) else s_max
    hit_edge = bool(np.any(bad)) and not bool(inside[first_bad])
    # straight glide home without terrain: an upper bound on the turn-back distance
    def straight_margin(s: float) -> float:
        la, lo, a = P(s)
        d, c = rhumb(np.array(la), np.array(lo), np.array(home.lat), np.array(home.lon))
        r = float(glide.ratio(float(c))[0]) if float(d) > 0 else 1.0
        if not (math.isfinite(r) and r > 0):
            return -math.inf
        return a - float(d) / r - home.elevation_m - arrive_h

    lo_b, hi_b = 0.0, s_max
    if straight_margin(0.0) < 0:
        hi_b = 0.0
    else:
        for _ in range(80):
            mid = 0.5 * (lo_b + hi_b)
            lo_b, hi_b = (mid, hi_b) if straight_margin(mid) >= 0 else (lo_b, mid)
        hi_b = lo_b
    s_hi = min(hi_b, s_hit)
    limited = (("terrain edge" if hit_edge else "outbound terrain") if s_hit < hi_b
               else "glide home")
    if limited == "terrain edge":
        warnings.append("the outbound course leaves the terrain before the turn-back point: "
                        "the answer is clipped to the terrain's extent")

    probes: list[tuple[float, bool]] = []
    spacing = grid.spacing_m  # the search's grid (the terrain's own unless pooled)
    t = time.perf_counter()
    home_in = bool(grid_contains(grid, np.array(home.lat), np.array(home.lon)))
    back_s = None
    if use_front and home_in:
        from glideplan.reach.grid import native_terrain
        from glideplan.reach.native import native_back_search

        sterrain, _, notes, _ = native_terrain(problem, glide.max_ratio, clear_h)
        warnings += notes
        spacing = max(sterrain.spacing_m)
        back_s = native_back_search(sterrain, (home.lat, home.lon,
                                               home.elevation_m + arrive_h),
                                    glide, clear_h, alt + 1.0)

    def probe(s: float) -> tuple[bool, FlownPath | None]:
        la, lo, a = P(s)
        cands = [fly(glide, fine, clear_h, np.array([la, home.lat]),
                     np.array([lo, home.lon]), a)]
        if back_s is not None:
            from glideplan.reach.native import back_path, need_at

            nd, i, j = need_at(back_s, sterrain, glide, la, lo)
            if math.isfinite(nd):
                bla, blo = back_path(back_s, sterrain, i, j)
                cands += front_candidates(glide, fine, clear_h,
                                          np.concatenate([[la], bla, [home.lat]]),
                                          np.concatenate([[lo], blo, [home.lon]]), a)
        good = [c for c in cands if c.clear and
                c.arrival_altitude - home.elevation_m - arrive_h >= -1e-6]
        best = max(good, key=lambda c: c.arrival_altitude) if good else None
        probes.append((s, best is not None))
        return best is not None, best

    ok0, path0 = probe(0.0) if home_in else (False, None)
    if not ok0:
        return _result(Status.UNREACHABLE, "home is out of reach already: turn back is not "
                       "enough", problem, home, course, glide, 0.0, P(0.0), None, "glide home",
                       None, None, probes, fine, spacing, warnings, {"total_s": time.perf_counter()
                                                                  - t_all}, clear_h)
    timings: dict[str, float] = {}

    def flight(s: float, tail_la: FloatArray, tail_lo: FloatArray) -> FlownPath:
        la, lo, a = P(s)
        return fly(glide, fine, clear_h, np.concatenate([[la], tail_la]),
                   np.concatenate([[lo], tail_lo]), a)

    def fine_ok(f: FlownPath) -> bool:
        return f.clear and f.arrival_altitude - home.elevation_m - arrive_h >= -1e-6

    def along_path(path: FlownPath, a_: float, b_: float) -> tuple[float, FlownPath]:
        """Largest s in [a_, b_] from which the path's tail (its waypoints after the first)
        still works, flown (bisection to 1 m); (a_, path) if not even at a_."""
        tail_la, tail_lo = path.waypoints_lat[1:], path.waypoints_lon[1:]
        best = flight(a_, tail_la, tail_lo)
        if not fine_ok(best):
            return a_, path
        end = flight(b_, tail_la, tail_lo)
        if fine_ok(end):
            return b_, end
        while b_ - a_ > _REFINE_TOL_M:
            mid = 0.5 * (a_ + b_)
            f = flight(mid, tail_la, tail_lo)
            if fine_ok(f):
                a_, best = mid, f
            else:
                b_ = mid
        return a_, best

    s_lo, back = 0.0, path0
    assert back is not None
    ok_hi, path_hi = probe(s_hi) if s_hi > 0 else (True, path0)
    if ok_hi and path_hi is not None:
        s_lo, back = s_hi, path_hi
    else:
        cell = min(sterrain.spacing_m) if back_s is not None else grid.spacing_m
        if back_s is not None:
            s_lo, back = _graph_crossing(back_s, sterrain, glide, P, s_hi, cell, probe,
                                         s_lo, back)
        # then the verified flights: the return path's tail flown from further out, and a
        # probe a third of a cell beyond, until the probe fails (the first crossing)
        for _ in range(_MAX_PROBES):
            s_lo, back = along_path(back, s_lo, s_hi)
            s_next = s_lo + cell / 3.0
            if s_next >= s_hi:
                break
            ok, path = probe(s_next)
            if not ok or path is None:
                break
            s_lo, back = s_next, path
        else:
            limited = "search budget"
            warnings.append(f"the search stopped after {_MAX_PROBES} probes: the turn-back "
                            f"point is at least {s_lo / 1000:.2f} km out (a lower bound)")
    timings["probes_s"] = time.perf_counter() - t
    s_star = s_lo
    outbound = fly(glide, fine, clear_h, np.array([lat0, P(s_star)[0]]),
                   np.array([lon0, P(s_star)[1]]), alt)
    timings["total_s"] = time.perf_counter() - t_all
    margin = back.arrival_altitude - home.elevation_m - arrive_h
    if limited == "glide home" and margin > 1.0 and back.min_clearance_m < clear_h + 1.0:
        limited = "terrain on the way home"
    msg = (f"turn back after {s_star / 1000:.2f} km along {course:g} deg at "
           f"{P(s_star)[2]:.0f} m: home reached at {back.arrival_altitude:.0f} m "
           f"({margin:+.1f} m over the arrival height); limited by {limited}")
    return _result(Status.SOLVED, msg, problem, home, course, glide, s_star, P(s_star),
                   outbound, limited, back, margin, probes, fine, spacing, warnings, timings,
                   clear_h)


def _graph_crossing(back_s: Any, sterrain: Terrain, glide: Glide, P: Any, s_hi: float,
                    cell: float, probe: Any, s_lo: float, back: FlownPath
                    ) -> tuple[float, FlownPath]:
    """The backward search's answer along the course, verified: walk s in thirds of a cell
    from 0 to the first point where the altitude there is below the altitude needed
    (`native.need_at`), then the largest s before it whose return flies clear (a probe there;
    if the flight does not verify, bisection on s with probes down to s_lo)."""
    from glideplan.reach.native import need_at

    ss = np.arange(0.0, s_hi, cell / 3.0)
    s_graph = s_lo
    for s in ss[1:]:
        la, lo, a = P(float(s))
        if need_at(back_s, sterrain, glide, la, lo)[0] > a:
            break
        s_graph = float(s)
    if s_graph <= s_lo:
        return s_lo, back
    ok, path = probe(s_graph)
    if ok and path is not None:
        return s_graph, path
    a_, b_ = s_lo, s_graph
    while b_ - a_ > cell / 3.0:
        mid = 0.5 * (a_ + b_)
        ok, path = probe(mid)
        if ok and path is not None:
            a_, back = mid, path
        else:
            b_ = mid
    return a_, back


def grid_contains(grid: ReachGrid, lat: FloatArray, lon: FloatArray) -> NDArray[np.bool_]:
    """Inside the front's grid (its nodes' extent)."""
    return ((lat >= grid.lat[0]) & (lat <= grid.lat[-1]) & (lon >= grid.lon[0])
            & (lon <= grid.lon[-1]))


def _special_nodes(grid: ReachGrid, pts: list[tuple[float, float]]) -> list[tuple[int, int]]:
    return cell_nodes(grid.lat, grid.lon, pts)


def _result(status: Status, message: str, problem: ReachProblem, home: Landable, course: float,
            glide: Glide, s: float, p: tuple[float, float, float], outbound: FlownPath | None,
            limited: str, back: FlownPath | None, margin: float | None,
            probes: list[tuple[float, bool]], terrain: Terrain, resolution_m: float,
            warnings: list[str], timings: dict[str, float], clear_h: float
            ) -> TurnbackResult:
    return TurnbackResult(
        status=status, message=message, start=problem.start, home=home, course_deg=course,
        safety_height=problem.safety_height, glide=glide, distance_m=s, lat=p[0], lon=p[1],
        altitude_m=p[2], arrival_altitude_m=None if back is None else back.arrival_altitude,
        arrival_margin_m=margin, limited_by=limited, outbound=outbound, back=back,
        probes=tuple(probes), terrain=terrain, resolution_m=resolution_m,
        warnings=tuple(warnings), timings=timings, terrain_clearance=clear_h,
        arrival_height=problem.safety_height)
