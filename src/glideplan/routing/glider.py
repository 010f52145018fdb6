"""The glider-scale path along a route, and closed-loop following through the same field.

At the vehicle's scale the dissertation's machinery applies. The route is sampled into
waypoint poses (position, ground course) every `spacing` metres; consecutive poses are joined
by Dubins paths (§2.7) of the feasible radius R0' = R0 (1 + eps)^2 (eq. 3.3), with
eps = max |c| / V over the route (the current is the disturbance of bound eps V, so the path
is trackable, appendix A). The vehicle (speed V, turn rate |u| <= V / R0) follows the chained
path with Breivik-Fossen lookahead guidance (`glideplan.simulation.guidance`) and the control
law of `glideplan.simulation.closed_loop` (saturated course feedback plus the path's turn rate
as feedforward), pushed by the field's current at its own position and time (the simulator's
`FieldDisturbance`, evaluated every step); we report the cross-track error along the way and
the miss distance at the goal: where the vehicle crosses the goal's finish line (the line
through the goal orthogonal to the final course), as in the cross-track study. eps >= 1 (a
current as fast as the vehicle) has no feasible radius: the result says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.geodesy import LocalProjection
from glideplan.results import Outcome, Reason
from glideplan.routing.route import RouteResult
from glideplan.routing.verify import local_current
from glideplan.simulation.disturbances import VelocityFunction
from glideplan.solution import Status
from glideplan.track import Track

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["FlyablePath", "GliderFollow", "TrochoidChain", "flyable_path", "follow_route",
           "trochoid_chain", "with_flyable_path"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False, kw_only=True)
class GliderFollow(Outcome):
    """Outcome of building and following the flyable path (m, s): an `Outcome`.

    status: SOLVED (crossed the goal's finish line), LOST (stopped on land, off the field or
    timed out; `message` says which) or INFEASIBLE (no feasible radius: eps >= 1). `track`:
    the simulated vehicle, geographic, heading its ground course.
    """

    radius_m: float
    disturbance_ratio: float
    feasible_radius_m: float | None
    legs: int = 0
    path_length_m: float = 0.0
    duration_s: float | None = None
    max_cross_track_m: float | None = None
    rms_cross_track_m: float | None = None
    final_distance_m: float | None = None
    track: Track = field(default_factory=Track.empty)
    flyable: FlyablePath | None = None

    def to_dict(self) -> dict[str, Any]:
        return {
            **super().to_dict(),
            "radius_m": self.radius_m,
            "disturbance_ratio": self.disturbance_ratio,
            "feasible_radius_m": self.feasible_radius_m,
            "legs": self.legs,
            "path_length_m": self.path_length_m,
            "duration_s": self.duration_s,
            "max_cross_track_m": self.max_cross_track_m,
            "rms_cross_track_m": self.rms_cross_track_m,
            "final_distance_m": self.final_distance_m,
            "track": self.track.to_dict() if self.track.size else {},
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """The followed track (lon, lat; deg)."""
        from glideplan.plotting import plot_track
        from glideplan.results import as_figure

        label = f"glider following, R0 = {self.radius_m:.4g} m"
        return as_figure(plot_track(self.track, ax, label=label,
                                    title=f"following: {self.status.value}", **kwargs))


def _waypoints(x: FloatArray, y: FloatArray, spacing: float) -> FloatArray:
    """Poses (M, 3) every `spacing` m of arc length, course from the neighbours."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    keep = np.concatenate([[True], np.diff(s) > 0])
    s, x, y = s[keep], x[keep], y[keep]
    n = max(math.ceil(s[-1] / spacing), 1)
    sq = np.linspace(0.0, s[-1], n + 1)
    wx, wy = np.interp(sq, s, x), np.interp(sq, s, y)
    d = min(spacing / 2, s[-1] / 4)
    ax, ay = np.interp(np.maximum(sq - d, 0), s, x), np.interp(np.maximum(sq - d, 0), s, y)
    bx, by = np.interp(np.minimum(sq + d, s[-1]), s, x), np.interp(np.minimum(sq + d, s[-1]), s, y)
    return np.stack([wx, wy, np.arctan2(by - ay, bx - ax)], axis=1)


