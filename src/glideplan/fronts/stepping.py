"""The pieces of one front step (`glideplan.fronts.solver.propagate`): the kernel's arguments,
the drift levels' obstacle mask, and the watch on phi at the goal.

A step is TVD-RK2 over the active nodes (`glideplan.fronts.kernel.rk_stage`, then
`stage_two`); the goal is passed at the time phi(goal) crosses 0, interpolated linearly in t
between the two steps that bracket it, and the front runs ceil(4 / cfl) more steps so the
arrival map is complete around the goal.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fronts.grid import LatLonGrid

if TYPE_CHECKING:
    from glideplan.fronts.solver import FrontProblem

FloatArray = NDArray[np.float64]


def bilinear_phi(phi: FloatArray, grid: LatLonGrid, fi: float, fj: float) -> float:
    """phi at the fractional node (fi, fj), bilinear (periodic in longitude if the grid is)."""
    ny, nx = phi.shape
    i = int(np.clip(math.floor(fi), 0, ny - 2))
    wy = float(np.clip(fi - i, 0.0, 1.0))
    if grid.periodic:
        j = math.floor(fj) % nx
        j1 = (j + 1) % nx
        wx = fj - math.floor(fj)
    else:
        j = int(np.clip(math.floor(fj), 0, nx - 2))
        j1 = j + 1
        wx = float(np.clip(fj - j, 0.0, 1.0))
    return float((1 - wy) * ((1 - wx) * phi[i, j] + wx * phi[i, j1])
                 + wy * ((1 - wx) * phi[i + 1, j] + wx * phi[i + 1, j1]))


@dataclass(frozen=True, eq=False)
class StepArgs:
    """The kernel's fixed arguments for one problem: grid shape, spacings, speeds, drifts."""

    ny: int
    nx: int
    periodic: bool
    spacings: tuple[FloatArray, FloatArray, FloatArray, float, float, float, FloatArray]
    a: FloatArray
    b: FloatArray
    s: FloatArray
    tb: FloatArray
    band: float

    @classmethod
    def of(cls, problem: FrontProblem) -> StepArgs:
        """Spacings as the kernel uses them: 1/h, 1/h^2, h/2 per row (x) and for y;
        1/min(hx, hy)."""
        g = problem.grid
        ny, nx = g.shape
        hx = np.ascontiguousarray(g.hx)
        hy = float(g.hy)
        sp = (1.0 / hx, 1.0 / hx**2, 0.5 * hx, 1.0 / hy, 1.0 / hy**2, 0.5 * hy,
              1.0 / np.minimum(hx, hy))
        return cls(ny, nx, g.periodic, sp, np.ascontiguousarray(problem.speeds),
                   np.ascontiguousarray(problem.drifts),
                   np.ascontiguousarray(problem.drift_scales), problem.block_times.ravel(),
                   problem.band)


@dataclass(eq=False)
class MayBlock:
    """Nodes that may ever be blocked: a finite block time, or NaN in a drift level seen so far
    (the kernel's `may` mask, uint8)."""

    may_b: NDArray[np.bool_]
    may: NDArray[np.uint8]
    seen: set[int]

    @classmethod
    def of(cls, tb: FloatArray) -> MayBlock:
        may_b = tb < np.inf
        return cls(may_b, may_b.astype(np.uint8), set())

    def see(self, drift: Any, t: float) -> None:
        """Add the NaN nodes of the drift levels bracketing t (each level once)."""
        k_lo = drift.bracket(t)[0]
        for k in (k_lo, min(k_lo + 1, drift.times.size - 1)):
            if k not in self.seen:
                self.seen.add(k)
                self.may_b |= ~np.isfinite(drift.level(k)[0])
                self.may = self.may_b.astype(np.uint8)


@dataclass(eq=False)
class GoalWatch:
    """phi at the goal between steps: the time it crosses 0, then the steps run after it."""

    gfi: float
    gfj: float
    gi: int
    gj: int
    phi_old: float
    time: float | None = None
    extra: int = 0

    @classmethod
    def at(cls, grid: LatLonGrid, goal: tuple[float, float], phi: FloatArray) -> GoalWatch:
        """Watch `goal` (lat, lon) on `grid`, phi (ny, nx) the state before the first step."""
        gfi_, gfj_ = grid.frac_index(goal[0], goal[1])
        gfi, gfj = float(gfi_), float(gfj_)
        if not bool(grid.contains(goal[0], goal[1])):
            raise InvalidParameterError("goal", goal, "lies outside the front's grid")
        phi_old = bilinear_phi(phi, grid, gfi, gfj)
        ny, nx = grid.shape
        gi = int(np.clip(round(gfi), 1, ny - 2))
        gj = round(gfj) % nx if grid.periodic else int(np.clip(round(gfj), 1, nx - 2))
        return cls(gfi, gfj, gi, gj, phi_old)

    def done(self, grid: LatLonGrid, phi: FloatArray, arrival: FloatArray, tb: FloatArray,
             t: float, dt: float, cfl: float) -> bool:
        """After the step to t (of length dt): True once the goal is passed and its 3x3
        neighbours are reached or blocked, or 40/cfl steps after the extra ones."""
        if self.time is None:
            pg = bilinear_phi(phi, grid, self.gfi, self.gfj)
            if pg <= 0.0:
                self.time = (t - dt + dt * self.phi_old / (self.phi_old - pg)
                             if self.phi_old > 0 else t)
                self.extra = math.ceil(4.0 / cfl)
            self.phi_old = pg
            return False
        self.extra -= 1
        nx = grid.shape[1]
        rows = slice(self.gi - 1, self.gi + 2)
        cols: Any = ([(self.gj + d) % nx for d in (-1, 0, 1)] if grid.periodic
                     else slice(self.gj - 1, self.gj + 2))
        around = arrival[rows, cols]
        blk = tb[rows, cols] < t
        return bool((self.extra <= 0 and np.all(np.isfinite(around) | blk))
                    or self.extra < -math.ceil(40.0 / cfl))
