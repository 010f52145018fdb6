"""Minimum altitude loss to a pose in steady wind with the turning polar: the direct method.

The sailplane (`glideplan.vehicles.sailplane`) is handed to the shared engine
(`glideplan.planners.direct`) as controls (V, phi) in [v_min, v_max] x [-bank_max, bank_max]
with kinematics (V, g tan(phi) / V), the wind as the engine's drift (an NLP parameter: one
transcription serves every goal and wind), the cost rate
w_phi(V) + MC (the turning polar plus MacCready's price of time; MC = 0 is pure altitude
loss) and the path constraints V^2 cos(phi) >= v_min^2 (stall speed v_min sqrt(n) in a turn)
and, with `turn_rate_max`, |g tan(phi) / V| <= u_max. The starts are the known-wind planner's
paths (`glideplan.planners.wind`: convected Dubins paths, trochoids over ground) flown at the
straight speed to fly with the bank limit's turn radius, cheapest words first.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.direct import ControlSystem, DirectResult, solve_direct
from glideplan.planners.dubins import WORDS
from glideplan.planners.final_glide.segment import DriftingSampled
from glideplan.planners.wind import (
    DriftingStraight,
    TrochoidArc,
    convected_dubins,
    convected_dubins_path,
)
from glideplan.pose import Pose
from glideplan.sailplane.maccready import speed_to_fly
from glideplan.validation import check_nonnegative
from glideplan.vehicles.sailplane import Sailplane
from glideplan.vehicles.sailplane_polar import GRAVITY, SailplanePolar

__all__ = [
    "ArrivalResult",
    "control_system",
    "guess_paths",
    "guess_speed_and_radius",
    "lead_in_straight",
    "solve_arrival",
]

GUESS_BANK_FRACTION = 0.8  # warm-start turns use 80 % of the bank limit


@functools.lru_cache(maxsize=64)
def _system(
    polar: SailplanePolar,
    bank_max: float,
    turn_rate_max: float | None,
    turning_polar: bool,
    mc: float,
) -> ControlSystem:
    import casadi as ca

    a, b, c, vmin = polar.a, polar.b, polar.c, polar.v_min

    def cost(q: ca.SX) -> ca.SX:
        if not turning_polar:
            return (a * q[0] + b) * q[0] + c + mc
        n = 1.0 / ca.cos(q[1])
        return a * ca.sqrt(n) * q[0] ** 2 + b * n * q[0] + n * ca.sqrt(n) * c + mc

    def constraints(q: ca.SX) -> list:
        out = []
        if turning_polar:
            out.append((q[0] ** 2 * ca.cos(q[1]) - vmin**2, 0.0, math.inf))
        if turn_rate_max is not None:
            out.append((GRAVITY * ca.tan(q[1]) / q[0], -turn_rate_max, turn_rate_max))
        return out

    def controls_from(v: np.ndarray, u: np.ndarray) -> np.ndarray:
        return np.stack([v, np.arctan(u * v / GRAVITY)], axis=-1)

    if not turning_polar and turn_rate_max is not None:
        # chapter 5's glider: controls (V, u) in a box, as in `plan min-altitude --method
        # direct` (a bound on g tan(phi) / V as a nonlinear constraint makes the controls ring
        # around short bang arcs); the bank limit is a constraint only where it binds
        tan_max = math.tan(bank_max)

        def turn_bank(q: ca.SX) -> list:
            if GRAVITY * tan_max / polar.v_max >= turn_rate_max:
                return []
            return [(q[1] * q[0] / GRAVITY, -tan_max, tan_max)]

        return ControlSystem(
            name="sailplane-small-bank",
            control_names=("airspeed", "turn_rate"),
            lower=(polar.v_min, -turn_rate_max),
            upper=(polar.v_max, turn_rate_max),
            kinematics=lambda q: (q[0], q[1]),
            cost_rate=cost,
            path_constraints=turn_bank,
        )

    return ControlSystem(
        name="sailplane-turning-polar" if turning_polar else "sailplane-small-bank",
        control_names=("airspeed", "bank"),
        lower=(polar.v_min, -bank_max),
        upper=(polar.v_max, bank_max),
        kinematics=lambda q: (q[0], GRAVITY * ca.tan(q[1]) / q[0]),
        cost_rate=cost,
        path_constraints=constraints,
        controls_from=controls_from,
    )


def control_system(vehicle: Sailplane, mc: float = 0.0) -> ControlSystem:
    """The sailplane for the engine (the wind goes to `solve_direct` as its drift).

    Cached per (polar, limits, MC) so the engine's transcriptions are reused for every goal
    and wind.
    """
    return _system(
        vehicle.polar,
        vehicle.bank_max,
        vehicle.turn_rate_max,
        vehicle.turning_polar,
        float(check_nonnegative("mc", mc)),
    )


def guess_speed_and_radius(vehicle: Sailplane, mc: float = 0.0) -> tuple[float, float]:
    """Airspeed (m/s) and turn radius (m) of the warm-start paths.

    The still-air speed to fly for MC (at least 1.25 x the wind speed so the known-wind
    planner applies) and the turn radius at 80 % of the bank limit, within the stall and
    turn-rate limits.
    """
    p = vehicle.polar
    v = float(speed_to_fly(p, mc))
    v = min(max(v, 1.25 * vehicle.wind_speed), p.v_max)
    bank = GUESS_BANK_FRACTION * vehicle.bank_max
    if vehicle.turning_polar:  # stay above the stall speed in the turn
        bank = min(bank, 0.95 * math.acos(min(1.0, (p.v_min / v) ** 2)))
    u = GRAVITY * math.tan(bank) / v
    if vehicle.turn_rate_max is not None:
        u = min(u, GUESS_BANK_FRACTION * vehicle.turn_rate_max)
    return v, v / u


def guess_paths(
    goal: Pose,
    vehicle: Sailplane,
    wind: tuple[float, float],
    *,
    mc: float = 0.0,
    max_starts: int = 2,
) -> list[Path]:
    """Convected Dubins (trochoid) paths to `goal` in `wind`, fastest words first."""
    v, radius = guess_speed_and_radius(vehicle, mc)
    sol = convected_dubins(goal, speed=v, radius=radius, wind=wind)
    order = np.argsort(sol.times)
    out: list[Path] = []
    for k in order[: int(max_starts)]:
        if not math.isfinite(sol.times[k]) or sol.times[k] <= 0.0:
            continue
        out.append(
            convected_dubins_path(
                Pose(), WORDS[k], sol.segment_lengths[k], radius=sol.radius, speed=v, wind=wind
            )
        )
    return out


@dataclass(frozen=True, eq=False)
class ArrivalResult:
    """The engine's result and the drifting path built from its controls (None on failure)."""

    direct: DirectResult
    path: Path | None
    guesses: tuple[Path, ...]

    @property
    def ok(self) -> bool:
        return self.path is not None