@dataclass(frozen=True, eq=False)
class FlyablePath:
    """The Dubins chain of radius R0' along a route, in the route's local plane (aeqd about its
    start; m, rad): `path` one row of `PathArrays` (None when eps >= 1), `pieces` Dubins pieces."""

    proj: LocalProjection
    path: Any  # glideplan.simulation.PathArrays, one row, or None
    disturbance_ratio: float
    feasible_radius_m: float | None
    pieces: int
    message: str = ""

    @property
    def length_m(self) -> float:
        return 0.0 if self.path is None else float(self.path.length[0])

    def sample(self, spacing: float) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
        """Points every <= `spacing` m along the path: arc length s, x, y (m), course (rad)."""
        if self.path is None:
            raise InvalidParameterError("radius", self.feasible_radius_m, self.message)
        n = max(2, math.ceil(self.length_m / spacing) + 1)
        s = np.linspace(0.0, self.length_m, n)
        x, y, chi = self.path.points_along(0, s)
        return s, x, y, chi


def flyable_path(
    result: RouteResult,
    field_: FlowField,
    speed: float,
    radius: float,
    spacing: float | None = None,
    end_course: float | None = None,
) -> FlyablePath:
    """The route's flyable path for turn radius `radius` (m) (module docstring).

    spacing: distance between the route's waypoint poses (m; default max(10 R0', L / 300));
    end_course: the ground course (rad, in the route's local plane) to end with, e.g. the
    next leg's initial course so that a chain of legs keeps a continuous course (default: the
    route's own final course).
    """
    from glideplan.planners.dubins import WORDS, dubins_shortest, feasible_radius, word_directions
    from glideplan.simulation import PathArrays
    from glideplan.validation import check_physical

    check_physical("radius", radius, "turn_radius")  # validation.PHYSICAL_RANGES
    if not result.ok:
        raise InvalidParameterError("route", result.status, "needs a solved route")
    proj = LocalProjection(float(result.lat[0]), float(result.lon[0]))
    u, v = field_.velocity(result.depart_s + result.t, result.lat, result.lon)
    eps = float(np.nanmax(np.hypot(u, v))) / speed
    if eps >= 1.0:
        return FlyablePath(proj, None, eps, None, 0,
                           message=f"the current reaches {eps:.2f} x the speed: no feasible "
                           "radius R0' = R0 (1 + eps)^2 exists for eps >= 1")
    r_f = float(feasible_radius(radius, eps))
    x, y = result.x, result.y
    total = float(np.sum(np.hypot(np.diff(x), np.diff(y))))
    spacing = spacing if spacing is not None else max(10.0 * r_f, total / 300.0)
    poses = _waypoints(x, y, spacing)
    if end_course is not None:
        poses[-1, 2] = end_course
    starts, goals = poses[:-1], poses[1:]
    # Each Dubins piece in its own start frame: the goal relative to the start pose.
    c, s = np.cos(starts[:, 2]), np.sin(starts[:, 2])
    dx, dy = goals[:, 0] - starts[:, 0], goals[:, 1] - starts[:, 1]
    rel = np.stack([c * dx + s * dy, -s * dx + c * dy, goals[:, 2] - starts[:, 2]], axis=1)
    batch = dubins_shortest(np.zeros(3), rel, r_f)
    dirs = np.array([word_directions(WORDS[k]) for k in batch.word_index], dtype=float)
    # One path of every piece in turn (each piece ends at the next one's start pose).
    path = PathArrays.from_segments(starts[:1], dirs.reshape(1, -1),
                                    batch.segment_lengths.reshape(1, -1), r_f)
    return FlyablePath(proj, path, eps, r_f, int(starts.shape[0]))


