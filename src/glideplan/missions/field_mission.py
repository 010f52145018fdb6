"""Missions through a current (or wind) field: each leg routed with `glideplan.routing`.

With a spatially and temporally varying field there is no Dubins closed form: each leg is the
time-optimal route of the routing issue (`glideplan.routing.route`: the reachable front of
Lolla et al. 2012, backtracked and refined by Zermelo shooting, verified by integrating its
heading controls through the field). Legs are chained in time: leg i + 1 departs when leg i
arrives. The router models a point mass steering its heading freely, so waypoint headings are
not constrained: the heading reported at a waypoint is the heading through the water when
leaving it (at the last waypoint, when arriving); a heading given in the route is noted as
not enforced.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import compass_to_heading
from glideplan.missions.plan import Track
from glideplan.missions.route import Route
from glideplan.validation import check_positive

__all__ = ["FieldLeg", "FieldMission", "plan_mission_in_field"]


@dataclass(frozen=True, eq=False)
class FieldLeg:
    """One leg routed through the field: waypoint indices, the `RouteResult`, length, time."""

    index: int
    start: int
    end: int
    result: Any  # glideplan.routing.RouteResult
    length_m: float
    duration_s: float

    @property
    def word(self) -> str:
        return str(self.result.method)

    @property
    def ok(self) -> bool:
        return bool(self.result.ok)


@dataclass(frozen=True, eq=False)
class FieldMission:
    """A mission routed through a field; the interface of `MissionPlan` the exporters use."""

    route: Route
    headings: NDArray[np.float64]
    legs: tuple[FieldLeg, ...]
    speed: float
    field_info: dict[str, Any]
    stats: dict[str, Any] = field(default_factory=dict)
    objective: str = "time"
    radius: float | None = None
    wind: tuple[float, float] | None = None

    @property
    def ok(self) -> bool:
        return all(leg.ok for leg in self.legs)

    @property
    def total_length_m(self) -> float:
        return float(sum(leg.length_m for leg in self.legs))

    @property
    def total_duration_s(self) -> float:
        return float(sum(leg.duration_s for leg in self.legs))

    @property
    def headings_deg(self) -> list[float]:
        """Compass heading through the water at each waypoint (leaving it; the last: arriving)."""
        return [float((90.0 - math.degrees(h)) % 360.0) for h in self.headings]

    def track_spacing(self, tolerance: float) -> float:
        """The router's own samples are used (no closed form to resample)."""
        return 0.0

    def track(self, spacing: float | None = None) -> Track:
        """The legs' route samples in the mission's local plane (m), chained in time."""
        assert self.route.projection is not None
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
        return Track(np.concatenate(xs), np.concatenate(ys), np.concatenate(hs),
                     np.concatenate(legs).astype(np.intp), np.concatenate(ts))

    def to_dict(self) -> dict[str, Any]:
        r = self.route
        assert r.lat is not None and r.lon is not None
        return {
            "status": "solved" if self.ok else "unreachable",
            "objective": "time",
            "speed": self.speed,
            "radius": None,
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
                }
                for leg in self.legs
            ],
            "stats": self.stats,
        }


def plan_mission_in_field(
    route: Route, flow: Any, *, speed: float, depart: Any = None,
    depth_range: tuple[float, float] | None = None, resolution: float | None = None,
) -> FieldMission:
    """Route every leg of a geographic `route` through `flow` (a FlowField or file paths).

    `depart` (datetime64, seconds since the field's epoch, or None: its first time), the
    `depth_range` (m) and grid `resolution` (m) go to `glideplan.routing.route`.
    """
    from glideplan.routing import route as route_leg

    speed = check_positive("speed", speed)
    if route.lat is None or route.lon is None:
        raise InvalidParameterError(
            "field", "local route", "routing through a field needs a geographic route (lat/lon)")
    legs: list[FieldLeg] = []
    t = depart
    info: dict[str, Any] = {}
    for i in range(route.n - 1):
        res = route_leg(flow, (float(route.lat[i]), float(route.lon[i])),
                        (float(route.lat[i + 1]), float(route.lon[i + 1])), speed,
                        depart=t, depth_range=depth_range, resolution=resolution)
        info = dict(res.field_info)
        if not res.ok:
            legs.append(FieldLeg(i, i, i + 1, res, math.nan, math.nan))
            break
        duration = float(res.duration_s or 0.0)
        legs.append(FieldLeg(i, i, i + 1, res, float(res.distance_m), duration))
        t = float(res.depart_s) + duration
    h = np.full(route.n, np.nan)
    for leg in legs:
        if leg.ok and len(leg.result.heading_deg):
            h[leg.start] = compass_to_heading(float(leg.result.heading_deg[0]))
            h[leg.end] = compass_to_heading(float(leg.result.heading_deg[-1]))
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
    return FieldMission(route, np.nan_to_num(h), tuple(legs), speed, info, stats)
