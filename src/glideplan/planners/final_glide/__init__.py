"""Final glide to an arrival heading in steady wind with the turning polar.

The minimum-altitude-loss path of a `Sailplane` from the start (heading given, or chosen by
`best_start_heading` when free) to a goal pose, with airspeed and bank as controls, in a
steady uniform wind, losing altitude at the turning polar's rate w_phi(V) = n^{3/2} w(V/sqrt n)
(plus MacCready's MC per second of flight when MC > 0). It is solved with the direct engine
(`glideplan.planners.direct`, collocation + IPOPT, the wind as its drift), warm-started from
the known-wind planner's paths (`glideplan.planners.wind`, trochoids over ground), and, like
every planner, verified by `plan()` integrating the controls through the wind.

For chapter 5's small-bank model (sink independent of bank, turn rate <= u_max) the BSB family
with drift is synthesised (`synthesis.py`: the wind adds a constant to the Hamiltonian, so the
families keep their shape and the straight flies MacCready's headwind speed) and the direct
method checks it. Not done: BBBB, B_ms and B_stall^4 with drift, and any synthesis for the
turning polar (its extremals are those of chapter 6, not chapter 5); there the direct method
is the solver.
"""

from __future__ import annotations

import math
import time
from typing import Any

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.final_glide.direct import (
    ArrivalResult,
    control_system,
    guess_paths,
    guess_speed_and_radius,
    lead_in_straight,
    solve_arrival,
)
from glideplan.planners.final_glide.segment import DriftingSampled, DriftingSegment
from glideplan.planners.final_glide.start_heading import best_start_heading, straight_turn_arrival
from glideplan.planners.final_glide.synthesis import BSBDrift, bsb_with_drift
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import Pose
from glideplan.solution import Candidate, Status
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider
from glideplan.vehicles.sailplane import Sailplane

__all__ = [
    "ArrivalResult",
    "BSBDrift",
    "DriftingSampled",
    "DriftingSegment",
    "best_start_heading",
    "bsb_with_drift",
    "control_system",
    "guess_paths",
    "guess_speed_and_radius",
    "lead_in_straight",
    "plan_final_glide",
    "solve_arrival",
    "straight_turn_arrival",
]


def _rotate(v: tuple[float, float], angle: float) -> tuple[float, float]:
    c, s = math.cos(angle), math.sin(angle)
    return (c * v[0] - s * v[1], s * v[0] + c * v[1])


@register_planner(
    "final_glide",
    vehicle=Sailplane,
    objective="altitude",
    method="direct",
    description="Final glide to a pose in steady wind, turning polar, airspeed and bank "
    "controls: direct collocation + IPOPT warm-started from convected Dubins paths",
)
def plan_final_glide(
    problem: Problem,
    *,
    mc: float = 0.0,
    n_intervals: int = 40,
    max_starts: int = 2,
    approach: bool = True,
) -> PlannerOutput:
    """Minimum altitude loss (+ MC x time) to the goal pose; the candidate's cost is the
    altitude loss (m) of the returned path. Extras: `warm_starts` (word and altitude loss of
    each known-wind guess). With `approach`, a far glide's long first straight is flown at
    the MacCready speed (`lead_in_straight`) and the direct method solves the approach.

    For the chapter 5 small-bank model (`turning_polar=False` with `turn_rate_max`, MC = 0)
    the BSB synthesis with drift (`synthesis.bsb_with_drift`) adds its candidates; the direct
    method, started independently from the known-wind guesses, is the check (extras
    `synthesis_cost` / `direct_cost`); `plan()` returns the cheapest verified candidate.
    (Seeding the direct method with the synthesis path makes it ring: a BSB's first arc can
    be shorter than one mesh interval.)"""
    vehicle = problem.vehicle
    assert isinstance(vehicle, Sailplane)
    wind = vehicle.wind_in_frame(problem.frame.heading)
    t0 = time.perf_counter()
    synth = _synthesis(problem.goal, vehicle, wind, mc)
    t_synth = time.perf_counter() - t0
    lead = lead_in_straight(problem.goal, vehicle, wind, mc=mc) if approach else ()
    gate = lead[-1].end if lead else Pose()
    local = problem.goal.relative_to(gate)
    res = solve_arrival(
        local,
        vehicle,
        _rotate(wind, -gate.heading),
        mc=mc,
        n_intervals=n_intervals,
        max_starts=max_starts,
    )
    stats: dict[str, Any] = {
        k: v for k, v in res.direct.stats.items() if isinstance(v, (int, float, str, bool))
    }
    stats["solve_seconds"] = time.perf_counter() - t0
    stats["synthesis_seconds"] = t_synth
    stats["starts"] = [s.to_dict() for s in res.direct.starts]
    extras: dict[str, Any] = {
        "warm_starts": [
            {"word": g.word, "altitude_loss": g.with_vehicle(vehicle).cost("altitude")}
            for g in res.guesses
        ]
    }
    cands = _synthesis_candidates(synth, vehicle)
    if synth:
        extras["synthesis_cost"] = synth[0].cost
        extras["synthesis_word"] = synth[0].word
    if res.path is None:
        if cands:
            return PlannerOutput(tuple(cands), stats, "the direct check failed", extras)
        return PlannerOutput(
            (), stats, res.direct.message or "IPOPT failed", extras, failure=Status.SOLVER_FAILED
        )
    return _with_direct(res, gate, lead, vehicle, mc, cands, stats, extras)


