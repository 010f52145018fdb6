"""Missions through a current (or wind) field: each leg routed with `glideplan.routing`.

With a spatially and temporally varying field there is no Dubins closed form: each leg is the
time-optimal route of the routing package (`glideplan.routing.route`: the reachable front of
Lolla et al. 2012, backtracked and refined by Zermelo shooting, verified by integrating its
heading controls through the field). Legs are chained in time: leg i + 1 departs when leg i
arrives. The router models a point mass steering its heading freely, so waypoint headings are
not constrained: the heading reported at a waypoint is the heading through the water when
leaving it (at the last waypoint, when arriving); a heading given in the route is noted as
not enforced.

With a turn radius R0 (`radius`), each routed leg becomes the glider-scale flyable path of
`glideplan.routing.glider`: Dubins pieces of the feasible radius R0' = R0 (1 + eps)^2 (eq. 3.3)
with eps = max |c| / V along that leg, joined at every waypoint with a continuous course (each
leg ends on the next leg's initial ground course), and followed in closed loop through the same
field (the current at the vehicle's position as the disturbance; cross-track error reported per
leg). The mission's track, and so every exported file, is then that flyable path; its times are
the route's times at the same fraction of the distance.
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import LocalProjection, compass_to_heading
from glideplan.missions.plan import LegTotals, Track, mission_outcome
from glideplan.missions.route import Route
from glideplan.results import Outcome, Reason
from glideplan.solution import Status
from glideplan.validation import check_positive

if TYPE_CHECKING:
    from glideplan.fields.field import FlowField
    from glideplan.missions.straight_legs import StraightLegList
    from glideplan.routing.glider import GliderFollow
    from glideplan.routing.result import RouteResult

__all__ = ["FieldLeg", "FieldMission", "plan_mission_in_field"]


@dataclass(frozen=True, eq=False)
class FieldLeg:
    """One leg routed through the field: waypoint indices, the `RouteResult`, length, time."""

    index: int
    start: int
    end: int
    result: RouteResult
    length_m: float
    duration_s: float
    glider: GliderFollow | None = None  # the flyable path followed, with a radius

    @property
    def word(self) -> str:
        return str(self.result.method)

    @property
    def ok(self) -> bool:
        return bool(self.result.ok)

    @property
    def status(self) -> Status:
        return self.result.status

    @property
    def reason(self) -> Reason | None:
        return self.result.reason

    @property
    def status_text(self) -> str:
        """The leg's route status and message."""
        res = self.result
        return str(res.status) + (f": {res.message}" if getattr(res, "message", "") else "")


