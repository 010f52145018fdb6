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
from glideplan.results import Outcome, Reason
from glideplan.sailplane.straight import straight_final_glide
from glideplan.solution import Status
from glideplan.track import Track
from glideplan.units import WindEN, wind_to_compass
from glideplan.validation import check_finite, check_physical
from glideplan.vehicles.sailplane_polar import SailplanePolar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

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


@dataclass(frozen=True, eq=False, kw_only=True)
class FinalGlide(Outcome):
    """The outcome of `final_glide()`: an `Outcome` (`glideplan.results`).

    status SOLVED / BELOW_GLIDE / UNREACHABLE (module docstring); altitudes in m (None when
    unreachable); `wind` (east, north) m/s; `track` the ground track with altitude and the
    air heading (geographic; with an arrival heading the planned path, else the straight
    line); `solution` the verified
    `Solution` of `plan()` with an arrival heading; `details` the rest of the `--json` object
    (speeds to fly, the straight glide, the path's word, endpoint error, ...).
    """

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

    def to_dict(self) -> dict[str, Any]:
        """The JSON object of `glideplan glide final --json`."""
        return {
            **super().to_dict(),  # the base keys first, as every product's (README)
            **self.details,
            "altitude_required_m": self.altitude_required_m,
            "arrival_margin_m": self.arrival_margin_m,
            "glide_ratio_required": self.glide_ratio_required,
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """Ground track and altitude profile (`sailplane.plot.final_glide_figure`): two panels,
        in a new figure, in the pair of axes `ax`, or side by side inside the one axes `ax`."""
        from glideplan.results import as_figure
        from glideplan.sailplane.plot import final_glide_figure

        return as_figure(final_glide_figure(self.drawing, ax=ax))


def _finite(v: float | None) -> float | None:
    return float(v) if v is not None and math.isfinite(v) else None


@dataclass(frozen=True, eq=False)
class FinalGlideRequest:
    """The final-glide problem, checked (`final_glide_request`): the polar, start (lat, lon,
    altitude m), goal (lat, lon, elevation m), MC (m/s), the wind (east, north) m/s towards
    (`wind_given`: False in still air), safety height (m), the compass headings (deg; None
    free / straight), bank limit (deg) and the number of track samples."""

    polar: SailplanePolar
    start: tuple[float, float, float]
    goal: tuple[float, float, float]
    mc: float
    wind: tuple[float, float]
    wind_given: bool
    safety_height: float
    arrival_heading: float | None
    start_heading: float | None
    bank_max: float
    track_points: int


@dataclass(frozen=True, eq=False)
class _Frame:
    """The local plane about the start: projection, goal (gx, gy) m, distance (m), track
    angle (rad CCW from east), and the arrival heading still to plan (None: straight)."""

    proj: Any
    gx: float
    gy: float
    dist: float
    track: float
    arrival_heading: float | None


@dataclass(frozen=True, eq=False)
class _Glide:
    """One solve step's answer: the altitude loss (m; inf when no airspeed makes progress),
    its JSON details, the drawing, the samples' times (s) and air headings (rad) of a planned
    path (None: straight), the verified `Solution`, and a failed plan (status, message)."""

    loss: float
    details: dict[str, Any]
    drawing: FinalGlideDrawing
    times: np.ndarray | None = None
    headings: np.ndarray | None = None
    solution: Solution | None = None
    failed: Solution | None = None


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
    Bad input raises `InvalidParameterError` naming the parameter (`start latitude`, `mc`, ...);
    a plan to the arrival heading that fails is a status (its own), never an exception.

    A pipeline: the request (`final_glide_request`), the local frame (`_frame`), the straight
    glide (always), one solve step (`_straight`, `_no_progress` or `_arrival`), the result
    (`_final`).
    """
    req = final_glide_request(polar, start, goal, mc=mc, wind=wind, safety_height=safety_height,
                              arrival_heading=arrival_heading, start_heading=start_heading,
                              bank_max=bank_max, track_points=track_points)
    frame = _frame(req)
    sg = straight_final_glide(req.polar, frame.dist, frame.track, wind=req.wind, mc=req.mc,
                              start_altitude=req.start[2], goal_elevation=req.goal[2],
                              safety_height=req.safety_height)
    row = sg.row()
    if frame.dist <= 0.0:  # start = goal: nothing to fly (as plan() answers a start = goal)
        row.update(altitude_loss=0.0, duration=0.0)
    title = (f"{polar.name} ({polar.mass_kg:.0f} kg): final glide {frame.dist / 1000:.1f} km "
             f"on bearing {_bearing(frame):.0f}°, MC {req.mc:g} m/s")
    if frame.arrival_heading is None:
        step = _straight(req, frame, row, title)
    elif not math.isfinite(row["altitude_loss"]):
        step = _no_progress(req, frame, row, title)  # no path to plan
    else:
        step = _arrival(req, frame, row, title)
    return _final(req, frame, row, step)


def final_glide_request(
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
) -> FinalGlideRequest:
    """`final_glide`'s arguments checked into a `FinalGlideRequest` (bad input raises
    `InvalidParameterError` naming the parameter)."""
    from glideplan.geodesy import check_latlon

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
    return FinalGlideRequest(polar, (float(lat0), float(lon0), alt0),
                             (float(lat1), float(lon1), elev1), mc, (wx, wy), wind is not None,
                             safety, arrival_heading, start_heading, bank_max, track_points)


def _frame(req: FinalGlideRequest) -> _Frame:
    """The local plane about the start and the goal in it; a start = goal with a free (or
    the same) start heading needs no turn: no arrival heading to plan."""
    from glideplan.geodesy import MAX_SCALE_DISTORTION, LocalProjection

    (lat0, lon0, _), (lat1, lon1, _) = req.start, req.goal
    proj = LocalProjection(lat0, lon0)
    gx, gy = (float(v) for v in proj.to_local(lat1, lon1))
    dist = math.hypot(gx, gy)
    try:
        proj.check_extent(np.array([lat0, lat1]), np.array([lon0, lon1]))
    except InvalidParameterError as exc:  # named as the goal, in a final glide's words
        raise InvalidParameterError(
            "goal", (lat1, lon1), f"is {dist / 1000:.0f} km from the start: too far for the "
            f"final glide's one local plane about the start ({exc.value} > "
            f"{MAX_SCALE_DISTORTION:g})") from None
    arrival_heading, start_heading = req.arrival_heading, req.start_heading
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
    return _Frame(proj, gx, gy, dist, math.atan2(gy, gx), arrival_heading)


def _bearing(frame: _Frame) -> float:
    from glideplan.geodesy import heading_to_compass

    return float(heading_to_compass(frame.track))


def _straight_json(row: dict[str, float]) -> dict[str, Any]:
    """The straight glide's JSON (speeds km/h, winds m/s, crab deg, duration s)."""
    return {
        "altitude_loss_m": _finite(row["altitude_loss"]),
        "speed_to_fly_kmh": _finite(row["speed"] * 3.6),
        "ground_speed_kmh": _finite(row["ground_speed"] * 3.6),
        "headwind_ms": -row["tailwind"],
        "crosswind_ms": row["crosswind"],
        "crab_angle_deg": _finite(math.degrees(row["crab"])),
        "duration_s": _finite(row["duration"]),
    }


