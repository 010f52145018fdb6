"""Dubins shortest paths: the six words in closed form, batched over pose arrays.

Implements dissertation section 2.7 (eqs. 2.10-2.11: the candidate set LSL, LSR, RSL, RSR,
RLR, LRL) and the feasible turn radius R0' = R0 (1 + eps)^2 of section 3.2 (eq. 3.3,
appendix A). The closed forms are those of REFERENCE_NOTES section 4.2 (Shkel & Lumelsky
2001), rewritten in the start frame with the turning-circle centres: for a unit radius the
start circles are centred at (0, +-1), the goal circles at (x -+ sin psi, y +- cos psi), and
every word follows from the vector V between the two circle centres it uses; the formulas
are written once, in `glideplan.planners.dubins_kernel`, and this module wraps them.

All functions broadcast over `(..., 3)` pose arrays (x, y, heading in rad) without a Python
loop per query.
"""

from __future__ import annotations

import importlib.util
import math
import sys
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.dubins_kernel import (
    DIRECTIONS,
    WORDS,
    compiled_min_lengths,
    flat_word_totals,
    mod_2pi_snapped,
    segment_table,
    shortest_word,
)
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import TWO_PI as TWO_PI  # re-exported: callers use dubins.TWO_PI
from glideplan.pose import Pose
from glideplan.segments import Arc, Segment, Straight
from glideplan.solution import Candidate, Status
from glideplan.validation import check_finite_array, check_in_range, check_positive
from glideplan.vehicles.dubins_car import DubinsCar

__all__ = [
    "WORDS",
    "DubinsBatch",
    "dubins_distance",
    "dubins_path",
    "dubins_segment_lengths",
    "dubins_shortest",
    "dubins_word_lengths",
    "feasible_radius",
    "word_directions",
]

_DIRECTIONS = DIRECTIONS
COMPILED = True  # False: `dubins_distance` always on the NumPy kernel (the tests' reference)
_COMPILED_FROM = 50_000  # queries from which the compiled kernel pays for importing numba


def word_directions(word: str) -> tuple[int, int, int]:
    """Turn directions (+1 left, -1 right, 0 straight) of the three segments of a word."""
    try:
        return _DIRECTIONS[word.upper()]
    except (KeyError, AttributeError):
        raise InvalidParameterError("word", word, f"must be one of {', '.join(WORDS)}") from None


def feasible_radius(radius: ArrayLike, eps: ArrayLike) -> np.ndarray | float:
    """Feasible turn radius R0' = R0 (1 + eps)^2 (eq. 3.3) for a disturbance ratio eps in [0, 1).

    `radius` is the vehicle's minimum turn radius R0 (m) and `eps = delta_max / v` the ratio of
    the disturbance bound to the flow-relative speed (eq. 3.1). A Dubins path planned with R0'
    can be tracked under any disturbance of magnitude <= delta_max (appendix A).
    """
    r = np.asarray(radius, dtype=float)
    e = np.asarray(eps, dtype=float)
    if not np.all(np.isfinite(r)) or np.any(r <= 0.0):
        raise InvalidParameterError("radius", radius, "must be finite and > 0")
    if not np.all(np.isfinite(e)) or np.any(e < 0.0) or np.any(e >= 1.0):
        raise InvalidParameterError(
            "disturbance_ratio", eps, "must lie in [0, 1) (disturbance bound below the speed)"
        )
    out = r * (1.0 + e) ** 2
    return float(out) if out.ndim == 0 else out


# ----- query handling (the word formulas are in `dubins_kernel`) --------------------------


def _normalise(start: ArrayLike, goal: ArrayLike, radius: ArrayLike) -> tuple[np.ndarray, ...]:
    """Validated goals in the start frame scaled by 1/radius: x, y, psi, radius (shape `(...)`)."""
    s, g, r, shape = _flat_queries(start, goal, radius)
    dx = g[:, 0] - s[:, 0]
    dy = g[:, 1] - s[:, 1]
    c, sn = np.cos(s[:, 2]), np.sin(s[:, 2])
    inv = 1.0 / r
    x = (c * dx + sn * dy) * inv
    y = (c * dy - sn * dx) * inv
    psi = mod_2pi_snapped(g[:, 2] - s[:, 2])
    r = np.broadcast_to(r, x.shape)
    return tuple(a.reshape(shape) for a in (x, y, psi, r))