@dataclass(frozen=True, eq=False, kw_only=True)
class FieldMission(LegTotals, Outcome):
    """A mission routed through a field; the interface of `MissionPlan` the exporters use.

    An `Outcome` (`glideplan.results`): status SOLVED or the first failed leg's (UNREACHABLE,
    NOT_VERIFIED; `missions.plan.mission_outcome`). `warnings`:
    the field's (`FlowField.warnings`) and the legs' routes', and headings given but not
    enforced.
    """

    route: Route
    headings: NDArray[np.float64]
    legs: tuple[FieldLeg, ...]
    speed: float
    field_info: dict[str, Any]
    stats: dict[str, Any] = field(default_factory=dict)
    objective: str = "time"
    radius: float | None = None
    straight_legs: StraightLegList | None = None

    @property
    def depart_time(self) -> np.datetime64 | None:
        """The first leg's departure (UTC; None without a calendar)."""
        return self.legs[0].result.depart if self.legs else None

    @property
    def smallest_radius(self) -> float | None:
        """The smallest feasible radius R0' of the legs' flyable paths (m), None without."""
        radii = [leg.glider.feasible_radius_m for leg in self.legs
                 if leg.glider is not None and leg.glider.feasible_radius_m is not None]
        return min(radii) if radii else None

    def track_spacing(self, tolerance: float) -> float:
        """Flyable paths: the spacing whose arcs of radius R0' leave their chords by <= 1 % of
        `tolerance` (sagitta s^2 / (8 R0')); otherwise the router's own samples (0)."""
        r = self.smallest_radius
        if r is None:
            return 0.0
        return min(r / 10.0, math.sqrt(0.08 * r * tolerance))

    def track(self, spacing: float | None = None) -> Track:
        """The track in the mission's local plane (m), chained in time: the legs' flyable paths
        sampled every `spacing` m (default R0' / 10) with a radius, else the route samples."""
        assert self.route.projection is not None
        if self.smallest_radius is not None:
            return self._flyable_track(spacing or self.smallest_radius / 10.0)
        xs, ys, hs, legs, ts = [], [], [], [], []
        t0 = 0.0
        for leg in self.legs:
            res = leg.result
            first = 0 if leg.index == 0 else 1
            x, y = self.route.projection.to_local(res.lat, res.lon)
            x[0], y[0] = self.route.x[leg.start], self.route.y[leg.start]
            x[-1], y[-1] = self.route.x[leg.end], self.route.y[leg.end]
            xs.append(x[first:])
            ys.append(y[first:])
            hs.append(np.asarray(compass_to_heading(res.heading_deg), dtype=float)[first:])
            legs.append(np.full(x.size - first, leg.index))
            ts.append(t0 + np.asarray(res.t, dtype=float)[first:])
            t0 += leg.duration_s
        return Track(t=np.concatenate(ts), x=np.concatenate(xs), y=np.concatenate(ys),
                     heading=np.concatenate(hs), leg=np.concatenate(legs).astype(np.intp))

    def _flyable_track(self, spacing: float) -> Track:
        proj = self.route.projection
        assert proj is not None
        xs, ys, hs, legs, ts = [], [], [], [], []
        t0 = 0.0
        for leg in self.legs:
            assert leg.glider is not None and leg.glider.flyable is not None
            fp = leg.glider.flyable
            s, lx, ly, chi = fp.sample(spacing)
            lat, lon = fp.proj.to_geographic(lx, ly)
            x, y = proj.to_local(lat, lon)
            # course: the tangent carried into the mission's plane by a short step along it
            lat2, lon2 = fp.proj.to_geographic(lx + np.cos(chi), ly + np.sin(chi))
            x2, y2 = proj.to_local(lat2, lon2)
            res = leg.result
            first = 0 if leg.index == 0 else 1
            x[0], y[0] = self.route.x[leg.start], self.route.y[leg.start]
            x[-1], y[-1] = self.route.x[leg.end], self.route.y[leg.end]
            rs = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(res.x), np.diff(res.y)))])
            t = np.interp(s / s[-1] * rs[-1], rs, np.asarray(res.t, dtype=float))
            xs.append(x[first:])
            ys.append(y[first:])
            hs.append(np.arctan2(y2 - y, x2 - x)[first:])
            legs.append(np.full(x.size - first, leg.index))
            ts.append(t0 + t[first:])
            t0 += leg.duration_s
        return Track(t=np.concatenate(ts), x=np.concatenate(xs), y=np.concatenate(ys),
                     heading=np.concatenate(hs), leg=np.concatenate(legs).astype(np.intp))

    def to_dict(self, straight_legs: StraightLegList | None = None) -> dict[str, Any]:
        """The `--json` object of `glideplan mission plan --field` (the CLI adds `files`);
        `straight_legs` as in `MissionPlan.to_dict`."""
        r = self.route
        assert r.lat is not None and r.lon is not None
        return self._with_track({
            **super().to_dict(),
            "objective": "time",
            "speed": self.speed,
            "radius": self.radius,
            "wind": None,
            "field": self.field_info,
            "total_length_m": self.total_length_m,
            "total_duration_s": self.total_duration_s,
            "headings_deg": self.headings_deg,
            "headings_given": [not f for f in r.free.tolist()],
            "waypoints": [{"name": r.names[i], "lat": float(r.lat[i]), "lon": float(r.lon[i]),
                           "x": float(r.x[i]), "y": float(r.y[i])} for i in range(r.n)],
            "legs": [
                {
                    "from": r.names[leg.start],
                    "to": r.names[leg.end],
                    "word": leg.word,
                    "length_m": leg.length_m,
                    "duration_s": leg.duration_s,
                    "status": leg.result.status,
                    "endpoint_error": {"position": leg.result.endpoint_error_m},
                    "straight_line_duration_s": leg.result.straight_line_duration_s,
                    "depart": _iso(leg.result.depart),
                    "arrive": _iso(leg.result.arrive),
                    "depart_s": float(leg.result.depart_s),
                    "glider": None if leg.glider is None else {
                        k: v for k, v in leg.glider.to_dict().items() if k != "track"},
                }
                for leg in self.legs
            ],
            "stats": self.stats,
        }, straight_legs)