def follow_route(
    result: RouteResult,
    field_: FlowField,
    speed: float,
    radius: float,
    spacing: float | None = None,
    dt: float | None = None,
    end_course: float | None = None,
) -> GliderFollow:
    """Build the flyable path of `result` for turn radius `radius` (m) and follow it.

    spacing, end_course: as `flyable_path`; dt: simulation step (s; default 0.1 R0 / V). The
    follower is `simulation.follow_paths` with the field as a `FieldDisturbance` (evaluated
    at the vehicle's position every step). The result's `flyable` holds the path.
    """
    from glideplan.simulation import FieldDisturbance, FollowerSettings, follow_paths

    fp = flyable_path(result, field_, speed, radius, spacing, end_course)
    eps, r_f, proj = fp.disturbance_ratio, fp.feasible_radius_m, fp.proj
    if fp.path is None:
        return GliderFollow(status=Status.INFEASIBLE, radius_m=radius, disturbance_ratio=eps,
                            feasible_radius_m=None, message=fp.message, flyable=fp,
                            reason=Reason.NO_FEASIBLE_RADIUS)
    path_length = fp.length_m
    t0 = result.depart_s
    settings = FollowerSettings(
        speed=speed, max_turn_rate=speed / radius, lookahead=radius,
        # gamma = V / R0 (1/s) keeps the path-parameter update stable: gamma dt = 0.1
        gamma=speed / radius, boundary_layer=0.2,
        dt=dt if dt is not None else 0.1 * radius / speed, timeout_factor=3.0,
    )
    current = FieldDisturbance(_follower_velocity(result, field_, proj, radius, speed),
                               t0=float(t0))
    res = follow_paths(fp.path, current.stream(1, settings.dt), settings=settings,
                       disturbance_bound=eps * speed, record=True)
    assert res.tracks is not None and res.cross_track is not None
    xy = res.tracks[:, 0, :]
    steps = res.cross_track.shape[0]
    e = np.abs(res.cross_track[:, 0])
    e = e[np.isfinite(e)] if np.isfinite(e).any() else np.zeros(1)
    every = np.unique(np.r_[np.arange(0, steps + 1, 20), steps])
    lat, lon = proj.to_geographic(xy[every, 0], xy[every, 1])
    status, message = Status.SOLVED, "followed to the goal's finish line"
    reason: Reason | None = None
    if not res.crossed[0]:
        status = Status.LOST
        if res.stopped is not None and res.stopped[0]:
            reason, message = _why_stopped(field_, proj, t0 + steps * settings.dt, xy[-1])
        else:
            reason = Reason.TIMEOUT
            message = "did not cross the goal's finish line before the time-out"
    end = fp.path.end[0]
    final = float(res.error[0]) if res.crossed[0] else math.hypot(
        xy[-1, 0] - end[0], xy[-1, 1] - end[1])
    px, py = xy[every, 0], xy[every, 1]
    course = (np.arctan2(np.gradient(py), np.gradient(px)) if every.size > 1
              else np.zeros(every.size))
    return GliderFollow(
        status=status, radius_m=radius, disturbance_ratio=eps, feasible_radius_m=r_f,
        legs=fp.pieces, path_length_m=path_length, duration_s=float(res.time[0]),
        max_cross_track_m=float(e.max()), rms_cross_track_m=float(np.sqrt(np.mean(e**2))),
        final_distance_m=final, message=message, reason=reason,
        track=Track(every * settings.dt, px, py, course, lat=lat, lon=lon),
        flyable=fp,
    )


#: Legs up to this long (m) are followed through the current sampled once on a grid
#: (`routing.local_sampler`) of this spacing (m).
SAMPLED_MAX_M, SAMPLED_SPACING_M = 30_000.0, 100.0


def _follower_velocity(result: RouteResult, field_: FlowField, proj: LocalProjection,
                       radius: float, speed: float) -> VelocityFunction:
    """The follower's current: `_local_velocity`, sampled on the leg's box for short legs
    (the box grown by 5 R0 + 10 %, the field's levels over 3x the route's duration)."""
    exact = _local_velocity(field_, proj)
    x, y = proj.to_local(np.asarray(result.lat, dtype=float), np.asarray(result.lon, float))
    w, h = float(np.ptp(x)), float(np.ptp(y))
    if max(w, h) > SAMPLED_MAX_M or result.duration_s is None:
        return exact
    pad = 5 * radius + 0.1 * max(w, h) + SAMPLED_SPACING_M
    box = (float(np.min(x)) - pad, float(np.max(x)) + pad, float(np.min(y)) - pad,
           float(np.max(y)) + pad)
    t0, t1 = float(result.depart_s), float(result.depart_s) + 3.0 * float(result.duration_s)
    levels = field_.time_levels
    if levels is None:
        times = np.array([t0]) if field_.time_span is None else None
    else:
        k0 = max(int(np.searchsorted(levels, t0, side="right")) - 1, 0)
        k1 = min(int(np.searchsorted(levels, t1)) + 1, levels.size)
        times = np.asarray(levels[k0:k1], dtype=float)
    if times is None or times.size == 0:
        return exact
    from glideplan.routing.local_sampler import sampled_velocity

    try:
        fast = sampled_velocity(exact, box, times, SAMPLED_SPACING_M,
                                sample=_levels(field_, proj))
    except InvalidParameterError:
        return exact
    if times.size == 1:  # steady: one level answers every time
        return lambda t, xx, yy: fast(float(times[0]), xx, yy)
    return fast


