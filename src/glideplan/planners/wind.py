"""Time-optimal paths in a known steady uniform wind or current ("convected" Dubins paths).

Dissertation §3.2 and appendix A (eq. A.4, Corollary A.2); Techy & Woolsey (2009); McGee &
Hedrick (2007); Bakolas & Tsiotras (2010). In the air- (water-) relative frame F_A, which
drifts with the wind w, the kinematics are those of the Dubins car, so a time-optimal path is
an air-frame Dubins path — circular arcs and straights, trochoids over ground — that reaches
the goal when the goal, seen from F_A, has moved to the *virtual target*
g(T) = (x1 - wx T, y1 - wy T, psi1). For each of the six words W the arrival time T_W is the
smallest root of

    F_W(T) = L_W(start -> g(T)) - v T            (REFERENCE_NOTES §3.4)

with L_W the air-frame length of W (F_W(0) > 0). T* = min_W T_W. The roots are bracketed on a
grid of T (`wind_kernel`: F_W of all words in one vectorised call of the Dubins kernel, and the
crossing test the mission costs share) and polished with
Brent's method on a scalar, independent implementation of the six words (REFERENCE_NOTES
§4.2, the (alpha, beta) form). A bracket across one of L_W's 2 pi R jumps (an arc wrapping
through a full turn) is not a root and is discarded.

Corollary A.2: with an unknown bounded disturbance eps v on top of the known wind, planning in
F_A with the feasible radius R0' = R0 (1 + eps)^2 keeps the path trackable, provided
w + eps v < v.

Over ground the path is made of `TrochoidArc` and `DriftingStraight` segments
(`glideplan.segments.drifting`, re-exported here): an air-frame arc or straight plus the
drift w t. They report `drift = (wx, wy)`, so `glideplan.verify`
integrates the inertial dynamics (A.4) along their controls. Their `length` is the air-relative
distance flown (v times the duration); `ground_length` is the length of the ground track.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.dubins import (
    WORDS,
    feasible_radius,
    word_directions,
)
from glideplan.planners.dubins_kernel import word_segments
from glideplan.planners.wind_kernel import crossing_cells, word_residuals
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import TWO_PI, Pose
from glideplan.segments import DriftingStraight, Segment, TrochoidArc
from glideplan.solution import Candidate, Status
from glideplan.validation import check_finite, check_in_range, check_positive
from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind

__all__ = [
    "DriftingStraight",
    "TrochoidArc",
    "WindSolution",
    "convected_dubins",
    "convected_dubins_path",
    "virtual_target_residual",
]

# Grid step for bracketing the roots of F_W, in units of R / v. F_W changes by at most about
# (1 + w |grad L_W|) per unit; a pair of roots closer than this could be missed (measure-zero).
_GRID_STEP = 0.05
# A bracket whose polished |F_W| (units of R) exceeds this straddles a 2 pi jump, not a root.
_ROOT_TOL = 1e-7
# The bracketing grid is evaluated this many cells at a time (memory ~ 100 bytes per cell),
# and refused beyond _MAX_GRID_POINTS cells (a wind within ~1e-5 of the airspeed).
_CHUNK = 65536
_MAX_GRID_POINTS = 4_000_000
# Arrival times beyond this (units of R / v) are refused: the end position's rounding error,
# about 1e-16 per unit of distance flown times a few hundred operations, would pass 1e-6 R.
_MAX_TAU = 1e9


# ----- the Dubins words for one virtual target (unit radius, start at the origin) ----------


def _word_tpq(k: int, x: float, y: float, psi: float) -> tuple[float, float, float] | None:
    """Segment lengths (t, p, q) of word WORDS[k] to (x, y, psi), unit radius; None infeasible.

    The one Dubins kernel (`glideplan.planners.dubins_kernel`, eq. 2.11) on Python floats:
    root polishing evaluates one word hundreds of times per query.
    """
    return word_segments(k, x, y, psi)


def virtual_target_residual(
    tau: float, k: int, goal: tuple[float, float, float], wind: tuple[float, float]
) -> float:
    """F_W(tau) = L_W(g(tau)) - tau in units of R and R / v (NaN when W is infeasible).

    `goal` is normalised by the planning radius R, `wind` by the airspeed v, `tau` = T v / R.
    """
    x1, y1, psi1 = goal
    tpq = _word_tpq(k, x1 - wind[0] * tau, y1 - wind[1] * tau, psi1)
    if tpq is None:
        return math.nan
    return tpq[0] + tpq[1] + tpq[2] - tau


# ----- the solver ---------------------------------------------------------------------------


@dataclass(frozen=True)
class WindSolution:
    """Arrival time of each word (s; inf when none) and its air-frame segment lengths (m)."""

    times: np.ndarray
    segment_lengths: np.ndarray
    radius: float
    # per word, grid cells with a sign change where the root polish failed (NaN inside the
    # cell) before the word's first root: an earlier arrival may hide there
    skipped_brackets: tuple[int, ...] = (0, 0, 0, 0, 0, 0)

    @property
    def best(self) -> int:
        """Index into WORDS of the fastest word."""
        return int(np.argmin(self.times))

    @property
    def time(self) -> float:
        """The minimum time T* (s)."""
        return float(np.min(self.times))


def _feasible_end(
    fn: Callable[[float], float], a: float, b: float, left_feasible: bool
) -> tuple[float, float]:
    """Shrink [a, b] to its feasible part, given that fn is finite at one end only."""
    lo, hi = (a, b) if left_feasible else (b, a)  # lo finite, hi NaN
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if math.isfinite(fn(mid)):
            lo = mid
        else:
            hi = mid
    return (a, lo) if left_feasible else (lo, b)


def _polish(
    k: int, a: float, b: float, goal: tuple[float, float, float], wind: tuple[float, float]
) -> tuple[float | None, bool]:
    """The smallest valid root of F_W in the grid cell [a, b] (or None), and whether the
    cell was skipped: a sign change where Brent's method failed (NaN inside the cell).

    Tried on the branch of F_W through F(a) (unwrapped by multiples of 2 pi: a root just
    before an arc wraps) and on F_W itself (a root just after a wrap); a root is valid when
    F_W itself vanishes there (the principal branch: every arc in [0, 2 pi)).
    """
    from scipy.optimize import brentq  # imported where used (start-up time)

    def raw(tau: float) -> float:
        return virtual_target_residual(tau, k, goal, wind)

    fa, fb = raw(a), raw(b)
    # a word that exists at only one end of the cell: move that end to the feasibility
    # boundary (F_W is steep there, so roots crowd towards it)
    if math.isfinite(fa) != math.isfinite(fb):
        a, b = _feasible_end(raw, a, b, math.isfinite(fa))
        fa, fb = raw(a), raw(b)
    if not (fa > 0.0 and math.isfinite(fb)):
        return None, False

    def unwrapped(tau: float) -> float:
        f = raw(tau)
        return f - TWO_PI * round((f - fa) / TWO_PI) if math.isfinite(f) else f

    best: float | None = None
    failed = False
    # without a 2 pi jump across the cell the two branches are the same function: solve once
    branches = (unwrapped, raw) if round((fb - fa) / TWO_PI) else (raw,)
    for fn in branches:
        fend = fn(b)
        if not fend <= 0.0:
            continue
        try:
            root = b if fend == 0.0 else brentq(fn, a, b, xtol=1e-14, rtol=1e-15)
        except ValueError:  # NaN inside the cell (a word's feasibility boundary)
            failed = True
            continue
        if abs(raw(root)) <= _ROOT_TOL * max(1.0, root) and (best is None or root < best):
            best = root
    return best, failed and best is None


def _excess_time(excess: float, goal_xy: tuple[float, float], wind: tuple[float, float]) -> float:
    """The tau >= 0 at which tau - |p - w tau| = `excess` (p the goal, w the wind, |w| < 1).

    h(tau) = tau - |p - w tau| rises with slope in [1 - |w|, 1 + |w|], so the root is unique;
    any root of F_W lies where 0 <= h(tau) <= L_W - |g(tau)| (a path is no shorter than the
    straight line), which bounds the search window independently of the goal's distance.
    """
    from scipy.optimize import brentq  # imported where used (start-up time)

    px, py = goal_xy
    wx, wy = wind

    def h(tau: float) -> float:
        return tau - math.hypot(px - wx * tau, py - wy * tau) - excess

    # h(hi) >= 0 in exact arithmetic; the margin covers rounding
    hi = (math.hypot(px, py) + excess) / (1.0 - math.hypot(wx, wy)) * (1.0 + 1e-9) + 1.0
    if h(0.0) >= 0.0:
        return 0.0
    return float(brentq(h, 0.0, hi, xtol=1e-12, rtol=4 * np.finfo(float).eps))


def _root_window(
    goal: tuple[float, float, float], wind: tuple[float, float]
) -> tuple[float, float, int]:
    """Start, end and number of grid points of the bracketing scan (normalised units).

    Every word's path exceeds the straight line to g(tau) by at most 6 pi (CCC: three arcs
    below 2 pi each; CSC: at most 2 + 4 pi), so every first root lies in
    [h^-1(0), h^-1(6 pi)], a window of width at most 6 pi / (1 - |w|) whatever the goal.
    """
    wmag = math.hypot(*wind)
    lo = _excess_time(0.0, goal[:2], wind)
    hi = _excess_time(3.0 * TWO_PI, goal[:2], wind) + _GRID_STEP
    if hi > _MAX_TAU:
        raise InvalidParameterError(
            "goal",
            float(f"{math.hypot(goal[0], goal[1]):.6g}"),
            f"distance (in turn radii R) is too far for this wind: the arrival time would "
            f"exceed {_MAX_TAU:.0e} R / v, where rounding alone exceeds the verification "
            "tolerance of 1e-6 R",
        )
    lo = max(0.0, lo - _GRID_STEP)  # F_W > 0 strictly before h^-1(0)
    count = max(3, math.ceil((hi - lo) / _GRID_STEP) + 1)
    if count > _MAX_GRID_POINTS:
        raise InvalidParameterError(
            "wind",
            wmag * 1.0,
            f"wind speed / airspeed {wmag:.6g} is too close to 1: the arrival-time search "
            f"would scan {count} grid points (limit {_MAX_GRID_POINTS}; needs wind speed "
            f"<= {1.0 - 3.0 * TWO_PI / (_MAX_GRID_POINTS * _GRID_STEP):.6g} * airspeed)",
        )
    return lo, hi, count


def _first_roots(
    goal: tuple[float, float, float], wind: tuple[float, float]
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Smallest root tau_W of each word's F_W (normalised units), its (t, p, q), and the
    number of cells skipped before it (see `_polish`).

    The grid over the window of `_root_window` is scanned in chunks (bounded memory) and the
    scan stops once every word has its first root.
    """
    x1, y1, psi1 = goal
    taus = np.full(6, np.inf)
    tpqs = np.full((6, 3), np.nan)
    skipped = np.zeros(6, dtype=int)
    wmag = math.hypot(*wind)
    if wmag == 0.0:  # still air: T_W = L_W / v
        for k in range(6):
            tpq = _word_tpq(k, x1, y1, psi1)
            if tpq is not None:
                taus[k] = sum(tpq)
                tpqs[k] = tpq
        return taus, tpqs, skipped
    for k in range(6):  # the goal is the start: arrival at T = 0 (all arcs empty)
        tpq = _word_tpq(k, x1, y1, psi1)
        if tpq is not None and sum(tpq) <= 1e-12:
            taus[k], tpqs[k] = 0.0, (0.0, 0.0, 0.0)
    lo, hi, count = _root_window(goal, wind)
    origin, target = np.zeros((1, 3)), np.array([[x1, y1, psi1]])
    w = np.asarray(wind, dtype=float)
    open_words = [k for k in range(6) if taus[k] != 0.0]
    for first in range(0, count - 1, _CHUNK):
        idx = np.arange(first, min(count, first + _CHUNK + 1))
        grid = lo + (hi - lo) * idx / (count - 1)
        # F_W of the six words at the virtual targets g(grid) (n, 6), and the cells where
        # each may cross zero: the kernel the mission costs share (`wind_kernel`)
        f = word_residuals(origin, target, w, grid)
        cand = crossing_cells(f[:-1], f[1:])
        for k in list(open_words):
            for i in np.nonzero(cand[:, k])[0]:
                root, skip = _polish(k, float(grid[i]), float(grid[i + 1]), goal, wind)
                skipped[k] += skip
                if root is not None:
                    tpq = _word_tpq(k, x1 - wind[0] * root, y1 - wind[1] * root, psi1)
                    assert tpq is not None
                    taus[k] = root
                    tpqs[k] = tpq
                    open_words.remove(k)
                    break
        if not open_words:
            break
    return taus, tpqs, skipped


