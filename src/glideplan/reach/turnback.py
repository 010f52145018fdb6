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
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M, check_latlon, rhumb_destination
from glideplan.reach.flight import FlownPath, fly, rhumb
from glideplan.reach.grid import ReachGrid, reach_grid
from glideplan.reach.model import Glide
from glideplan.reach.problem import Landable, ReachProblem
from glideplan.reach.turnback_search import _Prober, _search, grid_contains
from glideplan.results import Outcome, Reason
from glideplan.sailplane.polar import SailplanePolar
from glideplan.solution import Status
from glideplan.terrain.grid import Terrain
from glideplan.validation import check_finite

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["TurnbackResult", "turnback"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False, kw_only=True)
class TurnbackResult(Outcome):
    """The turn-back point: status SOLVED (found, return flown and clear) or UNREACHABLE
    (home is out of reach already at the start); distance_m out along the course; the point
    and the altitude there; the return's arrival altitude at home (flown) and its margin
    above home elevation + arrival height; reason (a `Reason`; `limited_by` its words):
    GLIDE_HOME ("glide home") or OUTBOUND_TERRAIN ("outbound terrain")
    (the outbound glide itself meets terrain + clearance first); outbound and return
    flights; probes: (s, reachable) of the search. safety_height: the arrival height (as
    `ReachResult`); terrain_clearance, arrival_height: the two heights (m; None: both are
    safety_height, results built before the two heights existed)."""

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
    outbound: FlownPath | None
    back: FlownPath | None
    probes: tuple[tuple[float, bool], ...]
    terrain: Terrain | None
    resolution_m: float
    timings: dict[str, float] = field(default_factory=dict)
    terrain_clearance: float | None = None
    arrival_height: float | None = None

    @property
    def limited_by(self) -> str:
        """What limits the distance, in words ("glide home", "outbound terrain", "terrain
        edge", "terrain on the way home", "search budget"; "home out of reach")."""
        return "" if self.reason is None else _phrase(self.reason)

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
            **super().to_dict(),
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
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """Map (terrain, outbound, turn-back point, return) and the altitude profile."""
        from glideplan.reach.plot import plot_turnback
        from glideplan.results import as_figure

        return as_figure(plot_turnback(self, ax=ax, **kwargs))


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


@dataclass(frozen=True, eq=False)
class TurnbackRequest:
    """The turn-back problem, checked: start (lat, lon, ALT m), compass course (deg), home,
    the glide (polar, MC, wind), the terrain (None: flat at home's elevation), the two
    heights (m) and the search's resolution (m; None: the terrain's)."""

    start: tuple[float, float, float]
    course_deg: float
    home: Landable
    glide: Glide
    terrain: Terrain | None
    clearance_m: float
    arrival_m: float
    resolution_m: float | None