def _levels(field_: FlowField, proj: LocalProjection) -> Any:
    """(times, x, y) -> (u, v) (nt, n) in local axes: `local_current` at many times, the
    points' lat/lon and rotation computed once."""
    from glideplan.routing.grid import local_rotation, rotate_to_local

    def sample(times: FloatArray, x: FloatArray, y: FloatArray) -> tuple[FloatArray,
                                                                         FloatArray]:
        lat, lon = proj.to_geographic(x, y)
        lat, lon = np.atleast_1d(lat), np.atleast_1d(lon)
        cg, sg = local_rotation(proj, lat, lon)
        us, vs = [], []
        for t in times:
            u, v = field_.velocity(float(t), lat, lon)
            cx, cy = rotate_to_local(np.atleast_1d(u), np.atleast_1d(v), cg, sg)
            us.append(cx)
            vs.append(cy)
        return np.array(us), np.array(vs)

    return sample


def _local_velocity(field_: FlowField, proj: LocalProjection) -> VelocityFunction:
    """The field's current in local axes at (t, x, y), NaN off the field or on land."""

    def velocity(t: float, x: FloatArray, y: FloatArray) -> tuple[FloatArray, FloatArray]:
        try:
            return local_current(field_, proj, t, x, y)
        except InvalidParameterError:
            if np.size(x) == 1:
                return np.full(1, np.nan), np.full(1, np.nan)
            pairs = [velocity(t, x[i:i + 1], y[i:i + 1]) for i in range(np.size(x))]
            return np.concatenate([p[0] for p in pairs]), np.concatenate([p[1] for p in pairs])

    return velocity


def _why_stopped(field_: FlowField, proj: LocalProjection, t: float, xy: FloatArray
                 ) -> tuple[Reason, str]:
    try:
        local_current(field_, proj, t, xy[:1], xy[1:2])
    except InvalidParameterError as exc:
        return Reason.LEFT_FIELD, f"the vehicle left the field ({exc})"
    return Reason.LAND, "the vehicle reached land"


@dataclass(frozen=True, eq=False, kw_only=True)
class TrochoidChain(Outcome):
    """The route's flyable path from trochoid pieces (m, s): each piece the minimum-time path of
    the Dubins car in the piece's mean current (`planners.wind.convected_dubins`, dissertation
    §3.2), planned with R0' = R0 (1 + eps')^2 for the residual eps' = max |c - c_mean| / V.

    duration_s: the pieces' times in their mean currents, summed; max_piece_error_m: largest
    endpoint error of a piece, its controls integrated through its mean current (`verify`);
    field_endpoint_error_m: the whole chain's heading controls flown open loop through the
    field itself (`routing.verify.integrate_headings`), distance from the route's end.
    """

    residual_ratio: float
    feasible_radius_m: float | None
    pieces: int = 0
    duration_s: float | None = None
    ground_length_m: float = 0.0
    max_piece_error_m: float | None = None
    field_endpoint_error_m: float | None = None
    track: Track = field(default_factory=Track.empty)

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {k: getattr(self, k) for k in (
            "residual_ratio", "feasible_radius_m", "pieces", "duration_s",
            "ground_length_m", "max_piece_error_m", "field_endpoint_error_m")}
        return {**super().to_dict(), **out}

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """The chain's waypoint poses (lon, lat; deg)."""
        from glideplan.plotting import plot_track
        from glideplan.results import as_figure

        label = f"trochoid chain, {self.pieces} pieces"
        return as_figure(plot_track(self.track, ax, label=label,
                                    title=f"trochoid chain: {self.status.value}", **kwargs))


def with_flyable_path(result: RouteResult, field_: FlowField, speed: float,
                      radius: float) -> RouteResult:
    """`result` with its flyable path of turn radius `radius` (m) followed through the field
    (`follow_route`: `result.glider`) and, unless no radius is feasible, its trochoid chain
    (`trochoid_chain`: `result.trochoid`); a route that is not solved is returned as is."""
    from dataclasses import replace

    if not result.ok:
        return result
    glider = follow_route(result, field_, speed, radius)
    chain = (None if glider.status is Status.INFEASIBLE
             else trochoid_chain(result, field_, speed, radius))
    return replace(result, glider=glider, trochoid=chain)