def _flat_queries(
    start: ArrayLike, goal: ArrayLike, radius: ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, ...]]:
    """Validated, broadcast `(m, 3)` start and goal arrays, radius (scalar or `(m,)`), shape."""
    s = check_finite_array("start", start, last_dim=3)
    g = check_finite_array("goal", goal, last_dim=3)
    r = np.asarray(radius, dtype=float)
    if not np.all(np.isfinite(r)) or np.any(r <= 0.0):
        raise InvalidParameterError(
            "radius", radius if r.ndim == 0 else "array", "must be finite and > 0"
        )
    shape = np.broadcast_shapes(s.shape[:-1], g.shape[:-1], r.shape)
    s = np.broadcast_to(s, (*shape, 3)).reshape(-1, 3)
    g = np.broadcast_to(g, (*shape, 3)).reshape(-1, 3)
    if r.ndim:
        r = np.broadcast_to(r, shape).reshape(-1)
    return s, g, r, shape


# ----- public batch functions -----------------------------------------------------------------


def dubins_segment_lengths(start: ArrayLike, goal: ArrayLike, radius: ArrayLike) -> np.ndarray:
    """Segment lengths of all six Dubins words (eq. 2.11): `(..., 6, 3)`, NaN when infeasible.

    `start`, `goal`: `(..., 3)` poses (x, y in m; heading in rad), broadcast together;
    `radius`: minimum turn radius (m), scalar or broadcastable to `(...)`. Row k is word
    `WORDS[k]`; the three lengths (m) are those of its first turn, middle segment and last turn.
    """
    x, y, psi, r = _normalise(start, goal, radius)
    return segment_table(x, y, psi) * r[..., None, None]


def dubins_word_lengths(start: ArrayLike, goal: ArrayLike, radius: ArrayLike) -> np.ndarray:
    """Total lengths (m) of the six Dubins words (eq. 2.11): `(..., 6)`, NaN when infeasible."""
    s, g, r, shape = _flat_queries(start, goal, radius)
    tot = flat_word_totals(s, g, r)
    tot[np.isinf(tot)] = np.nan
    np.maximum(tot, 0.0, out=tot, where=~np.isnan(tot))
    tot *= r
    return tot.T.reshape(*shape, 6)


