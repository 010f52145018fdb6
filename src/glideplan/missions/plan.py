"""Plan a multi-leg mission: optimal headings, one verified path per leg, the dense track.

`plan_mission(route, speed=..., radius=...)` chooses the free headings (`headings.py`: DP over
K candidates, then refinement), then plans every leg with `glideplan.plan()` — the Dubins
planner in still air, the convected-Dubins planner with a wind — so each leg's path is
verified by integrating the vehicle's equations of motion and carries its endpoint error.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import heading_to_compass, wind_from_to_vector
from glideplan.missions.headings import (
    HeadingPlan,
    LegCost,
    StillAirCost,
    WindCost,
    optimise_headings,
)
from glideplan.missions.route import Route
from glideplan.path import Path
from glideplan.solution import Solution, Status
from glideplan.track import Track
from glideplan.validation import check_physical

__all__ = ["MissionLeg", "MissionPlan", "Track", "plan_mission"]

OBJECTIVES = ("length", "time")


@dataclass(frozen=True, eq=False)
class MissionLeg:
    """One leg: waypoint indices, the verified `Solution`, ground length (m), duration (s)."""

    index: int
    start: int
    end: int
    solution: Solution
    length_m: float
    duration_s: float

    @property
    def path(self) -> Path:
        assert self.solution.path is not None
        return self.solution.path

    @property
    def word(self) -> str:
        return self.solution.word

    @property
    def ok(self) -> bool:
        return self.solution.ok

    @property
    def status_text(self) -> str:
        """The leg's status and message (`Solution`)."""
        sol = self.solution
        return sol.status.value + (f": {sol.message}" if sol.message else "")


