"""Path synthesis: every member of every family of `FAMILIES` that reaches the goal.

The start is the origin with heading 0 (the planner's frame); the goal is (x1, y1, psi1) in
metres and radians. Orientations whose first turn is R are solved as the mirror image (goal
(x1, -y1, -psi1)) of the L orientation and reflected back. Every candidate is an explicit
`Path` of `HeadingSpeedArc`, `Arc` and `Straight` segments; its cost is the closed-form
altitude loss (m).

Solvers (one per `Family.solver`):

- "bsb": with lambda = v_stf - v_ms fixed, the component of the boundary condition normal to
  the straight is a trigonometric polynomial of degree 2 in the first arc's angle alpha
  (the projection form of (C.16)-(C.21): no division by cos(alpha), so cos(alpha) = 0 needs
  no special case). With z = e^{i alpha} it is a quartic; `numpy.roots` gives all its roots,
  each polished by Newton's method. The straight's length follows from the parallel
  component and must be >= 0.
- "chain": a chain of n B arcs. H = 0 puts every switch where v = v_stf, i.e. at
  phi = psi - theta = +-s with cos s = -(v_stf - v_ms)/lambda, so interior arcs turn exactly
  2 s and the chain is fixed by (s, first arc angle); the last arc follows from the final
  heading. The two position equations are solved by scanning a grid over
  s in (pi/2, pi] x first-arc fraction in [0, 1] for cells that may hold a root and
  polishing each with a vectorised Newton iteration (deterministic multi-start).
- "single_b": one B arc turning psi1 (mod 2 pi) or one more full turn (a loop to a goal
  just behind the start); without clipping the position is linear in lambda e^{i theta}
  (solved exactly); with clipping, Newton from that solution.
- "constant_speed": B_ms and B_stall^n (n = 1..4, middle arcs of pi): the position
  equations are linear in e^{i a1}, solved algebraically (re-derived (C.26)-(C.28), with the
  y condition that the extracted text omits); these reach only a measure-zero set of goals.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import NamedTuple

import numpy as np

from glideplan.path import Path
from glideplan.planners.min_altitude._tasks import (
    _ANGLE_TOL,
    _MIRROR,
    _Found,
    _saturated_time,
    _Setup,
    _Task,
    _wrap,
)
from glideplan.planners.min_altitude.chains import _newton_2d, _solve_chains
from glideplan.planners.min_altitude.families import FAMILIES, Family
from glideplan.pose import TWO_PI, Pose
from glideplan.solution import Candidate, Status
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = ["DEFAULT_GRID", "synthesize"]

DEFAULT_GRID = (40, 64)  # chain solver: switch-angle x first-arc samples


def synthesize(
    goal: Pose,
    glider: QuadraticPolarGlider,
    *,
    families: Sequence[Family] = FAMILIES,
    grid: tuple[int, int] = DEFAULT_GRID,
) -> tuple[Candidate, ...]:
    """All candidates of `families` from the origin (heading 0) to `goal`, lowest cost first.

    Args:
        goal: final pose (m, rad) in the frame of the start.
        glider: the vehicle (its polar, speed range and turn-rate limit).
        families: rows of the candidate table to search (default: all of `FAMILIES`).
        grid: samples of the chain solver's scan (switch angle, first-arc fraction).

    Returns:
        Feasible candidates (each with its `Path`, carrying `glider`), sorted by altitude loss
        (m); duplicates (same turn word and cost) are kept once.
    """
    st = _Setup.of(glider)
    tasks = [_Task.of(fam, word, goal) for fam in families for word in fam.words]
    found: list[_Pending] = []
    for solver in dict.fromkeys(task.family.solver for task in tasks):
        group = [task for task in tasks if task.family.solver == solver]
        for task, f in _SOLVERS[solver](group, st, grid):
            letters = f.letters
            if letters or f.keep_empty:
                word = letters.translate(_MIRROR) if task.reflect else letters
                found.append(_Pending(word, task.family.name, f.cost, task, f))
    # the segments are built for the candidates kept only, directly in the goal's frame
    return tuple(_candidate(p, glider) for p in _unique(found))


class _Pending(NamedTuple):
    """A solution before its path is built: turn word, family, cost (m) and the solver's."""

    word: str
    family: str
    cost: float
    task: _Task
    found: _Found


def _candidate(p: _Pending, glider: QuadraticPolarGlider) -> Candidate:
    """The candidate of a solution, its path built (mirrored for a mirrored task)."""
    path = Path(tuple(p.found.segments(glider, mirror=p.task.reflect)), glider)
    info = {"orientation": p.task.word, **p.found.info}
    if p.task.reflect and "angles" in info:  # solvers report the L-first mirror image
        info["angles"] = [-a for a in info["angles"]]
    return Candidate(p.word, p.family, p.cost, path, Status.FEASIBLE, info)


