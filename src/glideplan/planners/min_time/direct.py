"""The independent check: minimum time by direct collocation (`method="direct"`).

The same optimal control problem (4.1)-(4.6) in time form, x' = v cos psi, y' = v sin psi,
psi' = u with v in [v_min, v_max], |u| <= u_max and cost rate 1, transcribed and solved with
IPOPT by `glideplan.planners.direct.solve_direct`, multi-started from the synthesis's best
candidates (distinct families) and from Dubins paths at R (flown at v_max) and at r (v_min).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from glideplan.path import Path
from glideplan.planners.direct import ControlSystem, DirectResult, solve_direct
from glideplan.planners.direct.guesses import dubins_guesses
from glideplan.planners.min_time.synthesis import extremal_path, normalised_goal, synthesize
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import Pose
from glideplan.segments import Sampled
from glideplan.solution import Candidate, Status
from glideplan.validation import check_integer
from glideplan.vehicles.variable_speed_car import VariableSpeedCar
from glideplan.words import run_word

__all__ = [
    "classify_controls",
    "control_system",
    "initial_guesses",
    "plan_time_optimal_direct",
    "solve_time_optimal_direct",
]


def control_system(vehicle: VariableSpeedCar) -> ControlSystem:
    """Controls (v, u) in [v_min, v_max] x [-u_max, u_max], cost rate 1 (eq. 4.6 in time)."""
    return ControlSystem(
        name="variable-speed-car-time",
        control_names=("v", "u"),
        lower=(vehicle.v_min, -vehicle.u_max),
        upper=(vehicle.v_max, vehicle.u_max),
        kinematics=lambda c: (c[0], c[1]),
        cost_rate=lambda c: 1.0 + 0.0 * c[0],
    )


def initial_guesses(
    vehicle: VariableSpeedCar, goal: Pose, *, synthesis_starts: int = 3
) -> list[Path]:
    """Guesses: the synthesis's cheapest paths of distinct families, then Dubins paths."""
    out: list[Path] = []
    if synthesis_starts > 0:
        res = synthesize(normalised_goal(goal, vehicle), vehicle.speed_ratio)
        seen: set[tuple[str, str]] = set()
        for ext in sorted(res.extremals, key=lambda e: e.cost):
            path = extremal_path(ext, vehicle)
            key = (path.family, path.word)
            if key in seen:
                continue
            seen.add(key)
            out.append(path)
            if len(out) >= synthesis_starts:
                break
    out += dubins_guesses(
        goal, [vehicle.bang_radius], arc_speed=vehicle.v_max, straight_speed=vehicle.v_max
    )
    if vehicle.v_min < vehicle.v_max:
        out += dubins_guesses(
            goal,
            [vehicle.corner_radius],
            arc_speed=vehicle.v_min,
            straight_speed=vehicle.v_max,
            words=("LRL", "RLR"),
        )
    return out


def solve_time_optimal_direct(
    vehicle: VariableSpeedCar,
    goal: Pose,
    *,
    guesses: list[Path] | None = None,
    synthesis_starts: int = 3,
    n_intervals: int = 60,
    mesh_tol: float = 1e-5,
    max_refinements: int = 4,
    max_iterations: int = 500,
    time_limit: float | None = None,
) -> DirectResult:
    """Direct collocation solve from the origin to `goal` (a `DirectResult`).

    `time_limit`: wall-clock seconds for the direct solve (all starts), or None for no limit.
    """
    gs = (
        guesses
        if guesses is not None
        else initial_guesses(vehicle, goal, synthesis_starts=synthesis_starts)
    )
    return solve_direct(
        goal,
        control_system(vehicle),
        guesses=gs,
        n_intervals=n_intervals,
        mesh_tol=mesh_tol,
        max_refinements=max_refinements,
        length_scale=vehicle.bang_radius,
        time_scale=1.0 / vehicle.u_max,
        ipopt_options={"max_iter": int(max_iterations)},
        time_limit=time_limit,
    )


def classify_controls(
    vehicle: VariableSpeedCar,
    t: np.ndarray,
    speed: np.ndarray,
    turn_rate: np.ndarray,
    *,
    tol: float = 0.05,
    min_fraction: float = 0.01,
) -> tuple[str, str]:
    """Family (B/C/S labels) and turn word of a sampled control history (Table 4.1).

    A sample is S where |u| < tol u_max, else B if v is nearer v_max, C if nearer v_min
    (anything else is '?'); runs shorter than `min_fraction` of the time are absorbed.
    """
    vmid = 0.5 * (vehicle.v_min + vehicle.v_max)
    straight = np.abs(turn_rate) < tol * vehicle.u_max
    labels = np.where(straight, "S", np.where(speed >= vmid, "B", "C"))
    dirs = np.where(straight, "S", np.where(turn_rate > 0, "L", "R"))
    dt = np.gradient(t)
    least = min_fraction * (float(t[-1] - t[0]) or 1.0)
    fam, word = (
        run_word(values, dt, min_weight=least, keep_all_if_empty=True) for values in (labels, dirs)
    )
    return fam, word


@register_planner(
    "time-optimal-direct",
    vehicle=VariableSpeedCar,
    objective="time",
    method="direct",
    default=False,
    description="Minimum time with variable speed by direct collocation (independent check)",
)
def plan_time_optimal_direct(
    problem: Problem,
    *,
    n_intervals: int = 60,
    synthesis_starts: int = 3,
    mesh_tol: float = 1e-5,
    max_refinements: int = 4,
    max_iterations: int = 500,
    time_limit: float | None = None,
) -> PlannerOutput:
    """Multi-start direct collocation; the best start after mesh refinement is the answer.

    `time_limit`: wall-clock seconds for the direct solve (all starts), or None for no limit.
    """
    vehicle = problem.vehicle
    assert isinstance(vehicle, VariableSpeedCar)
    for name, value, low in (
        ("n_intervals", n_intervals, 4),
        ("synthesis_starts", synthesis_starts, 0),
        ("max_refinements", max_refinements, 0),
        ("max_iterations", max_iterations, 1),
    ):
        check_integer(name, value, low)
    goal = problem.goal
    if (
        math.hypot(goal.x, goal.y) < 1e-12
        and abs(math.remainder(goal.heading, 2 * math.pi)) < 1e-12
    ):
        return PlannerOutput(candidates=(), message="the goal is the start: nothing to fly")
    res = solve_time_optimal_direct(
        vehicle,
        goal,
        synthesis_starts=int(synthesis_starts),
        n_intervals=int(n_intervals),
        mesh_tol=mesh_tol,
        max_refinements=int(max_refinements),
        max_iterations=int(max_iterations),
        time_limit=time_limit,
    )
    stats: dict[str, Any] = {
        k: v
        for k, v in res.stats.items()
        if isinstance(v, (int, float, str, bool, list, dict, type(None)))
    }
    stats["starts"] = [s.to_dict() for s in res.starts]
    if not res.ok or res.path is None:
        return PlannerOutput(
            (), stats, message=res.message, failure=Status.SOLVER_FAILED, warnings=res.warnings
        )
    path = res.path.with_vehicle(vehicle)
    seg = path.segments[0]
    assert isinstance(seg, Sampled)  # the direct engine returns one sampled segment
    family, word = classify_controls(vehicle, seg.t, seg.speed, seg.turn_rate)
    info = {"collocation_cost": res.cost, "classified_family": family}
    cand = Candidate(word, family, path.duration, path, Status.FEASIBLE, info)
    return PlannerOutput((cand,), stats, warnings=res.warnings)
