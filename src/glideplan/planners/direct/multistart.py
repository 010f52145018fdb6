"""The multi-start and mesh-refinement bookkeeping of `solve_direct`: the wall-clock limit,
the failed result, the option checks, and the refinement of a converged start (bisect every
mesh interval until the relative cost change |J_{k+1} - J_k| / |J_{k+1}| < mesh_tol)."""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.direct.collocation import SCHEMES
from glideplan.planners.direct.results import DirectResult, StartResult
from glideplan.pose import Pose
from glideplan.results import Reason
from glideplan.solution import Status
from glideplan.validation import check_integer, check_positive

if TYPE_CHECKING:
    from glideplan.planners.direct.engine import _Problem, _Solve


class Deadline:
    """The wall-clock limit of one `solve_direct` call (None: no limit)."""

    def __init__(self, t_start: float, limit: float | None) -> None:
        if limit is not None:
            limit = check_positive("time_limit", limit)
        self.t_start = t_start
        self.limit = limit

    def expired(self) -> bool:
        return self.limit is not None and time.perf_counter() - self.t_start >= self.limit

    def budget(self) -> float | None:
        """IPOPT wall time (s) for the next solve: the largest limit / 2^j within the time left.

        Powers of two keep the number of distinct (cached) solvers small; the whole call
        then ends within the limit plus the time to build a solver.
        """
        if self.limit is None:
            return None
        left = self.limit - (time.perf_counter() - self.t_start)
        if left <= 0.0:
            return self.limit * 2.0**-20
        return self.limit * 2.0 ** -min(20, math.ceil(math.log2(self.limit / left)))

    def failure(
        self, stats: dict[str, Any], iterations: int, starts: list[StartResult], total: int
    ) -> DirectResult:
        """The failed result of a call stopped by the limit."""
        stats["time_limit_reached"] = True
        message = (
            f"time limit of {self.limit:g} s reached "
            f"({len(starts)} of {total} start(s) solved before it)"
        )
        return failed(stats, iterations, self.t_start, starts, message)


def failed(
    stats: dict[str, Any],
    iterations: int,
    t_start: float,
    starts: list[StartResult],
    message: str,
) -> DirectResult:
    """A failed `DirectResult` (no path) with the effort spent."""
    stats.update(iterations=iterations, seconds=time.perf_counter() - t_start)
    return DirectResult(status=Status.FAILED, path=None, cost=math.inf, stats=stats,
                        starts=tuple(starts), message=message, reason=Reason.SOLVER)


def check_options(
    goal: Pose,
    guesses: Sequence[Path],
    n_intervals: int,
    scheme: str,
    mesh_tol: float,
    max_refinements: int,
    output_density: int,
) -> None:
    if not isinstance(goal, Pose):
        raise InvalidParameterError("goal", goal, "must be a Pose")
    if len(guesses) == 0:
        raise InvalidParameterError("guesses", guesses, "needs at least one initial-guess Path")
    for i, g in enumerate(guesses):
        if not isinstance(g, Path) or not g.duration > 0.0:
            raise InvalidParameterError(f"guesses[{i}]", g, "must be a Path of positive duration")
    if scheme not in SCHEMES:
        raise InvalidParameterError("scheme", scheme, f"must be one of {', '.join(SCHEMES)}")
    check_integer("n_intervals", n_intervals, 2)
    check_positive("mesh_tol", mesh_tol)
    check_integer("max_refinements", max_refinements, 0)
    check_integer("output_density", output_density, 1)



@dataclass(frozen=True)
class Converged:
    """A start that converged on the first mesh: its solve, heading branch k (psi(T) =
    goal.heading + 2 pi k), cost scale and index among the guesses."""

    solve: _Solve
    turns: int
    cost_scale: float
    index: int


@dataclass(frozen=True)
class Refined:
    """A converged start after mesh refinement: the last good solve, the mesh sizes and
    costs along the way, whether the cost settled, the IPOPT iterations spent and whether the
    time limit stopped it."""

    solve: _Solve
    meshes: list[int]
    costs: list[float]
    converged: bool
    index: int
    iterations: int
    timed_out: bool


def refine(
    prob: _Problem, start: Converged, max_refinements: int, mesh_tol: float, clock: Deadline
) -> Refined:
    """Bisect every mesh interval until the relative cost change is below `mesh_tol`."""
    cur = start.solve
    meshes, costs = [cur.transcription.n_intervals], [cur.cost]
    iterations = 0
    for _ in range(max_refinements):
        nxt = prob.refine(cur, start.turns, start.cost_scale)
        iterations += max(nxt.iterations, 0)
        if clock.expired():
            return Refined(cur, meshes, costs, False, start.index, iterations, True)
        if not nxt.ok:
            break
        change = abs(nxt.cost - cur.cost) / max(abs(nxt.cost), 1e-12)
        cur = nxt
        meshes.append(cur.transcription.n_intervals)
        costs.append(cur.cost)
        if change < mesh_tol:
            return Refined(cur, meshes, costs, True, start.index, iterations, False)
    return Refined(cur, meshes, costs, False, start.index, iterations, False)