def dubins_distance(
    start: ArrayLike, goal: ArrayLike, radius: ArrayLike = 1.0, *, return_index: bool = False
) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Optimal Dubins path length (m) for `(..., 3)` start/goal poses (section 2.7): `(...)`.

    The fast path of `dubins_shortest`: only the six word lengths are formed and the minimum
    taken. With `return_index`, also the index of the optimal word in `WORDS` (ties go to the
    first word). Evaluated by the compiled kernel (`dubins_kernel.compiled_min_lengths`, the
    heading DP's and the benchmark's; within ~1e-15 relative of the NumPy kernel, degenerate
    queries by the scalar kernel) once numba is loaded or for batches of at least
    `_COMPILED_FROM` queries (where numba's import pays for itself), else by the NumPy
    kernel, so a small query never imports numba (CLI start-up).
    """
    s, g, r, shape = _flat_queries(start, goal, radius)
    if _use_compiled(s.shape[0]):
        length, idx = compiled_min_lengths(s, g, r, index=return_index)
        np.maximum(length, 0.0, out=length)
        length *= r
        if return_index:
            return length.reshape(shape), idx.reshape(shape)
        return length.reshape(shape)
    tot = flat_word_totals(s, g, r)
    length = tot[0].copy()
    if return_index:
        idx = np.zeros(length.shape, dtype=np.intp)
        for k in range(1, 6):
            np.putmask(idx, tot[k] < length, k)
            np.minimum(length, tot[k], out=length)
    else:
        np.min(tot, axis=0, out=length)
    np.maximum(length, 0.0, out=length)
    length *= r
    if return_index:
        return length.reshape(shape), idx.reshape(shape)
    return length.reshape(shape)


def _use_compiled(m: int) -> bool:
    """Whether `dubins_distance` takes the compiled kernel for m queries (see there)."""
    if not COMPILED or m == 0:
        return False
    if "numba" in sys.modules:
        return True
    return m >= _COMPILED_FROM and importlib.util.find_spec("numba") is not None


@dataclass(frozen=True, eq=False)
class DubinsBatch:
    """Optimal Dubins paths for a batch of queries: length (m), word index and segment lengths."""

    length: np.ndarray
    word_index: np.ndarray
    segment_lengths: np.ndarray

    @property
    def words(self) -> np.ndarray:
        """The optimal words as a string array of the batch shape."""
        return np.asarray(WORDS)[self.word_index]


def dubins_shortest(start: ArrayLike, goal: ArrayLike, radius: ArrayLike = 1.0) -> DubinsBatch:
    """Optimal Dubins path for each `(..., 3)` start/goal pair (section 2.7, eq. 2.11).

    Returns `DubinsBatch(length (...), word_index (...), segment_lengths (..., 3))` with
    lengths in the units of the positions; ties go to the first word in `WORDS`.
    """
    length, idx, seg = shortest_word(dubins_segment_lengths(start, goal, radius))
    return DubinsBatch(length=length, word_index=idx, segment_lengths=seg)


def dubins_path(
    start: Pose | ArrayLike,
    goal: Pose | ArrayLike,
    radius: float,
    speed: float = 1.0,
    word: str | None = None,
    label_turn: str = "B",
) -> Path | None:
    """The Dubins path of `word` (the shortest when None) from `start` to `goal` (section 2.7).

    Arcs of `radius` (m) and straights flown at `speed` (m/s); arcs carry label `label_turn`.
    Returns None when `word` is infeasible for these poses. Zero-length pieces are kept so the
    path always has three segments (its `word` property drops them).
    """
    radius = check_positive("radius", radius)
    speed = check_positive("speed", speed)
    start = start if isinstance(start, Pose) else _pose("start", start)
    goal = goal if isinstance(goal, Pose) else _pose("goal", goal)
    table = dubins_segment_lengths(start.as_array(), goal.as_array(), radius)
    if word is None:
        totals = np.where(np.isnan(table[:, 0]), np.inf, table.sum(axis=-1))
        k = int(np.argmin(totals))
    else:
        word_directions(word)
        k = WORDS.index(word.upper())
    if np.isnan(table[k, 0]):
        return None
    return _build_path(start, WORDS[k], table[k], radius, speed, label_turn)


def _pose(name: str, value: Any) -> Pose:
    try:
        return Pose.from_array(value)
    except (InvalidParameterError, TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a Pose or (x, y, heading)") from None


def _build_path(
    start: Pose, word: str, lengths: np.ndarray, radius: float, speed: float, label_turn: str
) -> Path:
    segments: list[Segment] = []
    pose = start
    for direction, length in zip(_DIRECTIONS[word], lengths, strict=True):
        seg: Segment
        if direction == 0:
            seg = Straight(pose, float(length), speed)
        else:
            seg = Arc(pose, float(length) / radius, radius, direction, speed, label_turn)
        segments.append(seg)
        pose = seg.end
    return Path(tuple(segments))


# ----- registered planners -------------------------------------------------------------------


def _candidates(
    problem: Problem, disturbance_ratio: float, objective: str
) -> tuple[PlannerOutput, float]:
    vehicle = problem.vehicle
    assert isinstance(vehicle, DubinsCar)
    eps = check_in_range("disturbance_ratio", disturbance_ratio, 0.0, 1.0, high_open=True)
    radius = float(feasible_radius(vehicle.turn_radius, eps))
    table = dubins_segment_lengths(problem.start.as_array(), problem.goal.as_array(), radius)
    cands = []
    for k, word in enumerate(WORDS):
        info: dict[str, Any] = {"radius": radius}
        if np.isnan(table[k, 0]):
            cands.append(Candidate(word, "", math.inf, None, Status.INFEASIBLE, info))
            continue
        path = _build_path(problem.start, word, table[k], radius, vehicle.speed, "B")
        info["segment_lengths"] = [float(v) for v in table[k]]
        cost = path.length if objective == "length" else path.length / vehicle.speed
        cands.append(Candidate(word, path.family, cost, path, Status.FEASIBLE, info))
    extras = {
        "radius": radius,
        "nominal_radius": vehicle.turn_radius,
        "disturbance_ratio": eps,
    }
    return PlannerOutput(candidates=tuple(cands), extras=extras), radius


@register_planner(
    "dubins",
    vehicle=DubinsCar,
    objective="length",
    description="Dubins shortest paths, feasible turn radius R0 (1 + eps)^2 (2.7, 3.2)",
)
def plan_dubins(problem: Problem, *, disturbance_ratio: float = 0.0) -> PlannerOutput:
    """Shortest Dubins path (eq. 2.11) with the feasible radius R0' = R0 (1 + eps)^2 (eq. 3.3).

    Every word is a candidate; cost is the length (m). `disturbance_ratio` is eps = delta_max / v
    in [0, 1) (eq. 3.1); 0 plans with the vehicle's own minimum turn radius.
    """
    return _candidates(problem, disturbance_ratio, "length")[0]


@register_planner(
    "dubins",
    vehicle=DubinsCar,
    objective="time",
    description="Dubins minimum-time paths at constant speed (2.7, 3.2)",
)
def plan_dubins_time(problem: Problem, *, disturbance_ratio: float = 0.0) -> PlannerOutput:
    """Minimum-time Dubins path: the shortest path flown at constant speed (cost = length / v, s).

    Same candidates as `plan_dubins` (eqs. 2.11, 3.3).
    """
    return _candidates(problem, disturbance_ratio, "time")[0]