def _iso(when: np.datetime64 | None) -> str | None:
    """ISO 8601 UTC with milliseconds (None without a calendar)."""
    return None if when is None else str(when.astype("datetime64[ms]")) + "Z"


def plan_mission_in_field(
    route: Route, flow: FlowField | str | pathlib.Path | Sequence[str | pathlib.Path], *,
    speed: float, depart: Any = None,
    depth_range: tuple[float, float] | None = None, resolution: float | None = None,
    radius: float | None = None, land_clearance_m: float | None = None,
    progress: bool = False,
) -> FieldMission:
    """Route every leg of a geographic `route` through `flow` (a FlowField or file paths).

    `depart` (datetime64, seconds since the field's epoch, or None: its first time), the
    `depth_range` (m), grid `resolution` (m) and `land_clearance_m` go to
    `glideplan.routing.route` (routes on the sphere: legs of any length); leg i + 1
    departs when leg i arrives. `radius` R0 (m): build and follow each leg's flyable path
    (module docstring). A leg that would depart at or after the field's last time raises
    `PlanningError`.
    """
    from glideplan.fields.field import FlowField

    speed = check_positive("speed", speed)
    if radius is not None:
        radius = check_positive("radius", radius)
    if route.lat is None or route.lon is None:
        raise InvalidParameterError(
            "field", "local route", "routing through a field needs a geographic route (lat/lon)")
    if not isinstance(flow, FlowField):
        from glideplan.fields import open_field

        flow, depth_range = open_field(flow, depth_range=depth_range), None
    _check_waypoints(route, flow, depart)
    legs, info = _all_legs(route, flow, speed, depart, depth_range, resolution,
                           land_clearance_m, progress)
    if radius is not None and all(leg.ok for leg in legs):
        legs = _fly_legs(legs, flow, speed, radius)
    h = np.full(route.n, np.nan)
    for leg in legs:
        if leg.ok and len(leg.result.heading_deg):
            h[leg.start] = compass_to_heading(float(leg.result.heading_deg[0]))
            h[leg.end] = compass_to_heading(float(leg.result.heading_deg[-1]))
    stats = _field_stats(route, legs, radius)
    # what the user must see: the field's warnings (e.g. depth range extended to the surface,
    # held constant in time, regridded), the legs' routes', headings given but not enforced
    warnings = list(route.warnings) + list(flow.warnings)
    for leg in legs:
        warnings += [w for w in leg.result.warnings if w not in warnings]
    warnings += [f"heading given at {name} is not enforced when routing through a field (the "
                 "router steers a point mass)" for name in stats["headings_not_enforced"]]
    return FieldMission(**mission_outcome(legs, route.names), route=route,
                        headings=np.nan_to_num(h), legs=tuple(legs), speed=speed,
                        field_info=info, stats=stats, radius=radius, warnings=tuple(warnings))


def _all_legs(route: Route, flow: FlowField, speed: float, depart: Any,
              depth_range: tuple[float, float] | None, resolution: float | None,
              land_clearance_m: float | None, progress: bool) -> tuple[list[FieldLeg], dict[
                  str, Any]]:
    """Every leg routed: batched when the field is steady and the legs many (only their
    departure times chain), else one after the other with a progress bar; the field's info."""
    from glideplan.missions.field_legs import BATCH_MIN_LEGS, steady_legs

    if flow.time_span is None and route.n - 1 >= BATCH_MIN_LEGS:
        # a steady field: the legs are independent (only their departure times chain)
        return _chain(steady_legs(route, flow, speed, resolution, land_clearance_m, progress),
                      flow, depart)
    bar, task = None, None
    if progress and route.n > 2:
        from glideplan.progress import start_progress_bar

        bar, task = start_progress_bar("legs", route.n - 1, with_rate=True)
    try:
        return _route_legs(route, flow, speed, depart, depth_range, resolution,
                           land_clearance_m, bar, task)
    finally:
        if bar is not None:
            bar.stop()


