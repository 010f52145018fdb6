"""Headings at the waypoints of a multi-leg mission: dynamic programme, refinement, heuristics.

The cost of a route with headings h_0..h_{n-1} is a chain, J = sum_i c_i(h_i, h_{i+1}), with
c_i the optimal leg cost (Dubins length or time, or the convected-Dubins time in a wind). On
K candidate headings per free waypoint the exact minimum is a dynamic programme,

    V_0(a) = 0,  V_{i+1}(b) = min_a [V_i(a) + c_i(a, b)],

O(n K^2) with one K x K matrix of leg costs per leg (`leg_costs.dubins_length_matrix`). The
candidates are a uniform grid plus the headings the heuristics would choose there, so the
result is never worse than a heuristic. A local continuous refinement follows: L-BFGS-B
(SciPy) on all free headings within one grid step of the DP choice, with central-difference
gradients, then red-black sweeps of a vectorised golden-section search on each free heading
(the cost seen by heading i depends only on its two neighbours, so all even, then all odd,
waypoints move at once); a move is kept only if it lowers the cost, so the refined total is
never above the DP's.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.missions.leg_costs import dubins_dp_step, dubins_length_matrix
from glideplan.missions.wind_costs import convected_times
from glideplan.planners.dubins import dubins_distance
from glideplan.pose import TWO_PI, mod_2pi

__all__ = [
    "HeadingPlan",
    "LegCost",
    "StillAirCost",
    "WindCost",
    "alternating_headings",
    "bisector_headings",
    "headings_cost",
    "optimise_headings",
    "point_at_next_headings",
]

_GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0

Progress = Callable[[str, int, int], None]
"""A progress report: phase name, steps done, steps in all."""


class LegCost(Protocol):
    """Cost of leg i between headings: all pairs (`matrix`) or elementwise (`pairs`)."""

    def matrix(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]: ...

    def pairs(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]: ...


@dataclass(frozen=True, eq=False)
class StillAirCost:
    """Dubins length (m) or time (s, length / speed) of the legs between `points` (n, 2)."""

    points: NDArray[np.float64]
    radius: float
    scale: float = 1.0  # 1 for length, 1 / speed for time
    precision: str = "single"  # of `matrix` ("double": exact to rounding); `dp_step` is float64

    def __post_init__(self) -> None:
        if self.precision not in ("single", "double"):
            raise InvalidParameterError("precision", self.precision, "must be single or double")

    def matrix(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]:
        dtype = np.float32 if self.precision == "single" else np.float64
        m = dubins_length_matrix(self.points[i], self.points[i + 1], a, b, self.radius, dtype)
        return m * self.scale if self.scale != 1.0 else m

    def pairs(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]:
        s = np.column_stack([np.broadcast_to(self.points[i], (a.size, 2)), a])
        g = np.column_stack([np.broadcast_to(self.points[i + 1], (b.size, 2)), b])
        return np.asarray(dubins_distance(s, g, self.radius)) * self.scale

    def dp_step(
        self, i: int, value: NDArray[np.float64], a: NDArray[np.float64], b: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.intp]] | None:
        """One DP step over leg i (compiled, float64, without the K x K matrix); None: use
        `matrix`."""
        return dubins_dp_step(value, self.points[i], self.points[i + 1], a, b, self.radius,
                              self.scale)


    def pairs_many(
        self, legs: NDArray[np.intp], a: NDArray[np.float64], b: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Elementwise costs of legs `legs` between headings a and b."""
        s = np.column_stack([self.points[legs], a])
        g = np.column_stack([self.points[legs + 1], b])
        return np.asarray(dubins_distance(s, g, self.radius)) * self.scale


