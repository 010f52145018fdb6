"""What the direct engine returns: one `StartResult` per start and the `DirectResult`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from glideplan.path import Path
from glideplan.results import Outcome
from glideplan.solution import Status

__all__ = ["DirectResult", "StartResult"]


@dataclass(frozen=True)
class StartResult:
    """One start of the multi-start: its guess's word, cost, status and solver effort."""

    index: int
    cost: float
    status: str
    iterations: int
    heading_turns: int  # k of the heading branch psi(T) = goal.heading + 2 pi k
    label: str = ""

    def __iter__(self):  # unpacks as (cost, status)
        return iter((self.cost, self.status))

    def to_dict(self) -> dict[str, Any]:
        return {
            "index": self.index,
            "cost": self.cost if math.isfinite(self.cost) else None,
            "status": self.status,
            "iterations": self.iterations,
            "heading_turns": self.heading_turns,
            "label": self.label,
        }


@dataclass(frozen=True, eq=False, kw_only=True)
class DirectResult(Outcome):
    """Outcome of `solve_direct`.

    `status` is `Status.SOLVED` or `Status.FAILED` ("solved" / "failed"); `path` (one
    `Sampled` segment from the origin) is None on failure; `cost` is the collocation cost on
    the final mesh (inf on failure); `stats` holds iterations, seconds, mesh sizes and the
    cost on each mesh, starts tried and succeeded, and the endpoint error of the returned
    path's controls; `starts` has one `StartResult` (unpacks as (cost, status)) per guess;
    `controls` the dense control history by name (plus "t", "speed", "turn_rate") along the
    returned path; `warnings` what the caller must pass on (a failed re-timing). An
    `Outcome` (`glideplan.results`): a failure's reason is SOLVER.
    """

    path: Path | None
    cost: float
    stats: dict[str, Any]
    starts: tuple[StartResult, ...]
    controls: Mapping[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.status is Status.SOLVED and self.path is None:
            raise ValueError("a solved DirectResult needs its path")
