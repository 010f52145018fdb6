"""Minimum-time synthesis over a grid of goals (Figs 4.9-4.11), through `run_batch`.

For a fixed final heading, every goal (x, y) of the grid gets the optimal time, the family and
turn word of the optimal path, and the time of the Dubins path at v_max (radius R), whose
ratio to the optimum shows what flying at constant maximum speed costs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.batch import run_batch
from glideplan.planners.dubins import dubins_shortest
from glideplan.planners.min_time import synthesis
from glideplan.planners.min_time.solvers import Extremal
from glideplan.planners.min_time.synthesis import synthesize
from glideplan.planners.min_time.table import CANDIDATE_TYPES
from glideplan.validation import check_finite, check_finite_array
from glideplan.vehicles.variable_speed_car import VariableSpeedCar
from glideplan.words import run_word

__all__ = ["TimeOptimalGrid", "best_time", "time_optimal_grid"]

_DUBINS = [t for t in CANDIDATE_TYPES if t.group == "Dubins"]


@dataclass(frozen=True, eq=False)
class TimeOptimalGrid:
    """Optimal time (s), family and word per goal (rows follow `ys`, columns `xs`)."""

    vehicle: VariableSpeedCar
    heading: float
    xs: np.ndarray
    ys: np.ndarray
    time: np.ndarray
    family: np.ndarray
    word: np.ndarray
    dubins_time: np.ndarray

    @property
    def ratio(self) -> np.ndarray:
        """Dubins-at-v_max time over optimal time (>= 1; nan where the goal is the start)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.time > 0.0, self.dubins_time / self.time, np.nan)


def best_time(vehicle: VariableSpeedCar, x: float, y: float, heading: float) -> tuple:
    """(time (s), family, word) of the minimum-time path from the origin to (x, y, heading)."""
    scale = vehicle.bang_radius
    goal = np.array([x / scale, y / scale, heading])
    if math.hypot(goal[0], goal[1]) < 1e-12 and abs(math.remainder(heading, 2 * math.pi)) < 1e-12:
        return 0.0, "", ""
    best = synthesize(goal, vehicle.speed_ratio).best
    if best is None:  # pragma: no cover - the Dubins candidates always exist
        return math.inf, "", ""
    return _summary(best, vehicle)


def _summary(best: Extremal, vehicle: VariableSpeedCar) -> tuple[float, str, str]:
    """(time (s), family, word) of an optimal extremal (zero-length moves dropped)."""
    merged: list[tuple[str, int]] = []
    for lab, d, amount in best.moves:
        if amount > 1e-12 and (not merged or merged[-1] != (lab, d)):
            merged.append((lab, d))
    family = "".join(lab for lab, _ in merged)
    word = run_word("S" if lab == "S" else ("L" if d > 0 else "R") for lab, d in merged)
    return best.cost / vehicle.u_max, family, word


def _row(args: tuple[VariableSpeedCar, np.ndarray, float, float]) -> list[tuple]:
    vehicle, xs, y, heading = args
    if not synthesis.COMPILED or vehicle.speed_ratio >= 1.0:
        return [best_time(vehicle, float(x), y, heading) for x in xs]
    return _compiled_row(vehicle, xs, y, heading)


def _compiled_row(vehicle: VariableSpeedCar, xs: np.ndarray, y: float,
                  heading: float) -> list[tuple]:
    """`best_time` of every goal of a row with the compiled kernels: the row's Dubins words in
    one call, and per goal only the winner becomes an `Extremal` (`compiled.best_extremal`,
    the same optimum as `synthesize(goal).best`)."""
    from glideplan.planners.min_time.compiled import best_extremal

    scale, rho = vehicle.bang_radius, vehicle.speed_ratio
    goals = np.array([[float(x) / scale, y / scale, heading] for x in xs])
    tables = synthesis.dubins_tables_many(goals, sorted({rho, 1.0}))
    out = []
    for x, goal, table in zip(xs, goals, tables, strict=True):
        if math.hypot(goal[0], goal[1]) < 1e-12 and abs(math.remainder(heading, 2 * math.pi)) < (
            1e-12
        ):
            out.append((0.0, "", ""))
            continue
        dubins = synthesis._dubins_extremals(_DUBINS, goal, rho, table, compiled=True)
        best = best_extremal(goal, rho, dubins)
        out.append(_summary(best, vehicle) if best is not None else best_time(
            vehicle, float(x), y, heading))  # fmt: skip
    return out


def time_optimal_grid(
    vehicle: VariableSpeedCar,
    xs: ArrayLike,
    ys: ArrayLike,
    heading: float,
    *,
    processes: int | None = None,
    scheduler: Any = None,
    progress: bool = False,
) -> TimeOptimalGrid:
    """Synthesis for every goal (x, y, heading) with x in `xs`, y in `ys` (m, rad).

    One batch item per row of the grid, run by `glideplan.batch.run_batch` (a local process
    pool by default, Dask with `scheduler`).
    """
    xs = check_finite_array("xs", xs).ravel()
    ys = check_finite_array("ys", ys).ravel()
    heading = check_finite("heading", heading)
    # solve one goal here first: the kernels (numba) and this ratio's tables are loaded once
    # and the pool's forked workers inherit them instead of each loading them again
    if synthesis.COMPILED:
        from glideplan.planners.min_time import compiled  # noqa: F401  (imports numba)
    synthesize(np.array([1.0, 1.0, 1.0]), vehicle.speed_ratio)
    rows = run_batch(
        _row,
        [(vehicle, xs, float(y), heading) for y in ys],
        scheduler=scheduler,
        processes=processes,
        progress=progress,
        description=f"time-optimal grid, heading {heading:.3f} rad",
    )
    time = np.array([[c[0] for c in row] for row in rows])
    family = np.array([[c[1] for c in row] for row in rows], dtype=object)
    word = np.array([[c[2] for c in row] for row in rows], dtype=object)
    gx, gy = np.meshgrid(xs, ys)
    goals = np.stack([gx, gy, np.full_like(gx, heading)], axis=-1)
    dub = dubins_shortest(np.zeros(3), goals, vehicle.bang_radius).length / vehicle.v_max
    return TimeOptimalGrid(vehicle, heading, xs, ys, time, family, word, np.asarray(dub))
