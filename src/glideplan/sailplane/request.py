"""A final-glide request on the Earth: geographic edges in, numbers and a track out.

Start (lat, lon, altitude) and goal (lat, lon, elevation) in WGS84 degrees and metres, wind as
speed and compass direction it blows FROM, headings as compass bearings: converted once with
`glideplan.geodesy` into a local plane about the start (azimuthal equidistant: the distance and
bearing to the goal are the geodesic ones). The straight final glide
(`straight.straight_final_glide`) always runs; with an arrival heading, the path is planned
by `plan()` with the `final_glide` planner (verified by integration) from the given or the best
start heading (`planners.final_glide.best_start_heading`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.sailplane.polar import SailplanePolar
from glideplan.sailplane.straight import straight_final_glide
from glideplan.validation import check_finite, check_nonnegative

__all__ = ["FinalGlideDrawing", "run_final"]


@dataclass(frozen=True, eq=False)
class FinalGlideDrawing:
    """What a figure needs: local track (m; x east, y north), distance along it (m), altitude
    (m), levels (m), the problem in words (`title`), and the wind: speed (m/s) and the compass
    direction it blows FROM (deg; None when no wind was given)."""

    x: np.ndarray
    y: np.ndarray
    distance: np.ndarray
    altitude: np.ndarray
    goal_elevation: float
    safety_height: float
    title: str
    straight: dict[str, np.ndarray] = field(default_factory=dict)
    wind_speed: float = 0.0
    wind_from_deg: float | None = None


def _finite(v: float | None) -> float | None:
    return float(v) if v is not None and math.isfinite(v) else None


def run_final(
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
) -> tuple[dict[str, Any], FinalGlideDrawing]:
    """The JSON object of `glideplan glide final` and the data of its figure.

    Headings and the wind direction are compass degrees (wind: where it blows FROM).
    """
    from glideplan.geodesy import (
        LocalProjection,
        check_latlon,
        heading_to_compass,
        wind_from_to_vector,
    )

    lat0, lon0, alt0 = start
    lat1, lon1, elev1 = goal
    check_latlon(lat0, lon0, "--from")
    check_latlon(lat1, lon1, "--to")
    alt0 = check_finite("--from altitude", alt0)
    elev1 = check_finite("--to elevation", elev1)
    mc = check_nonnegative("--mc", mc)
    safety = check_nonnegative("--safety-height", safety_height)
    wx, wy = (0.0, 0.0) if wind is None else wind_from_to_vector(*wind)
    wind_speed = math.hypot(wx, wy)
    proj = LocalProjection(float(lat0), float(lon0))
    gx, gy = (float(v) for v in proj.to_local(lat1, lon1))
    proj.check_extent(np.array([lat0, lat1]), np.array([lon0, lon1]))
    dist = math.hypot(gx, gy)
    if dist <= 0.0:
        raise InvalidParameterError("--to", goal, "must differ from the start position")
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
    straight = {
        "altitude_loss_m": _finite(row["altitude_loss"]),
        "speed_to_fly_kmh": _finite(row["speed"] * 3.6),
        "ground_speed_kmh": _finite(row["ground_speed"] * 3.6),
        "headwind_ms": -row["tailwind"],
        "crosswind_ms": row["crosswind"],
        "crab_angle_deg": _finite(math.degrees(row["crab"])),
        "duration_s": _finite(row["duration"]),
    }
    data: dict[str, Any] = {
        "polar": polar.name,
        "mass_kg": polar.mass_kg,
        "distance_m": dist,
        "bearing_deg": float(heading_to_compass(track)),
        "mc": mc,
        "safety_height_m": safety,
        "wind": {"speed_ms": wind_speed, "from_deg": None if wind is None else wind[1]},
    }
    floor = elev1 + safety
    title = (
        f"{polar.name} ({polar.mass_kg:.0f} kg): final glide {dist / 1000:.1f} km "
        f"on bearing {data['bearing_deg']:.0f}°, MC {mc:g} m/s"
    )
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
        drawing = FinalGlideDrawing(
            x=np.array([0.0, gx]),
            y=np.array([0.0, gy]),
            distance=s,
            # the start altitude is known even when the goal is not reachable (loss inf)
            altitude=alt0 - (s / dist) * loss if math.isfinite(loss) else np.array([alt0, np.nan]),
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
        data_arr, drawing = _arrival(
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
    data.update(
        altitude_required_m=_finite(required),
        arrival_margin_m=_finite(alt0 - required),
        glide_ratio_required=dist / height if height > 0.0 else None,
        status=_status(loss, alt0 - required),
    )
    if not math.isfinite(loss):
        data["message"] = _unreachable_why(polar, wind, row)
    drawing = replace(
        drawing,
        wind_speed=wind_speed,
        wind_from_deg=None if wind is None else float(wind[1]) % 360.0,
    )
    return data, drawing


def _status(loss: float, margin: float) -> str:
    """`unreachable` (no airspeed makes progress: the loss is infinite), else `reachable` when
    the arrival margin is >= 0 m, `below glide` when it is negative."""
    if not math.isfinite(loss):
        return "unreachable"
    return "reachable" if margin >= 0.0 else "below glide"


def _unreachable_why(
    polar: SailplanePolar, wind: tuple[float, float] | None, row: dict[str, float]
) -> str:
    """Why no airspeed makes progress: the wind (m/s, compass FROM) against the polar's top
    speed, with its headwind and crosswind components on the track (m/s)."""
    speed, from_deg = (0.0, 0.0) if wind is None else (float(wind[0]), float(wind[1]) % 360.0)
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
) -> tuple[dict[str, Any], FinalGlideDrawing]:
    from glideplan.geodesy import compass_to_heading, heading_to_compass
    from glideplan.planners.final_glide import best_start_heading
    from glideplan.planning import plan
    from glideplan.pose import Pose
    from glideplan.vehicles.sailplane import Sailplane

    check_finite("--arrival-heading", arrival_heading)
    bank = check_finite("--bank-max", bank_max)
    if not 0.0 < bank <= 80.0:
        raise InvalidParameterError("--bank-max", bank_max, "must be in (0, 80] degrees")
    speed = math.hypot(*wind)
    vehicle = Sailplane(
        polar,
        bank_max=math.radians(bank),
        wind_speed=speed,
        wind_direction=math.atan2(wind[1], wind[0]) if speed > 0.0 else 0.0,
    )
    goal_pose = Pose(gx, gy, float(compass_to_heading(arrival_heading)))
    if start_heading is None:
        psi0 = best_start_heading((0.0, 0.0), goal_pose, vehicle, mc=mc)
    else:
        psi0 = float(compass_to_heading(check_finite("--start-heading", start_heading)))
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
    lat, lon = proj.to_geographic(smp.x, smp.y)
    alt = alt0 - smp.cost
    ground = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(smp.x), np.diff(smp.y)))])
    gsx = smp.speed[-1] * math.cos(smp.heading[-1]) + wind[0]
    gsy = smp.speed[-1] * math.sin(smp.heading[-1]) + wind[1]
    loss = float(sol.cost)
    data = {
        "_loss": loss,
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
        "track": {"lat": lat.tolist(), "lon": lon.tolist(), "alt": alt.tolist()},
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
    return data, drawing


def raise_planning(message: str) -> None:
    from glideplan.errors import PlanningError

    raise PlanningError(f"final glide: no verified path: {message}")
