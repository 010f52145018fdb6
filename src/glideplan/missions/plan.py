"""Plan a multi-leg mission: optimal headings, one verified path per leg, the dense track.

`plan_mission(route, speed=..., radius=...)` chooses the free headings (`headings.py`: DP over
K candidates, then refinement), then plans every leg with `glideplan.plan()` — the Dubins
planner in still air, the convected-Dubins planner with a wind — so each leg's path is
verified by integrating the vehicle's equations of motion and carries its endpoint error.

Wind inside the library is one vector, `wind = (east, north)` m/s the air (water) moves
TOWARDS (`glideplan.units.WindEN`); the compass form (speed, direction it blows FROM in degrees)
appears only at the edges: the CLI's `--wind` and the JSON of `to_dict()`.

`MissionPlan.to_dict()` (and `FieldMission.to_dict()`) is exactly the `--json` object of
`glideplan mission plan` (the CLI only adds `files`, the files it wrote).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import heading_to_compass
from glideplan.missions.headings import (
    HeadingPlan,
    LegCost,
    StillAirCost,
    WindCost,
    optimise_headings,
)
from glideplan.missions.route import Route
from glideplan.path import Path
from glideplan.results import Outcome, Reason
from glideplan.solution import Solution, Status
from glideplan.track import Track, iso_times
from glideplan.units import WindEN, wind_to_compass
from glideplan.validation import check_finite, check_physical

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from glideplan.missions.straight_legs import StraightLegList

__all__ = ["DEFAULT_MAX_DEVIATION_M", "MissionLeg", "MissionPlan", "Track", "mission_outcome",
           "plan_mission"]

OBJECTIVES = ("length", "time")
# The straight-leg deviation of `to_dict()` when none is given (m): the CLI's default, half its
# default 100 m acceptance radius (`glideplan.formats.ExportOptions`).
DEFAULT_MAX_DEVIATION_M = 50.0


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
    def status(self) -> Status:
        return self.solution.status

    @property
    def reason(self) -> Reason | None:
        return self.solution.reason

    @property
    def status_text(self) -> str:
        """The leg's status and message (`Solution`)."""
        sol = self.solution
        return sol.status.value + (f": {sol.message}" if sol.message else "")


def mission_outcome(legs: Sequence[Any], names: Sequence[str]) -> dict[str, Any]:
    """The `Outcome` fields of a mission from its legs (each with `ok`, `status`, `reason`,
    `status_text`, `index`, `start`, `end`): SOLVED with the legs and totals when every leg
    is, else the first failing leg's status and reason (NO_PATH, NOT_VERIFIED,
    SOLVER_FAILED, UNREACHABLE, ...; reason LEG_FAILED when the leg gives none) and a message
    naming the leg."""
    for leg in legs:
        if not leg.ok:
            return {"status": leg.status, "reason": leg.reason or Reason.LEG_FAILED,
                    "message": (f"leg {leg.index + 1} ({names[leg.start]} -> "
                                f"{names[leg.end]}): {leg.status_text}")}
    length = float(sum(leg.length_m for leg in legs))
    duration = float(sum(leg.duration_s for leg in legs))
    return {"status": Status.SOLVED, "reason": None,
            "message": f"{len(legs)} legs, {length:.0f} m, {duration:.0f} s"}