def solve_arrival(
    goal: Pose,
    vehicle: Sailplane,
    wind: tuple[float, float],
    *,
    mc: float = 0.0,
    max_starts: int = 2,
    n_intervals: int = 40,
    max_refinements: int = 2,
    mesh_tol: float = 1e-4,
    guesses: list[Path] | None = None,
) -> ArrivalResult:
    """Minimum of integral (w_phi(V) + MC) dt from the origin (heading 0) to `goal` in `wind`."""
    starts = (
        guesses
        if guesses is not None
        else guess_paths(goal, vehicle, wind, mc=mc, max_starts=max_starts)
    )
    if not starts:
        raise InvalidParameterError("goal", goal, "the known-wind planner found no warm start")
    v, radius = guess_speed_and_radius(vehicle, mc)
    system = control_system(vehicle, mc)
    res = solve_direct(
        goal,
        system,
        guesses=starts,
        n_intervals=n_intervals,
        max_refinements=max_refinements,
        mesh_tol=mesh_tol,
        length_scale=radius,
        time_scale=radius / v,
        max_refined_starts=1,
        output_density=2,  # the Hermite-Simpson midpoints; fewer kinks for verification
        drift=(float(wind[0]), float(wind[1])),
    )
    if not res.ok:
        return ArrivalResult(res, None, tuple(starts))
    ctl = res.controls
    seg = res.path.segments[0] if res.path is not None else None
    assert seg is not None
    drifting = DriftingSampled(
        ctl["t"],
        np.asarray(seg.x),  # type: ignore[attr-defined]
        np.asarray(seg.y),  # type: ignore[attr-defined]
        np.asarray(seg.heading),  # type: ignore[attr-defined]
        ctl["speed"],
        ctl["turn_rate"],
        "D",
        {"system": system.name},
        (float(wind[0]), float(wind[1])),
    )
    return ArrivalResult(res, Path((drifting,), vehicle), tuple(starts))


def lead_in_straight(
    goal: Pose,
    vehicle: Sailplane,
    wind: tuple[float, float],
    *,
    mc: float = 0.0,
    approach_radii: float = 12.0,
) -> tuple[TrochoidArc | DriftingStraight, ...]:
    """The long first straight of a far glide, flown at the MacCready speed (or nothing).

    When the fastest warm start begins with a straight (after at most a slight turn, < 0.05
    rad, kept as it is) longer than `approach_radii` turn radii, the glider flies that
    straight's heading at the speed to fly for its ground track (`maccready.speed_to_fly`
    with its tail- and crosswind) until `approach_radii / 2` radii of it are left; the
    direct method then solves only the approach from there, on a mesh that resolves its
    turns (a uniform mesh over a 30 km glide would not).
    """
    starts = guess_paths(goal, vehicle, wind, mc=mc, max_starts=1)
    if not starts:
        return ()
    segs = [sg for sg in starts[0].segments if sg.duration > 0.0]
    lead: list[TrochoidArc | DriftingStraight] = []
    if segs and isinstance(segs[0], TrochoidArc) and segs[0].angle < 0.05 and len(segs) > 1:
        lead.append(segs[0])
        segs = segs[1:]
    first = segs[0] if segs else None
    v, radius = guess_speed_and_radius(vehicle, mc)
    if not isinstance(first, DriftingStraight) or first.length_m <= approach_radii * radius:
        return ()
    wx, wy = wind
    h = first.start.heading
    chi = math.atan2(v * math.sin(h) + wy, v * math.cos(h) + wx)
    wt = wx * math.cos(chi) + wy * math.sin(chi)
    wc = -wx * math.sin(chi) + wy * math.cos(chi)
    vs = float(speed_to_fly(vehicle.polar, mc, wt, wc))
    if not math.isfinite(vs):
        return ()
    ground_guess = math.hypot(v * math.cos(h) + wx, v * math.sin(h) + wy) * first.duration
    ground_speed = math.hypot(vs * math.cos(h) + wx, vs * math.sin(h) + wy)
    keep = ground_guess - 0.5 * approach_radii * radius
    if keep <= 0.0 or ground_speed <= 0.0:
        return ()
    lead.append(DriftingStraight(first.start, vs * keep / ground_speed, vs, (float(wx), float(wy))))
    return tuple(lead)