def _field_stats(route: Route, legs: list[FieldLeg], radius: float | None) -> dict[str, Any]:
    """The mission's numbers: max endpoint error, legs routed, headings not enforced, the
    projection, and (with `radius`) the flyable paths' radii, length, cross-track error."""
    assert route.lat is not None and route.lon is not None
    errors = [e for e in (leg.result.endpoint_error_m for leg in legs) if e is not None]
    stats: dict[str, Any] = {
        "max_endpoint_error": max(errors) if errors else None,
        "legs_routed": len(legs),
        "headings_not_enforced": [route.names[i] for i in np.nonzero(~route.free)[0]],
        "projection": {
            "kind": "aeqd", "lat0": route.lat[0], "lon0": route.lon[0],
            "scale_distortion": route.distortion,
            "roundtrip_error_deg": route.roundtrip_error_deg,
        },
    }
    if radius is not None:
        flown = [leg.glider for leg in legs if leg.glider is not None]
        stats["flyable"] = {
            "feasible_radius_m": [g.feasible_radius_m for g in flown],
            "path_length_m": sum(g.path_length_m for g in flown),
            "max_cross_track_m": max((g.max_cross_track_m or 0.0) for g in flown),
        } if len(flown) == len(legs) else None
    return stats



def _check_waypoints(route: Route, flow: FlowField, depart: Any) -> None:
    """Every waypoint inside the field and in water at the departure, else an error naming
    it by its name and place in the file (`Route.labels`: "line 3") and the cause
    (`FlowField.nan_cause`: land, outside a regridded grid, below the sea floor...)."""
    from glideplan.fields.field import to_seconds

    assert route.lat is not None and route.lon is not None
    if depart is not None:
        t0 = float(to_seconds(depart, flow.epoch))
    else:
        t0 = flow.time_span[0] if flow.time_span is not None else 0.0
        levels = flow.time_levels
        if flow.time_span is None and levels is not None:
            t0 = float(levels[0])
    for i in range(route.n):
        name = f"{route.source} {route.labels[i]} ({route.names[i]})"
        lat, lon = float(route.lat[i]), float(route.lon[i])
        flow.check_position(lat, lon, name=name)
        u, v = flow.velocity(t0, lat, lon)
        if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
            raise InvalidParameterError(name, (round(lat, 7), round(lon, 7)),
                                        flow.nan_cause(t0, lat, lon))


def _route_legs(route: Route, flow: FlowField, speed: float, depart: Any,
                depth_range: tuple[float, float] | None, resolution: float | None,
                land_clearance_m: float | None, bar: Any, task: Any) -> tuple[
                    list[FieldLeg], dict[str, Any]]:
    """Route the legs in turn (leg i + 1 departs when leg i arrives); stop at a failed leg."""
    from glideplan.errors import PlanningError
    from glideplan.missions.field_legs import fast_leg
    from glideplan.routing import RouteSettings
    from glideplan.routing import route as route_leg

    assert route.lat is not None and route.lon is not None
    legs: list[FieldLeg] = []
    t = depart
    info: dict[str, Any] = {}
    for i in range(route.n - 1):
        if i > 0 and flow.time_span is not None and float(t) >= flow.time_span[1]:
            raise PlanningError(
                f"leg {i + 1} ({route.names[i]} -> {route.names[i + 1]}) would depart at "
                f"{flow.format_time(float(t))}, at or after the field's last time "
                f"{flow.format_time(flow.time_span[1])}")
        a, b = (float(route.lat[i]), float(route.lon[i])), (float(route.lat[i + 1]),
                                                              float(route.lon[i + 1]))
        # a short leg in open water: Zermelo shooting in its own cube of nodes (field_legs)
        res = fast_leg(flow, a, b, speed, t, resolution, land_clearance_m)
        if res is None:
            res = route_leg(flow, a, b, speed, depart=t, depth_range=depth_range,
                            settings=RouteSettings(resolution=resolution,
                                                   land_clearance_m=land_clearance_m))
        if bar is not None:
            bar.update(task, advance=1)
        info = dict(res.field_info)
        legs.append(_field_leg(i, res))
        if not res.ok:
            break
        duration = legs[-1].duration_s
        t = float(res.depart_s) + duration
    return legs, info