def _synthesis_candidates(synth: list[BSBDrift], vehicle: Sailplane) -> list[Candidate]:
    """The BSB synthesis's paths as feasible candidates (theta, straight speed, lambda)."""
    return [
        Candidate(
            c.word,
            "BSB",
            c.cost,
            c.path.with_vehicle(vehicle),
            Status.FEASIBLE,
            {"theta": c.theta, "straight_speed": c.speed, "lam": c.lam},
        )
        for c in synth
    ]


def _with_direct(res: Any, gate: Pose, lead: tuple[Any, ...], vehicle: Sailplane, mc: float,
                 cands: list[Candidate], stats: dict[str, Any],
                 extras: dict[str, Any]) -> PlannerOutput:
    """Add the direct method's path (the lead-in straight, then the approach from `gate`) to
    the candidates, unless its controls miss the goal (re-timing failed): then a warning,
    and a failure if nothing else is left."""
    seg = res.path.segments[0]
    assert isinstance(seg, DriftingSampled)
    path = res.path.transformed(gate)
    if lead:
        path = Path((*lead, *path.segments), vehicle)
    stats["lead_in_straight_m"] = lead[-1].length if lead else 0.0
    word = seg.turn_word(0.05 * float(vehicle.max_turn_rate(vehicle.polar.v_best_glide)))
    cost = path.cost("altitude")
    extras["direct_cost"] = cost
    # the engine's own endpoint error of the controls it returns (after re-timing): when
    # re-timing failed (controls ringing around a turn shorter than a mesh interval) the
    # path misses the goal and is not offered
    miss = float(res.direct.stats.get("endpoint_error", {}).get("position", 0.0))
    if miss > 1e-6 * max(1.0, vehicle.length_scale):
        warnings = (
            f"the direct method's controls miss the goal by {miss:.3g} m (re-timing failed); "
            "its path is not offered" + (", the synthesis is" if cands else ""),
        )
        if not cands:
            return PlannerOutput((), stats, warnings[0], extras, failure=Status.SOLVER_FAILED)
        return PlannerOutput(tuple(cands), stats, "", extras, warnings=warnings)
    cands.append(
        Candidate(
            word,
            "direct",
            cost,
            path,
            Status.FEASIBLE,
            {"collocation_cost": res.direct.cost, "mc": mc},
        )
    )
    return PlannerOutput(tuple(cands), stats, res.direct.message, extras)


def _synthesis(
    goal: Pose, vehicle: Sailplane, wind: tuple[float, float], mc: float
) -> list[BSBDrift]:
    """BSB-with-drift candidates when the vehicle is chapter 5's glider (else none)."""
    if vehicle.turning_polar or vehicle.turn_rate_max is None or mc != 0.0:
        return []
    p = vehicle.polar
    # the bank limit must allow u_max at every speed, or the B arcs are not admissible
    if float(vehicle.max_turn_rate(p.v_max)) < vehicle.turn_rate_max * (1 - 1e-12):
        return []
    try:
        glider = QuadraticPolarGlider(p.a, p.b, p.c, p.v_min, p.v_max, vehicle.turn_rate_max)
    except InvalidParameterError:  # the polar breaks Assumptions 5.2.1-5.2.4
        return []
    return bsb_with_drift(goal, glider, wind)
