"""Minimum-time synthesis (section 4.8): solve every candidate type, build paths, pick the best.

`synthesize` walks `CANDIDATE_TYPES` in normalised units and returns every extremal found;
`plan_time_optimal` is the planner registered for `VariableSpeedCar` with objective "time".

With `COMPILED` (the default) the Gamma_TST and rigid types and the Gamma_umax reach are
solved by the numba kernels of `compiled`; `COMPILED = False` runs the NumPy reference
(`solvers`, `fixed_turn_rate`, `dubins_segment_lengths`): the same extremals, costs equal
to rounding (tests/min_time/test_min_time_compiled.py). The first synthesis of a process
runs the reference unless numba is already imported: a one-off plan (the CLI) does not pay
numba's import and cache load (~0.4 s of CPU), every later one runs the kernels.
Candidates carry `LazyPath`s: a path is built when it is first used (the winner, by the
verification of `plan()`; the others only if asked for).
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from glideplan.path import Path
from glideplan.planners.dubins import WORDS as DUBINS_WORDS
from glideplan.planners.dubins import dubins_segment_lengths
from glideplan.planners.dubins_kernel import mod_2pi_snapped, segment_table, word_segments
from glideplan.planners.min_time.fixed_turn_rate import cheapest_fixed_turn_rate
from glideplan.planners.min_time.solvers import Extremal, solve_all
from glideplan.planners.min_time.table import (
    CANDIDATE_TYPES,
    GROUPS,
    SUPPLEMENTARY_MAX_INTERIOR,
    SUPPLEMENTARY_TYPES,
    CandidateType,
)
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import Pose
from glideplan.segments import Arc, Segment, Straight
from glideplan.solution import Candidate, Status
from glideplan.vehicles.variable_speed_car import VariableSpeedCar

__all__ = [
    "COMPILED",
    "LazyPath",
    "SynthesisResult",
    "extremal_path",
    "normalised_goal",
    "plan_time_optimal",
    "synthesize",
]

PI = math.pi
_ZERO = 1e-12
COMPILED = True  # False: the NumPy reference (the benchmarks' baseline, the tests' reference)

Solver = Callable[[np.ndarray, float, str], list[Extremal]]


def _reference_solve(goal: np.ndarray, rho: float, key: str) -> list[Extremal]:
    return solve_all(goal, rho, (key,))[key]


_calls = 0


def _compiled_now() -> bool:
    """Whether this synthesis runs the kernels: `COMPILED`, from the second call of the
    process on (or as soon as numba is imported)."""
    global _calls
    _calls += 1
    return COMPILED and (_calls > 1 or "numba" in sys.modules)


def _solvers(
    compiled: bool,
) -> tuple[Solver, Callable[[np.ndarray, float], tuple[float, float]] | None]:
    """The rigid/TST solver and the Gamma_umax reach of the compiled path or the reference."""
    if compiled:
        from glideplan.planners.min_time import compiled as kernels

        return kernels.solve, kernels.reach_distance
    return _reference_solve, None


@dataclass(frozen=True)
class SynthesisResult:
    """All extremals found for one goal (normalised units) and the seconds spent per group."""

    extremals: tuple[Extremal, ...]
    seconds: dict[str, float] = field(default_factory=dict)

    @property
    def best(self) -> Extremal | None:
        return min(self.extremals, key=lambda e: e.cost, default=None)


def normalised_goal(goal: Pose, vehicle: VariableSpeedCar) -> np.ndarray:
    """The goal (from the origin) in units of R = v_max/u_max: array (x, y, heading)."""
    scale = vehicle.bang_radius
    return np.array([goal.x / scale, goal.y / scale, goal.heading])


def _dubins_extremals(
    types: list[CandidateType],
    goal: np.ndarray,
    rho: float,
    tables: dict[float, list[list[float]]] | None = None,
    compiled: bool = False,
) -> list[Extremal]:
    """Gamma_Dubins: BSB and BBB at radius 1 (speed 1), CCC at radius rho (speed rho).

    Lengths from `glideplan.planners.dubins` (or the given `_dubins_tables`); the time of a
    CCC path at speed rho on radius rho equals its total heading change, so every cost below
    is a time (eq. 4.6).
    """
    out: list[Extremal] = []
    if tables is None:
        radii = sorted({rho if t.word == "CCC" else 1.0 for t in types})
        tables = _dubins_tables(goal, radii, compiled)
    for ctype in types:
        radius, label = (rho, "C") if ctype.word == "CCC" else (1.0, "B")
        row = tables[radius][DUBINS_WORDS.index(ctype.orientation)]
        if math.isnan(row[0]):
            continue
        moves = []
        for letter, length in zip(ctype.orientation, row, strict=True):
            if letter == "S":
                moves.append(("S", 0, length))
            else:
                moves.append((label, 1 if letter == "L" else -1, length / radius))
        cost = sum(x for _, _, x in moves)
        out.append(Extremal(ctype, tuple(moves), cost, {"lengths": list(row)}))
    return out


def _dubins_tables(
    goal: np.ndarray, radii: list[float], compiled: bool
) -> dict[float, list[list[float]]]:
    """Segment lengths (6, 3) of the six Dubins words from the origin to `goal` per radius.

    The reference calls `dubins_segment_lengths` per radius; the compiled path evaluates the
    same word formulas on floats (`word_segments`), with the same normalisation (x * (1/r)).
    """
    if not compiled:
        origin = np.zeros(3)
        return {r: dubins_segment_lengths(origin, goal, r).tolist() for r in radii}
    out: dict[float, list[list[float]]] = {}
    for r in radii:  # scalar word formulas (`dubins_kernel.word_segments`): no array set-up
        inv = 1.0 / r
        rows = []
        for k in range(len(DUBINS_WORDS)):
            seg = word_segments(k, goal[0] * inv, goal[1] * inv, goal[2] - 0.0)
            rows.append([math.nan] * 3 if seg is None else [v * r for v in seg])
        out[r] = rows
    return out


def dubins_tables_many(goals: np.ndarray, radii: list[float]) -> list[dict[float, Any]]:
    """`_dubins_tables` (compiled path) of many goals (n, 3) in one `segment_table` call."""
    r = np.array(radii)
    inv = 1.0 / r
    psi = mod_2pi_snapped(np.broadcast_to((goals[:, 2] - 0.0)[:, None], (len(goals), len(r))))
    table = segment_table(goals[:, :1] * inv, goals[:, 1:2] * inv, psi) * r[:, None, None]
    rows = table.tolist()
    return [{radius: row[i] for i, radius in enumerate(radii)} for row in rows]


def _umax_extremals(
    types: list[CandidateType], goal: np.ndarray, rho: float, compiled: bool = False
) -> list[Extremal]:
    """Gamma_umax: the cheapest fixed-turn-rate path of each orientation (singular speed)."""
    out: list[Extremal] = []
    reach = _solvers(compiled)[1]
    for d in (1, -1):
        of_d = [t for t in types if t.directions[0] == d]
        if not of_d:
            continue
        found = cheapest_fixed_turn_rate(goal, rho, d, reach=reach)
        if found is None:
            continue
        moves, cost, loops = found
        pattern = "".join(m[0] for m in moves)
        n_c = pattern.count("C")
        if n_c == 2:  # the Gamma_umax word it realises: two C arcs in two simple turns
            word = {"CBCB": "CBBCB", "BCBC": "BCBBC", "CBC": "CBBC"}.get(pattern, "BCBBCB")
        else:  # fewer or more C arcs: a face of (or loops beyond) the most general word
            word = "BCBBCB"
        ctype = next((t for t in of_d if t.word == word), of_d[0])
        out.append(Extremal(ctype, tuple(moves), cost, {"pattern": pattern, "loops": loops}))
    return out


MAX_INTERIOR_TURNS = 12


def synthesize(
    goal: np.ndarray,
    rho: float,
    *,
    types: Iterable[CandidateType] = CANDIDATE_TYPES,
    supplementary: bool = True,
) -> SynthesisResult:
    """Every extremal of every candidate type for a normalised goal (x, y, heading).

    Units: R = 1, u_max = 1, rho = v_min/v_max; costs are times in units of 1/u_max. With
    rho = 1 (equal speeds) only the Dubins candidates BSB and BBB are solved.

    With `supplementary` (the default) the rigid sequences that (4.24) and B.4 leave out are
    solved as well (`SUPPLEMENTARY_TYPES`, group key "supplementary"): B.4's sub-optimality
    argument fails for some goals, whose optimum is then C B T B C. Rigid sequences with
    m > 3 interior turns cost more than m pi, so they are added while m pi is below the best
    cost found (up to `MAX_INTERIOR_TURNS`).
    """
    goal = np.asarray(goal, dtype=float)
    by_group: dict[str, list[CandidateType]] = {g: [] for g in GROUPS}
    for t in types:
        by_group[t.group].append(t)
    if rho >= 1.0:
        by_group = {"Dubins": [t for t in by_group["Dubins"] if t.word != "CCC"]}
    found: list[Extremal] = []
    seconds: dict[str, float] = {}
    compiled = _compiled_now()
    solve = _solvers(compiled)[0]
    for group, members in by_group.items():
        if not members:
            continue
        t0 = time.perf_counter()
        if group in ("TST", "TTTT"):
            wanted = {id(t) for t in members}
            found.extend(e for e in solve(goal, rho, group) if id(e.ctype) in wanted)
        elif group == "umax":
            found.extend(_umax_extremals(members, goal, rho, compiled))
        else:
            found.extend(_dubins_extremals(members, goal, rho, compiled=compiled))
        seconds[group] = time.perf_counter() - t0
    if supplementary and rho < 1.0:
        t0 = time.perf_counter()
        found.extend(solve(goal, rho, "supplementary"))
        best = min((e.cost for e in found), default=math.inf)
        m = SUPPLEMENTARY_MAX_INTERIOR + 1
        while m <= MAX_INTERIOR_TURNS and m * PI < best:
            key = f"interior{m}"
            found.extend(solve(goal, rho, key))
            best = min((e.cost for e in found), default=math.inf)
            m += 1
        seconds["supplementary"] = time.perf_counter() - t0
    return SynthesisResult(tuple(_deduplicate(found)), seconds)


def _signature(ext: Extremal) -> tuple:
    merged: list[list] = []
    for lab, d, x in ext.moves:
        if x <= _ZERO:
            continue
        if merged and merged[-1][0] == lab and merged[-1][1] == d:
            merged[-1][2] += x
        else:
            merged.append([lab, d, x])
    return tuple((lab, d, round(x, 7)) for lab, d, x in merged)


def _deduplicate(found: list[Extremal]) -> list[Extremal]:
    """Drop repeated paths (types sharing a face), keeping the first in table order."""
    seen: dict[tuple, Extremal] = {}
    out: list[Extremal] = []
    for ext in found:
        key = _signature(ext)
        if key in seen:
            first = seen[key]
            first.params.setdefault("also", []).append(ext.ctype.name)
            continue
        seen[key] = ext
        out.append(ext)
    return out


def extremal_path(ext: Extremal, vehicle: VariableSpeedCar, start: Pose = Pose()) -> Path:
    """The physical path of a normalised extremal: B arcs (R, v_max), C arcs (r, v_min), S."""
    big, small = vehicle.bang_radius, vehicle.corner_radius
    segments: list[Segment] = []
    pose = start
    for lab, d, x in _flown(ext):
        seg: Segment
        if lab == "S":
            seg = Straight(pose, x * big, vehicle.v_max)
        elif lab == "B":
            seg = Arc(pose, x, big, d, vehicle.v_max, "B")
        else:
            seg = Arc(pose, x, small, d, vehicle.v_min, "C")
        segments.append(seg)
        pose = seg.end
    return Path(tuple(segments), vehicle)


def _flown(ext: Extremal) -> list[tuple[str, int, float]]:
    """The moves that become segments: those longer than zero (else the first one)."""
    return [m for m in ext.moves if m[2] > _ZERO] or [ext.moves[0]]


def _word_family(ext: Extremal, vehicle: VariableSpeedCar) -> tuple[str, str]:
    """`extremal_path(ext, vehicle)`'s word and family, without building the path.

    The word is `Path.word`'s: runs of equal turn letters weighted by segment length
    (R x for S and B, r x for C), runs of zero length dropped, equal neighbours merged.
    """
    big, small = vehicle.bang_radius, vehicle.corner_radius
    moves = _flown(ext)
    runs: list[list[Any]] = []
    for lab, d, x in moves:
        letter = "S" if lab == "S" else ("L" if d > 0 else "R")
        weight = x * big if lab == "S" else (big if lab == "B" else small) * x
        if runs and runs[-1][0] == letter:
            runs[-1][1] += weight
        else:
            runs.append([letter, weight])
    word: list[str] = []
    for letter, weight in runs:
        if weight > 0.0 and (not word or word[-1] != letter):
            word.append(letter)
    return "".join(word), "".join(m[0] for m in moves)


class LazyPath(Path):
    """A `Path` whose segments are built on first use by `build()` (a function returning the
    full path); pickles and copies as a plain `Path`.

    The synthesis returns ~15 candidates a goal; `plan()` verifies (so builds) the best one,
    the others are built only when a caller reads them (figures, the explorer's lines).
    """

    def __init__(self, build: Callable[[], Path], vehicle: Any) -> None:
        object.__setattr__(self, "vehicle", vehicle)
        object.__setattr__(self, "_build", build)

    def __getattr__(self, name: str) -> Any:
        if name != "segments" or "_build" not in self.__dict__:
            raise AttributeError(name)
        segments = self.__dict__["_build"]().segments
        object.__setattr__(self, "segments", segments)
        return segments

    def transformed(self, frame: Pose, reflect: bool = False) -> Path:
        return LazyPath(lambda: Path.transformed(self, frame, reflect), self.vehicle)

    def with_vehicle(self, vehicle: Any) -> Path:
        return LazyPath(lambda: Path(self.segments, vehicle), vehicle)

    def __reduce__(self) -> tuple[Any, ...]:
        return (Path, (self.segments, self.vehicle))


def _candidate(ext: Extremal, vehicle: VariableSpeedCar) -> Candidate:
    path = LazyPath(lambda: extremal_path(ext, vehicle), vehicle)
    word, family = _word_family(ext, vehicle)
    violated = sorted(k for k, ok in ext.conditions.items() if not ok)
    info: dict[str, Any] = {
        "group": ext.ctype.group,
        "type": ext.ctype.name,
        "in_dissertation": ext.ctype.in_dissertation,
        "parameters": {
            k: (float(v) if isinstance(v, (float, np.floating)) else v)
            for k, v in ext.params.items()
        },
    }
    if violated:
        info["violates"] = violated  # strict sub-optimality bounds (4.22), (4.24)
    if ext.ctype.group == "umax":
        info["speed_profile"] = "not unique: every profile of this heading change takes this time"
    return Candidate(word, family, ext.cost / vehicle.u_max, path, Status.FEASIBLE, info)


@register_planner(
    "time-optimal",
    vehicle=VariableSpeedCar,
    objective="time",
    method="synthesis",
    description="Minimum-time paths with variable speed: synthesis over the 72 types (4.26)",
)
def plan_time_optimal(problem: Problem) -> PlannerOutput:
    """Every extremal of each candidate type of (4.26) (and the supplementary rigid types);
    the lowest wins.

    Costs are times (s). Each candidate's `info` holds its group, type (e.g. "CBSB LSR"),
    parameters, whether the type is in (4.26) (`in_dissertation`) and the strict
    sub-optimality bounds of the dissertation it breaks ((4.22), (4.24), `violates`); such
    candidates are kept: they are real paths to the goal, and B.4 behind (4.24) does not
    always hold.
    """
    vehicle = problem.vehicle
    assert isinstance(vehicle, VariableSpeedCar)
    goal = normalised_goal(problem.goal, vehicle)
    if np.hypot(goal[0], goal[1]) < _ZERO and abs(math.remainder(goal[2], 2 * PI)) < _ZERO:
        path = Path((Straight(Pose(), 0.0, vehicle.v_max),), vehicle)
        return PlannerOutput((Candidate("", "S", 0.0, path, info={"group": "trivial"}),))
    result = synthesize(goal, vehicle.speed_ratio)
    candidates = tuple(_candidate(e, vehicle) for e in result.extremals)
    counts: dict[str, int] = {}
    for e in result.extremals:
        counts[e.ctype.group] = counts.get(e.ctype.group, 0) + 1
    stats = {
        "candidate_types": len(CANDIDATE_TYPES),
        "supplementary_types": len(SUPPLEMENTARY_TYPES),
        "extremals_found": len(result.extremals),
        "extremals_by_group": counts,
        "seconds_by_group": dict(result.seconds),
    }
    return PlannerOutput(candidates, stats)