def _line(req: FinalGlideRequest, frame: _Frame, altitude: np.ndarray, title: str
          ) -> FinalGlideDrawing:
    """The drawing of the straight line to the goal with the given altitude profile."""
    return FinalGlideDrawing(x=np.array([0.0, frame.gx]), y=np.array([0.0, frame.gy]),
                             distance=np.array([0.0, frame.dist]), altitude=altitude,
                             goal_elevation=req.goal[2], safety_height=req.safety_height,
                             title=title)


def _straight(req: FinalGlideRequest, frame: _Frame, row: dict[str, float], title: str
              ) -> _Glide:
    """The straight glide is the answer (no arrival heading)."""
    straight, loss, alt0 = _straight_json(row), row["altitude_loss"], req.start[2]
    details = {key: straight[key] for key in (
        "altitude_loss_m", "speed_to_fly_kmh", "ground_speed_kmh", "headwind_ms",
        "crab_angle_deg", "duration_s")}
    # the start altitude is known even when the goal is not reachable (loss inf)
    altitude = (alt0 - np.array([0.0, 1.0]) * loss if math.isfinite(loss) and frame.dist > 0
                else np.array([alt0, alt0 - loss if math.isfinite(loss) else np.nan]))
    return _Glide(loss, details, _line(req, frame, altitude, title))