class LegTotals:
    """Totals over a mission's `legs` (each with `length_m`, `duration_s`, `ok`) and its
    `headings`, and the `Outcome` contract's status, message and plot shared by the mission
    results (`MissionPlan`, `glideplan.missions.FieldMission`)."""

    legs: tuple[Any, ...]
    headings: NDArray[np.float64]
    route: Route
    # the status of a mission that is not solved (a leg failed)
    failure_status: ClassVar[Status] = Status.FAILED
    warnings: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return all(leg.ok for leg in self.legs)

    @property
    def status(self) -> Status:
        """SOLVED when every leg is, else `failure_status` (FAILED, or UNREACHABLE in a field)."""
        return Status.SOLVED if self.ok else self.failure_status

    @property
    def message(self) -> str:
        """One line: the legs and totals, or the first leg that failed and why."""
        names = self.route.names
        for leg in self.legs:
            if not leg.ok:
                why = getattr(leg, "status_text", "")
                return f"leg {leg.index + 1} ({names[leg.start]} -> {names[leg.end]}): {why}"
        return (f"{len(self.legs)} legs, {self.total_length_m:.0f} m, "
                f"{self.total_duration_s:.0f} s")

    @property
    def total_length_m(self) -> float:
        return float(sum(leg.length_m for leg in self.legs))

    @property
    def total_duration_s(self) -> float:
        return float(sum(leg.duration_s for leg in self.legs))

    @property
    def headings_deg(self) -> list[float]:
        """Compass bearing (deg) at each waypoint, chosen or given."""
        return [float(b) for b in np.atleast_1d(heading_to_compass(self.headings))]

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The mission figure (`glideplan.missions.plot.plot_mission`); returns the figure."""
        from glideplan.missions.plot import plot_mission

        return plot_mission(self, ax=ax, **kwargs)  # type: ignore[arg-type]


@dataclass(frozen=True, eq=False)
class MissionPlan(LegTotals):
    """A planned mission: the route, chosen headings (rad), verified legs and statistics.

    An `Outcome` (`glideplan.results`): status SOLVED (every leg verified) or FAILED.
    """

    route: Route
    headings: NDArray[np.float64]
    legs: tuple[MissionLeg, ...]
    objective: str
    speed: float
    radius: float
    wind: tuple[float, float] | None  # (speed m/s, compass direction it blows FROM, deg)
    heading_plan: HeadingPlan
    stats: dict[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    def track_spacing(self, tolerance: float) -> float:
        """Sample spacing (m) whose arcs leave their chords by <= 1 % of `tolerance`.

        Sagitta s^2 / (8 R_ground) with R_ground = R (1 - w/v)^2 the tightest ground turn.
        """
        w = 0.0 if self.wind is None else self.wind[0]
        r_ground = self.radius * (1.0 - w / self.speed) ** 2
        return min(self.radius / 10.0, math.sqrt(0.08 * r_ground * tolerance))

    def track(self, spacing: float | None = None) -> Track:
        """Samples of the whole track every `spacing` metres of flight (default R / 10)."""
        step = spacing if spacing is not None else self.radius / 10.0
        xs, ys, hs, legs, ts = [], [], [], [], []
        t0 = 0.0
        for leg in self.legs:
            path = leg.path
            n = max(2, math.ceil(path.duration * self.speed / step) + 1)
            s = path.sample(n=n)
            first = 0 if leg.index == 0 else 1  # legs share their end points
            xs.append(s.x[first:])
            ys.append(s.y[first:])
            hs.append(s.heading[first:])
            legs.append(np.full(n - first, leg.index))
            ts.append(t0 + s.t[first:])
            t0 += path.duration
        return Track(t=np.concatenate(ts), x=np.concatenate(xs), y=np.concatenate(ys),
                     heading=np.concatenate(hs), leg=np.concatenate(legs).astype(np.intp))

    def to_dict(self) -> dict[str, Any]:
        """The mission as JSON data (without the track or files: the CLI adds those)."""
        r = self.route
        return {
            "status": self.status.value,
            "message": self.message,
            "warnings": list(self.warnings),
            "objective": self.objective,
            "speed": self.speed,
            "radius": self.radius,
            "wind": None if self.wind is None else
            {"speed": self.wind[0], "from_deg": self.wind[1]},
            "total_length_m": self.total_length_m,
            "total_duration_s": self.total_duration_s,
            "headings_deg": self.headings_deg,
            "headings_given": [not f for f in r.free.tolist()],
            "waypoints": [
                {"name": r.names[i], **(
                    {"lat": float(r.lat[i]), "lon": float(r.lon[i])}
                    if r.lat is not None and r.lon is not None else {}
                ), "x": float(r.x[i]), "y": float(r.y[i])}
                for i in range(r.n)
            ],
            "legs": [
                {
                    "from": r.names[leg.start],
                    "to": r.names[leg.end],
                    "word": leg.solution.word,
                    "length_m": leg.length_m,
                    "duration_s": leg.duration_s,
                    "status": leg.solution.status.value,
                    "endpoint_error": (
                        leg.solution.endpoint_error.to_dict()
                        if leg.solution.endpoint_error else None
                    ),
                }
                for leg in self.legs
            ],
            "stats": self.stats,
        }


def _ground_length(path: Path) -> float:
    return float(sum(getattr(seg, "ground_length", seg.length) for seg in path.segments))


def plan_mission(
    route: Route,
    *,
    speed: float,
    radius: float,
    objective: str = "length",
    wind: tuple[float, float] | None = None,
    headings: int | None = None,
    precision: str = "single",
    refine: bool = True,
    progress: Callable[[str, int, int], None] | None = None,
) -> MissionPlan:
    """Plan `route` for a vehicle of `speed` (m/s) and minimum turn `radius` (m).

    `objective` "length" (m) or "time" (s); `wind` = (speed m/s, compass direction it blows
    FROM, deg) plans time-optimal convected Dubins legs (the objective must be "time").
    `headings` = K candidates per free waypoint (default 360 in still air, 36 in a wind).
    `progress(phase, done, total)` reports the long phases ("headings": the DP over the
    legs; "legs": planning and verifying each leg) for a progress bar.
    """
    from glideplan.planning import plan
    from glideplan.pose import Pose
    from glideplan.vehicles.dubins_car import DubinsCar
    from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind

    speed = check_physical("speed", speed, "speed")  # validation.PHYSICAL_RANGES
    radius = check_physical("radius", radius, "turn_radius")
    if objective not in OBJECTIVES:
        raise InvalidParameterError("objective", objective, "must be length or time")
    k = headings if headings is not None else (36 if wind else 360)
    if not isinstance(k, int) or not 4 <= k <= 3600:
        raise InvalidParameterError("headings", k, "must be an integer in [4, 3600]")
    pts = route.points
    cost: LegCost
    vehicle: Any
    if wind is not None:
        if objective != "time":
            raise InvalidParameterError(
                "objective", objective, "with a wind the planner minimises time: use time"
            )
        u, v = wind_from_to_vector(float(wind[0]), float(wind[1]))
        w = math.hypot(u, v)
        vehicle = DubinsCarInWind(speed, radius, w, math.atan2(v, u) if w > 0 else 0.0)
        cost = WindCost(pts, radius, speed, (u, v))
    else:
        vehicle = DubinsCar(speed=speed, turn_radius=radius)
        cost = StillAirCost(pts, radius, 1.0 if objective == "length" else 1.0 / speed,
                            precision)
    hp = optimise_headings(cost, pts, route.headings, k, refine=refine, progress=progress)
    h = hp.headings
    t0 = time.perf_counter()
    legs = []
    for i in range(route.n - 1):
        sol = plan(
            Pose(float(pts[i, 0]), float(pts[i, 1]), float(h[i])),
            Pose(float(pts[i + 1, 0]), float(pts[i + 1, 1]), float(h[i + 1])),
            vehicle,
            objective if wind is None else "time",
        )
        if sol.path is None:
            legs.append(MissionLeg(i, i, i + 1, sol, math.nan, math.nan))
            if progress is not None:
                progress("legs", i + 1, route.n - 1)
            continue
        legs.append(
            MissionLeg(i, i, i + 1, sol, _ground_length(sol.path), float(sol.path.duration))
        )
        if progress is not None:
            progress("legs", i + 1, route.n - 1)
    errors = [leg.solution.endpoint_error.max for leg in legs if leg.solution.endpoint_error]
    stats: dict[str, Any] = dict(hp.stats)
    stats.update(
        {
            "legs_seconds": time.perf_counter() - t0,
            "max_endpoint_error": max(errors) if errors else None,
            "projection": (
                {
                    "kind": "aeqd",
                    "lat0": route.projection.lat0,
                    "lon0": route.projection.lon0,
                    "scale_distortion": route.distortion,
                    "roundtrip_error_deg": route.roundtrip_error_deg,
                }
                if route.projection is not None else None
            ),
            "planned_cost": hp.total,
        }
    )
    return MissionPlan(
        route=route, headings=h, legs=tuple(legs), objective=objective, speed=speed,
        radius=radius, wind=None if wind is None else (float(wind[0]), float(wind[1])),
        heading_plan=hp, stats=stats,
    )
