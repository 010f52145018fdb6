"""`RouteResult`: a route's outcome (the outcome contract of `glideplan.results`).

Built by keyword, frozen. status: `Status.SOLVED` (the heading controls, flown through the
field itself, end within `endpoint_tolerance_m` of the goal, in the water and in the field),
`Status.NOT_VERIFIED` (they miss by more, or touch land, or leave the field: the track and
times are kept, `message` says by how much; in a current stronger than the vehicle
`duration_s` is None, the held legs' time being no flown time: `routing.finer_grid`) or
`Status.UNREACHABLE` (`reason`, a
`glideplan.results.Reason`; `unreachable_reason` its word: "front_stopped" -- the
reachable set stopped growing; "field_extent" -- it reached the field's edge (or +-85 deg
latitude) without the goal; "time_span" -- the field's last time came first;
"max_duration" -- the given (or default) longest duration came first;
"window_limit" -- the window would exceed `RouteSettings.max_nodes` (a coarser grid goes on);
"outside_drift_cone" -- the goal lies outside the set the current and the vehicle's speed can
reach at all (`routing.extract.drift_cone`: found before any front, at any resolution);
"missing_data" -- the front reached a time step of the field with no data at all (all NaN);
`best_distance_m` the closest approach, `front` the furthest reach).

Times in s, distances in m (great-circle, on the router's sphere), positions WGS84 degrees.
`track` (a `glideplan.track.Track`): t (s after departure), x/y (m, the azimuthal-equidistant
plane about the start; meaningful for short routes), heading (rad, counter-clockwise from east,
of the through-water velocity), lat/lon (lon continuous across 180 deg). `to_dict()` is the
JSON of `glideplan route --json` (longitudes there in -180..180).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.results import Outcome, Reason
from glideplan.track import Track

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from glideplan.fields.field import FlowField

__all__ = ["UNREACHABLE_REASONS", "FrontMap", "RouteResult"]

FloatArray = NDArray[np.float64]

UNREACHABLE_REASONS = tuple(Reason(r) for r in (
    "front_stopped", "field_extent", "time_span", "max_duration", "window_limit",
    "outside_drift_cone", "polar_limit", "missing_data"))


@dataclass(frozen=True, eq=False)
class FrontMap:
    """The front's arrival times (s after departure; inf never reached) on its final window:
    lat (ny,), lon (nx,) degrees (lon in the route's unwrapped frame), obstacles (ny, nx)."""

    lat: FloatArray
    lon: FloatArray
    arrival: FloatArray
    obstacles: FloatArray | None = None


@dataclass(frozen=True, eq=False, kw_only=True)
class RouteResult(Outcome):
    """A route's outcome (module docstring)."""

    start: tuple[float, float] = (0.0, 0.0)
    goal: tuple[float, float] = (0.0, 0.0)
    speed: float = 0.0
    depart: np.datetime64 | None = None
    depart_s: float = 0.0
    duration_s: float | None = None
    distance_m: float = 0.0
    track: Track = field(default_factory=Track.empty)
    endpoint_error_m: float | None = None
    endpoint_tolerance_m: float | None = None
    straight_line_duration_s: float | None = None
    grid_duration_s: float | None = None
    refined_duration_s: float | None = None
    method: str = "none"
    best_distance_m: float = 0.0
    land_clearance_m: float = 0.0
    field_info: Mapping[str, Any] = field(default_factory=dict)
    stats: Mapping[str, Any] = field(default_factory=dict)
    front: FrontMap | None = None
    #: the flyable path followed through the field (`routing.glider.with_flyable_path`:
    #: a `GliderFollow`) and its trochoid chain (a `TrochoidChain`); JSON "glider"
    glider: Any = None
    trochoid: Any = None

    @property
    def unreachable_reason(self) -> str | None:
        """The reason's word when unreachable (the former field; JSON keeps the key)."""
        return None if self.reason is None else self.reason.value

    # The track's arrays, by the names missions, the glider path and the figures use.
    @property
    def t(self) -> FloatArray:
        return self.track.t

    @property
    def lat(self) -> FloatArray:
        return self.track.lat

    @property
    def lon(self) -> FloatArray:
        return self.track.lon

    @property
    def x(self) -> FloatArray:
        return self.track.x

    @property
    def y(self) -> FloatArray:
        return self.track.y

    @property
    def heading_deg(self) -> FloatArray:
        return self.track.heading_deg if self.track.size else np.zeros(0)

    @property
    def arrive(self) -> np.datetime64 | None:
        if self.depart is None or self.duration_s is None:
            return None
        return self.depart + np.timedelta64(round(self.duration_s * 1e3), "ms")

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of `glideplan route --json`."""

        def iso(d: np.datetime64 | None) -> str | None:
            return None if d is None else str(d.astype("datetime64[s]")) + "Z"

        track = self.track.to_dict() if self.track.size else {
            "t": [], "lat": [], "lon": [], "heading_deg": []}
        return {
            **super().to_dict(),
            "duration_s": self.duration_s,
            "distance_m": self.distance_m,
            "depart": iso(self.depart) if self.depart is not None else self.depart_s,
            "arrive": iso(self.arrive) if self.depart is not None else (
                None if self.duration_s is None else self.depart_s + self.duration_s),
            "track": track,
            "endpoint_error_m": self.endpoint_error_m,
            "endpoint_tolerance_m": self.endpoint_tolerance_m,
            "straight_line_duration_s": self.straight_line_duration_s,
            "grid_duration_s": self.grid_duration_s,
            "refined_duration_s": self.refined_duration_s,
            "method": self.method,
            "best_distance_m": self.best_distance_m,
            "unreachable_reason": self.unreachable_reason,
            "land_clearance_m": self.land_clearance_m,
            "field": dict(self.field_info),
            "stats": dict(self.stats),
            **({} if self.glider is None else {"glider": {
                **self.glider.to_dict(),
                **({} if self.trochoid is None else {"trochoid": self.trochoid.to_dict()})}}),
        }

    def plot(self, ax: Any = None, flow: FlowField | None = None, **kwargs: Any) -> Figure:
        """The route's figure (`glideplan.routing.plot.route_figure`); `flow` (a FlowField)
        draws land and the current (without it: the track, the front and the goal)."""
        from glideplan.results import as_figure
        from glideplan.routing.plot import route_figure

        kwargs.setdefault("glider", self.glider)
        return as_figure(route_figure(self, flow, ax=ax, **kwargs))
