"""`route()`: the time-optimal route through a flow field, on the sphere, front to verified track.

A pipeline of phases (`glideplan.routing.phases`, each testable alone) driven by a frozen
`RouteSettings`:

    setup -> grid -> front -> backtrack -> refine -> verify

Acceptance: a route is solved only when its heading controls, integrated through the field
itself (not the grid), end within `endpoint_tolerance_m` of the goal, stay in the water and in
the field. The tolerance is one routing-grid spacing h (`endpoint_tolerance_cells` x h): the
front locates the arrival to within a cell and the grid route is a chain of points a cell
apart, so one cell is the resolution the grid answer claims. A route that misses by more is
NOT_VERIFIED (track and numbers kept, the miss in `message`).

Which route is returned: the grid route (the kernel's characteristic, each leg held with its
crab angle: its duration is the legs' times) or the Zermelo-shooting route started from it,
whichever verifies; the shooting route is kept unless it is slower than the grid route by more
than GRID_TIME_TOLERANCE (the front's own discretisation error).

Unreachable only when it is: the front stopped growing ("front_stopped"), reached the field's
extent ("field_extent") or time span ("time_span"), or the duration limit ("max_duration");
never because a box was too small (the window grows with the front).
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.results import Reason
from glideplan.routing.result import FrontMap, RouteResult
from glideplan.routing.settings import RouteSettings
from glideplan.solution import Status
from glideplan.track import Track

__all__ = ["ENDPOINT_TOLERANCE_CELLS", "GRID_TIME_TOLERANCE", "RouteResult", "RouteSettings",
           "route"]

#: A verified shooting route is kept unless it is slower than the grid route by more than
#: this fraction (the grid time's discretisation error); `message` states both times.
GRID_TIME_TOLERANCE = 5e-3

#: A route found that takes longer than the straight line with crab angle by more than this
#: fraction (the grid time's discretisation error) gives way to the line when the line
#: verifies and keeps the land clearance (a grid too coarse for the field: 12 cells across a
#: uniform 0.5 m/s current routed a 0.3 m/s vehicle in 23.7 h, the line takes 16.76 h).
STRAIGHT_MARGIN = GRID_TIME_TOLERANCE

#: Without refinement, a route rescued by tracking the characteristic (extract.rescue) is
#: used only within this fraction of the front's arrival (the front's own error in currents
#: faster than the vehicle, measured up to 4.6 % at 40 cells): a slower one would be a worse
#: path than the front's (a lagging vehicle swept off it), however well verified.
RESCUE_TIME_TOLERANCE = 0.05

#: The default verified endpoint error of a solved route, in routing-grid spacings.
ENDPOINT_TOLERANCE_CELLS = 1.0

_SETTING_NAMES = {f for f in RouteSettings.__dataclass_fields__}


def route(
    field_: Any,
    start: tuple[float, float],
    goal: tuple[float, float],
    speed: float,
    depart: Any = None,
    resolution: float | None = None,
    depth_range: tuple[float, float] | None = None,
    *,
    settings: RouteSettings | None = None,
    **overrides: Any,
) -> RouteResult:
    """Time-optimal route from `start` to `goal` (lat, lon degrees) at water speed `speed` (m/s).

    field_: a FlowField, or NetCDF/GRIB path(s) (read with `depth_range` (m, positive down));
    depart: datetime64, seconds since the field's epoch, or None (the field's first time);
    resolution: grid spacing (m); settings: `RouteSettings` (keyword overrides of its fields
    are accepted, e.g. `refine=False`, `land_clearance_m=500.0`). Raises InvalidParameterError
    for bad input; an unreachable goal is a result (`unreachable_reason` says why).
    """
    from glideplan.routing import extract, phases

    settings = _settings(settings, resolution, overrides)
    clock = _Clock()
    problem = phases.setup(field_, start, goal, speed, depart, depth_range, settings)
    warnings = list(problem.warnings)
    clock.lap("setup")
    common: dict[str, Any] = dict(
        start=problem.start, goal=problem.goal, speed=problem.speed, depart=problem.depart,
        depart_s=problem.t0, field_info=problem.field_.describe())
    if problem.distance_m <= 1e-6:  # start = goal
        return _coincident(problem, warnings, clock.stats, common)
    cone = extract.drift_cone(problem, phases.spacing_for(problem))
    if cone is not None:  # outside the drift cone: no front needed, at any resolution
        clock.lap("drift_cone")
        clock.stats["spacing_m"] = phases.spacing_for(problem)
        return RouteResult(status=Status.UNREACHABLE, message=cone.message,
                           warnings=tuple(warnings), best_distance_m=problem.distance_m,
                           reason=Reason(cone.reason), stats=clock.stats, **common)
    attempt = _on_grid(problem, clock, list(warnings), dict(common))
    if attempt.strong and attempt.result.status in (Status.NOT_VERIFIED, Status.UNREACHABLE):
        from glideplan.routing import finer_grid  # the grid too coarse for the current

        return finer_grid.finer(problem, attempt, lambda p: _on_grid(
            p, _Clock(), list(warnings), dict(common)))
    return attempt.result


def _on_grid(problem: Any, clock: _Clock, warnings: list[str],
             common: dict[str, Any]) -> Any:
    """Front, backtrack, refine and verify on the problem's grid: a `finer_grid.Attempt`
    (the result, the current's peak on the window against the vehicle's speed, the miss)."""
    from glideplan.routing import extract, phases
    from glideplan.routing.finer_grid import Attempt

    rg, fo, g0, tolerance = _front(problem, clock)
    warnings += [w for w in rg.warnings if w not in warnings]
    common.update(land_clearance_m=rg.clearance_m, endpoint_tolerance_m=tolerance,
                  front=FrontMap(rg.window.lat, rg.window.lon, fo.arrival - problem.t0,
                                 rg.obstacle.astype(float)))
    if fo.goal_time is None:
        res = _unreachable(problem, rg, fo, warnings, clock.stats, common)
        peak = rg.currents.peak_speed()  # the window's nodes over the levels held
        return Attempt(res, peak >= problem.speed, peak)
    grid_T = fo.goal_time - problem.t0
    # where the current reaches the vehicle's speed, the characteristic's own controls
    # (extract.py); else (or when it fails) the polyline held leg by leg
    peak = extract.peak_current(problem, rg, fo.goal_time)
    strong = peak >= problem.speed
    swept_route = extract.rescue(problem, rg, fo, tolerance, tried=False,
                                 track=problem.settings.refine) if strong else None
    g = swept_route[0] if swept_route is not None else g0
    if g is None:
        g = _grid_route(problem, rg, fo)
    clock.lap("backtrack")
    best, flown, note, refined_T = _refined_or_grid(problem, rg, g, tolerance, clock, grid_T)
    ok = phases.flown_ok(flown, tolerance)
    # refine=False: the grid route's legs only (a coarse, quick route): when they miss, the
    # characteristic tracked in closed loop (its flown controls) -- also when swept
    if not ok and (not strong or not problem.settings.refine):
        rescued, note = _rescue(problem, rg, fo, tolerance, strong, grid_T, note, clock)
        if rescued is not None:
            best, flown = rescued
            ok = True
    straight = _straight_duration(problem, float(best.duration), clock)
    if straight is not None and problem.settings.refine and \
            straight < best.duration * (1 - STRAIGHT_MARGIN):
        line = phases.straight_line(problem, rg, tolerance, float(best.duration))
        if line is not None:
            note = _join(note, f"the straight line with crab angle ({straight / 3600:.4g} h, "
                         f"verified) is faster than the front's {best.method} route "
                         f"({best.duration / 3600:.4g} h; the grid may be too coarse): it "
                         "is the route")
            (best, flown), ok = line, True
            clock.lap("straight_line_route")
    note = _verification_note(flown, tolerance, note, warnings)
    result = _solved(problem, rg, best, flown, ok, note, warnings, clock, straight,
                     {**common, "grid_duration_s": float(grid_T),
                      "refined_duration_s": refined_T})
    if not ok:  # a narrow jet may pass between the 9 x 9 samples: the window's nodes too
        peak = max(peak, rg.currents.peak_speed())
    return Attempt(result, peak >= problem.speed, peak, _miss(flown))


def _miss(flown: Any) -> str:
    """How the flown controls failed, as a phrase ("" when they did not)."""
    if flown.on_land:
        return "its controls cross land"
    if flown.left_field:
        return "its controls leave the field"
    return f"its controls end {flown.endpoint_error_m / 1000:.3g} km from the goal"


def _settings(settings: RouteSettings | None, resolution: float | None,
              overrides: dict[str, Any]) -> RouteSettings:
    """The settings with `resolution` and the keyword overrides applied (unknown names refused)."""
    unknown = set(overrides) - _SETTING_NAMES
    if unknown:
        raise InvalidParameterError("route option", sorted(unknown)[0],
                                    f"unknown; known: {sorted(_SETTING_NAMES)}")
    settings = settings or RouteSettings()
    if resolution is not None:
        overrides["resolution"] = resolution
    if overrides:
        settings = replace(settings, **overrides)
    return settings


class _Clock:
    """Wall time per phase, into `stats` as `NAME_s` (s, 4 decimals)."""

    def __init__(self) -> None:
        self.stats: dict[str, Any] = {}
        self.t = time.perf_counter()

    def lap(self, name: str) -> None:
        """Record the time since the last lap under `name`."""
        now = time.perf_counter()
        self.stats[f"{name}_s"] = round(now - self.t, 4)
        self.t = now


def _coincident(problem: Any, warnings: list[str], stats: dict[str, Any],
                common: dict[str, Any]) -> RouteResult:
    """The route when start and goal coincide: solved, one point, zero time."""
    track = Track(np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1),
                  lat=np.array([problem.start[0]]), lon=np.array([problem.start[1]]))
    return RouteResult(status=Status.SOLVED, message="start and goal coincide",
                       warnings=tuple(warnings), duration_s=0.0, distance_m=0.0,
                       track=track, endpoint_error_m=0.0, endpoint_tolerance_m=0.0,
                       straight_line_duration_s=0.0, grid_duration_s=0.0, method="none",
                       stats=stats, **common)


def _front(problem: Any, clock: _Clock) -> tuple[Any, Any, Any, float]:
    """Grid and front (again at the strict clearance when the backtrack finds it closed),
    the backtracked grid route when there is one, the endpoint tolerance (m)."""
    from glideplan.routing import phases

    rg = phases.grid(problem)
    tolerance = problem.settings.endpoint_tolerance_cells * rg.spacing_m
    clock.lap("grid")
    fo, rg = phases.front(problem, rg)
    g0 = None
    if fo.goal_time is not None:
        try:
            g0 = phases.backtrack(problem, rg, fo)
        except InvalidParameterError:  # swept along: extract.py takes it
            g0 = None
        # closed at the full clearance: the front again
        if g0 is not None and g0.method == phases.CLOSED:
            rg = phases.strict_grid(problem, rg)
            fo, rg = phases.front(problem, rg)
            g0 = None
    clock.stats.update(grid_nodes=list(rg.window.shape), spacing_m=rg.spacing_m,
                       steps=fo.steps, window_growths=fo.growths,
                       periodic=rg.window.periodic,
                       field_levels_evaluated=rg.currents.evaluations)
    clock.lap("front")
    return rg, fo, g0, tolerance


def _unreachable(problem: Any, rg: Any, fo: Any, warnings: list[str], stats: dict[str, Any],
                 common: dict[str, Any]) -> RouteResult:
    """The answer when the front never reached the goal, with the real cause in `message`."""
    from glideplan.routing.sphere import straight_line_duration
    from glideplan.routing.window import MAX_LAT_DEG

    straight = straight_line_duration(problem.field_, problem.speed, problem.t0,
                                      problem.start, problem.goal, problem.t_max)
    why = fo.unreachable_reason or "front_stopped"
    msg = _unreachable_message(why, problem, fo.closest_m,
                               rg.clearance_m if rg.coast_xyz.shape[0] else 0.0)
    if why in ("front_stopped", "field_extent", "time_span", "max_duration"):
        why, msg = _real_cause(problem, rg, fo, why, msg)
    top = _great_circle_max_lat(problem.start, problem.goal)
    if top > MAX_LAT_DEG:
        why = "polar_limit"
        msg = (f"the great circle from start to goal passes {top:.1f} deg latitude and "
               f"routes are computed within +-{MAX_LAT_DEG:g} deg (the lat/lon lattice "
               f"degenerates at the poles): {msg}; plan via waypoints below "
               f"{MAX_LAT_DEG:g} deg")
    return RouteResult(status=Status.UNREACHABLE, message=msg, warnings=tuple(warnings),
                       straight_line_duration_s=straight, best_distance_m=fo.closest_m,
                       reason=Reason(why), stats=stats, **common)


def _real_cause(problem: Any, rg: Any, fo: Any, why: str, msg: str) -> tuple[str, str]:
    """A stopped front's cause when it is not the time: land cutting the goal off, or a
    time step with no data at all."""
    from glideplan.routing.cutoff import field_cut_off, nan_time_step

    shut = field_cut_off(problem.field_, problem.t0, problem.start, problem.goal,
                         rg.clearance_m)
    if shut is not None:  # not the time: no way joins start and goal
        why, msg = "front_stopped", _cut_off_message(shut, rg.clearance_m, fo.closest_m)
    gap = nan_time_step(problem.field_, problem.t0, fo.arrival)
    if gap is not None:  # a time step with no data at all stopped the front
        why = "missing_data"
        msg = (f"the field has no data at {problem.field_.format_time(gap)} (every "
               "current value NaN at that time step): the front cannot cross it; the "
               f"reachable set came within {fo.closest_m / 1000:.3g} km of the goal")
    return why, msg


def _grid_route(problem: Any, rg: Any, fo: Any) -> Any:
    """The backtracked polyline, or the characteristic when its legs outlast the field."""
    from glideplan.routing import extract, phases

    try:
        return phases.backtrack(problem, rg, fo)
    except InvalidParameterError:  # the polyline's legs outlast the field (swept along)
        g = extract.characteristic_candidate(problem, rg, fo)
        if g is None:
            raise
        return g


def _refined_or_grid(problem: Any, rg: Any, g: Any, tolerance: float, clock: _Clock,
                     grid_T: float | None = None) -> tuple[Any, Any, str, float | None]:
    """The Zermelo-shooting route from `g` if it verifies and is not slower than the grid
    route by more than GRID_TIME_TOLERANCE, else `g`: (best, flown, note, refined duration)."""
    from glideplan.routing import phases

    best, flown, note = g, None, ""
    refined_T = None
    flown_g = None
    if problem.settings.refine:
        shot, why_not = phases.refine(problem, rg, g, grid_T)
        clock.lap("refine")
        if shot is None:
            note = f"refinement not used: {why_not}"
        else:
            refined_T = shot.duration
            flown_r = phases.verify(problem, rg, shot)
            clock.lap("verify_refined")
            if phases.flown_ok(flown_r, tolerance) and \
                    shot.duration <= g.duration * (1 + GRID_TIME_TOLERANCE):
                best, flown = shot, flown_r
            else:
                flown_g = phases.verify(problem, rg, g)
                grid_ok = phases.flown_ok(flown_g, tolerance)
                clock.lap("verify_grid")
                if flown_r.on_land or flown_r.left_field:
                    note = "refinement rejected: its controls cross land or leave the field"
                elif flown_r.endpoint_error_m > max(flown_g.endpoint_error_m, tolerance):
                    note = "refinement rejected: larger endpoint error than the grid route"
                elif grid_ok:
                    note = "refinement rejected: slower than the grid route"
                else:
                    best, flown = shot, flown_r
                    note = (f"the grid route's controls miss the goal by "
                            f"{flown_g.endpoint_error_m:.3g} m (beyond the tolerance); the "
                            "refined route is the verified one")
    if flown is None:
        flown = flown_g if flown_g is not None else phases.verify(problem, rg, g)
        clock.lap("verify_grid")
    return best, flown, note, refined_T


def _rescue(problem: Any, rg: Any, fo: Any, tolerance: float, strong: bool, grid_T: float,
            note: str, clock: _Clock) -> tuple[Any, str]:
    """The characteristic tracked in closed loop when the routes missed: ((candidate, flown)
    or None, note)."""
    from glideplan.routing import extract

    refine = problem.settings.refine
    rescued = extract.rescue(problem, rg, fo, tolerance, tried=strong, home=not refine)
    clock.lap("rescue")
    if rescued is not None and not refine and \
            rescued[0].duration > grid_T * (1 + RESCUE_TIME_TOLERANCE):
        note = _join(note, f"the characteristic tracked in closed loop verifies but takes "
                     f"{rescued[0].duration / 3600:.4g} h against the front's "
                     f"{grid_T / 3600:.4g} h: not used (refine or a finer grid)")
        rescued = None
    if rescued is not None:
        note = _join(note, f"the {rescued[0].method} route is the verified one (the others "
                     "missed the goal)")
    return rescued, note


def _verification_note(flown: Any, tolerance: float, note: str, warnings: list[str]) -> str:
    """`note` with what the verification found (land, leaving the field, a miss); the
    stencil's land fills appended to `warnings`."""
    if flown.filled:
        warnings.append(f"verification: the field's interpolation stencil touched land at "
                        f"{flown.filled} of its evaluations; the nearest water current was "
                        "used there (verification only)")
    if flown.on_land or flown.left_field:
        return _join(note, "verification: the controls cross land" if flown.on_land else
                     f"verification: the controls leave the field ({flown.left_field})")
    if flown.endpoint_error_m > tolerance:
        return _join(note, f"verification: the heading controls flown through the field end "
                     f"{flown.endpoint_error_m:.3g} m from the goal, beyond the tolerance of "
                     f"{tolerance:.3g} m (one grid spacing); a finer grid (resolution) may help")
    return note


