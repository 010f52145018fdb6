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
from typing import Any

from glideplan.errors import InvalidParameterError
from glideplan.objectives import get_objective
from glideplan.pose import Pose
from glideplan.solution import Candidate, Solution, Status
from glideplan.vehicles.base import Vehicle
from glideplan.verify import EndpointError, endpoint_error

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
    solver_failed: bool = False
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
    """All registered planners (importing `glideplan` registers the built-in ones)."""
    return tuple(_REGISTRY)


def find_planner(vehicle: Vehicle, objective: str, method: str | None = None) -> PlannerSpec:
    """The planner for this vehicle type, objective and method (default method if None)."""
    if not isinstance(vehicle, Vehicle):
        raise InvalidParameterError("vehicle", vehicle, "must be a glideplan vehicle model")
    get_objective(objective)
    matches = [s for s in _REGISTRY if isinstance(vehicle, s.vehicle) and s.objective == objective]
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
        return value
    try:
        return Pose.from_array(value)
    except InvalidParameterError as err:
        raise InvalidParameterError(name, value, err.rule) from None


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
    endpoint error must be below `tolerance * max(1, vehicle.length_scale)` (m and rad).
    """
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
    local_goal = goal_p.relative_to(start_p)
    problem = Problem(Pose(0.0, 0.0, 0.0), local_goal, vehicle, objective, start_p)
    t0 = time.perf_counter()
    out = spec.function(problem, **options)
    elapsed = time.perf_counter() - t0
    candidates = sorted(
        (
            Candidate(
                c.word,
                c.family,
                c.cost,
                c.path.transformed(start_p).with_vehicle(vehicle) if c.path is not None else None,
                c.status,
                c.info,
            )
            for c in out.candidates
        ),
        key=lambda c: (not c.feasible, c.cost if math.isfinite(c.cost) else math.inf),
    )
    stats = {"planner_seconds": elapsed, **out.stats}
    feasible = [c for c in candidates if c.feasible]
    tol = tolerance * max(1.0, vehicle.length_scale)
    best: Candidate | None = None
    err: EndpointError | None = None
    rejected = 0
    for cand in feasible:
        assert cand.path is not None
        e = (
            endpoint_error(cand.path, goal_p)
            if verify
            else EndpointError(*cand.path.endpoint_gap(goal_p))
        )
        if e.position <= tol and e.heading <= tolerance:
            best, err = cand, e
            break
        rejected += 1
    if best is None:
        if out.solver_failed and not feasible:
            status = Status.SOLVER_FAILED
        elif feasible:
            status = Status.NOT_VERIFIED
        else:
            status = Status.NO_PATH
        message = (
            out.message
            or {
                Status.NO_PATH: "no candidate path reaches the goal",
                Status.NOT_VERIFIED: f"{rejected} candidate(s) failed verification by integration",
                Status.SOLVER_FAILED: "the solver failed",
            }[status]
        )
        return Solution(
            status,
            spec.name,
            objective,
            start_p,
            goal_p,
            vehicle,
            None,
            math.inf,
            "",
            "",
            tuple(candidates),
            None,
            message,
            stats,
            dict(out.extras),
            tuple(out.warnings),
        )
    assert best.path is not None
    warnings = tuple(out.warnings)
    if rejected:
        stats["rejected_by_verification"] = rejected
        warnings += (
            f"{rejected} cheaper candidate(s) failed verification by integration; "
            f"returned the cheapest verified one ({best.word}, cost {best.cost:.6g})",
        )
    return Solution(
        Status.SOLVED,
        spec.name,
        objective,
        start_p,
        goal_p,
        vehicle,
        best.path,
        best.cost,
        best.word,
        best.family,
        tuple(candidates),
        err,
        out.message,
        stats,
        dict(out.extras),
        warnings,
    )
