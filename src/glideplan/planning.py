"""The single entry point `plan()` and the registry of planners by vehicle, objective, method.

A planner is a function `(problem: Problem, **options) -> PlannerOutput`. It always receives
the problem normalised so that the start is the origin with zero heading; `plan()` maps the
candidates' paths back, verifies the best by integration (`glideplan.verify`) and returns a
`Solution`. Adding a planner adds a module that calls `register_planner`; nothing here changes.
"""

from __future__ import annotations

import inspect
import math
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from glideplan.errors import InvalidParameterError
from glideplan.objectives import get_objective
from glideplan.pose import Pose, wrap_to_pi
from glideplan.results import Reason
from glideplan.solution import Candidate, Solution, Status
from glideplan.validation import check_physical
from glideplan.vehicles.base import Vehicle
from glideplan.verify import EndpointError, endpoint_error

if TYPE_CHECKING:
    from glideplan.path import Path

__all__ = [
    "PlannerOutput",
    "PlannerSpec",
    "Problem",
    "find_planner",
    "plan",
    "register_planner",
    "registered_planners",
]


@dataclass(frozen=True)
class Problem:
    """A planning problem in the planner's frame (start at the origin, heading 0)."""

    start: Pose
    goal: Pose
    vehicle: Vehicle
    objective: str
    # The world pose of the planner's origin (the request's start): planners whose vehicle
    # carries world-fixed data, such as a wind vector, rotate it into the planner's frame.
    frame: Pose = field(default_factory=Pose)


@dataclass(frozen=True, eq=False)
class PlannerOutput:
    """What a planner returns: candidates (feasible ones carry a path), stats and extras."""

    candidates: tuple[Candidate, ...]
    stats: Mapping[str, Any] = field(default_factory=dict)
    message: str = ""
    extras: Mapping[str, Any] = field(default_factory=dict)
    # the planner's own failure when it returns no candidate (Status.SOLVER_FAILED: a
    # numerical solver did not converge); None: `plan()` decides (NO_PATH / NOT_VERIFIED)
    failure: Status | None = None
    # Things the user must know even when a path is returned (a skipped root bracket, a
    # failed re-timing, ...): one sentence each; `plan()` adds its own and the Solution
    # carries them all (and `--json` prints them).
    warnings: tuple[str, ...] = ()


PlannerFunction = Callable[..., PlannerOutput]


@dataclass(frozen=True)
class PlannerSpec:
    """A registered planner."""

    name: str
    vehicle: type[Vehicle]
    objective: str
    method: str
    function: PlannerFunction
    description: str
    default: bool
    options: tuple[str, ...]


_REGISTRY: list[PlannerSpec] = []

# Two poses closer than this (times the vehicle's length scale, and in rad) are the same pose.
_SAME_POSE_TOL = 1e-12


def register_planner(
    name: str,
    *,
    vehicle: type[Vehicle],
    objective: str,
    method: str = "synthesis",
    description: str = "",
    default: bool = True,
) -> Callable[[PlannerFunction], PlannerFunction]:
    """Decorator: register `function` for (vehicle type, objective, method)."""
    get_objective(objective)

    def deco(function: PlannerFunction) -> PlannerFunction:
        params = inspect.signature(function).parameters
        opts = tuple(
            p for p in list(params)[1:] if params[p].kind is inspect.Parameter.KEYWORD_ONLY
        )
        spec = PlannerSpec(name, vehicle, objective, method, function, description, default, opts)
        _REGISTRY[:] = [
            s
            for s in _REGISTRY
            if (s.vehicle, s.objective, s.method) != (vehicle, objective, method)
        ]
        _REGISTRY.append(spec)
        return function

    return deco


def registered_planners() -> tuple[PlannerSpec, ...]:
    """All registered planners (the built-in planner modules are imported on first use)."""
    from glideplan.planners import load_all

    load_all()
    return tuple(_REGISTRY)


def _matching(vehicle: Vehicle, objective: str, method: str | None) -> list[PlannerSpec]:
    """Registered planners for this vehicle and objective, importing planner modules as needed.

    First the modules listed for the vehicle model (`glideplan.planners.PLANNER_MODULES`),
    then, when they serve no planner for the request (or not its method), every module.
    """
    from glideplan.planners import load_all, load_for

    def found() -> list[PlannerSpec]:
        return [s for s in _REGISTRY if isinstance(vehicle, s.vehicle) and s.objective == objective]

    listed = load_for(type(vehicle))
    matches = found()
    if (
        not listed
        or not matches
        or (method is not None and all(s.method != method for s in matches))
    ):
        load_all()
        matches = found()
    return matches


def find_planner(vehicle: Vehicle, objective: str, method: str | None = None) -> PlannerSpec:
    """The planner for this vehicle type, objective and method (default method if None)."""
    if not isinstance(vehicle, Vehicle):
        raise InvalidParameterError("vehicle", vehicle, "must be a glideplan vehicle model")
    get_objective(objective)
    matches = _matching(vehicle, objective, method)
    if not matches:
        raise InvalidParameterError(
            "objective", objective, f"no planner for vehicle model {vehicle.model!r}"
        )
    if method is None:
        defaults = [s for s in matches if s.default] or matches
        return defaults[0]
    for s in matches:
        if s.method == method:
            return s
    known = ", ".join(sorted(s.method for s in matches))
    raise InvalidParameterError("method", method, f"must be one of {known}")