def _each(
    solve: Callable[[Pose, _Setup, Family, str], list[_Found]],
) -> Callable[[list[_Task], _Setup, tuple[int, int]], list[tuple[_Task, _Found]]]:
    """A solver of one task applied to each task of a group."""

    def run(tasks: list[_Task], st: _Setup, grid: tuple[int, int]) -> list[tuple[_Task, _Found]]:
        return [(t, f) for t in tasks for f in solve(t.goal, st, t.family, t.local_word)]

    return run


def _unique(cands: list[_Pending]) -> list[_Pending]:
    """Sort by cost and keep one of each path (same turn word and cost); a path that two
    families produce (e.g. a B arc with lambda = 0 is a B_ms arc) keeps the constant-speed
    family, else the one with fewer arcs."""

    def preference(c: _Pending) -> tuple[int, int]:
        return (0 if c.family.startswith(("Bms", "Bstall")) else 1, len(c.family))

    cands.sort(key=lambda c: c.cost)
    kept: list[_Pending] = []
    for c in cands:
        for i, k in enumerate(kept):
            if k.word == c.word and abs(k.cost - c.cost) <= 1e-9 * max(1.0, c.cost):
                if preference(c) < preference(k):
                    kept[i] = c
                break
        else:
            kept.append(c)
    return kept


# ----- BSB: all roots of a quartic in e^{i alpha} -------------------------------------------


def _solve_bsb(goal: Pose, st: _Setup, fam: Family, word: str) -> list[_Found]:
    """BSB of orientation `word` (first turn L): every root alpha of the quartic."""
    sg = 1.0 if word[2] == "L" else -1.0
    coeffs = _bsb_coefficients(goal, st, sg)
    if not any(coeffs):  # the goal is the start: nothing to fly
        return [_Found((("S", 0, 0.0),), 0.0, {"lambda": st.lam_s}, keep_empty=True)]
    out: list[_Found] = []
    for a0 in _bsb_angles(coeffs, st):
        found = _bsb_found(a0, goal, st, sg)
        if found is not None:
            out.append(found)
    return out


def _bsb_coefficients(goal: Pose, st: _Setup, sg: float) -> tuple[float, ...]:
    """(c0, c1, s1, c2, s2) of g(alpha) = c0 + c1 cos a + s1 sin a + c2 cos 2a + s2 sin 2a,
    the imaginary part of (x1 + i y1) e^{-i alpha} = L - (1/u) [(P(pi) - P(pi - alpha)) +
    sg (P(pi + gamma) - P(pi))] with gamma = psi1 - alpha (first turn L)."""
    g, u, sa = st.glider, st.glider.u_max, 1.0
    x1, y1, p1 = goal.x, goal.y, goal.heading
    vms, q = g.v_ms, st.lam_s / 4.0
    c0 = (sa - sg) * (vms + q) / u
    c1 = y1 + (-sa * vms + sg * vms * math.cos(p1)) / u
    s1 = -x1 + sg * vms * math.sin(p1) / u
    c2 = (-sa + sg * math.cos(2 * p1)) * q / u
    s2 = sg * q * math.sin(2 * p1) / u
    return c0, c1, s1, c2, s2


def _bsb_angles(coeffs: tuple[float, ...], st: _Setup) -> list[float]:
    """The distinct roots alpha in [0, 2 pi) of g: roots z = e^{i alpha} of the quartic
    z^2 g (all of them, `numpy.roots`), those on the unit circle polished by Newton's method
    on g (a failure leaves a residual, checked); alpha within 1e-9 of 0 or 2 pi is 0.
    Coefficients below 1e-14 of the largest, or all of them below 1e-14 R_stf, are zero."""
    c0, c1, s1, c2, s2 = coeffs
    poly = np.array(
        [(c2 - 1j * s2) / 2, (c1 - 1j * s1) / 2, c0, (c1 + 1j * s1) / 2, (c2 + 1j * s2) / 2]
    )
    big = np.max(np.abs(poly))
    if big < 1e-14 * st.scale:  # g = 0 to rounding (a goal on the start, heading ~1e-300):
        big = np.inf  # as the exact zero, no isolated root (np.roots overflowed: LinAlgError)
    poly = np.where(np.abs(poly) < 1e-14 * big, 0.0, poly)
    nz = np.flatnonzero(poly)
    roots = np.roots(poly[nz[0] :]) if nz.size > 1 else np.array([])

    def gfun(a: float) -> tuple[float, float]:
        ca, sa, c2a, s2a = math.cos(a), math.sin(a), math.cos(2 * a), math.sin(2 * a)
        return (c0 + c1 * ca + s1 * sa + c2 * c2a + s2 * s2a,
                -c1 * sa + s1 * ca - 2 * c2 * s2a + 2 * s2 * c2a)  # fmt: skip

    seen: list[float] = []
    for z in roots:
        if not abs(abs(z) - 1.0) < 1e-4:
            continue
        a0 = _newton_1d(gfun, float(np.angle(z)))
        if abs(gfun(a0)[0]) > 1e-9 * st.scale:
            continue
        a0 = float(_wrap(a0, 0.0))
        if a0 > TWO_PI - _ANGLE_TOL or a0 < _ANGLE_TOL:
            a0 = 0.0
        if not any(abs(a0 - b) < 1e-10 for b in seen):
            seen.append(a0)
    return seen


