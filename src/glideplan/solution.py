"""What a planner returns: candidates with their costs, and the verified solution."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any

from glideplan.errors import InvalidParameterError, PlanningError
from glideplan.path import Path
from glideplan.pose import Pose
from glideplan.vehicles.base import Vehicle
from glideplan.verify import EndpointError

__all__ = ["Candidate", "Solution", "Status"]


class Status(StrEnum):
    """Outcome of a planning request, of one candidate, or of one numerical solve.

    The one status vocabulary of the library (a `StrEnum`: members compare equal to their
    strings, which is what `--json` prints). A `Solution` is SOLVED, NO_PATH, NOT_VERIFIED or
    SOLVER_FAILED; a `Candidate` is FEASIBLE, INFEASIBLE, LOCAL or FAILED; a direct solve
    (`glideplan.planners.direct.DirectResult`) is SOLVED or FAILED. The products above
    `plan()` (`glideplan.results`) use the same members: a route is SOLVED, UNREACHABLE or
    NOT_VERIFIED; following a flyable path SOLVED, LOST or INFEASIBLE (no feasible radius); a
    trochoid chain SOLVED or INFEASIBLE; a mission SOLVED, FAILED or UNREACHABLE; a final
    glide SOLVED (arrives at or above the safety height), BELOW_GLIDE or UNREACHABLE.
    """

    SOLVED = "solved"  # a path was found and verified by integration (or a solve converged)
    NO_PATH = "no_path"  # no candidate satisfies the boundary conditions
    NOT_VERIFIED = "not_verified"  # candidates exist but none passed verification
    SOLVER_FAILED = "solver_failed"  # a numerical solver failed (e.g. IPOPT did not converge)
    FEASIBLE = "feasible"  # a candidate with a path that reaches the goal
    INFEASIBLE = "infeasible"  # a candidate type with no path for this goal
    LOCAL = "local"  # a converged start of a multi-start solve that is not the best
    FAILED = "failed"  # one numerical solve (a start, a candidate) did not converge
    # Products above plan() (routes, missions, glides, reach; see glideplan.results):
    UNREACHABLE = "unreachable"  # proven out of reach (the front stopped, or hit the field's
    #                              extent or time span; the result's `reason` says which)
    LOST = "lost"  # a closed-loop follower did not reach the goal (left the field, hit land,
    #                or timed out; the message says which)
    BELOW_GLIDE = "below_glide"  # a glide reaches the goal but arrives below the safety height


@dataclass(frozen=True, eq=False)
class Candidate:
    """One candidate of the sufficient set: its type word, family, cost and path."""

    word: str
    family: str
    cost: float
    path: Path | None = None
    status: Status = Status.FEASIBLE
    info: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        # a planner may pass the status's string; anything else is a bug
        status = next((s for s in _CANDIDATE_STATUSES if s == self.status), None)
        if status is None:
            known = ", ".join(s.value for s in _CANDIDATE_STATUSES)
            raise InvalidParameterError("status", self.status, f"must be one of {known}")
        object.__setattr__(self, "status", status)

    @property
    def feasible(self) -> bool:
        return (
            self.path is not None and self.status is Status.FEASIBLE and math.isfinite(self.cost)
        )

    def to_dict(self) -> dict[str, Any]:
        out: dict[str, Any] = {
            "word": self.word,
            "family": self.family,
            "cost": self.cost,
            "status": self.status.value,
        }
        out.update({k: v for k, v in self.info.items() if _jsonable(v)})
        return out


_CANDIDATE_STATUSES = (Status.FEASIBLE, Status.INFEASIBLE, Status.LOCAL, Status.FAILED)


def _jsonable(v: Any) -> bool:
    return isinstance(v, (int, float, str, bool, type(None), list, tuple, dict))


@dataclass(frozen=True, eq=False)
class Solution:
    """The result of `plan()`: the best verified path, all candidates and diagnostics."""

    status: Status
    planner: str
    objective: str
    start: Pose
    goal: Pose
    vehicle: Vehicle
    path: Path | None
    cost: float
    word: str
    family: str
    candidates: tuple[Candidate, ...]
    endpoint_error: EndpointError | None
    message: str = ""
    stats: Mapping[str, Any] = field(default_factory=dict)
    extras: Mapping[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    @property
    def ok(self) -> bool:
        return self.status is Status.SOLVED

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """The solution figure (`glideplan.plotting.plot_solution`); returns the axes."""
        from glideplan.plotting import plot_solution

        return plot_solution(self, ax=ax, **kwargs)

    def raise_for_status(self) -> Solution:
        """Return self when solved, else raise `PlanningError` with the message."""
        if not self.ok:
            raise PlanningError(f"{self.planner}: {self.status.value}: {self.message}")
        return self

    def to_dict(self) -> dict[str, Any]:
        """The JSON object the CLI prints (see docs/ARCHITECTURE.md)."""
        p = self.path
        out: dict[str, Any] = {
            "planner": self.planner,
            "objective": self.objective,
            "status": self.status.value,
            "message": self.message,
            "warnings": list(self.warnings),
            "cost": self.cost if math.isfinite(self.cost) else None,
            "word": self.word,
            "family": self.family,
            "length": p.length if p else None,
            "duration": p.duration if p else None,
            "endpoint_error": self.endpoint_error.to_dict() if self.endpoint_error else None,
            "start": {"x": self.start.x, "y": self.start.y, "heading": self.start.heading},
            "goal": {"x": self.goal.x, "y": self.goal.y, "heading": self.goal.heading},
            "vehicle": self.vehicle.to_dict(),
            "segments": [s.to_dict() for s in p.segments] if p else [],
            "candidates": [c.to_dict() for c in self.candidates],
            "stats": {k: v for k, v in self.stats.items() if _jsonable(v)},
        }
        out.update(self.extras)
        return out