def _no_progress(req: FinalGlideRequest, frame: _Frame, row: dict[str, float], title: str
                 ) -> _Glide:
    """No airspeed makes progress against the wind: no path to the arrival heading."""
    details: dict[str, Any] = {
        "altitude_loss_m": None, "speed_to_fly_kmh": None, "duration_s": None, "word": "",
        "track": {"lat": [], "lon": [], "alt": []}, "endpoint_error": None,
        "straight": _straight_json(row)}
    return _Glide(math.inf, details, _line(req, frame, np.array([req.start[2], np.nan]), title))


def _final(req: FinalGlideRequest, frame: _Frame, row: dict[str, float], step: _Glide
           ) -> FinalGlide:
    """The `FinalGlide` of a solve step: status, message, reason, the track and the JSON."""
    alt0, elev1 = req.start[2], req.goal[2]
    wind_speed = math.hypot(*req.wind)
    wind_from = wind_to_compass(*req.wind)[1] if req.wind_given else None
    data: dict[str, Any] = {
        "polar": req.polar.name, "mass_kg": req.polar.mass_kg, "distance_m": frame.dist,
        "bearing_deg": _bearing(frame), "mc": req.mc, "safety_height_m": req.safety_height,
        "wind": {"speed_ms": wind_speed, "from_deg": wind_from}, **step.details}
    floor = elev1 + req.safety_height
    loss = step.loss
    required, height, margin = floor + loss, alt0 - floor, alt0 - floor - loss
    status, reason = _status(loss, margin), None
    if step.failed is not None:
        status, reason = step.failed.status, step.failed.reason or Reason.SOLVER
        message = f"no verified path to the arrival heading: {step.failed.message}"
    elif status is Status.UNREACHABLE:
        reason, message = Reason.HEADWIND, _unreachable_why(req.polar, req.wind, row)
    else:
        reason = None if status is Status.SOLVED else Reason.BELOW_SAFETY_HEIGHT
        message = (f"arrives {abs(margin):.0f} m " + ("above" if margin >= 0.0 else "below")
                   + f" the goal elevation + safety height ({floor:.0f} m)")
    drawing = replace(step.drawing, wind=req.wind if req.wind_given else None)
    ground_track = _ground_track(frame, row, step, drawing, data.get("duration_s") or 0.0)
    if step.solution is not None:  # the planned path's samples: t, lat, lon, heading_deg, alt
        data["track"] = ground_track.to_dict()
    return FinalGlide(
        status=status, message=message, reason=reason, polar=req.polar, distance_m=frame.dist,
        wind=req.wind, altitude_loss_m=_finite(loss), altitude_required_m=_finite(required),
        arrival_margin_m=_finite(margin),
        glide_ratio_required=frame.dist / height if height > 0.0 else None,
        track=ground_track, drawing=drawing, details=data, solution=step.solution)


def _ground_track(frame: _Frame, row: dict[str, float], step: _Glide,
                  drawing: FinalGlideDrawing, t_end: float) -> Track:
    """The ground track: the planned path's samples (times, air headings), or a straight
    glide at constant ground speed, crabbing (no time when unreachable)."""
    lat_t, lon_t = frame.proj.to_geographic(drawing.x, drawing.y)
    if step.times is not None and step.headings is not None:
        times, heading = np.asarray(step.times, float), np.asarray(step.headings, float)
    else:
        times = drawing.distance / max(float(drawing.distance[-1]), 1e-300) * t_end
        crab = row["crab"] if math.isfinite(row["crab"]) else 0.0
        heading = np.full(times.size, frame.track + crab)
    return Track(times, drawing.x, drawing.y, heading, lat=lat_t, lon=lon_t,
                 alt=drawing.altitude)


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