def _newton_1d(fun: Callable[[float], tuple[float, float]], x: float) -> float:
    """Newton's method from x (value and derivative from `fun`): at most 20 steps, stopped
    when a step is <= 1e-15, at a zero value or a zero derivative (SciPy's `newton`)."""
    for _ in range(20):
        val, der = fun(x)
        if val == 0.0 or der == 0.0:
            return x
        nxt = x - val / der
        if abs(nxt - x) <= 1e-15:
            return nxt
        x = nxt
    return x


def _bsb_found(a0: float, goal: Pose, st: _Setup, sg: float) -> _Found | None:
    """The BSB path whose first arc turns alpha = a0 (L): the last arc closes the heading,
    the straight's length follows from the component along it (None if negative)."""
    g, lam, u = st.glider, st.lam_s, st.glider.u_max
    alpha = a0
    gamma = float(_wrap(goal.heading - alpha, 0.0))
    if gamma > TWO_PI - _ANGLE_TOL or gamma < _ANGLE_TOL:
        gamma = 0.0
    if sg < 0 and gamma > 0.0:
        gamma -= TWO_PI
    P, W, _ = st.kern.primitives(np.array([math.pi - alpha, math.pi, math.pi + gamma]), lam)
    rest = ((P[1] - P[0]) + sg * (P[2] - P[1])) / u
    e = complex(math.cos(alpha), -math.sin(alpha))
    length = ((goal.x + 1j * goal.y) * e).real + rest.real
    if length < -1e-9 * st.scale:
        return None
    length = max(length, 0.0)
    cost = ((W[1] - W[0]) + sg * (W[2] - W[1])) / u + length * g.w_stf / g.v_stf
    moves = (("B", 1, abs(alpha)), ("S", 0, length), ("B", int(sg), abs(gamma)))
    info = {"lambda": lam, "angles": [alpha, gamma], "straight_length": length}
    # the straight is flown at heading theta + pi
    return _Found(moves, float(cost), info, theta=alpha - math.pi)


# ----- a single B arc --------------------------------------------------------------------------


def _solve_single_b(goal: Pose, st: _Setup, fam: Family, word: str) -> list[_Found]:
    base = float(_wrap(goal.heading, 0.0))
    base = 0.0 if base > TWO_PI - _ANGLE_TOL else base
    # the heading change is psi1 modulo 2 pi, or one more turn (a loop ending nearby)
    return [f for a1 in (base, base + TWO_PI) if a1 > _ANGLE_TOL for f in _single_b(goal, st, a1)]