def _straight_duration(problem: Any, T: float, clock: _Clock) -> float | None:
    """The straight line with crab angle's duration (s), searched to 3 T (at least 1 h)."""
    from glideplan.routing.sphere import straight_line_duration

    straight = straight_line_duration(problem.field_, problem.speed, problem.t0, problem.start,
                                      problem.goal, problem.t0 + max(3 * T, 3600.0))
    clock.lap("straight_line")
    return straight


def _solved(problem: Any, rg: Any, best: Any, flown: Any, ok: bool, note: str,
            warnings: list[str], clock: _Clock, straight: float | None,
            common: dict[str, Any]) -> RouteResult:
    """The result of a route found: solved when verified, else not_verified (`straight`:
    the straight line with crab angle's duration, s, or None)."""
    from glideplan.routing.coast import track_clearance
    from glideplan.routing.sphere import gc_distance

    T = float(best.duration)
    near = track_clearance(problem, rg, best.lat, best.lon)
    if near is not None and math.isfinite(near):
        clock.stats["least_distance_to_land_m"] = round(near, 1)
        if near < rg.clearance_m * (1 - 1e-3):
            warnings.append(f"the track comes within {near:.0f} m of a land node, inside the "
                            f"{rg.clearance_m:.0f} m land clearance")
    dist = float(np.sum(gc_distance(best.lat[:-1], best.lon[:-1], best.lat[1:], best.lon[1:])))
    return RouteResult(
        status=Status.SOLVED if ok else Status.NOT_VERIFIED,
        message=note or ("solved" if ok else ""), warnings=tuple(warnings), duration_s=T,
        distance_m=dist, track=_track(problem, best),
        endpoint_error_m=float(flown.endpoint_error_m), straight_line_duration_s=straight,
        method=best.method, stats=clock.stats, **common)