class LegTotals:
    """Totals over a mission's `legs` (each with `length_m`, `duration_s`, `ok`) and its
    `headings`, and the plot shared by the mission results (`MissionPlan`,
    `glideplan.missions.FieldMission`; their status, message and reason: `mission_outcome`)."""

    legs: tuple[Any, ...]
    headings: NDArray[np.float64]
    route: Route
    stats: dict[str, Any]
    # the exported straight-leg list (`missions.straight_legs`), set by whoever exported it
    straight_legs: StraightLegList | None
    # (east, north) m/s the wind/current moves towards; None in still air or in a field
    wind_vector: tuple[float, float] | None = None

    def track(self, spacing: float | None = None) -> Track:
        raise NotImplementedError

    def track_spacing(self, tolerance: float) -> float:
        raise NotImplementedError

    @property
    def total_length_m(self) -> float:
        return float(sum(leg.length_m for leg in self.legs))

    @property
    def total_duration_s(self) -> float:
        return float(sum(leg.duration_s for leg in self.legs))

    @property
    def waypoint_eta_s(self) -> list[float]:
        """When each waypoint is reached (s after departure): 0, then the legs' durations
        summed (t_{i+1} = t_i + T_i); as many as the legs reach."""
        out = [0.0]
        for leg in self.legs:
            out.append(out[-1] + float(leg.duration_s))
        return out

    @property
    def depart_time(self) -> np.datetime64 | None:
        """The departure's UTC time (None: a mission with no calendar)."""
        return getattr(self, "depart", None)

    @property
    def headings_deg(self) -> list[float]:
        """Compass bearing (deg) at each waypoint, chosen or given."""
        return [float(b) for b in np.atleast_1d(heading_to_compass(self.headings))]

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """The mission figure (`glideplan.missions.plot.plot_mission`)."""
        from glideplan.missions.plot import plot_mission
        from glideplan.results import as_figure

        legs = kwargs.pop("legs", self.straight_legs)
        return as_figure(plot_mission(self, legs, ax=ax, **kwargs))  # type: ignore[arg-type]

    def track_json(self) -> dict[str, list[float]] | None:
        """The track of `--json`: lat/lon (deg, 1e-9; -180..180) of a geographic route, else
        x/y (m, 1e-4); None when a leg failed (no track)."""
        if not all(leg.ok for leg in self.legs):
            return None
        track = self.track()
        proj = self.route.projection
        if proj is None:
            return {"x": [round(float(v), 4) for v in track.x],
                    "y": [round(float(v), 4) for v in track.y]}
        lat, lon = proj.to_geographic(track.x, track.y)
        return {"lat": [round(float(v), 9) for v in np.atleast_1d(lat)],
                "lon": [round(float(v), 9) for v in np.atleast_1d(lon)]}

    def _with_track(self, data: dict[str, Any],
                    straight_legs: StraightLegList | None) -> dict[str, Any]:
        """`data` with the track and, in `stats`, the straight-leg list (`straight_legs`, a
        `StraightLegList`; default: the list within `DEFAULT_MAX_DEVIATION_M`)."""
        stats = dict(data.get("stats", {}))
        straight_legs = straight_legs or self.straight_legs
        if all(leg.ok for leg in self.legs):
            if straight_legs is None:
                from glideplan.missions.straight_legs import straight_leg_list

                straight_legs = straight_leg_list(self, DEFAULT_MAX_DEVIATION_M)  # type: ignore[arg-type]
            stats["straight_legs"] = {
                "waypoints": len(straight_legs.names),
                "tolerance_m": straight_legs.tolerance_m,
                "max_deviation_m": straight_legs.max_deviation_m,
                "sample_spacing_m": straight_legs.sample_spacing_m,
            }
        data["stats"] = stats
        data["track"] = self.track_json()
        etas = self.waypoint_eta_s
        times = iso_times(self.depart_time, etas)
        for w, eta, when in zip(data.get("waypoints", []), etas, times, strict=False):
            w["eta_s"] = eta
            w["eta"] = when
        return data


@dataclass(frozen=True, eq=False, kw_only=True)
class MissionPlan(LegTotals, Outcome):
    """A planned mission: the route, chosen headings (rad), verified legs and statistics.

    An `Outcome` (`glideplan.results`): status SOLVED (every leg verified) or the first failed
    leg's (`mission_outcome`).
    """

    route: Route
    headings: NDArray[np.float64]
    legs: tuple[MissionLeg, ...]
    objective: str
    speed: float
    radius: float
    heading_plan: HeadingPlan
    wind_vector: tuple[float, float] | None = None  # (east, north) m/s, moving TOWARDS
    stats: dict[str, Any] = field(default_factory=dict)
    straight_legs: StraightLegList | None = None
    depart: np.datetime64 | None = None  # UTC of the departure: the waypoints' ETAs as times

    def track_spacing(self, tolerance: float) -> float:
        """Sample spacing (m) whose arcs leave their chords by <= 1 % of `tolerance`.

        Sagitta s^2 / (8 R_ground) with R_ground = R (1 - w/v)^2 the tightest ground turn.
        """
        w = 0.0 if self.wind_vector is None else math.hypot(*self.wind_vector)
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

    def to_dict(self, straight_legs: StraightLegList | None = None) -> dict[str, Any]:
        """The `--json` object of `glideplan mission plan` (the CLI adds only `files`).

        The wind at this edge is compass: {"speed" m/s, "from_deg"}. `track`: lat/lon or x/y
        (`track_json`); `stats.straight_legs` describes `straight_legs` (the exported
        `StraightLegList`; default: the list within `DEFAULT_MAX_DEVIATION_M`).
        """
        r = self.route
        wind = None if self.wind_vector is None else wind_to_compass(*self.wind_vector)
        return self._with_track({
            **super().to_dict(),
            "objective": self.objective,
            "speed": self.speed,
            "radius": self.radius,
            "wind": None if wind is None else {"speed": wind[0], "from_deg": wind[1]},
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
        }, straight_legs)


def _ground_length(path: Path) -> float:
    return float(sum(getattr(seg, "ground_length", seg.length) for seg in path.segments))


