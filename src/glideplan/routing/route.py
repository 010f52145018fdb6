"""`route()`: the time-optimal route through a flow field, front to verified track.

Phases: local aeqd plane about the start (`geodesy.LocalProjection`) -> routing grid and the
field on it (`grid`) -> front propagation, the arrival-time map (`levelset`) -> backtracking
to the grid route (`backtrack`) -> Zermelo shooting refinement, kept only if it is not slower
(`refine`) -> verification of the heading controls through the field itself (`verify`).

Acceptance: a route is "solved" only when its heading controls, integrated through the field
itself (not the grid), end within `endpoint_tolerance_m` of the goal, stay in the water and
in the field. The tolerance is one routing-grid spacing h (ENDPOINT_TOLERANCE_CELLS x h): the
front locates the arrival to within a cell and the backtracked route is a chain of grid nodes,
so one cell is the resolution the grid answer claims (the refined routes end far closer:
0.1 % to 10 % of h on the double-gyre and uniform-current checks). A route that misses by more
is returned with status "unverified", its track and numbers kept and the miss in `message`.
"""

from __future__ import annotations

import math
import pathlib
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, to_seconds
from glideplan.geodesy import LocalProjection, heading_to_compass

if TYPE_CHECKING:
    from glideplan.routing.verify import FlownRoute

__all__ = ["ENDPOINT_TOLERANCE_CELLS", "GRID_TIME_TOLERANCE", "RouteResult", "route"]

#: The grid's arrival time can be optimistic by a little (the front's discretisation error,
#: measured <= 0.15% on the uniform-current checks); a verified refined route is kept unless
#: it is slower than the grid time by more than this fraction. When kept although slower,
#: `message` says so and both times are reported.
GRID_TIME_TOLERANCE = 5e-3