def _single_b(goal: Pose, st: _Setup, a1: float) -> list[_Found]:
    g, kern, u = st.glider, st.kern, st.glider.u_max
    z1 = complex(goal.x, goal.y)
    # v in [v_stall, v_stf] along the arc: the end lies within a1 (v_stf - v_stall) / 2u of
    # the end of the same turn flown at the mean speed
    mid, half = 0.5 * (g.v_stf + g.v_stall), 0.5 * (g.v_stf - g.v_stall)
    if abs(z1 + 1j * mid * (np.exp(1j * a1) - 1.0) / u) > half * a1 / u * (1 + 1e-9) + 1e-9:
        return []
    # unclipped: mu a1/2 + conj(mu) K = -u z1 - i v_ms (e^{i a1} - 1), mu = lam e^{i theta}
    K = (np.exp(2j * a1) - 1.0) / 4j
    rhs = -u * z1 - 1j * g.v_ms * (np.exp(1j * a1) - 1.0)
    A = np.array([[a1 / 2 + K.real, K.imag], [K.imag, a1 / 2 - K.real]])
    try:
        m1, m2 = np.linalg.solve(A, np.array([rhs.real, rhs.imag]))
    except np.linalg.LinAlgError:
        return []

    def fun(p: np.ndarray, q: np.ndarray, idx: np.ndarray | None = None) -> np.ndarray:
        lam, theta = np.hypot(p, q), np.arctan2(q, p)
        P, _, _ = kern.primitives(np.stack([-theta, a1 - theta]), np.stack([lam, lam]))
        return (np.exp(1j * theta) * (P[1] - P[0]) / u - z1) / st.scale

    if math.hypot(m1, m2) <= g.v_ms - g.v_stall:
        p, q = np.array([m1]), np.array([m2])
    else:  # the clipped arc: Newton from a few scalings of the unclipped solution
        rot = np.exp(1j * np.array([0.0, 0.0, 0.0, 0.5, -0.5]))
        mu = complex(m1, m2) * np.array([1.0, 0.6, 1.6, 1.0, 1.0]) * rot
        big = 50.0 * g.v_ms
        p, q, _ = _newton_2d(fun, mu.real, mu.imag, lower=(-big, -big), upper=(big, big))
    out: list[_Found] = []
    for m1, m2 in zip(p, q, strict=True):
        if abs(fun(np.array([m1]), np.array([m2]))[0]) > 1e-10:
            continue
        lam, theta = math.hypot(m1, m2), math.atan2(m2, m1)
        lo = float(_wrap(-theta, -math.pi))  # the arc covers phi in [lo, lo + a1]
        if lam > st.lam_s:  # H = 0: no switch inside, so v <= v_stf on the whole arc
            s = math.acos(-st.lam_s / lam)
            if lo < -s - _ANGLE_TOL or lo + a1 > s + _ANGLE_TOL:
                continue
        if lo + a1 > 3 * math.pi + _ANGLE_TOL:  # two headings phi = pi (Lemma 5.7.7)
            continue
        if any(abs(f.info["lambda"] - lam) < 1e-9 * (1 + lam) for f in out):
            continue
        _, W, _ = kern.primitives(np.array([-theta, a1 - theta]), lam)
        stall = _saturated_time(-theta, 1, a1, lam, g)
        info = {"lambda": lam, "angles": [a1], "saturated_time": stall}
        out.append(_Found((("B", 1, a1),), float((W[1] - W[0]) / u), info, theta=theta))
    return out


# ----- constant-speed families: B_ms and B_stall^n (algebraic) ----------------------------------


def _solve_constant_speed(goal: Pose, st: _Setup, fam: Family, word: str) -> list[_Found]:
    g, n = st.glider, fam.arcs
    v = g.v_ms if fam.speed == "v_ms" else g.v_stall
    r = v / g.u_max
    label = "Bms" if fam.speed == "v_ms" else "Bstall"
    z1, p1 = complex(goal.x, goal.y), goal.heading
    limit = TWO_PI if fam.speed == "v_ms" else math.pi
    if n == 1:
        angles = [float(_wrap(p1, 0.0))]
        if not _ANGLE_TOL < angles[0] < limit:
            return []
    else:
        # L a1, (R pi, L pi, ...), last: z = i r (1 +- e^{i psi1}) - 2 i r (n - 1) e^{i a1}
        sign = 1.0 if n % 2 == 0 else -1.0
        e1 = (1j * r * (1.0 + sign * np.exp(1j * p1)) - z1) / (2j * r * (n - 1))
        if abs(abs(e1) - 1.0) > 1e-9:
            return []
        a1 = float(_wrap(np.angle(e1), 0.0))
        an = float(_wrap(a1 - p1 if n % 2 == 0 else p1 - a1 + math.pi, 0.0))
        an = 0.0 if an > TWO_PI - _ANGLE_TOL else an
        angles = [a1, *([math.pi] * (n - 2)), an]
        if a1 > math.pi + _ANGLE_TOL or an > math.pi + _ANGLE_TOL:
            return []
        if n == 4 and a1 + an >= math.pi:
            return []
    cost = sum(angles) / g.u_max * float(g.sink_rate(v, 0.0))
    info = {
        "speed": v,
        "angles": [a * (1 if k % 2 == 0 else -1) for k, a in enumerate(angles)],
    }
    moves = tuple(("C", 1 if k % 2 == 0 else -1, a) for k, a in enumerate(angles))
    found = _Found(moves, cost, info, label=label)
    segs = found.segments(g)
    if not segs or Path(tuple(segs)).end.distance_to(goal) > 1e-9 * st.scale:
        return []
    return [found]


_SOLVERS: dict[str, Callable[[list[_Task], _Setup, tuple[int, int]], list]] = {
    "bsb": _each(_solve_bsb),
    "chain": _solve_chains,
    "single_b": _each(_solve_single_b),
    "constant_speed": _each(_solve_constant_speed),
}
