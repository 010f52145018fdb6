"""What a planner returns: candidates with their costs, and the verified solution."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from glideplan.errors import InvalidParameterError, PlanningError
from glideplan.path import Path
from glideplan.pose import Pose
from glideplan.results import Outcome
from glideplan.status import Status
from glideplan.vehicles.base import Vehicle
from glideplan.verify import EndpointError

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["Candidate", "Solution", "Status"]


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


@dataclass(frozen=True, kw_only=True, eq=False)
class Solution(Outcome):
    """The result of `plan()`: the best verified path, all candidates and diagnostics.

    An `Outcome` (`glideplan.results`): status SOLVED, NO_PATH, NOT_VERIFIED or SOLVER_FAILED
    (reason SOLVER)."""

    planner: str
    objective: str
    start: Pose
    goal: Pose
    vehicle: Vehicle
    path: Path | None
    cost: float
    word: str = ""
    family: str = ""
    candidates: tuple[Candidate, ...] = ()
    endpoint_error: EndpointError | None = None
    stats: Mapping[str, Any] = field(default_factory=dict)
    extras: Mapping[str, Any] = field(default_factory=dict)

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """The solution figure (`glideplan.plotting.plot_solution`)."""
        from glideplan.plotting import plot_solution
        from glideplan.results import as_figure

        return as_figure(plot_solution(self, ax=ax, **kwargs))

    def raise_for_status(self) -> Solution:
        """Return self when solved, else raise `PlanningError` with the message."""
        if not self.ok:
            raise PlanningError(f"{self.planner}: {self.status.value}: {self.message}")
        return self

    def to_dict(self) -> dict[str, Any]:
        """The JSON object the CLI prints (see docs/ARCHITECTURE.md)."""
        p = self.path
        out: dict[str, Any] = {
            **super().to_dict(),
            "planner": self.planner,
            "objective": self.objective,
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
