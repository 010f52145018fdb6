"""Minimum altitude loss with speed and load-factor controls by the direct method (6.8).

The chapter 6 problem (6.13-6.22) is transcribed by `glideplan.planners.direct` in the bank
angle form the dissertation used with GPOPS (6.53-6.54): controls phi in [-phi_max, phi_max]
and the speed fraction vbar in [0, 1],

    v = sqrt(sec(phi) / p2) (1 - vbar) + v_max vbar,   n = sec(phi),

so the control set is a box (vbar = 0 is the stall boundary, |phi| = phi_max the maximum
load factor). In time, speed = v, turn rate = tan(phi) / v and the cost rate is the sink
rate p1 (v^3 + sec(phi)^2 / v) (6.8). The alternative formulation="load-factor" uses the
controls (v, psi_dot) with the nonlinear constraints n^2 = 1 + (v psi_dot)^2 <= n_max^2 and
n <= p2 v^2 (an independent transcription, used as a cross-check).

Initial guesses come from the chapter 6 analysis: Dubins paths (all six words) whose arcs
are flown with the best constant-radius turn (on the extremal locus or the stall boundary,
`glideplan.analysis.load_factor.best_turn`) at the corner radius and a few larger radii,
straights at wings-level minimum drag (v = n = 1). They are ranked by their own altitude
loss and the `max_starts` cheapest (distinct word and heading branch first) are solved.
"""

from __future__ import annotations

import functools
import math
from typing import Any

import numpy as np

from glideplan.analysis.load_factor import best_turn, classify_controls
from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.direct import ControlSystem, DirectResult, solve_direct
from glideplan.planners.direct.guesses import dubins_guesses
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import TWO_PI, Pose
from glideplan.segments import Sampled
from glideplan.solution import Candidate, Status
from glideplan.validation import check_integer
from glideplan.vehicles.load_factor_glider import LoadFactorGlider

__all__ = [
    "FORMULATIONS",
    "MAX_GOAL_DISTANCE",
    "control_system",
    "guess_radii",
    "initial_guesses",
    "plan_load_factor",
    "solve_load_factor",
]

FORMULATIONS = ("bank", "load-factor")
# The direct method's reach (nondimensional lengths, i.e. units of the glider's length
# scale): the first mesh of `n_intervals` intervals spreads over the whole path, and beyond
# this distance its refinement to 640 intervals takes minutes (1000 units: over 10 min
# here; 300 units: about 8 s). Farther goals are refused up front.
MAX_GOAL_DISTANCE = 300.0


@functools.lru_cache(maxsize=32)
def control_system(glider: LoadFactorGlider, formulation: str = "bank") -> ControlSystem:
    """The glider as a `ControlSystem` for the direct engine (cached per glider)."""
    import casadi as ca  # heavy: imported when a direct solve is built

    p1, p2, vmax = glider.p1, glider.p2, glider.v_max
    if formulation == "bank":
        phi_max = glider.max_bank

        def speed_of(c):
            return ca.sqrt(1.0 / (p2 * ca.cos(c[1]))) * (1.0 - c[0]) + vmax * c[0]

        def kinematics(c):
            v = speed_of(c)
            return v, ca.tan(c[1]) / v

        def cost_rate(c):
            v = speed_of(c)
            return p1 * (v**3 + 1.0 / (ca.cos(c[1]) ** 2 * v))

        def controls_from(v: np.ndarray, u: np.ndarray) -> np.ndarray:
            phi = np.clip(np.arctan(v * u), -phi_max, phi_max)
            v_stall = np.sqrt(1.0 / (p2 * np.cos(phi)))
            vbar = (v - v_stall) / (vmax - v_stall)
            return np.stack([np.clip(vbar, 0.0, 1.0), phi], axis=-1)

        return ControlSystem(
            name=f"load-factor-glider-bank({glider.l_over_d_max:g},{glider.v_min:g},"
            f"{glider.v_max:g},{glider.n_max:g})",
            control_names=("vbar", "phi"),
            lower=(0.0, -phi_max),
            upper=(1.0, phi_max),
            kinematics=kinematics,
            cost_rate=cost_rate,
            controls_from=controls_from,
        )
    if formulation == "load-factor":
        n_lim = glider.n_limit
        u_big = 2.0 * math.sqrt(n_lim**2 - 1.0) / glider.v_min  # above any attainable rate

        def kinematics_vn(c):
            return c[0], c[1]

        def cost_rate_vn(c):
            return p1 * (c[0] ** 3 + (1.0 + (c[0] * c[1]) ** 2) / c[0])

        def constraints(c):
            lat2 = (c[0] * c[1]) ** 2  # n^2 - 1
            return [
                (lat2, -math.inf, n_lim**2 - 1.0),  # n <= n_max (6.17); n >= 1 always
                (p2**2 * c[0] ** 4 - 1.0 - lat2, 0.0, math.inf),  # n <= p2 v^2 (6.18)
            ]

        return ControlSystem(
            name=f"load-factor-glider-vn({glider.l_over_d_max:g},{glider.v_min:g},"
            f"{glider.v_max:g},{glider.n_max:g})",
            control_names=("v", "turn_rate"),
            lower=(glider.v_min, -u_big),
            upper=(vmax, u_big),
            kinematics=kinematics_vn,
            cost_rate=cost_rate_vn,
            path_constraints=constraints,
        )
    raise InvalidParameterError(
        "formulation", formulation, f"must be one of {', '.join(FORMULATIONS)}"
    )