def _as_pose(name: str, value: Pose | tuple[float, float, float] | Any) -> Pose:
    if isinstance(value, Pose):
        pose = value
    else:
        try:
            pose = Pose.from_array(value)
        except (InvalidParameterError, TypeError, ValueError) as err:
            rule = getattr(err, "rule", "must be a Pose or three numbers (x, y, heading)")
            raise InvalidParameterError(name, value, rule) from None
    for axis, coord in (("x", pose.x), ("y", pose.y)):
        check_physical(f"{name} {axis}", coord, "position")  # validation.PHYSICAL_RANGES
    return pose


def _verification_scale(vehicle: Vehicle) -> float:
    """The length (m) that scales the position tolerance: max(1, length scale), capped.

    The cap is the largest supported turn radius, so that no parameter, however absurd,
    can loosen the check beyond tolerance * 1e7 m.
    """
    from glideplan.validation import PHYSICAL_RANGES

    return min(max(1.0, vehicle.length_scale), PHYSICAL_RANGES["turn_radius"].high)


def _path_word(best: Candidate) -> str:
    """The returned path's word: zero-length segments dropped, equal turns merged.

    A candidate's word names its type in the sufficient set ("LSL" even when both arcs are
    empty, e.g. a straight downwind path); the solution reports what is flown. Paths of
    sampled controls (direct methods) keep the planner's classification of their controls.
    """
    path = best.path
    if path is None or any(seg.kind == "sampled" for seg in path.segments):
        return best.word
    return path.word


def _same_pose_solution(
    spec: PlannerSpec, objective: str, start: Pose, goal: Pose, vehicle: Vehicle
) -> Solution:
    """The solved zero-length path (cost 0) returned when the goal is the start."""
    from glideplan.path import Path
    from glideplan.segments import Straight

    speed = float(getattr(vehicle, "speed", getattr(vehicle, "v_max", 1.0)))
    path = Path((Straight(start, 0.0, speed=speed),), vehicle)
    cand = Candidate("", "", 0.0, path, Status.FEASIBLE, {"zero_length": True})
    return Solution(
        status=Status.SOLVED, planner=spec.name, objective=objective, start=start, goal=goal,
        vehicle=vehicle, path=path, cost=0.0, candidates=(cand,),
        endpoint_error=endpoint_error(path, goal),
        message="the goal is the start: the optimal path has zero length (cost 0)",
        stats={"planner_seconds": 0.0},
    )


def _placed(path: Path, start: Pose, vehicle: Vehicle) -> Path:
    """`path` (planned from the origin) moved to `start` and flown by `vehicle`; the same
    object when nothing changes (a start at the origin maps every point to itself)."""
    if start.x != 0.0 or start.y != 0.0 or start.heading != 0.0:
        path = path.transformed(start)
    return path if path.vehicle is vehicle else path.with_vehicle(vehicle)


def plan(
    start: Pose | tuple[float, float, float],
    goal: Pose | tuple[float, float, float],
    vehicle: Vehicle,
    objective: str | None = None,
    method: str | None = None,
    *,
    verify: bool = True,
    tolerance: float = 1e-6,
    **options: Any,
) -> Solution:
    """Plan an optimal path from `start` to `goal` (poses in m, rad) for `vehicle`.

    The vehicle model and objective select the planner (see `planners()`); `method` chooses
    among several (e.g. "synthesis" or "direct"). `options` go to the planner; an unknown
    option is an error. The best candidate is verified by integrating its controls; its
    endpoint error must be below `tolerance * min(max(1, vehicle.length_scale), 1e5 m)` in
    position and `tolerance` in heading (rad). Start and goal coordinates must lie within
    `PHYSICAL_RANGES["position"]` (1e7 m); vehicles refuse parameters outside the same table.

    Start equal to goal (positions within 1e-12 times that scale, headings within 1e-12 rad
    modulo 2 pi): every planner gives the same answer without being called, a solved
    zero-length path (one straight of length 0) with cost 0, empty word and family, and the
    message "the goal is the start". (A full loop is never preferred: it costs more.)

    Raises:
        InvalidParameterError: `vehicle` is not a glideplan vehicle, a pose is not three
            finite numbers, no planner matches, or an option is unknown.
    """
    start_p, goal_p, objective, spec = _request(start, goal, vehicle, objective, method,
                                                verify, tolerance, options)
    local_goal = goal_p.relative_to(start_p)
    scale = _verification_scale(vehicle)
    if (
        math.hypot(local_goal.x, local_goal.y) <= _SAME_POSE_TOL * scale
        and abs(float(wrap_to_pi(local_goal.heading))) <= _SAME_POSE_TOL
    ):
        return _same_pose_solution(spec, objective, start_p, goal_p, vehicle)
    problem = Problem(Pose(0.0, 0.0, 0.0), local_goal, vehicle, objective, start_p)
    t0 = time.perf_counter()
    out = spec.function(problem, **options)
    stats = {"planner_seconds": time.perf_counter() - t0, **out.stats}
    candidates = _world_candidates(out, start_p, vehicle)
    best, err, rejected = _verified(candidates, goal_p, tolerance * scale, tolerance, verify)
    common: dict[str, Any] = {
        "planner": spec.name, "objective": objective, "start": start_p, "goal": goal_p,
        "vehicle": vehicle, "candidates": tuple(candidates), "stats": stats,
        "extras": dict(out.extras)}
    if best is None or err is None:
        return _unsolved(out, candidates, rejected, common)
    assert best.path is not None
    warnings = tuple(out.warnings)
    if rejected:
        stats["rejected_by_verification"] = rejected
        warnings += (
            f"{rejected} cheaper candidate(s) failed verification by integration; "
            f"returned the cheapest verified one ({best.word}, cost {best.cost:.6g})",
        )
    return Solution(status=Status.SOLVED, path=best.path, cost=best.cost,
                    word=_path_word(best), family=best.family, endpoint_error=err,
                    message=out.message, warnings=warnings, **common)


