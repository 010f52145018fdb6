"""Table 4.3 re-solved: the example x1 = (0, 2, 2pi/3) with R = 1, r = 0.3 (section 4.9).

Two computations the reproduction needs beyond `plan()`:

- `dissertation_minimum(name)`: one row of Table 4.3 solved the dissertation's way, the
  constrained optimisation (4.27) in the dissertation's own parameterisation of the sequence
  (multi-start SLSQP), for the rows that are not extremals of the control problem;
- `descent_from(minimum)`: the direct method (`solve_time_optimal_direct`) started from that
  minimum, which shows whether it is a local optimum of the control problem.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.pose import Pose

__all__ = [
    "EXAMPLE_GOAL",
    "WEAK_TYPES",
    "WeakMinimum",
    "descent_from",
    "dissertation_minimum",
    "example_car",
    "path_of",
]

EXAMPLE_GOAL = Pose(0.0, 2.0, 2.0 * math.pi / 3.0)
PI = math.pi

Move = tuple[str, int, float]
Constraint = Callable[[np.ndarray], float]

# The dissertation's own parameterisation (4.27) of the rows that are not extremals:
# name -> (moves(p), bounds, inequality constraints g(p) >= 0, parameter names)
_WEAK: dict[str, tuple[Callable[[np.ndarray], list[Move]], list[tuple[float, float]],
                       list[Constraint], tuple[str, ...]]] = {
    "CBSB LSL": (
        lambda p: [("C", 1, p[0]), ("B", 1, p[1]), ("S", 0, p[2]), ("B", 1, p[3])],
        [(0, PI), (0, PI), (0, 10), (0, PI)],
        [lambda p: p[1] - p[3]],
        ("beta1", "gamma1", "L", "alpha2"),
    ),
    "CBSBC LSL": (
        lambda p: [("C", 1, p[0]), ("B", 1, p[1]), ("S", 0, p[2]), ("B", 1, p[1]),
                   ("C", 1, p[3])],
        [(0, PI), (0, PI), (0, 10), (0, PI)],
        [],
        ("beta1", "gamma1=alpha2", "L", "beta2"),
    ),
    "BCBB LR": (
        lambda p: [("B", 1, p[0]), ("C", 1, p[1]), ("B", 1, p[2]), ("B", -1, p[3])],
        [(0, PI), (0, 2 * PI), (0, PI), (0, PI)],
        [lambda p: p[2] - p[0], lambda p: p[2] - p[3], lambda p: 2 * PI - 2 * p[2] - p[1]],
        ("alpha1", "beta1", "gamma1", "alpha2"),
    ),
    "BTB RLR": (
        lambda p: [("B", -1, p[0]), ("B", 1, p[1]), ("C", 1, p[2]), ("B", 1, p[1]),
                   ("B", -1, p[3])],
        [(0, PI), (0, PI), (0, 2 * PI), (0, PI)],
        [lambda p: p[1] - p[0], lambda p: p[1] - p[3], lambda p: 2 * PI - 2 * p[1] - p[2]],
        ("gamma1", "alpha2=gamma2", "beta2", "alpha3"),
    ),
    "CBSBCB RSR": (
        lambda p: [("C", -1, p[0]), ("B", -1, p[1]), ("S", 0, p[2]), ("B", -1, p[1]),
                   ("C", -1, PI), ("B", -1, p[3])],
        [(0, PI), (0, PI), (0, 10), (0, PI)],
        [lambda p: p[1] - p[3]],
        ("beta1", "gamma1=alpha2", "L", "gamma2"),
    ),
}  # fmt: skip
WEAK_TYPES = tuple(_WEAK)


@dataclass(frozen=True)
class WeakMinimum:
    """The lowest converged minimum of (4.27) for one type: time, parameters, the bounds
    active there (e.g. "gamma1 = pi") and the moves (family letter, direction, angle or
    length)."""

    name: str
    cost: float
    parameters: tuple[float, ...]
    active: tuple[str, ...]
    moves: tuple[Move, ...]


def example_car() -> Any:
    """The normalised model of section 4.9: v_min = 0.3, v_max = 1, u_max = 1."""
    from glideplan.vehicles.variable_speed_car import VariableSpeedCar

    return VariableSpeedCar(0.3, 1.0, 1.0)


def path_of(moves: tuple[Move, ...] | list[Move]) -> Any:
    """The `Path` of a move list (B arcs radius 1 at speed 1, C arcs radius 0.3 at 0.3)."""
    from glideplan.path import Path
    from glideplan.segments import Arc, Straight

    segs: list[Any] = []
    pose = Pose()
    for lab, d, x in moves:
        if x <= 1e-12:
            continue
        seg = (
            Straight(pose, x, 1.0)
            if lab == "S"
            else Arc(pose, x, 1.0 if lab == "B" else 0.3, d, 1.0 if lab == "B" else 0.3, lab)
        )
        segs.append(seg)
        pose = seg.end
    return Path(tuple(segs), example_car())


def _bound_text(value: float) -> str:
    for k, text in ((0.0, "0"), (0.5, "pi/2"), (1.0, "pi"), (2.0, "2 pi")):
        if abs(value - k * PI) < 1e-9:
            return text
    return f"{value:.4g}"


def dissertation_minimum(name: str, starts: int = 20, seed: int = 0) -> WeakMinimum | None:
    """Re-solve one row of Table 4.3 the dissertation's way: (4.27) in its parameterisation.

    Multi-start SLSQP from uniform samples of the parameter box (deterministic seed); the
    lowest converged cost (boundary conditions met to 1e-8), or None if no start converged.
    """
    from scipy.optimize import minimize

    from glideplan.planners.min_time.geometry import compose

    build, bounds, ineq, names = _WEAK[name]
    goal = EXAMPLE_GOAL

    def resid(p: np.ndarray) -> np.ndarray:
        pos, h = compose(build(p), 0.3, ())
        return np.array([pos[0] - goal.x, pos[1] - goal.y, (h - goal.heading + PI) % (2 * PI) - PI])

    cons = [{"type": "eq", "fun": resid}] + [{"type": "ineq", "fun": g} for g in ineq]
    rng = np.random.default_rng(seed)
    best: WeakMinimum | None = None
    for _ in range(starts):
        p0 = np.array([rng.uniform(lo, hi) for lo, hi in bounds])
        res = minimize(
            lambda p: sum(m[2] for m in build(p)),
            p0,
            method="SLSQP",
            bounds=bounds,
            constraints=cons,
            options={"maxiter": 300, "ftol": 1e-12},
        )
        if not res.success or np.max(np.abs(resid(res.x))) > 1e-8:
            continue
        if any(g(res.x) < -1e-8 for g in ineq):
            continue
        if best is None or res.fun < best.cost - 1e-9:
            active = tuple(
                f"{n} = {_bound_text(lo if abs(v - lo) < 1e-6 else hi)}"
                for n, v, (lo, hi) in zip(names, res.x, bounds, strict=True)
                if abs(v - lo) < 1e-6 or abs(v - hi) < 1e-6
            )
            moves = tuple((lab, d, float(x)) for lab, d, x in build(res.x))
            best = WeakMinimum(name, float(res.fun), tuple(map(float, res.x)), active, moves)
    return best


def descent_from(minimum: WeakMinimum) -> float | None:
    """Minimum time the direct method reaches when started from `minimum`'s path (None if
    it fails): below `minimum.cost`, the minimum is not a local optimum of the problem."""
    from glideplan.planners.min_time import solve_time_optimal_direct

    res = solve_time_optimal_direct(example_car(), EXAMPLE_GOAL, guesses=[path_of(minimum.moves)])
    return float(res.cost) if res.ok else None