def trochoid_chain(
    result: RouteResult,
    field_: FlowField,
    speed: float,
    radius: float,
    spacing: float | None = None,
) -> TrochoidChain:
    """Join the route's waypoint poses (as `flyable_path`) by convected-Dubins pieces, each in
    the mean of the current sampled on the route between its poses (TrochoidChain)."""
    from glideplan.planners.dubins import WORDS, feasible_radius
    from glideplan.planners.wind import convected_dubins, convected_dubins_path
    from glideplan.pose import Pose
    from glideplan.routing.verify import integrate_headings
    from glideplan.validation import check_physical
    from glideplan.verify import endpoint_error

    check_physical("radius", radius, "turn_radius")  # validation.PHYSICAL_RANGES
    if not result.ok:
        raise InvalidParameterError("route", result.status, "needs a solved route")
    proj = LocalProjection(float(result.lat[0]), float(result.lon[0]))
    x, y = result.x, result.y
    cx, cy = local_current(field_, proj, result.depart_s + result.t, x, y)  # type: ignore[arg-type]
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    total = float(s[-1])
    eps_all = float(np.nanmax(np.hypot(cx, cy))) / speed
    r_guess = float(feasible_radius(radius, min(eps_all, 0.99)))
    spacing = spacing if spacing is not None else max(10.0 * r_guess, total / 300.0)
    poses = _waypoints(x, y, spacing)
    n = poses.shape[0] - 1
    edges = np.linspace(0.0, total, n + 1)
    piece = np.clip(np.searchsorted(edges, s, side="right") - 1, 0, n - 1)
    mean = np.stack([np.bincount(piece, c, n) / np.maximum(np.bincount(piece, None, n), 1)
                     for c in (cx, cy)], axis=1)
    residual = float(np.max(np.hypot(cx - mean[piece, 0], cy - mean[piece, 1]))) / speed
    if float(np.max(np.hypot(mean[:, 0], mean[:, 1]))) / speed + residual >= 1.0:
        return TrochoidChain(status=Status.INFEASIBLE, residual_ratio=residual,
                             feasible_radius_m=None, reason=Reason.NO_FEASIBLE_RADIUS,
                             message="mean current + residual reach the speed: no feasible "
                             "radius (|c| + eps' V must be < V)")
    r_f = float(feasible_radius(radius, residual))
    duration, ground, worst = 0.0, 0.0, 0.0
    nodes_t, nodes_h = [0.0], [float(poses[0, 2])]
    piece_t = [0.0]
    for i in range(n):
        a, b = poses[i], poses[i + 1]
        c, sn = math.cos(a[2]), math.sin(a[2])
        dx, dy = b[0] - a[0], b[1] - a[1]
        goal = (c * dx + sn * dy, -sn * dx + c * dy, b[2] - a[2])
        wind = (c * mean[i, 0] + sn * mean[i, 1], -sn * mean[i, 0] + c * mean[i, 1])
        sol = convected_dubins(goal, speed=speed, radius=radius, wind=wind, eps=residual)
        if not math.isfinite(sol.time):
            return TrochoidChain(status=Status.INFEASIBLE, residual_ratio=residual,
                                 feasible_radius_m=r_f, pieces=i,
                                 message=f"piece {i + 1}: no convected Dubins path found")
        k = sol.best
        path = convected_dubins_path(Pose(*a), WORDS[k], sol.segment_lengths[k], radius=r_f,
                                     speed=speed, wind=(float(mean[i, 0]), float(mean[i, 1])))
        worst = max(worst, endpoint_error(path, Pose(*b)).position)
        for seg in path.segments:
            # heading nodes: at the segment's ends and every <= pi/4 of turn in between
            turn = abs(getattr(seg, "angle", 0.0))
            m = max(1, math.ceil(turn / (math.pi / 4)))
            local = np.linspace(0.0, seg.duration, m + 1)[1:]
            nodes_t.extend((duration + local).tolist())
            nodes_h.extend(seg.states(local)[2].tolist())
            duration += seg.duration
        ground += sum(float(getattr(seg, "ground_length", seg.length)) for seg in path.segments)
        piece_t.append(duration)
    flown = integrate_headings(field_, proj, speed, result.depart_s + np.array(nodes_t),
                               np.array(nodes_h), (float(x[-1]), float(y[-1])))
    lat, lon = proj.to_geographic(poses[:, 0], poses[:, 1])
    return TrochoidChain(
        status=Status.SOLVED, residual_ratio=residual, feasible_radius_m=r_f, pieces=n,
        duration_s=duration, ground_length_m=ground, max_piece_error_m=worst,
        field_endpoint_error_m=float(flown.endpoint_error_m),
        message=f"{n} convected Dubins pieces",
        track=Track(np.array(piece_t), poses[:, 0], poses[:, 1], poses[:, 2], lat=lat, lon=lon),
    )