#: The verified endpoint error a solved route may have, in routing-grid spacings (module
#: docstring): endpoint_tolerance_m = ENDPOINT_TOLERANCE_CELLS x spacing_m.
ENDPOINT_TOLERANCE_CELLS = 1.0

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class RouteResult:
    """A route's outcome. Times in s, distances in m, positions WGS84 degrees.

    status: "solved", "unreachable" or "unverified" (the controls flown through the field
    miss the goal by more than endpoint_tolerance_m, or cross land or leave the field; the
    track and times are kept, `message` says by how much); duration_s: arrival minus
    departure (None when unreachable); t: track times (s after departure); lat/lon: track;
    heading_deg: compass heading through the water along the track; endpoint_error_m:
    distance from the goal where the heading controls, integrated through the field, end;
    endpoint_tolerance_m: the largest endpoint error of a solved route (one grid spacing,
    module docstring); method: "zermelo-shooting", "direct-shooting",
    "polyline-collocation" (refined routes) or "grid" (the backtracked grid route);
    best_distance_m: how close the reachable set came to the goal (0 when reached).
    """

    status: str
    depart: np.datetime64 | None
    depart_s: float
    duration_s: float | None
    distance_m: float
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    heading_deg: FloatArray
    endpoint_error_m: float | None
    straight_line_duration_s: float | None
    grid_duration_s: float | None
    refined_duration_s: float | None
    method: str
    best_distance_m: float
    field_info: Mapping[str, Any]
    stats: Mapping[str, Any]
    message: str = ""
    x: FloatArray = field(default_factory=lambda: np.zeros(0))
    y: FloatArray = field(default_factory=lambda: np.zeros(0))
    extras: Mapping[str, Any] = field(default_factory=dict)
    endpoint_tolerance_m: float | None = None

    @property
    def ok(self) -> bool:
        return self.status == "solved"

    @property
    def arrive(self) -> np.datetime64 | None:
        if self.depart is None or self.duration_s is None:
            return None
        return self.depart + np.timedelta64(round(self.duration_s * 1e3), "ms")

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of `glideplan route --json`."""

        def iso(d: np.datetime64 | None) -> str | None:
            return None if d is None else str(d.astype("datetime64[s]")) + "Z"

        out: dict[str, Any] = {
            "status": self.status,
            "duration_s": self.duration_s,
            "distance_m": self.distance_m,
            "depart": iso(self.depart) if self.depart is not None else self.depart_s,
            "arrive": iso(self.arrive) if self.depart is not None else (
                None if self.duration_s is None else self.depart_s + self.duration_s),
            "track": {"t": self.t.tolist(), "lat": self.lat.tolist(), "lon": self.lon.tolist(),
                      "heading_deg": self.heading_deg.tolist()},
            "endpoint_error_m": self.endpoint_error_m,
            "endpoint_tolerance_m": self.endpoint_tolerance_m,
            "straight_line_duration_s": self.straight_line_duration_s,
            "grid_duration_s": self.grid_duration_s,
            "refined_duration_s": self.refined_duration_s,
            "method": self.method,
            "best_distance_m": self.best_distance_m,
            "message": self.message,
            "field": dict(self.field_info),
            "stats": dict(self.stats),
        }
        out.update(self.extras)
        return out


def _as_field(field_: Any, depth_range: tuple[float, float] | None) -> FlowField:
    if isinstance(field_, FlowField):
        if depth_range is not None:
            raise InvalidParameterError(
                "depth_range", depth_range, "applies when reading files; average the field first"
            )
        return field_
    if isinstance(field_, (str, pathlib.Path)) or (
        isinstance(field_, Sequence) and all(isinstance(p, (str, pathlib.Path)) for p in field_)
    ):
        from glideplan.fields.io import open_field

        return open_field(field_, depth_range=depth_range)
    raise InvalidParameterError("field", type(field_).__name__, "must be a FlowField or file(s)")


def _check_point(fld: FlowField, t: float, lat: float, lon: float, name: str) -> None:
    la, lo = fld.check_position(lat, lon, name=name)
    u, v = fld.velocity(t, la, lo)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise InvalidParameterError(name, (lat, lon), "is on land (no current data: NaN)")


def _verified(flown: FlownRoute, tolerance: float) -> bool:
    """The acceptance rule (module docstring): in the water, in the field, within tolerance."""
    return not (flown.on_land or flown.left_field) and flown.endpoint_error_m <= tolerance


def _distance(x: FloatArray, y: FloatArray) -> float:
    return float(np.sum(np.hypot(np.diff(x), np.diff(y)))) if x.size > 1 else 0.0


def route(
    field_: Any,
    start: tuple[float, float],
    goal: tuple[float, float],
    speed: float,
    depart: Any = None,
    resolution: float | None = None,
    depth_range: tuple[float, float] | None = None,
    *,
    max_duration: float | None = None,
    refine: bool = True,
    margin: float = 0.5,
    cells: int = 200,
    cfl: float = 0.5,
) -> RouteResult:
    """Time-optimal route from `start` to `goal` (lat, lon degrees) at water speed `speed` (m/s).

    field_: a FlowField, or NetCDF/GRIB path(s) (read with `depth_range` (m, positive down));
    depart: datetime64, seconds since the field's epoch, or None (the field's first time);
    resolution: grid spacing (m; default: the start-goal box grown by `margin` x distance on
    each side, over `cells` cells); max_duration: give up after this long (s; default the
    field's time span, or 20 x the still-water time). Raises InvalidParameterError for bad
    input (speed <= 0, points outside the field or on land); an unreachable goal is a result.
    """
    from glideplan.routing.backtrack import backtrack
    from glideplan.routing.grid import CurrentSampler, build_grid
    from glideplan.routing.levelset import propagate_front, start_disk_radius
    from glideplan.routing.refine import (
        direct_refinement,
        polyline_refinement,
        zermelo_shooting,
    )
    from glideplan.routing.verify import integrate_headings, straight_line_duration

    clock = {"start": time.perf_counter()}
    stats: dict[str, Any] = {}

    def lap(name: str) -> None:
        now = time.perf_counter()
        stats[f"{name}_s"] = round(now - clock["start"], 4)
        clock["start"] = now

    if not (isinstance(speed, (int, float)) and math.isfinite(speed) and speed > 0):
        raise InvalidParameterError("speed", speed, "must be finite and > 0 (m/s)")
    fld = _as_field(field_, depth_range)
    if depart is None:
        t0 = fld.time_span[0] if fld.time_span is not None else 0.0
    else:
        t0 = float(to_seconds(depart, fld.epoch))
    fld.check_time(t0)
    _check_point(fld, t0, start[0], start[1], "from")
    _check_point(fld, t0, goal[0], goal[1], "to")
    proj = LocalProjection(float(start[0]), float(start[1]))
    gxa, gya = proj.to_local(goal[0], goal[1])
    goal_xy = (float(gxa), float(gya))
    proj.check_extent(goal[0], goal[1])
    dist = math.hypot(*goal_xy)
    if dist <= 0.0:
        raise InvalidParameterError("to", goal, "coincides with the start")
    if fld.time_span is not None:
        t_max = fld.time_span[1]
        if max_duration is not None:
            t_max = min(t_max, t0 + max_duration)
    else:
        t_max = t0 + (max_duration if max_duration is not None else max(20.0 * dist / speed, 3600))
    if max_duration is not None and not (math.isfinite(max_duration) and max_duration > 0):
        raise InvalidParameterError("max_duration", max_duration, "must be finite and > 0 (s)")
    lap("setup")

    grid = build_grid(fld, proj, goal_xy, resolution, margin=margin, cells=cells)
    sampler = CurrentSampler.for_span(grid, fld, t0, t_max, sample_dt=dist / speed / 48.0)
    stats.update(grid_nodes=[int(grid.y.size), int(grid.x.size)], spacing_m=grid.spacing,
                 time_levels=int(sampler.levels.size))
    tolerance = ENDPOINT_TOLERANCE_CELLS * float(grid.spacing)
    lap("grid")
    r0 = start_disk_radius(grid, sampler.land(), goal_xy)
    front = propagate_front(grid, sampler, speed, t0, t_max, goal_xy, cfl=cfl, start_radius=r0)
    stats.update(steps=front.steps, reached_fraction=round(front.reached_fraction, 4),
                 field_levels_evaluated=sampler.evaluations)
    lap("front")
    depart_dt = None if fld.epoch is None else fld.epoch + np.timedelta64(round(t0 * 1e3),
                                                                           "ms")
    info = fld.describe()
    if front.goal_time is None:
        lap("backtrack")
        return RouteResult(
            "unreachable", depart_dt, t0, None, 0.0, np.zeros(0), np.zeros(0), np.zeros(0),
            np.zeros(0), None, straight_line_duration(fld, proj, speed, t0, goal_xy, t_max),
            None, None, "none", front.closest_distance_m, info, stats,
            message=f"the goal is not reachable by {fld.format_time(t_max)}: the reachable set "
            f"came within {front.closest_distance_m:.0f} m", endpoint_tolerance_m=tolerance,
        )
    g = backtrack(grid, sampler, front.arrival, speed, t0, goal_xy, front.goal_time, r0)
    lap("backtrack")
    grid_T = front.goal_time - t0
    flown_g = integrate_headings(fld, proj, speed, g.t, g.heading, goal_xy)
    grid_verified = _verified(flown_g, tolerance)
    lap("verify_grid")
    best = ("grid", g.t, g.x, g.y, g.heading, grid_T, flown_g)
    refined_T = None
    note = ""
    if refine:
        k = min(max(1, g.t.size // 20), g.t.size - 1)
        theta0 = float(np.arctan2(np.mean(np.sin(g.heading[1:k + 1])),
                                  np.mean(np.cos(g.heading[1:k + 1]))))
        tol = max(1e-3 * grid.spacing, 0.01)
        shot = zermelo_shooting(sampler, speed, t0, goal_xy, theta0, grid_T, tol_m=tol)
        if not shot.converged:
            land = sampler.land()
            shot_name = "direct-shooting"
            if not np.any(land & grid.inside):  # open water (edges of the field aside)
                shot = direct_refinement(sampler, speed, t0, goal_xy, g.t, g.heading, grid_T,
                                         tol_m=max(0.05 * grid.spacing, 1.0))
            if np.any(land) and not shot.converged:
                from scipy.ndimage import distance_transform_edt

                # Signed: distance to the nearest land node outside, minus the distance to
                # the nearest water node inside (a gradient everywhere for the optimiser).
                clearance = (distance_transform_edt(~land) - distance_transform_edt(land)) \
                    * grid.spacing
                shot = polyline_refinement(sampler, speed, t0, goal_xy, g.x, g.y, clearance,
                                           margin=grid.spacing)
                shot_name = "polyline-collocation"
        else:
            shot_name = "zermelo-shooting"
        lap("refine")
        if shot.converged:
            refined_T = shot.duration
            flown_r = integrate_headings(fld, proj, speed, shot.t, shot.heading, goal_xy,
                                         hold=shot_name == "polyline-collocation")
            lap("verify_refined")
            if flown_r.on_land or flown_r.left_field:
                note = "refinement rejected: its track crosses land or leaves the field"
            elif flown_r.endpoint_error_m > max(flown_g.endpoint_error_m, tolerance):
                note = "refinement rejected: larger endpoint error than the grid route"
            elif refined_T > grid_T * (1 + GRID_TIME_TOLERANCE) and grid_verified:
                note = "refinement rejected: slower than the grid route"
            else:
                # Kept when not slower, or when the grid route fails verification (its time is
                # then an estimate that no flown control reaches).
                best = (shot_name, shot.t, shot.x, shot.y, shot.heading, refined_T, flown_r)
                if refined_T > grid_T:
                    note = (f"the grid time is optimistic by {refined_T / grid_T - 1:.2%} (its "
                            "discretisation error); the refined route is the verified one")
                if not grid_verified:
                    note = (note + "; " if note else "") + (
                        f"the grid route's controls miss the goal by "
                        f"{flown_g.endpoint_error_m:.3g} m (beyond the tolerance)")
        else:
            note = f"refinement not used: {shot.message}"
    method, tt, xx, yy, hh, T, flown = best
    lat, lon = proj.to_geographic(xx, yy)
    straight = straight_line_duration(fld, proj, speed, t0, goal_xy, t0 + max(3 * T, 3600.0))
    lap("straight_line")
    if flown.on_land or flown.left_field:
        note = (note + "; " if note else "") + (
            "verification: the controls cross land" if flown.on_land else
            f"verification: the controls leave the field ({flown.left_field})")
    elif flown.endpoint_error_m > tolerance:
        note = (note + "; " if note else "") + (
            f"verification: the heading controls flown through the field end "
            f"{flown.endpoint_error_m:.3g} m from the goal, beyond the tolerance of "
            f"{tolerance:.3g} m (one grid spacing); a finer grid (resolution) or the "
            "refinement may help")
    return RouteResult(
        "solved" if _verified(flown, tolerance) else "unverified", depart_dt, t0, float(T),
        _distance(xx, yy), tt - t0, lat, lon,
        np.asarray(heading_to_compass(hh), dtype=float), float(flown.endpoint_error_m),
        straight, float(grid_T), refined_T, method, 0.0, info, stats, message=note, x=xx, y=yy,
        endpoint_tolerance_m=tolerance,
    )