def plan_mission(
    route: Route,
    *,
    speed: float,
    radius: float,
    objective: str = "length",
    wind: WindEN | None = None,
    wind_vector: WindEN | None = None,
    headings: int | None = None,
    precision: str = "single",
    refine: bool = True,
    progress: Callable[[str, int, int], None] | None = None,
) -> MissionPlan:
    """Plan `route` for a vehicle of `speed` (m/s) and minimum turn `radius` (m).

    `objective` "length" (m) or "time" (s); `wind` = (east, north) m/s the steady wind
    (current) moves TOWARDS (`glideplan.units.WindEN`, as every planner and product takes it)
    plans time-optimal convected Dubins legs (the objective must be "time"); `wind_vector` is
    an older name of the same vector (give at most one). A compass wind (speed, FROM deg) is
    converted at the edge by `glideplan.units.wind_from_compass`.
    `headings` = K candidates per free waypoint (default 360 in still air, 36 in a wind).
    `progress(phase, done, total)` reports the long phases ("headings": the DP over the
    legs; "legs": planning and verifying each leg) for a progress bar.
    """
    speed = check_physical("speed", speed, "speed")  # validation.PHYSICAL_RANGES
    radius = check_physical("radius", radius, "turn_radius")
    if objective not in OBJECTIVES:
        raise InvalidParameterError("objective", objective, "must be length or time")
    wind_vector = _wind(wind, wind_vector)
    k = headings if headings is not None else (36 if wind_vector is not None else 360)
    if not isinstance(k, int) or not 4 <= k <= 3600:
        raise InvalidParameterError("headings", k, "must be an integer in [4, 3600]")
    vehicle, cost = _vehicle_and_cost(route, speed, radius, objective, wind_vector, precision)
    hp = optimise_headings(cost, route.points, route.headings, k, refine=refine,
                           progress=progress)
    t0 = time.perf_counter()
    legs = _plan_legs(route, hp.headings, vehicle,
                      objective if wind_vector is None else "time", progress)
    errors = [leg.solution.endpoint_error.max for leg in legs if leg.solution.endpoint_error]
    stats: dict[str, Any] = dict(hp.stats)
    stats.update(
        {
            "legs_seconds": time.perf_counter() - t0,
            "max_endpoint_error": max(errors) if errors else None,
            "projection": _projection_stats(route),
            "planned_cost": hp.total,
        }
    )
    return MissionPlan(
        **mission_outcome(legs, route.names),
        route=route, headings=hp.headings, legs=tuple(legs), objective=objective, speed=speed,
        radius=radius, wind_vector=wind_vector, heading_plan=hp, stats=stats,
        warnings=tuple(route.warnings),  # what reading the route file skipped or assumed
    )


def _wind(wind: WindEN | None, wind_vector: WindEN | None) -> WindEN | None:
    """The one wind vector of `wind` or its older name `wind_vector` (checked, m/s)."""
    if wind is not None and wind_vector is not None:
        raise InvalidParameterError("wind", wind, "give either wind or wind_vector, not both")
    name = "wind" if wind_vector is None else "wind_vector"
    wind_vector = wind if wind is not None else wind_vector
    if wind_vector is not None:
        wind_vector = (check_finite(f"{name} east", wind_vector[0]),
                       check_finite(f"{name} north", wind_vector[1]))
        check_physical(name, math.hypot(*wind_vector), "wind_speed")
    return wind_vector


def _vehicle_and_cost(route: Route, speed: float, radius: float, objective: str,
                      wind_vector: WindEN | None, precision: str) -> tuple[Any, LegCost]:
    """The vehicle the legs are planned for and the heading DP's leg cost: convected Dubins
    in a wind (time only), else the Dubins car (length, or time = length / speed)."""
    from glideplan.vehicles.dubins_car import DubinsCar
    from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind

    pts = route.points
    if wind_vector is not None:
        if objective != "time":
            raise InvalidParameterError(
                "objective", objective, "with a wind the planner minimises time: use time"
            )
        u, v = wind_vector
        return (DubinsCarInWind(speed, radius, wind=(u, v)),
                WindCost(pts, radius, speed, (u, v)))
    return (DubinsCar(speed=speed, turn_radius=radius),
            StillAirCost(pts, radius, 1.0 if objective == "length" else 1.0 / speed,
                         precision))


def _plan_legs(route: Route, h: Any, vehicle: Any, objective: str,
               progress: Callable[[str, int, int], None] | None) -> list[MissionLeg]:
    """Each leg planned (and verified) by `glideplan.plan` between the chosen headings."""
    from glideplan.planning import plan
    from glideplan.pose import Pose

    pts = route.points
    legs = []
    for i in range(route.n - 1):
        sol = plan(
            Pose(float(pts[i, 0]), float(pts[i, 1]), float(h[i])),
            Pose(float(pts[i + 1, 0]), float(pts[i + 1, 1]), float(h[i + 1])),
            vehicle,
            objective,
        )
        if sol.path is None:
            legs.append(MissionLeg(index=i, start=i, end=i + 1, solution=sol,
                                   length_m=math.nan, duration_s=math.nan))
        else:
            legs.append(MissionLeg(index=i, start=i, end=i + 1, solution=sol,
                                   length_m=_ground_length(sol.path),
                                   duration_s=float(sol.path.duration)))
        if progress is not None:
            progress("legs", i + 1, route.n - 1)
    return legs


def _projection_stats(route: Route) -> dict[str, Any] | None:
    """The projection of a lat/lon route (kind, centre, distortion, round trip), else None."""
    if route.projection is None:
        return None
    return {
        "kind": "aeqd",
        "lat0": route.projection.lat0,
        "lon0": route.projection.lon0,
        "scale_distortion": route.distortion,
        "roundtrip_error_deg": route.roundtrip_error_deg,
    }