def guess_radii(glider: LoadFactorGlider) -> tuple[float, ...]:
    """Turn radii for the Dubins guesses: the corner radius, the radius where the extremal
    locus meets the stall boundary, and a wide turn."""
    from glideplan.analysis.load_factor import locus_stall_intersection

    v_lim, n_lim = locus_stall_intersection(glider)
    r_lim = v_lim**2 / math.sqrt(n_lim**2 - 1.0)
    rc = glider.corner_radius
    return tuple(sorted({rc, max(r_lim, rc * 1.2), max(2.0 * r_lim, rc * 2.0)}))


def _altitude(glider: LoadFactorGlider, path: Path) -> float:
    return path.with_vehicle(glider).cost("altitude")


def initial_guesses(
    glider: LoadFactorGlider,
    goal: Pose,
    *,
    radii: tuple[float, ...] | None = None,
    max_starts: int | None = None,
) -> list[Path]:
    """Dubins guesses flown with the best turn for each radius, cheapest first.

    Ranking is by each guess's own altitude loss; with `max_starts`, the cheapest guess of
    every distinct (word, heading branch) comes first, then the rest by cost.
    """
    rs = guess_radii(glider) if radii is None else tuple(radii)
    cands: list[tuple[float, str, int, Path]] = []
    for r in rs:
        v_arc, _ = best_turn(glider, r)
        for p in dubins_guesses(goal, [r], arc_speed=v_arc, straight_speed=1.0):
            k = round((p.end.heading - goal.heading) / TWO_PI)
            cands.append((_altitude(glider, p), p.word, k, p))
    cands.sort(key=lambda c: c[0])
    if max_starts is None:
        return [c[3] for c in cands]
    seen: set[tuple[str, int]] = set()
    first: list[tuple[float, str, int, Path]] = []
    rest: list[tuple[float, str, int, Path]] = []
    for c in cands:
        key = (c[1], c[2])
        (rest if key in seen else first).append(c)
        seen.add(key)
    return [c[3] for c in (first + rest)[: max(1, int(max_starts))]]


def solve_load_factor(
    glider: LoadFactorGlider,
    goal: Pose,
    *,
    n_intervals: int = 40,
    scheme: str = "hermite-simpson",
    mesh_tol: float = 1e-5,
    max_refinements: int = 4,
    max_starts: int = 4,
    formulation: str = "bank",
    guesses: list[Path] | None = None,
    ipopt_options: dict[str, Any] | None = None,
    time_limit: float | None = None,
) -> DirectResult:
    """Solve the chapter 6 problem from the origin to `goal` (a `DirectResult`).

    `time_limit`: wall-clock seconds for the direct solve (all starts), or None for no limit.
    """
    system = control_system(glider, formulation)
    gs = guesses if guesses is not None else initial_guesses(glider, goal, max_starts=max_starts)
    return solve_direct(
        goal,
        system,
        guesses=gs,
        n_intervals=n_intervals,
        scheme=scheme,
        mesh_tol=mesh_tol,
        max_refinements=max_refinements,
        ipopt_options=ipopt_options,
        time_limit=time_limit,
    )


def control_history(glider: LoadFactorGlider, path: Path) -> dict[str, np.ndarray]:
    """Arc length, speed, load factor, bank angle (rad) and turn direction at the path's nodes."""
    seg = path.segments[0]
    if not isinstance(seg, Sampled):
        raise InvalidParameterError("path", seg.kind, "must be a direct-method (sampled) path")
    t, v, u = seg.t, seg.speed, seg.turn_rate
    s = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(t))])
    return {
        "t": t,
        "s": s,
        "v": v,
        "n": glider.load_factor(v, u),
        "bank": glider.bank_angle(v, u),
        "direction": np.sign(u),
    }


