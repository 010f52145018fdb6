"""The glider-scale path along a route, and closed-loop following through the same field.

At the vehicle's scale the dissertation's machinery applies. The route is sampled into
waypoint poses (position, ground course) every `spacing` metres; consecutive poses are joined
by Dubins paths (§2.7) of the feasible radius R0' = R0 (1 + eps)^2 (eq. 3.3), with
eps = max |c| / V over the route (the current is the disturbance of bound eps V, so the path
is trackable, appendix A). The vehicle (speed V, turn rate |u| <= V / R0) follows the chained
path with Breivik-Fossen lookahead guidance (`glideplan.simulation.guidance`) and the control
law of `glideplan.simulation.closed_loop` (saturated course feedback plus the path's turn rate
as feedforward), pushed by the field's current at its own position and time; we report the
cross-track error along the way and the miss distance at the goal. eps >= 1 (a current as fast
as the vehicle) has no feasible radius: the result says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.fields.field import FlowField
from glideplan.geodesy import LocalProjection
from glideplan.routing.route import RouteResult
from glideplan.routing.verify import local_current

__all__ = ["GliderFollow", "follow_route"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class GliderFollow:
    """Outcome of building and following the flyable path (m, s)."""

    status: str
    radius_m: float
    disturbance_ratio: float
    feasible_radius_m: float | None
    legs: int = 0
    path_length_m: float = 0.0
    duration_s: float | None = None
    max_cross_track_m: float | None = None
    rms_cross_track_m: float | None = None
    final_distance_m: float | None = None
    message: str = ""
    track: dict[str, Any] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "status": self.status,
            "radius_m": self.radius_m,
            "disturbance_ratio": self.disturbance_ratio,
            "feasible_radius_m": self.feasible_radius_m,
            "legs": self.legs,
            "path_length_m": self.path_length_m,
            "duration_s": self.duration_s,
            "max_cross_track_m": self.max_cross_track_m,
            "rms_cross_track_m": self.rms_cross_track_m,
            "final_distance_m": self.final_distance_m,
            "message": self.message,
            "track": self.track,
        }


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


def follow_route(
    result: RouteResult,
    field_: FlowField,
    speed: float,
    radius: float,
    spacing: float | None = None,
    dt: float | None = None,
    refresh: int = 10,
) -> GliderFollow:
    """Build the flyable path of `result` for turn radius `radius` (m) and follow it."""
    from glideplan.errors import InvalidParameterError
    from glideplan.planners.dubins import WORDS, dubins_shortest, feasible_radius, word_directions
    from glideplan.simulation.guidance import PathArrays, lookahead_guidance

    if not (math.isfinite(radius) and radius > 0):
        raise InvalidParameterError("radius", radius, "must be finite and > 0 (m)")
    if not result.ok:
        raise InvalidParameterError("route", result.status, "needs a solved route")
    proj = LocalProjection(float(result.lat[0]), float(result.lon[0]))
    t0 = result.depart_s
    u, v = field_.velocity(t0 + result.t, result.lat, result.lon)
    eps = float(np.nanmax(np.hypot(u, v))) / speed
    if eps >= 1.0:
        return GliderFollow("infeasible", radius, eps, None,
                            message=f"the current reaches {eps:.2f} x the speed: no feasible "
                            "radius R0' = R0 (1 + eps)^2 exists for eps >= 1")
    r_f = float(feasible_radius(radius, eps))
    x, y = result.x, result.y
    total = float(np.sum(np.hypot(np.diff(x), np.diff(y))))
    spacing = spacing if spacing is not None else max(10.0 * r_f, total / 300.0)
    poses = _waypoints(x, y, spacing)
    starts, goals = poses[:-1], poses[1:]
    # Each Dubins piece in its own start frame: the goal relative to the start pose.
    c, s = np.cos(starts[:, 2]), np.sin(starts[:, 2])
    dx, dy = goals[:, 0] - starts[:, 0], goals[:, 1] - starts[:, 1]
    rel = np.stack([c * dx + s * dy, -s * dx + c * dy, goals[:, 2] - starts[:, 2]], axis=1)
    batch = dubins_shortest(np.zeros(3), rel, r_f)
    dirs = np.array([word_directions(WORDS[k]) for k in batch.word_index], dtype=float)
    legs = [PathArrays.from_segments(starts[i:i + 1], dirs[i:i + 1],
                                     batch.segment_lengths[i:i + 1], r_f)
            for i in range(starts.shape[0])]
    path_length = float(sum(leg.length[0] for leg in legs))

    umax = speed / radius
    dt = dt if dt is not None else 0.1 * radius / speed
    # gamma = V / R0 (1/s) keeps the path-parameter update stable: gamma dt = 0.1.
    lookahead, gamma, phi_b = radius, speed / radius, 0.2
    px, py, psi = float(poses[0, 0]), float(poses[0, 1]), float(poses[0, 2])
    varpi, k, t = 0.0, 0, t0
    cross: list[float] = []
    out_t, out_x, out_y = [0.0], [px], [py]
    t_max = t0 + 3.0 * (result.duration_s or 0.0) + 10 * path_length / speed
    c_now = np.zeros(2)
    step = 0
    status, message = "followed", ""
    while True:
        if step % refresh == 0:
            try:
                ccx, ccy = local_current(field_, proj, t, px, py)
            except InvalidParameterError as exc:
                status, message = "lost", f"the vehicle left the field ({exc})"
                break
            c_now = np.array([ccx[0], ccy[0]])
            if not np.all(np.isfinite(c_now)):
                status, message = "lost", "the vehicle reached land"
                break
        gvx, gvy = speed * math.cos(psi) + c_now[0], speed * math.sin(psi) + c_now[1]
        leg = legs[k]
        cmd = lookahead_guidance(leg, np.array([varpi]), np.array([px]), np.array([py]),
                                 np.array([gvx]), np.array([gvy]),
                                 lookahead=lookahead, gamma=gamma)
        cross.append(float(cmd.cross_track[0]))
        chi = math.atan2(gvy, gvx)
        err = (float(cmd.course[0]) - chi + math.pi) % (2 * math.pi) - math.pi
        turn = umax * max(-1.0, min(1.0, err / phi_b)) + float(cmd.path_turn_rate[0])
        turn = max(-umax, min(umax, turn))
        if abs(turn) > 1e-12:
            px += speed / turn * (math.sin(psi + turn * dt) - math.sin(psi))
            py += -speed / turn * (math.cos(psi + turn * dt) - math.cos(psi))
        else:
            px += speed * math.cos(psi) * dt
            py += speed * math.sin(psi) * dt
        px += c_now[0] * dt
        py += c_now[1] * dt
        psi += turn * dt
        varpi += float(cmd.varpi_rate[0]) * dt
        t += dt
        step += 1
        if step % 20 == 0:
            out_t.append(t - t0)
            out_x.append(px)
            out_y.append(py)
        while varpi >= leg.length[0] and k < len(legs) - 1:
            varpi -= leg.length[0]
            k += 1
            leg = legs[k]
        if k == len(legs) - 1 and varpi >= leg.length[0]:
            break
        if t > t_max:
            status, message = "lost", "timed out before the end of the path"
            break
    gx, gy = float(result.x[-1]), float(result.y[-1])
    lat, lon = proj.to_geographic(np.array(out_x), np.array(out_y))
    e = np.abs(np.array(cross)) if cross else np.zeros(1)
    return GliderFollow(
        status, radius, eps, r_f, len(legs), path_length, t - t0, float(e.max()),
        float(np.sqrt(np.mean(e**2))), math.hypot(px - gx, py - gy), message,
        {"t": out_t, "lat": lat.tolist(), "lon": lon.tolist()},
    )