def _request(start: Pose | tuple[float, float, float], goal: Pose | tuple[float, float, float],
             vehicle: Vehicle, objective: str | None, method: str | None, verify: bool,
             tolerance: float, options: Mapping[str, Any]
             ) -> tuple[Pose, Pose, str, PlannerSpec]:
    """`plan()`'s arguments checked: start and goal poses, the objective and the planner
    (bad input raises `InvalidParameterError` naming the parameter)."""
    if not isinstance(vehicle, Vehicle):
        raise InvalidParameterError(
            "vehicle", vehicle, "must be a glideplan vehicle model (e.g. DubinsCar(1.0, 1.0))"
        )
    if not isinstance(verify, bool):
        raise InvalidParameterError("verify", verify, "must be True or False")
    if not isinstance(tolerance, (int, float)) or isinstance(tolerance, bool):
        raise InvalidParameterError("tolerance", tolerance, "must be a real number")
    if not 0.0 < tolerance < 1.0:
        raise InvalidParameterError("tolerance", tolerance, "must lie in (0, 1)")
    start_p, goal_p = _as_pose("start", start), _as_pose("goal", goal)
    objective = objective or vehicle.default_objective
    spec = find_planner(vehicle, objective, method)
    unknown = sorted(set(options) - set(spec.options))
    if unknown:
        known = ", ".join(spec.options) or "none"
        raise InvalidParameterError(
            unknown[0],
            options[unknown[0]],
            f"is not an option of planner {spec.name!r} (known: {known})",
        )
    return start_p, goal_p, objective, spec


def _world_candidates(out: PlannerOutput, start: Pose, vehicle: Vehicle) -> list[Candidate]:
    """The planner's candidates placed at the world start, feasible first, cheapest first."""
    return sorted(
        (
            Candidate(
                c.word,
                c.family,
                c.cost,
                _placed(c.path, start, vehicle) if c.path is not None else None,
                c.status,
                c.info,
            )
            for c in out.candidates
        ),
        key=lambda c: (not c.feasible, c.cost if math.isfinite(c.cost) else math.inf),
    )


def _verified(candidates: list[Candidate], goal: Pose, tol: float, tolerance: float,
              verify: bool) -> tuple[Candidate | None, EndpointError | None, int]:
    """The cheapest feasible candidate whose controls, integrated (or its path's own end
    without `verify`), end within `tol` (m) and `tolerance` (rad) of the goal; its endpoint
    error; how many cheaper ones were rejected."""
    rejected = 0
    for cand in candidates:
        if not cand.feasible:
            continue
        assert cand.path is not None
        e = (
            endpoint_error(cand.path, goal)
            if verify
            else EndpointError(*cand.path.endpoint_gap(goal))
        )
        if e.position <= tol and e.heading <= tolerance:
            return cand, e, rejected
        rejected += 1
    return None, None, rejected


def _unsolved(out: PlannerOutput, candidates: list[Candidate], rejected: int,
              common: Mapping[str, Any]) -> Solution:
    """No verified path: the planner's own failure (SOLVER_FAILED, reason SOLVER) when it
    returned no feasible candidate, NOT_VERIFIED when some failed verification, else
    NO_PATH."""
    feasible = any(c.feasible for c in candidates)
    if out.failure is not None and not feasible:
        status = out.failure
    elif feasible:
        status = Status.NOT_VERIFIED
    else:
        status = Status.NO_PATH
    message = out.message or {
        Status.NO_PATH: "no candidate path reaches the goal",
        Status.NOT_VERIFIED: f"{rejected} candidate(s) failed verification by integration",
    }.get(status, "the solver failed")
    return Solution(status=status, path=None, cost=math.inf, message=message,
                    warnings=tuple(out.warnings),
                    reason=Reason.SOLVER if status is Status.SOLVER_FAILED else None, **common)