#: A leg too long for the routing window: what a mission can do about it.
LEG_WINDOW_ADVICE = ("split the leg with a waypoint between its ends (a shorter leg needs a "
                     "smaller routing window)")


def _field_leg(i: int, res: RouteResult) -> FieldLeg:
    """Leg i from waypoint i to i + 1 of a route result (length and duration NaN if failed)."""
    if not res.ok:
        if res.unreachable_reason == "window_limit":  # advice a mission can follow
            from dataclasses import replace

            from glideplan.routing.route import WINDOW_ADVICE

            res = replace(res, message=res.message.replace(WINDOW_ADVICE, LEG_WINDOW_ADVICE))
        return FieldLeg(index=i, start=i, end=i + 1, result=res, length_m=math.nan,
                        duration_s=math.nan)
    return FieldLeg(index=i, start=i, end=i + 1, result=res, length_m=float(res.distance_m),
                    duration_s=float(res.duration_s or 0.0))


def _chain(results: list[RouteResult], flow: FlowField, depart: Any) -> tuple[
        list[FieldLeg], dict[str, Any]]:
    """Legs routed independently in a steady field, chained in time: leg i + 1 departs when
    leg i arrives (the first at `depart`, or the first leg's own departure); stop at a
    failed leg."""
    from dataclasses import replace

    from glideplan.fields.field import to_seconds

    legs: list[FieldLeg] = []
    t = float(results[0].depart_s) if depart is None else float(to_seconds(depart, flow.epoch))
    for i, res in enumerate(results):
        when = None if flow.epoch is None else flow.epoch + np.timedelta64(round(t * 1e3), "ms")
        res = replace(res, depart_s=t, depart=when)
        legs.append(_field_leg(i, res))
        if not res.ok:
            break
        duration = legs[-1].duration_s
        t += duration
    return legs, dict(results[0].field_info)


def _fly_legs(legs: list[FieldLeg], flow: FlowField, speed: float, radius: float) -> list[FieldLeg]:
    """Each leg's flyable path, ending on the next leg's initial ground course, followed in
    closed loop through `flow` (glideplan.routing.glider.follow_route)."""
    from glideplan.errors import PlanningError
    from glideplan.routing.glider import flyable_path, follow_route
    from glideplan.routing.grid import local_rotation, rotate_to_local

    # Initial course of each leg: in its own aeqd plane, whose axes are east/north at its start.
    first = []
    for leg in legs:
        fp = flyable_path(leg.result, flow, speed, radius)
        if fp.path is None:
            raise PlanningError(f"leg {leg.index + 1}: no flyable path: {fp.message}")
        first.append(float(fp.path.h0[0, 0]))
    out = []
    for k, leg in enumerate(legs):
        end_course = None
        if k + 1 < len(legs):
            res = leg.result
            proj = LocalProjection(float(res.lat[0]), float(res.lon[0]))
            lat, lon = np.atleast_1d(res.lat[-1]), np.atleast_1d(res.lon[-1])
            cg, sg = local_rotation(proj, lat, lon)
            ex, ny = rotate_to_local(np.cos(first[k + 1]), np.sin(first[k + 1]), cg, sg)
            end_course = float(np.arctan2(ny[0], ex[0]))
        glider = follow_route(leg.result, flow, speed, radius, end_course=end_course)
        out.append(FieldLeg(index=leg.index, start=leg.start, end=leg.end, result=leg.result,
                            length_m=leg.length_m, duration_s=leg.duration_s, glider=glider))
    return out