def _join(a: str, b: str) -> str:
    return f"{a}; {b}" if a else b


def _track(problem: Any, cand: Any) -> Track:
    """The candidate as a `Track`: t after departure, x/y in the aeqd plane about the start
    (short routes), heading (rad CCW from east) of the through-water velocity."""
    from glideplan.geodesy import LocalProjection

    lat, lon = np.asarray(cand.lat, dtype=float), np.asarray(cand.lon, dtype=float)
    # The track's longitudes are unwrapped about the start (continuous across 180 deg, so
    # below -180 going west): the projection takes them wrapped.
    x, y = LocalProjection(*problem.start).to_local(lat, (lon + 180.0) % 360.0 - 180.0)
    heading = math.pi / 2 - np.asarray(cand.chi, dtype=float)
    return Track(np.asarray(cand.t, dtype=float) - problem.t0, x, y, heading, lat=lat, lon=lon)


def _great_circle_max_lat(start: tuple[float, float], goal: tuple[float, float]) -> float:
    """Largest |latitude| (deg) on the great circle between two points (181 samples by
    spherical linear interpolation of their unit vectors)."""
    la, lo = np.radians([start[0], goal[0]]), np.radians([start[1], goal[1]])
    p = np.stack([np.cos(la) * np.cos(lo), np.cos(la) * np.sin(lo), np.sin(la)], axis=1)
    omega = math.acos(min(1.0, max(-1.0, float(p[0] @ p[1]))))
    if omega < 1e-12:
        return float(abs(start[0]))
    if omega > math.pi - 1e-9:  # antipodes: every meridian plane, one through a pole
        return 90.0
    f = np.linspace(0.0, 1.0, 181)[:, None]
    pts = (np.sin((1.0 - f) * omega) * p[0] + np.sin(f * omega) * p[1]) / math.sin(omega)
    return float(np.degrees(np.max(np.abs(np.arcsin(np.clip(pts[:, 2], -1.0, 1.0))))))