@register_planner(
    "load-factor",
    vehicle=LoadFactorGlider,
    objective="altitude",
    method="direct",
    description="Minimum altitude loss, speed and load-factor controls, direct method (6.8)",
)
def plan_load_factor(
    problem: Problem,
    *,
    n_intervals: int = 40,
    scheme: str = "hermite-simpson",
    mesh_tol: float = 1e-5,
    max_refinements: int = 4,
    max_starts: int = 4,
    formulation: str = "bank",
    classification_tol: float = 2e-3,
    max_iterations: int = 1000,
    time_limit: float | None = None,
) -> PlannerOutput:
    """Direct collocation from analytic guesses; the best start, refined, is the answer.

    `time_limit`: wall-clock seconds for the direct solve (all starts), or None for no limit.
    Steps: `_checked_goal` (inputs), `solve_load_factor`, then `_failed_output` or
    `_solved_output` (the best path with its arc classification and control history).
    """
    glider = problem.vehicle
    assert isinstance(glider, LoadFactorGlider)
    early = _checked_goal(problem, max_starts, max_iterations)
    if early is not None:
        return early
    res = solve_load_factor(
        glider,
        problem.goal,
        n_intervals=n_intervals,
        scheme=scheme,
        mesh_tol=mesh_tol,
        max_refinements=max_refinements,
        max_starts=max_starts,
        formulation=formulation,
        ipopt_options={"max_iter": int(max_iterations)},
        time_limit=time_limit,
    )
    stats = {
        k: v
        for k, v in res.stats.items()
        if isinstance(v, (int, float, str, bool, list, dict, type(None)))
    }
    if not res.ok:
        return _failed_output(res, stats)
    return _solved_output(glider, res, stats, classification_tol)


def _checked_goal(problem: Problem, max_starts: int, max_iterations: int) -> PlannerOutput | None:
    """Validate the direct method's options and goal; the answer when there is nothing to
    fly (the goal is the start), else None."""
    check_integer("max_starts", max_starts, 1)
    check_integer("max_iterations", max_iterations, 1)
    goal = problem.goal
    if math.hypot(goal.x, goal.y) < 1e-12 and abs(goal.heading) < 1e-12:
        return PlannerOutput(candidates=(), message="the goal is the start: nothing to fly")
    distance = math.hypot(goal.x, goal.y) / problem.vehicle.length_scale
    if distance > MAX_GOAL_DISTANCE:
        raise InvalidParameterError(
            "goal",
            float(f"{distance:.6g}"),
            f"distance from the start must be at most {MAX_GOAL_DISTANCE:g} length units "
            "for the load-factor direct method (farther, its mesh refinement takes minutes)",
        )
    return None


def _failed_output(res: DirectResult, stats: dict[str, Any]) -> PlannerOutput:
    """Every start as a failed candidate, with IPOPT's message."""
    cands = tuple(
        Candidate(s.label, "D", math.inf, None, Status.FAILED, {"ipopt": s.status})
        for s in res.starts
    )
    return PlannerOutput(
        candidates=cands,
        stats=stats,
        message=f"direct method failed: {res.message}",
        extras={"starts": [s.to_dict() for s in res.starts]},
        failure=Status.SOLVER_FAILED,
        warnings=res.warnings,
    )


def _solved_output(
    glider: LoadFactorGlider, res: DirectResult, stats: dict[str, Any], classification_tol: float
) -> PlannerOutput:
    """The best start's path (word from its arc classification) and the other starts."""
    assert res.path is not None  # a solved DirectResult carries its path
    path = res.path.with_vehicle(glider)
    hist = control_history(glider, path)
    arcs = classify_controls(
        glider, hist["s"], hist["v"], hist["n"], hist["direction"], tol=classification_tol
    )
    best = Candidate(
        arcs.turn_word.replace("-", "") or "S",
        path.family,
        path.cost("altitude"),
        path,
        Status.FEASIBLE,
        {"collocation_cost": res.cost, "start": res.stats.get("best_start")},
    )
    others = tuple(
        Candidate(
            s.label,
            "D",
            s.cost,
            None,
            Status.LOCAL if math.isfinite(s.cost) else Status.FAILED,
            {"start": s.index, "coarse_mesh_cost": s.cost if math.isfinite(s.cost) else None},
        )
        for s in res.starts
        if s.index != res.stats.get("best_start")
    )
    extras = {
        "collocation_cost": res.cost,
        "arcs": arcs.to_dict(),
        "controls": {
            "s": hist["s"],
            "v": hist["v"],
            "n": hist["n"],
            "bank_deg": np.degrees(hist["bank"]),
            "label": [str(x) for x in arcs.labels],
        },
        "starts": [s.to_dict() for s in res.starts],
    }
    return PlannerOutput(
        candidates=(best, *others),
        stats=stats,
        message=res.message,
        extras=extras,
        warnings=res.warnings,
    )