def convected_dubins(
    goal: Pose | ArrayLike,
    *,
    speed: float,
    radius: float,
    wind: tuple[float, float],
    eps: float = 0.0,
) -> WindSolution:
    """Minimum-time arrival of each Dubins word from the origin (heading 0) to `goal` over ground.

    `goal` (x, y in m, heading in rad) is given in the start frame; `speed` is the airspeed v
    (m/s), `radius` the minimum turn radius R0 (m), `wind` (wx, wy) (m/s) in the same frame and
    `eps` the bound on an additional unknown disturbance, as a fraction of v: the path is
    planned with R0 (1 + eps)^2 (Corollary A.2), which needs |w| + eps v < v.
    """
    g = goal if isinstance(goal, Pose) else Pose.from_array(goal)
    v = check_positive("speed", speed)
    r0 = check_positive("radius", radius)
    eps = check_in_range("eps", eps, 0.0, 1.0, high_open=True)
    wx, wy = check_finite("wind x", wind[0]), check_finite("wind y", wind[1])
    w = math.hypot(wx, wy)
    if w + eps * v >= v:
        raise InvalidParameterError(
            "wind",
            w,
            f"wind speed + eps * speed must be < speed (here {w:g} + {eps:g} * {v:g} >= {v:g})",
        )
    r = float(feasible_radius(r0, eps))
    taus, tpqs, skipped = _first_roots((g.x / r, g.y / r, g.heading), (wx / v, wy / v))
    return WindSolution(
        times=taus * r / v,
        segment_lengths=tpqs * r,
        radius=r,
        skipped_brackets=tuple(int(c) for c in skipped),
    )


