"""Final glide on the Earth: `final_glide()`, a service above `plan()`, returning `FinalGlide`.

Start (lat, lon, altitude) and goal (lat, lon, elevation) in WGS84 degrees and metres, the wind
as its (east, north) velocity in m/s (where the air moves TOWARDS; the CLI converts its compass
"from" direction), headings as compass bearings (degrees, the geographic edge): converted once
with `glideplan.geodesy` into a local plane about the start (azimuthal equidistant: the
distance and bearing to the goal are the geodesic ones). The straight final glide
(`straight.straight_final_glide`) always runs; with an arrival heading, the path is planned
by `plan()` with the `final_glide` planner (verified by integration) from the given or the best
start heading (`planners.final_glide.best_start_heading`).

Status (`glideplan.solution.Status`): SOLVED when the glide arrives at or above the goal
elevation + safety height, BELOW_GLIDE when it arrives lower, UNREACHABLE when no airspeed
makes progress against the wind (no altitude is enough).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.sailplane.straight import straight_final_glide
from glideplan.solution import Status
from glideplan.track import Track
from glideplan.units import WindEN, wind_to_compass
from glideplan.validation import check_finite, check_physical
from glideplan.vehicles.sailplane_polar import SailplanePolar

if TYPE_CHECKING:
    from glideplan.solution import Solution

__all__ = ["FinalGlide", "FinalGlideDrawing", "final_glide"]


@dataclass(frozen=True, eq=False)
class FinalGlideDrawing:
    """What a figure needs: local track (m; x east, y north), distance along it (m), altitude
    (m), levels (m), the problem in words (`title`), and the wind (east, north) m/s blowing
    TOWARDS (None when no wind was given; the figure labels it in compass degrees)."""

    x: np.ndarray
    y: np.ndarray
    distance: np.ndarray
    altitude: np.ndarray
    goal_elevation: float
    safety_height: float
    title: str
    straight: dict[str, np.ndarray] = field(default_factory=dict)
    wind: WindEN | None = None


@dataclass(frozen=True, eq=False)
class FinalGlide:
    """The outcome of `final_glide()`: an `Outcome` (`glideplan.results`).

    status SOLVED / BELOW_GLIDE / UNREACHABLE (module docstring); altitudes in m (None when
    unreachable); `wind` (east, north) m/s; `track` the ground track with altitude and the
    air heading (geographic; with an arrival heading the planned path, else the straight
    line); `solution` the verified
    `Solution` of `plan()` with an arrival heading; `details` the rest of the `--json` object
    (speeds to fly, the straight glide, the path's word, endpoint error, ...).
    """

    status: Status
    message: str
    polar: SailplanePolar
    distance_m: float
    wind: tuple[float, float]
    altitude_loss_m: float | None
    altitude_required_m: float | None
    arrival_margin_m: float | None
    glide_ratio_required: float | None
    track: Track
    drawing: FinalGlideDrawing
    details: Mapping[str, Any] = field(default_factory=dict)
    solution: Solution | None = None
    warnings: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return self.status is Status.SOLVED

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of `glideplan glide final --json`."""
        return {
            **self.details,
            "altitude_required_m": self.altitude_required_m,
            "arrival_margin_m": self.arrival_margin_m,
            "glide_ratio_required": self.glide_ratio_required,
            "status": self.status.value,
            "message": self.message,
            "warnings": list(self.warnings),
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Ground track and altitude profile (`sailplane.plot.final_glide_figure`); returns the
        figure (two panels: `ax` is not used)."""
        from glideplan.sailplane.plot import final_glide_figure

        return final_glide_figure(self.drawing)


def _finite(v: float | None) -> float | None:
    return float(v) if v is not None and math.isfinite(v) else None


def final_glide(
    polar: SailplanePolar,
    start: tuple[float, float, float],
    goal: tuple[float, float, float],
    *,
    mc: float = 0.0,
    wind: tuple[float, float] | None = None,
    safety_height: float = 300.0,
    arrival_heading: float | None = None,
    start_heading: float | None = None,
    bank_max: float = 45.0,
    track_points: int = 200,
) -> FinalGlide:
    """Altitude needed to reach `goal` from `start`: straight, or to an arrival heading.

    start: (lat, lon, altitude m); goal: (lat, lon, elevation m); mc: MacCready setting (m/s);
    wind: (east, north) velocity of the air (m/s, towards), None for still air;
    safety_height: arrival height above the goal (m); arrival_heading, start_heading: compass
    degrees (start heading None: the best one); bank_max: bank limit in turns (degrees).
    Bad input raises `InvalidParameterError` naming the parameter (`start latitude`, `mc`, ...).
    """
    from glideplan.geodesy import LocalProjection, check_latlon, heading_to_compass

    lat0, lon0, alt0 = start
    lat1, lon1, elev1 = goal
    check_latlon(lat0, lon0, "start")
    check_latlon(lat1, lon1, "goal")
    alt0 = check_physical("start altitude", alt0, "altitude")  # validation.PHYSICAL_RANGES
    elev1 = check_physical("goal elevation", elev1, "elevation")
    mc = check_physical("mc", mc, "mc")
    safety = check_physical("safety_height", safety_height, "height")
    wx, wy = (0.0, 0.0) if wind is None else (
        check_finite("wind east", wind[0]), check_finite("wind north", wind[1]))
    wind_speed = math.hypot(wx, wy)
    proj = LocalProjection(float(lat0), float(lon0))
    gx, gy = (float(v) for v in proj.to_local(lat1, lon1))
    proj.check_extent(np.array([lat0, lat1]), np.array([lon0, lon1]))
    dist = math.hypot(gx, gy)
    same_heading = start_heading is None or (arrival_heading is not None and abs(
        math.remainder(float(start_heading) - float(arrival_heading), 360.0)) < 1e-9)
    if dist <= 0.0 and arrival_heading is not None:
        if not same_heading:
            raise InvalidParameterError(
                "start_heading", start_heading,
                "with the goal at the start position it must equal the arrival heading "
                "(a turn on the spot is not a final glide)")
        # start = goal, heading free or equal: the glider is there, on the arrival heading:
        # solved with zero loss, as plan() answers a start = goal
        arrival_heading = None
    track = math.atan2(gy, gx)
    sg = straight_final_glide(
        polar,
        dist,
        track,
        wind=(wx, wy),
        mc=mc,
        start_altitude=alt0,
        goal_elevation=elev1,
        safety_height=safety,
    )
    row = sg.row()
    if dist <= 0.0:  # start = goal: nothing to fly (as plan() answers a start = goal)
        row.update(altitude_loss=0.0, duration=0.0)
    straight = {
        "altitude_loss_m": _finite(row["altitude_loss"]),
        "speed_to_fly_kmh": _finite(row["speed"] * 3.6),
        "ground_speed_kmh": _finite(row["ground_speed"] * 3.6),
        "headwind_ms": -row["tailwind"],
        "crosswind_ms": row["crosswind"],
        "crab_angle_deg": _finite(math.degrees(row["crab"])),
        "duration_s": _finite(row["duration"]),
    }
    wind_from = None if wind is None else wind_to_compass(wx, wy)[1]
    data: dict[str, Any] = {
        "polar": polar.name,
        "mass_kg": polar.mass_kg,
        "distance_m": dist,
        "bearing_deg": float(heading_to_compass(track)),
        "mc": mc,
        "safety_height_m": safety,
        "wind": {"speed_ms": wind_speed, "from_deg": wind_from},
    }
    floor = elev1 + safety
    title = (
        f"{polar.name} ({polar.mass_kg:.0f} kg): final glide {dist / 1000:.1f} km "
        f"on bearing {data['bearing_deg']:.0f}°, MC {mc:g} m/s"
    )
    sol = None
    if arrival_heading is None:
        loss = row["altitude_loss"]
        data.update(
            altitude_loss_m=_finite(loss),
            speed_to_fly_kmh=straight["speed_to_fly_kmh"],
            ground_speed_kmh=straight["ground_speed_kmh"],
            headwind_ms=straight["headwind_ms"],
            crab_angle_deg=straight["crab_angle_deg"],
            duration_s=straight["duration_s"],
        )
        s = np.linspace(0.0, dist, 2)
        frac = s / dist if dist > 0.0 else s
        drawing = FinalGlideDrawing(
            x=np.array([0.0, gx]),
            y=np.array([0.0, gy]),
            distance=s,
            # the start altitude is known even when the goal is not reachable (loss inf)
            altitude=alt0 - frac * loss if math.isfinite(loss) else np.array([alt0, np.nan]),
            goal_elevation=elev1,
            safety_height=safety,
            title=title,
        )
    elif not math.isfinite(row["altitude_loss"]):
        # no airspeed makes progress against this wind: no path to plan
        loss = math.inf
        data.update(
            altitude_loss_m=None,
            speed_to_fly_kmh=None,
            duration_s=None,
            word="",
            track={"lat": [], "lon": [], "alt": []},
            endpoint_error=None,
            straight=straight,
        )
        drawing = FinalGlideDrawing(
            x=np.array([0.0, gx]),
            y=np.array([0.0, gy]),
            distance=np.array([0.0, dist]),
            altitude=np.array([alt0, np.nan]),
            goal_elevation=elev1,
            safety_height=safety,
            title=title,
        )
    else:
        data_arr, drawing, sol = _arrival(
            polar,
            proj,
            alt0,
            elev1,
            safety,
            gx,
            gy,
            (wx, wy),
            mc,
            arrival_heading,
            start_heading,
            bank_max,
            track_points,
            title,
        )
        loss = data_arr.pop("_loss")
        data.update(data_arr)
        data["straight"] = straight
        data["extra_loss_vs_straight_m"] = (
            loss - row["altitude_loss"] if math.isfinite(row["altitude_loss"]) else None
        )
    required = floor + loss
    height = alt0 - floor
    margin = alt0 - required
    status = _status(loss, margin)
    if status is Status.UNREACHABLE:
        message = _unreachable_why(polar, (wx, wy), row)
    else:
        message = (f"arrives {margin:.0f} m " + ("above" if margin >= 0.0 else "below")
                   + f" the goal elevation + safety height ({floor:.0f} m)")
    drawing = replace(drawing, wind=None if wind is None else (wx, wy))
    lat_t, lon_t = proj.to_geographic(drawing.x, drawing.y)
    if sol is not None:  # the planned path: its sample times and air headings
        times = np.asarray(data.pop("_times"), dtype=float)
        heading = np.asarray(data.pop("_headings"), dtype=float)
    else:  # a straight glide at constant ground speed, crabbing (no time when unreachable)
        t_end = data.get("duration_s") or 0.0
        times = drawing.distance / max(float(drawing.distance[-1]), 1e-300) * t_end
        crab = row["crab"] if math.isfinite(row["crab"]) else 0.0
        heading = np.full(times.size, track + crab)
    ground_track = Track(times, drawing.x, drawing.y, heading, lat=lat_t, lon=lon_t,
                         alt=drawing.altitude)
    if sol is not None:  # the planned path's samples: t, lat, lon, heading_deg, alt
        data["track"] = ground_track.to_dict()
    return FinalGlide(
        status=status,
        message=message,
        polar=polar,
        distance_m=dist,
        wind=(wx, wy),
        altitude_loss_m=_finite(loss),
        altitude_required_m=_finite(required),
        arrival_margin_m=_finite(margin),
        glide_ratio_required=dist / height if height > 0.0 else None,
        track=ground_track,
        drawing=drawing,
        details=data,
        solution=sol,
    )


def _status(loss: float, margin: float) -> Status:
    """UNREACHABLE (no airspeed makes progress: the loss is infinite), else SOLVED when the
    arrival margin is >= 0 m, BELOW_GLIDE when it is negative."""
    if not math.isfinite(loss):
        return Status.UNREACHABLE
    return Status.SOLVED if margin >= 0.0 else Status.BELOW_GLIDE


def _unreachable_why(polar: SailplanePolar, wind: tuple[float, float], row: dict[str, float]
                     ) -> str:
    """Why no airspeed makes progress: the wind ((east, north) m/s; said as speed and the
    compass direction it blows from) against the polar's top speed, with its headwind and
    crosswind components on the track (m/s)."""
    speed, from_deg = wind_to_compass(*wind)
    along = row["tailwind"]
    part = f"headwind {-along:.1f}" if along <= 0.0 else f"tailwind {along:.1f}"
    return (
        f"the wind ({speed:g} m/s from {from_deg:.0f}°: {part} m/s, crosswind "
        f"{abs(row['crosswind']):.1f} m/s on the track) is too strong to make "
        f"progress towards the goal at any airspeed up to the polar's "
        f"{polar.v_max * 3.6:.0f} km/h"
    )


def _arrival(
    polar: SailplanePolar,
    proj: Any,
    alt0: float,
    elev1: float,
    safety: float,
    gx: float,
    gy: float,
    wind: tuple[float, float],
    mc: float,
    arrival_heading: float,
    start_heading: float | None,
    bank_max: float,
    track_points: int,
    title: str,
) -> tuple[dict[str, Any], FinalGlideDrawing, Solution]:
    from glideplan.geodesy import compass_to_heading, heading_to_compass
    from glideplan.planners.final_glide import best_start_heading
    from glideplan.planning import plan
    from glideplan.pose import Pose
    from glideplan.vehicles.sailplane import Sailplane

    check_finite("arrival_heading", arrival_heading)
    bank = check_finite("bank_max", bank_max)
    if not 0.0 < bank <= 80.0:
        raise InvalidParameterError("bank_max", bank_max, "must be in (0, 80] degrees")
    vehicle = Sailplane(polar, bank_max=math.radians(bank), wind=wind)
    goal_pose = Pose(gx, gy, float(compass_to_heading(arrival_heading)))
    if start_heading is None:
        psi0 = best_start_heading((0.0, 0.0), goal_pose, vehicle, mc=mc)
    else:
        psi0 = float(compass_to_heading(check_finite("start_heading", start_heading)))
    sol = plan(Pose(0.0, 0.0, psi0), goal_pose, vehicle, "altitude", mc=mc)
    if not sol.ok or sol.path is None:
        raise_planning(sol.message or sol.status.value)
    assert sol.path is not None and sol.endpoint_error is not None
    path = sol.path
    # half the samples over the whole glide, half over the approach (the last segment)
    t_gate = path.duration - path.segments[-1].duration
    half = max(2, track_points // 2)
    times = np.unique(
        np.concatenate(
            [np.linspace(0.0, path.duration, half), np.linspace(t_gate, path.duration, half)]
        )
    )
    smp = path.sample(times=times, objective="altitude")
    assert smp.cost is not None
    alt = alt0 - smp.cost
    ground = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(smp.x), np.diff(smp.y)))])
    gsx = smp.speed[-1] * math.cos(smp.heading[-1]) + wind[0]
    gsy = smp.speed[-1] * math.sin(smp.heading[-1]) + wind[1]
    loss = float(sol.cost)
    data = {
        "_loss": loss,
        "_times": smp.t,
        "_headings": smp.heading,
        "altitude_loss_m": loss,
        "speed_to_fly_kmh": float(smp.speed[0] * 3.6),
        "duration_s": path.duration,
        "word": sol.word,
        "start_heading_deg": float(heading_to_compass(psi0)),
        "start_heading_free": start_heading is None,
        "arrival_heading_deg": float(arrival_heading) % 360.0,
        "arrival_track_deg": float(heading_to_compass(math.atan2(gsy, gsx))),
        "bank_max_deg": bank,
        "path_ground_length_m": float(ground[-1]),
        "track": {},  # `final_glide` puts the `Track` here
        "endpoint_error": sol.endpoint_error.to_dict(),
        "planner": sol.planner,
        "approach_warm_starts": sol.extras.get("warm_starts", []),
    }
    drawing = FinalGlideDrawing(
        x=smp.x,
        y=smp.y,
        distance=ground,
        altitude=alt,
        goal_elevation=elev1,
        safety_height=safety,
        title=(
            f"{title}, arrival heading {float(arrival_heading) % 360.0:.0f}° "
            f"(path {sol.word}, start heading {heading_to_compass(psi0):.0f}°)"
        ),
    )
    return data, drawing, sol


def raise_planning(message: str) -> None:
    from glideplan.errors import PlanningError

    raise PlanningError(f"final glide: no verified path: {message}")