@dataclass(frozen=True, eq=False)
class WindCost:
    """Convected-Dubins arrival time (s) of the legs in a steady wind (wx, wy) m/s."""

    points: NDArray[np.float64]
    radius: float
    speed: float
    wind: tuple[float, float]

    def matrix(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]:
        aa, bb = np.meshgrid(a, b, indexing="ij")
        return self.pairs(i, aa.ravel(), bb.ravel()).reshape(a.size, b.size)

    def pairs(self, i: int, a: NDArray[np.float64], b: NDArray[np.float64]) -> NDArray[
        np.float64
    ]:
        s = np.column_stack([np.broadcast_to(self.points[i], (a.size, 2)), a])
        g = np.column_stack([np.broadcast_to(self.points[i + 1], (b.size, 2)), b])
        return convected_times(s, g, speed=self.speed, radius=self.radius, wind=self.wind)

    def pairs_many(
        self, legs: NDArray[np.intp], a: NDArray[np.float64], b: NDArray[np.float64]
    ) -> NDArray[np.float64]:
        """Elementwise costs of legs `legs` between headings a and b."""
        s = np.column_stack([self.points[legs], a])
        g = np.column_stack([self.points[legs + 1], b])
        return convected_times(s, g, speed=self.speed, radius=self.radius, wind=self.wind)


@dataclass(frozen=True, eq=False)
class HeadingPlan:
    """Chosen headings (rad), per-leg costs, total cost, and how they were found."""

    headings: NDArray[np.float64]
    leg_costs: NDArray[np.float64]
    total: float
    stats: dict[str, Any] = field(default_factory=dict)


def _leg_bearings(points: NDArray[np.float64]) -> NDArray[np.float64]:
    d = np.diff(points, axis=0)
    return np.arctan2(d[:, 1], d[:, 0])


def _with_fixed(h: NDArray[np.float64], fixed: NDArray[np.float64]) -> NDArray[np.float64]:
    return np.where(np.isnan(fixed), h, fixed)