def _arrival(req: FinalGlideRequest, frame: _Frame, row: dict[str, float], title: str
             ) -> _Glide:
    """The path to the arrival heading: `plan()` with the `final_glide` planner from the
    given or the best start heading, verified by integration; its samples and JSON. A plan
    that fails is returned as `failed` (a status, not an exception)."""
    from glideplan.geodesy import compass_to_heading, heading_to_compass
    from glideplan.planners.final_glide import best_start_heading
    from glideplan.planning import plan
    from glideplan.pose import Pose
    from glideplan.vehicles.sailplane import Sailplane

    assert frame.arrival_heading is not None
    arrival_heading = check_finite("arrival_heading", frame.arrival_heading)
    bank = check_finite("bank_max", req.bank_max)
    if not 0.0 < bank <= 80.0:
        raise InvalidParameterError("bank_max", req.bank_max, "must be in (0, 80] degrees")
    wind, mc = req.wind, req.mc
    vehicle = Sailplane(req.polar, bank_max=math.radians(bank), wind=wind)
    goal_pose = Pose(frame.gx, frame.gy, float(compass_to_heading(arrival_heading)))
    if req.start_heading is None:
        psi0 = best_start_heading((0.0, 0.0), goal_pose, vehicle, mc=mc)
    else:
        psi0 = float(compass_to_heading(check_finite("start_heading", req.start_heading)))
    sol = plan(Pose(0.0, 0.0, psi0), goal_pose, vehicle, "altitude", mc=mc)
    if not sol.ok or sol.path is None or sol.endpoint_error is None:
        failed = _no_progress(req, frame, row, title)
        return replace(failed, loss=math.nan, failed=sol)
    path = sol.path
    # half the samples over the whole glide, half over the approach (the last segment)
    t_gate = path.duration - path.segments[-1].duration
    half = max(2, req.track_points // 2)
    times = np.unique(np.concatenate(
        [np.linspace(0.0, path.duration, half), np.linspace(t_gate, path.duration, half)]))
    smp = path.sample(times=times, objective="altitude")
    assert smp.cost is not None
    ground = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(smp.x), np.diff(smp.y)))])
    gsx = smp.speed[-1] * math.cos(smp.heading[-1]) + wind[0]
    gsy = smp.speed[-1] * math.sin(smp.heading[-1]) + wind[1]
    loss = float(sol.cost)
    details = {
        "altitude_loss_m": loss, "speed_to_fly_kmh": float(smp.speed[0] * 3.6),
        "duration_s": path.duration, "word": sol.word,
        "start_heading_deg": float(heading_to_compass(psi0)),
        "start_heading_free": req.start_heading is None,
        "arrival_heading_deg": float(arrival_heading) % 360.0,
        "arrival_track_deg": float(heading_to_compass(math.atan2(gsy, gsx))),
        "bank_max_deg": bank, "path_ground_length_m": float(ground[-1]),
        "track": {},  # `_final` puts the `Track` here
        "endpoint_error": sol.endpoint_error.to_dict(), "planner": sol.planner,
        "approach_warm_starts": sol.extras.get("warm_starts", []),
        "straight": _straight_json(row),
        "extra_loss_vs_straight_m": (loss - row["altitude_loss"]
                                     if math.isfinite(row["altitude_loss"]) else None),
    }
    drawing = FinalGlideDrawing(
        x=smp.x, y=smp.y, distance=ground, altitude=req.start[2] - smp.cost,
        goal_elevation=req.goal[2], safety_height=req.safety_height,
        title=(f"{title}, arrival heading {float(arrival_heading) % 360.0:.0f}° "
               f"(path {sol.word}, start heading {heading_to_compass(psi0):.0f}°)"))
    return _Glide(loss, details, drawing, smp.t, smp.heading, sol)