@dataclass(frozen=True, eq=False)
class _Outbound:
    """The outbound glide along the course: start, direction chi (rad CCW from east) and the
    glide ratio r_out; `at(s)` the point s metres out and its altitude ALT - s / r_out."""

    lat0: float
    lon0: float
    alt: float
    chi: float
    r_out: float

    def at(self, s: float) -> tuple[float, float, float]:
        la, lo = rhumb_destination(self.lat0, self.lon0, self.chi, np.array(s))
        return float(la), float(lo), self.alt - s / self.r_out


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
    arrival; safety_height: the former single height, sets both (an explicit one wins).

    A pipeline: the request (`turnback_request`), the outbound limits (`_outbound_limit`),
    the backward search and probes (`_Prober`), the search along the course (`_search`), the
    result (`_solved`)."""
    import time

    t_all = time.perf_counter()
    req = turnback_request(start, course_deg, home, polar, terrain=terrain, mc=mc, wind=wind,
                           safety_height=safety_height, safety_glide_ratio=safety_glide_ratio,
                           resolution_m=resolution_m, terrain_clearance=terrain_clearance,
                           arrival_height=arrival_height)
    problem, grid, way = _setup(req)
    warnings = list(problem.terrain.warnings)
    s_hi, limited = _outbound_limit(req, problem, grid, way)
    if limited is Reason.TERRAIN_EDGE:
        warnings.append("the outbound course leaves the terrain before the turn-back point: "
                        "the answer is clipped to the terrain's extent")
    t = time.perf_counter()
    prober = _Prober(req, problem, grid, way)
    warnings += prober.notes
    ok0, path0 = prober.probe(0.0) if prober.home_in else (False, None)
    if not ok0 or path0 is None:
        return _result(Status.UNREACHABLE, "home is out of reach already: turn back is not "
                       "enough", problem, req, 0.0, way.at(0.0), None,
                       Reason.HOME_OUT_OF_REACH, None, None, prober, warnings,
                       {"total_s": time.perf_counter() - t_all})
    s_star, back, limited = _search(prober, s_hi, path0, limited, warnings)
    timings = {"probes_s": time.perf_counter() - t}
    p_star = way.at(s_star)
    outbound = fly(req.glide, problem.terrain, req.clearance_m,
                   np.array([way.lat0, p_star[0]]), np.array([way.lon0, p_star[1]]), way.alt)
    timings["total_s"] = time.perf_counter() - t_all
    margin = back.arrival_altitude - req.home.elevation_m - req.arrival_m
    if (limited is Reason.GLIDE_HOME and margin > 1.0
            and back.min_clearance_m < req.clearance_m + 1.0):
        limited = Reason.TERRAIN_ON_THE_WAY_HOME
    msg = (f"turn back after {s_star / 1000:.2f} km along {req.course_deg:g} deg at "
           f"{p_star[2]:.0f} m: home reached at {back.arrival_altitude:.0f} m "
           f"({margin:+.1f} m over the arrival height); limited by {_phrase(limited)}")
    return _result(Status.SOLVED, msg, problem, req, s_star, p_star, outbound, limited, back,
                   margin, prober, warnings, timings)


def turnback_request(
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
) -> TurnbackRequest:
    """`turnback`'s arguments checked into a `TurnbackRequest` (bad input raises
    `InvalidParameterError` naming the parameter)."""
    from glideplan.reach.solve import two_heights

    course = check_finite("course", course_deg)
    if not isinstance(home, Landable):
        if len(home) != 3:
            raise InvalidParameterError("home", home, "must be (lat, lon, elevation_m)")
        check_latlon(home[0], home[1], "home")
        home = Landable("HOME", float(home[0]), float(home[1]), float(home[2]))
    clear_h, arrive_h = two_heights(safety_height, terrain_clearance, arrival_height)
    glide = Glide(polar, mc, wind, safety_glide_ratio)
    return TurnbackRequest((float(start[0]), float(start[1]), float(start[2])), course, home,
                           glide, terrain, clear_h, arrive_h, resolution_m)


def _setup(req: TurnbackRequest) -> tuple[ReachProblem, ReachGrid, _Outbound]:
    """The reach problem (flat ground without terrain), its grid and the outbound glide."""
    lat0, lon0, alt = req.start
    home, glide = req.home, req.glide
    terrain = req.terrain
    if terrain is None:
        reach = max(alt - home.elevation_m, 0.0) * glide.max_ratio
        terrain = _flat(home, req.start, reach + 5000.0)
    problem = ReachProblem(terrain, req.start, glide, (home,), req.arrival_m, req.resolution_m)
    if not math.isfinite(float(terrain.elevation(home.lat, home.lon))):
        raise InvalidParameterError("home", (home.lat, home.lon), "lies outside the terrain")
    grid = reach_grid(problem, glide.max_ratio)
    chi = math.radians(90.0 - req.course_deg)
    r_out = float(glide.along(np.array([chi])).ratio[0])
    if not (math.isfinite(r_out) and r_out > 0):
        raise InvalidParameterError("course", req.course_deg,
                                    "the wind allows no progress along it")
    return problem, grid, _Outbound(lat0, lon0, alt, chi, r_out)


def _outbound_limit(req: TurnbackRequest, problem: ReachProblem, grid: ReachGrid,
                    way: _Outbound) -> tuple[float, Reason]:
    """The upper bound s_hi of the turn-back distance and what sets it: where the outbound
    glide loses the clearance (OUTBOUND_TERRAIN) or leaves the data (TERRAIN_EDGE), or the
    straight glide home without terrain (GLIDE_HOME; bisection on its margin)."""
    home, fine = req.home, problem.terrain
    # within s_max: beyond it the glider is below home elevation + arrival height already
    s_max = max((way.alt - home.elevation_m - req.arrival_m) * way.r_out, 0.0)
    step = min(fine.spacing_m) / 3.0
    ss = np.linspace(0.0, s_max, max(2, math.ceil(s_max / step) + 1))
    la_s, lo_s = rhumb_destination(way.lat0, way.lon0, way.chi, ss)
    ground = fine.elevation(la_s, lo_s)
    inside = np.isfinite(ground) & np.asarray(grid_contains(grid, la_s, lo_s))
    clear = np.where(inside, way.alt - ss / way.r_out - np.where(inside, ground, 0.0), -np.inf)
    bad = ~(clear >= req.clearance_m - 1e-6)
    first_bad = int(np.argmax(bad))
    s_hit = float(ss[max(first_bad - 1, 0)]) if np.any(bad) else s_max
    hit_edge = bool(np.any(bad)) and not bool(inside[first_bad])

    def straight_margin(s: float) -> float:
        la, lo, a = way.at(s)
        d, c = rhumb(np.array(la), np.array(lo), np.array(home.lat), np.array(home.lon))
        r = float(req.glide.ratio(float(c))[0]) if float(d) > 0 else 1.0
        if not (math.isfinite(r) and r > 0):
            return -math.inf
        return a - float(d) / r - home.elevation_m - req.arrival_m

    lo_b, hi_b = 0.0, s_max
    if straight_margin(0.0) < 0:
        hi_b = 0.0
    else:
        for _ in range(80):
            mid = 0.5 * (lo_b + hi_b)
            lo_b, hi_b = (mid, hi_b) if straight_margin(mid) >= 0 else (lo_b, mid)
        hi_b = lo_b
    if s_hit < hi_b:
        return s_hit, Reason.TERRAIN_EDGE if hit_edge else Reason.OUTBOUND_TERRAIN
    return hi_b, Reason.GLIDE_HOME


def _phrase(reason: Reason) -> str:
    """The reason as the words of `limited_by` ("glide home", "outbound terrain", ...)."""
    return reason.value.replace("_", " ")


def _result(status: Status, message: str, problem: ReachProblem, req: TurnbackRequest,
            s: float, p: tuple[float, float, float], outbound: FlownPath | None,
            reason: Reason, back: FlownPath | None, margin: float | None, prober: _Prober,
            warnings: list[str], timings: dict[str, float]) -> TurnbackResult:
    return TurnbackResult(
        status=status, message=message, reason=reason, start=problem.start, home=req.home,
        course_deg=req.course_deg, safety_height=problem.safety_height, glide=req.glide,
        distance_m=s, lat=p[0], lon=p[1], altitude_m=p[2],
        arrival_altitude_m=None if back is None else back.arrival_altitude,
        arrival_margin_m=margin, outbound=outbound, back=back,
        probes=tuple(prober.probes), terrain=problem.terrain, resolution_m=prober.spacing,
        warnings=tuple(warnings), timings=timings, terrain_clearance=req.clearance_m,
        arrival_height=problem.safety_height)
