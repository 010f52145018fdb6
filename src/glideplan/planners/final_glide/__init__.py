"""Final glide to an arrival heading in steady wind with the turning polar (issue 14).

The minimum-altitude-loss path of a `Sailplane` from the start (heading given, or chosen by
`best_start_heading` when free) to a goal pose, with airspeed and bank as controls, in a
steady uniform wind, losing altitude at the turning polar's rate w_phi(V) = n^{3/2} w(V/sqrt n)
(plus MacCready's MC per second of flight when MC > 0). It is solved with the direct engine
(`glideplan.planners.direct`, collocation + IPOPT, the wind as its drift), warm-started from
the known-wind planner's paths (`glideplan.planners.wind`, trochoids over ground), and, like
every planner, verified by `plan()` integrating the controls through the wind.

Not done: a chapter 5 style synthesis with drift (the families BSB, BBBB, B_ms, B_stall^4 with
the wind's extra constant in the Hamiltonian); the direct method is the only solver here.
"""

from __future__ import annotations

import math
import time
from typing import Any

from glideplan.path import Path
from glideplan.planners.final_glide.direct import (
    ArrivalResult,
    control_system,
    guess_paths,
    guess_speed_and_radius,
    lead_in_straight,
    solve_arrival,
)
from glideplan.planners.final_glide.segment import DriftingSampled
from glideplan.planners.final_glide.start_heading import best_start_heading, straight_turn_arrival
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import Pose
from glideplan.solution import Candidate
from glideplan.vehicles.sailplane import Sailplane

__all__ = [
    "ArrivalResult",
    "DriftingSampled",
    "best_start_heading",
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
    "controls: direct collocation + IPOPT warm-started from convected Dubins paths (issue 14)",
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
    the MacCready speed (`lead_in_straight`) and the direct method solves the approach."""
    vehicle = problem.vehicle
    assert isinstance(vehicle, Sailplane)
    psi_w = vehicle.wind_direction - problem.frame.heading
    wind = (vehicle.wind_speed * math.cos(psi_w), vehicle.wind_speed * math.sin(psi_w))
    t0 = time.perf_counter()
    lead = lead_in_straight(problem.goal, vehicle, wind, mc=mc) if approach else ()
    gate = lead[-1].end if lead else Pose()
    res = solve_arrival(
        problem.goal.relative_to(gate),
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
    stats["starts"] = [s.to_dict() for s in res.direct.starts]
    extras = {
        "warm_starts": [
            {"word": g.word, "altitude_loss": g.with_vehicle(vehicle).cost("altitude")}
            for g in res.guesses
        ]
    }
    if res.path is None:
        return PlannerOutput(
            (), stats, res.direct.message or "IPOPT failed", extras, solver_failed=True
        )
    seg = res.path.segments[0]
    assert isinstance(seg, DriftingSampled)
    path = res.path.transformed(gate)
    if lead:
        path = Path((*lead, *path.segments), vehicle)
    stats["lead_in_straight_m"] = lead[-1].length if lead else 0.0
    word = seg.turn_word(0.05 * float(vehicle.max_turn_rate(vehicle.polar.v_best_glide)))
    cand = Candidate(
        word,
        "direct",
        path.cost("altitude"),
        path,
        "feasible",
        {"collocation_cost": res.direct.cost, "mc": mc},
    )
    return PlannerOutput((cand,), stats, res.direct.message, extras)