def point_at_next_headings(
    points: NDArray[np.float64], fixed: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Heading at each waypoint toward the next one (the last keeps the last leg's bearing)."""
    b = _leg_bearings(points)
    return _with_fixed(np.append(b, b[-1]), fixed)


def bisector_headings(
    points: NDArray[np.float64], fixed: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Heading along the bisector of the incoming and outgoing legs (ends: along their leg)."""
    b = _leg_bearings(points)
    u = np.stack([np.cos(b), np.sin(b)], axis=-1)
    s = np.zeros((len(points), 2))
    s[:-1] += u
    s[1:] += u
    h = np.arctan2(s[:, 1], s[:, 0])
    reverse = np.hypot(s[:, 0], s[:, 1]) < 1e-12  # a U-turn: no bisector, take the outgoing leg
    h[reverse] = np.append(b, b[-1])[reverse]
    return _with_fixed(h, fixed)


def alternating_headings(
    points: NDArray[np.float64], fixed: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Savla-Frazzoli-Bullo alternating algorithm: every other leg (0, 2, ...) flown straight."""
    b = _leg_bearings(points)
    n = len(points)
    idx = np.arange(n)
    leg = np.where((idx % 2 == 0) & (idx <= n - 2), idx, idx - 1)
    return _with_fixed(b[leg], fixed)


def headings_cost(
    cost: LegCost, headings: NDArray[np.float64]
) -> tuple[float, NDArray[np.float64]]:
    """Total cost and per-leg costs of a full heading assignment."""
    legs = np.array(
        [float(cost.pairs(i, headings[i : i + 1], headings[i + 1 : i + 2])[0])
         for i in range(len(headings) - 1)]
    )
    return float(legs.sum()), legs


def _candidates(
    fixed: NDArray[np.float64], k: int, extra: list[NDArray[np.float64]]
) -> list[NDArray[np.float64]]:
    grid = np.arange(k) * (TWO_PI / k)
    sets = []
    for i, h in enumerate(fixed):
        if not math.isnan(h):
            sets.append(np.array([h]))
        else:
            more = np.array([e[i] for e in extra])
            sets.append(np.unique(np.concatenate([grid, mod_2pi(more)])))
    return sets


def _dynamic_programme(
    cost: LegCost, sets: list[NDArray[np.float64]], progress: Progress | None = None
) -> tuple[NDArray[np.float64], float]:
    """Exact minimum over the candidate sets (forward values, backward choice)."""
    value = np.zeros(sets[0].size)
    back = []
    step = getattr(cost, "dp_step", None)
    for i in range(len(sets) - 1):
        done = step(i, value, sets[i], sets[i + 1]) if step is not None else None
        if done is not None:  # compiled: the same minimum without the matrix
            value, arg = done
        else:
            total = value[:, None] + cost.matrix(i, sets[i], sets[i + 1])  # float64 sums
            arg = np.argmin(total, axis=0)
            value = total[arg, np.arange(arg.size)]
        back.append(arg)
        if progress is not None:
            progress("headings", i + 1, len(sets) - 1)
    j = int(np.argmin(value))
    best = float(value[j])
    h = np.empty(len(sets))
    h[-1] = sets[-1][j]
    for i in range(len(sets) - 2, -1, -1):
        j = int(back[i][j])
        h[i] = sets[i][j]
    return h, best


def _golden(
    cost: LegCost, h: NDArray[np.float64], idx: NDArray[np.intp], width: float, iters: int
) -> NDArray[np.float64]:
    """Golden-section search of each h[idx] in [h - width, h + width] (vectorised over idx)."""
    lo = h[idx] - width
    hi = h[idx] + width
    c = hi - _GOLDEN * (hi - lo)
    d = lo + _GOLDEN * (hi - lo)
    fc = _local_costs(cost, h, idx, c)
    fd = _local_costs(cost, h, idx, d)
    for _ in range(iters):
        left = fc < fd  # the minimum is in [lo, d]
        hi = np.where(left, d, hi)
        lo = np.where(left, lo, c)
        new_c = np.where(left, hi - _GOLDEN * (hi - lo), d)
        new_d = np.where(left, c, lo + _GOLDEN * (hi - lo))
        x = np.where(left, new_c, new_d)
        fx = _local_costs(cost, h, idx, x)
        fc, fd = np.where(left, fx, fd), np.where(left, fc, fx)
        c, d = new_c, new_d
    return np.where(fc < fd, c, d)


def _local_costs(
    cost: LegCost, h: NDArray[np.float64], idx: NDArray[np.intp], trial: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Cost of the (at most two) legs touching each waypoint idx[j] with heading trial[j]."""
    n = len(h)
    out = np.zeros(idx.size)
    has_prev = idx > 0
    if has_prev.any():
        i = idx[has_prev]
        out[has_prev] += _pairs_many(cost, i - 1, h[i - 1], trial[has_prev])
    has_next = idx < n - 1
    if has_next.any():
        i = idx[has_next]
        out[has_next] += _pairs_many(cost, i, trial[has_next], h[i + 1])
    return out


def _pairs_many(
    cost: LegCost, legs: NDArray[np.intp], a: NDArray[np.float64], b: NDArray[np.float64]
) -> NDArray[np.float64]:
    """Leg costs for different legs at once (one vectorised call when the cost allows it)."""
    many = getattr(cost, "pairs_many", None)
    if many is not None:
        return np.asarray(many(legs, a, b))
    return np.array([float(cost.pairs(int(i), a[k : k + 1], b[k : k + 1])[0])
                     for k, i in enumerate(legs)])


def optimise_headings(
    cost: LegCost,
    points: NDArray[np.float64],
    fixed: NDArray[np.float64],
    k: int = 72,
    *,
    refine: bool = True,
    include_heuristics: bool = True,
    sweeps: int = 3,
    progress: Progress | None = None,
) -> HeadingPlan:
    """Headings minimising the total leg cost: DP over K candidates, then local refinement.

    `progress("headings", done, total)` is called after each leg of the DP, `progress("refine",
    0 | 1, 1)` before and after the refinement (for a progress bar).
    """
    t0 = time.perf_counter()
    extra = []
    if include_heuristics:
        extra = [f(points, fixed) for f in (point_at_next_headings, bisector_headings,
                                            alternating_headings)]
    sets = _candidates(fixed, k, extra)
    h, dp_total = _dynamic_programme(cost, sets, progress)
    t1 = time.perf_counter()
    free = np.nonzero(np.isnan(fixed))[0]
    n_sweeps = 0
    total, legs = _chain_cost(cost, h)
    if refine and free.size:
        if progress is not None:
            progress("refine", 0, 1)
        cheap = isinstance(cost, StillAirCost)  # the wind times cost far more per call
        h, total, legs, n_sweeps = _refine(
            cost, h, free, TWO_PI / k, sweeps if cheap else 1,
            max_iter=200 if cheap else 15, golden_iters=30 if cheap else 12)
        if progress is not None:
            progress("refine", 1, 1)
    t2 = time.perf_counter()
    stats = {
        "headings_per_waypoint": k,
        "dp_cost": dp_total,
        "refined_cost": total,
        "refine_sweeps": n_sweeps,
        "dp_seconds": t1 - t0,
        "refine_seconds": t2 - t1,
    }
    return HeadingPlan(np.asarray(mod_2pi(h)), legs, total, stats)


def _refine(
    cost: LegCost, h: NDArray[np.float64], free: NDArray[np.intp], width: float, sweeps: int,
    max_iter: int = 200, golden_iters: int = 30,
) -> tuple[NDArray[np.float64], float, NDArray[np.float64], int]:
    """Local continuous refinement of the free headings within `width` of the DP choice.

    L-BFGS-B (SciPy) on the free headings with central-difference gradients (each heading
    touches two legs, so the whole gradient is two vectorised leg evaluations per side),
    then red-black golden-section sweeps; every step is kept only if the total decreases.
    """
    from scipy.optimize import minimize

    n = len(h)
    legs = np.arange(n - 1)
    total, leg_c = _chain_cost(cost, h)
    eps = 1e-7

    def fun(z: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
        hh = h.copy()
        hh[free] = z
        a, b = hh[:-1], hh[1:]
        m = a.size
        # one vectorised call: the legs, then central differences in each end's heading
        c = _pairs_many(cost, np.tile(legs, 5), np.concatenate([a, a + eps, a - eps, a, a]),
                        np.concatenate([b, b, b, b + eps, b - eps])).reshape(5, m)
        grad = np.zeros(n)
        grad[:-1] += (c[1] - c[2]) / (2 * eps)
        grad[1:] += (c[3] - c[4]) / (2 * eps)
        return float(c[0].sum()), grad[free]

    z0 = h[free].copy()
    res = minimize(fun, z0, jac=True, method="L-BFGS-B",
                   bounds=list(zip(z0 - width, z0 + width, strict=True)),
                   options={"maxiter": max_iter, "ftol": 1e-13, "gtol": 1e-10})
    trial = h.copy()
    trial[free] = res.x
    t_total, t_legs = _chain_cost(cost, trial)
    if t_total < total:
        h, total, leg_c = trial, t_total, t_legs
    done = 0
    for done in range(1, sweeps + 1):  # noqa: B007
        before = total
        for parity in (0, 1):
            idx = free[free % 2 == parity]
            if idx.size == 0:
                continue
            new = _golden(cost, h, idx, width / 4, iters=golden_iters)
            better = _local_costs(cost, h, idx, new) < _local_costs(cost, h, idx, h[idx])
            h[idx[better]] = new[better]
        total, leg_c = _chain_cost(cost, h)
        if before - total <= 1e-9 * max(1.0, abs(total)):
            break
    return h, total, leg_c, done


def _chain_cost(cost: LegCost, h: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
    legs = np.arange(len(h) - 1)
    c = _pairs_many(cost, legs, h[:-1], h[1:])
    return float(c.sum()), c