#: The advice of a "window_limit" answer (`plan_mission_in_field` gives its own: a mission
#: plan has no resolution option).
WINDOW_ADVICE = "a coarser resolution reaches further"


def _cut_off_message(shut: str, clearance: float, closest: float) -> str:
    """The message of a goal no water joins to the start (`phases.cut_off`)."""
    came = f"the reachable set came within {closest / 1000:.3g} km of the goal"
    if shut == "clearance":
        return (f"the land clearance ({clearance:.0f} m) closes every passage to the goal: "
                "water joins start and goal only through gaps narrower than twice the "
                f"clearance; a smaller --land-clearance opens it: {came}")
    return f"land separates the goal from the start's water (no passage at all): {came}"


def _unreachable_message(why: str, problem: Any, closest: float, clearance: float) -> str:
    fld = problem.field_
    came = f"the reachable set came within {closest / 1000:.3g} km of the goal"
    if why == "front_stopped":
        text = f"the reachable front stopped growing: {came}"
        if clearance > 0:
            text += (f" (routes keep {clearance:.0f} m from land; a smaller --land-clearance "
                     "may open a narrow passage)")
        return text
    if why == "field_extent":
        return f"the reachable front reached the field's edge without the goal: {came}"
    if why == "time_span":
        return f"the field ends ({fld.format_time(problem.t_max)}) before the goal is " \
               f"reached: {came}"
    if why == "window_limit":
        return (f"the routing window reached its size limit ({problem.settings.max_nodes:g} "
                f"nodes) before the goal: {came}; {WINDOW_ADVICE}")
    return (f"the goal is not reached within the duration limit "
            f"({(problem.t_max - problem.t0) / 3600:.4g} h): {came}")