def convected_dubins_path(
    start: Pose,
    word: str,
    segment_lengths: ArrayLike,
    *,
    radius: float,
    speed: float,
    wind: tuple[float, float],
) -> Path:
    """The ground path of an air-frame Dubins `word` with air-frame `segment_lengths` (m)."""
    segments: list[Segment] = []
    pose = start
    drift = (float(wind[0]), float(wind[1]))
    for direction, length in zip(word_directions(word), np.asarray(segment_lengths), strict=True):
        seg: Segment
        if direction == 0:
            seg = DriftingStraight(pose, float(length), speed, drift)
        else:
            seg = TrochoidArc(pose, float(length) / radius, radius, direction, speed, drift)
        segments.append(seg)
        pose = seg.end
    return Path(tuple(segments))


@register_planner(
    "wind",
    vehicle=DubinsCarInWind,
    objective="time",
    description="Time-optimal paths in a steady uniform wind (convected Dubins; 3.2, A.4)",
)
def plan_wind(problem: Problem, *, disturbance_ratio: float = 0.0) -> PlannerOutput:
    """Time-optimal convected Dubins path (Techy & Woolsey 2009) to the goal over ground.

    Every word is a candidate (cost: arrival time, s). `disturbance_ratio` = eps =
    delta_max / v (the same option as the Dubins planner) plans with the feasible radius
    R0 (1 + eps)^2 of Corollary A.2 (needs w + eps v < v).
    """
    eps = disturbance_ratio
    vehicle = problem.vehicle
    assert isinstance(vehicle, DubinsCarInWind)
    # the wind is given in the world; the planner works in the start frame
    wind = vehicle.wind_in_frame(problem.frame.heading)
    sol = convected_dubins(
        problem.goal, speed=vehicle.speed, radius=vehicle.turn_radius, wind=wind, eps=eps
    )
    cands = []
    for k, word in enumerate(WORDS):
        info: dict[str, Any] = {"radius": sol.radius}
        if not math.isfinite(sol.times[k]):
            cands.append(Candidate(word, "", math.inf, None, Status.INFEASIBLE, info))
            continue
        path = convected_dubins_path(
            problem.start,
            word,
            sol.segment_lengths[k],
            radius=sol.radius,
            speed=vehicle.speed,
            wind=wind,
        )
        info["air_segment_lengths"] = [float(s) for s in sol.segment_lengths[k]]
        cands.append(Candidate(word, path.family, float(sol.times[k]), path, Status.FEASIBLE, info))
    extras = {
        "radius": sol.radius,
        "nominal_radius": vehicle.turn_radius,
        "eps": float(eps),
        "wind": {"east": vehicle.wind[0], "north": vehicle.wind[1]},
    }
    warnings = tuple(
        f"word {word}: {count} root bracket(s) of F_W skipped before its first arrival "
        "(Brent's method met the word's feasibility boundary inside the cell); an earlier "
        "arrival of this word may have been missed"
        for word, count in zip(WORDS, sol.skipped_brackets, strict=True)
        if count
    )
    return PlannerOutput(candidates=tuple(cands), extras=extras, warnings=warnings)
