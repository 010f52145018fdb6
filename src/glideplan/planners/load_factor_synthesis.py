"""Minimum altitude loss with speed and load-factor controls: synthesis from the extremals.

The chapter 6 necessary conditions (6.23-6.52) reduce, in arc length, to a curvature-cost
problem: the hodograph's lower boundary G(kappa) (extremal locus, then stall boundary, up
to the corner; convex, so no relaxation) is the least sink per unit length for a curvature,
and the adjoint w = -l_psi / (2 p1) selects kappa = k*(w) (`load_factor_kernel`). Its arcs
are, in order of |w|: extremal-locus arcs (|w| < w_lim, 6.41-6.44), stall-boundary arcs
(w_lim <= |w| < w_c, 6.49-6.50) and corner arcs (|w| >= w_c: the tightest turn, 6.51);
wings-level flight is the saddle of the canonical system, approached only (6.44).

The extremals are the orbits G*(w) = P cos phi of a pendulum-like system
(`load_factor_orbits`): rotations (P < 1, one turn direction), librations (P > 1, turns
with inflections) and, between them, turn - wings level - turn. They are tabulated once per
glider on a grid of P (`_tables`); for a goal, every P gives the line headings alpha where
the goal's lateral condition holds (algebraic) and the along-line mismatch there (a table
difference); its sign changes between neighbouring P bracket the extremals to the goal, which
are solved by regula falsi on the orbits, ranked by cost and the cheapest polished by Newton
shooting on a fine step. Its cost is checked against an upper bound (Dubins paths flown with
the best constant turn): a synthesis that is costlier than that missed the optimum. Where
the synthesis has no candidate (or fails the check) the planner says so and the direct method
answers.
"""

from __future__ import annotations

import functools
import math
import time
from dataclasses import dataclass

import numpy as np

from glideplan.path import Path
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.pose import Pose
from glideplan.segments import Sampled
from glideplan.solution import Candidate, Status
from glideplan.vehicles.load_factor_glider import LoadFactorGlider

__all__ = [
    "TABLE_STEP",
    "Extremal",
    "dubins_bound",
    "extremal_path",
    "kernel_parameters",
    "p_grid",
    "plan_load_factor_synthesis",
    "synthesize",
]

TABLE_STEP = 0.025  # RK4 step of the orbit tables and of the regula falsi (error ~1e-7)
TABLE_LENGTH = 200.0  # longest tabulated period
FINE_STEP = 0.01  # RK4 step of the polishing Newton shooting
NODE_STEP = 0.004  # node spacing of the returned path (controls linear between nodes)
N_ALPHA = 96  # uniform line headings scanned per P (plus refinements near the saddle)
COST_MARGIN = 0.02  # brackets whose interpolated cost exceeds the best found by this are skipped
MAX_REFINE = 12
RESCUE_STARTS = 40  # search rows shot from where the brackets found no extremal below the bound


@dataclass(frozen=True)
class Extremal:
    """A converged extremal: initial adjoint (w0, Py), length, cost (altitude) and nodes."""

    w0: float
    py: float
    length: float
    cost: float
    nodes: np.ndarray
    residual: float
    modulus: float


def kernel_parameters(glider: LoadFactorGlider) -> np.ndarray | None:
    """(p2, a, k_lim, k_c, w_lim, w_c, ...tables), or None where the corner lies below the
    locus-stall intersection (n_limit < n_lim) or v_max < 1 (cases this synthesis does not
    cover)."""
    p2 = glider.p2
    a = 0.5 * (1.0 + p2**2)
    v4_lim = 2.0 / (1.0 + p2**2)
    n_int = math.sqrt(2.0 - v4_lim)
    if glider.n_limit < n_int * (1.0 + 1e-9) or glider.v_max < 1.0 or p2 <= 1.0:
        return None
    k_lim = math.sqrt(1.0 / v4_lim - 1.0)
    k_c = p2 * math.sqrt(1.0 - 1.0 / glider.n_limit**2)
    w_lim = k_lim / math.sqrt(1.0 + k_lim**2)
    w_c = a * k_c * (p2**2 - k_c**2) ** -1.5
    from glideplan.planners.load_factor_kernel import extend_parameters

    return extend_parameters(np.array([p2, a, k_lim, k_c, w_lim, w_c]), 2048)


def p_grid() -> np.ndarray:
    """Orbit moduli: rotations P = 0.01 ... 1 - 1e-12, librations 1 + 1e-12 ... 101 (log
    spaced in P far from 1 and in |1 - P| near it: the time spent near wings-level flight
    grows like log(1 / |1 - P|)); denser for 1.001 < P < 101, where the root curves of
    short goals with one inflection are born and die within a few percent of P."""
    rot = np.concatenate([np.geomspace(0.01, 0.5, 14), 1.0 - 10.0 ** -np.linspace(0.35, 12, 55)])
    lib = 1.0 + 10.0 ** -np.r_[np.linspace(-2.0, 3.0, 70), np.linspace(3.1, 12.0, 40)]
    return np.concatenate([rot, lib])


@functools.lru_cache(maxsize=8)
def _tables(glider: LoadFactorGlider) -> tuple[np.ndarray, ...] | None:
    """(P grid, stacked orbit tables, offsets, period info, kernel parameters), per glider."""
    from glideplan.planners.load_factor_orbits import build_tables

    prm = kernel_parameters(glider)
    if prm is None:
        return None
    ps = p_grid()
    rows, off, info = build_tables(ps, TABLE_STEP, prm, TABLE_LENGTH)
    return ps, rows, off, info, prm


def dubins_bound(glider: LoadFactorGlider, goal: Pose) -> tuple[float, str]:
    """An upper bound of the least altitude loss: the six Dubins words for a few radii,
    arcs flown with the best constant turn (2 p1 G(1/r) per length) and straights wings
    level (2 p1 per length)."""
    from glideplan.analysis.load_factor import best_turn
    from glideplan.planners.dubins_kernel import WORDS, word_segments

    best, word = math.inf, ""
    rc = glider.corner_radius
    for r in (rc, 1.15 * rc, 1.35 * rc, 1.7 * rc, 2.2 * rc, 3.0 * rc, 4.5 * rc):
        v, n = best_turn(glider, r)
        rate = glider.p1 * (v**2 + n**2 / v**2)  # altitude per unit length on the arc
        for k, name in enumerate(WORDS):
            seg = word_segments(k, goal.x / r, goal.y / r, goal.heading)
            if seg is None:
                continue
            t, p, q = seg
            arcs = t + q + (p if k >= 4 else 0.0)
            straight = 0.0 if k >= 4 else p
            cost = r * (rate * arcs + 2.0 * glider.p1 * straight)
            if cost < best:
                best, word = cost, name
    return best, word


def synthesize(
    glider: LoadFactorGlider, goal: Pose, *, polish: int = 1, bound: float = math.inf
) -> list[Extremal]:
    """Extremals from the origin to `goal`, cheapest first (at most `polish`).

    The orbit search (`_search`) brackets the extremals between tabulated moduli and solves
    the cheapest (`_solve_brackets`); where that finds none cheaper than `bound` (an upper
    bound of the optimum, e.g. `dubins_bound`), Newton shooting from the search's rows
    (`_rescue`) looks for the extremals whose root curves live between two tabulated moduli.
    """
    tabs = _tables(glider)
    if tabs is None:
        return []
    gx, gy, gpsi = float(goal.x), float(goal.y), float(goal.heading)
    if gx > 0.0 and abs(gy) <= 1e-12 * gx and abs(math.remainder(gpsi, 2.0 * math.pi)) <= 1e-12:
        # straight ahead: wings-level flight (v = n = 1, the saddle itself), 2 p1 per length
        nd = np.array([[0.0, 0, 0, 0, 0, 0, 0, 1, 0], [gx, 0, 0, 0, gx, gx, 0, 1, 0]])
        return [Extremal(0.0, 0.0, gx, 2.0 * glider.p1 * gx, nd, 0.0, 1.0)]
    rows, lmax = _search(tabs, goal)
    out: list[Extremal] = []
    for res in _solve_brackets(rows, tabs, goal, lmax):
        if len(out) >= polish:
            break
        al, p, length, w0 = res[0], res[1], res[2], res[5]
        ext = _polish(np.array([w0, p * math.sin(al), length]), float(p), glider, goal, tabs)
        if ext is not None:
            out.append(ext)
    if not out or out[0].cost > bound * (1.0 + 1e-9):
        out += _rescue(rows, tabs, glider, goal, bound)
    out.sort(key=lambda e: e.cost)
    return out[: max(1, polish)]


def _search(tabs: tuple, goal: Pose) -> tuple[np.ndarray, float]:
    """Every tabulated modulus's roots of the lateral condition with their along-line
    mismatch (`load_factor_orbits.search` rows) for extremals up to the length lmax."""
    from glideplan.planners.load_factor_orbits import search

    ps, rows_t, off, info, prm = tabs
    lmax = 2.0 * math.hypot(goal.x, goal.y) + 15.0
    rows = search(rows_t, off, info, ps, TABLE_STEP, prm, float(goal.x), float(goal.y),
                  float(goal.heading), lmax, N_ALPHA)  # fmt: skip
    return rows, lmax


def _solve_brackets(rows: np.ndarray, tabs: tuple, goal: Pose, lmax: float) -> list[np.ndarray]:
    """The brackets of the search rows (neighbouring moduli, root ends) solved cheapest
    first, while within `COST_MARGIN` of the best: (alpha, P, L, C, t, w0, |e2|, ok) rows,
    distinct, cheapest first."""
    from glideplan.planners.load_factor_orbits import brackets, ends, refine, refine_z

    ps, _, _, _, prm = tabs
    gx, gy, gpsi = float(goal.x), float(goal.y), float(goal.heading)
    seeds: list[tuple[float, tuple]] = [
        (c, (rows[int(ia)], rows[int(ib)], ps)) for ia, ib, c in brackets(rows, ps, gpsi, prm)
    ]
    # ends of roots are followed only below 1.5 times the cheapest bracket's estimate
    c_max = 1.5 * seeds[0][0] if seeds else math.inf
    for e in ends(rows, ps, gx, gy, gpsi, TABLE_STEP, lmax, prm, c_max):
        ra, rb = e[3:12], e[12:21]
        c = ra[6] + ra[4] / (ra[4] - rb[4]) * (rb[6] - ra[6]) if ra[4] != rb[4] else ra[6]
        seeds.append((c, (e[0], e[1], e[2] > 0.0, ra, rb)))
    seeds.sort(key=lambda sd: sd[0])
    found: list[np.ndarray] = []
    for c_est, args in seeds[:MAX_REFINE]:
        if found and c_est > min(f[3] for f in found) * (1.0 + COST_MARGIN):
            break
        if len(args) == 3:
            ra, rb, _ = args
            res = refine(ra, rb, ps, gx, gy, gpsi, TABLE_STEP, lmax, prm)
        else:
            za, zb, lib, ra, rb = args
            res = refine_z(za, zb, lib, ra, rb, gx, gy, gpsi, TABLE_STEP, lmax, prm)
        if res[7] == 0.0 or res[6] > 1e-8:
            continue
        if any(abs(f[2] - res[2]) < 1e-6 and abs(f[3] - res[3]) < 1e-7 for f in found):
            continue
        found.append(res)
    found.sort(key=lambda f: f[3])
    return found


def _polish(
    z0: np.ndarray, modulus: float, glider: LoadFactorGlider, goal: Pose, tabs: tuple
) -> Extremal | None:
    """The extremal from (w0, Py, L) ~ z0 by Newton shooting on the fine step, with its
    nodes (None if it does not converge)."""
    from glideplan.planners.load_factor_kernel import kink_nodes, shoot

    prm = tabs[4]
    gx, gy, gpsi = float(goal.x), float(goal.y), float(goal.heading)
    z = shoot(z0, gx, gy, gpsi, max(16, math.ceil(z0[2] / FINE_STEP)), prm, 4)
    if z[3] > 1e-7 or not z[2] > 0.0:
        return None
    # the path's nodes: the same RK4 steps as the last Newton iterations
    # and w (so kappa on the stall boundary) moving at most 0.02 per node (|w'| <= P)
    n = max(64, math.ceil(z[2] / NODE_STEP), math.ceil(z[2] * modulus / 0.02))
    z = shoot(z[:3], gx, gy, gpsi, n, prm, 2)
    if z[3] > 1e-10:
        return None
    nd = kink_nodes(z[0], z[1], z[2], n, prm)
    cost = 2.0 * glider.p1 * float(nd[-1, 4])
    return Extremal(float(z[0]), float(z[1]), float(z[2]), cost, nd, float(z[3]), modulus)


def _rescue(
    rows: np.ndarray, tabs: tuple, glider: LoadFactorGlider, goal: Pose, bound: float
) -> list[Extremal]:
    """Extremals by Newton shooting (table step) from the search rows cheaper than 1.3 x
    `bound` with the least along-line mismatch (at most `RESCUE_STARTS`), the cheapest
    polished: for goals whose extremal lies on a root curve born and dying between two
    tabulated moduli (no bracket sees it)."""
    from glideplan.planners.load_factor_kernel import g_star, integrate, shoot, w_of_g_star

    ps, _, _, _, prm = tabs
    gx, gy, gpsi = float(goal.x), float(goal.y), float(goal.heading)
    c_max = 1.3 * bound / (2.0 * glider.p1)
    cand = rows[rows[:, 6] < c_max] if math.isfinite(c_max) else rows
    cand = cand[np.argsort(np.abs(cand[:, 4]), kind="stable")][:RESCUE_STARTS]
    best: tuple[float, np.ndarray] | None = None
    for r in cand:
        p, al = ps[int(r[0])], r[3]
        s0 = 1.0 if int(r[1]) % 2 == 0 else -1.0
        z0 = np.array([s0 * w_of_g_star(p * math.cos(al), prm), p * math.sin(al), r[5]])
        n = max(16, math.ceil(r[5] / TABLE_STEP))
        z = shoot(z0, gx, gy, gpsi, n, prm, 12)
        if z[3] > 1e-8 or not z[2] > 0.0:
            continue
        c = integrate(z[0], z[1], z[2], max(16, math.ceil(z[2] / TABLE_STEP)), prm)[4]
        if best is None or c < best[0]:
            best = (c, z[:3].copy())
    if best is None:
        return []
    z = best[1]
    ext = _polish(z, math.hypot(g_star(z[0], prm), z[1]), glider, goal, tabs)
    return [] if ext is None else [ext]


def _corrected(t: np.ndarray, f: np.ndarray, smooth: np.ndarray) -> np.ndarray:
    """Node values whose piecewise-linear interpolant has the right mean on each interval:
    f - h^2 f'' / 12 (the linear interpolant of f exceeds f by h^2 f'' / 12 on average), so
    that integrating the sampled controls is fourth-order accurate instead of second."""
    h = np.diff(t)
    out = f.copy()
    slope = np.diff(f) / h
    f2 = 2.0 * np.diff(slope) / (h[1:] + h[:-1])
    corr = (h[1:] * h[:-1]) / 12.0 * f2
    corr[~smooth[1:-1]] = 0.0
    out[1:-1] -= corr
    return out


def extremal_path(glider: LoadFactorGlider, ext: Extremal) -> Path:
    """The extremal as a sampled path: speed v and turn rate kappa v at its nodes (corrected
    for the linear interpolation between nodes, `_corrected`)."""
    nd = ext.nodes
    t = nd[:, 5] - nd[0, 5]
    kink = nd[:, 8] > 0.0
    smooth = ~(kink | np.r_[kink[1:], False] | np.r_[False, kink[:-1]])
    v = _corrected(t, nd[:, 7], smooth)
    u = _corrected(t, nd[:, 6] * nd[:, 7], smooth)
    return Path((Sampled(t, nd[:, 0], nd[:, 1], nd[:, 2], v, u),)).with_vehicle(glider)


def _direct_answer(problem: Problem, why: str, seconds: float, extra: dict) -> PlannerOutput:
    """The direct method's answer, saying why the synthesis did not answer."""
    from glideplan.planners.load_factor import plan_load_factor

    out = plan_load_factor(problem)
    msg = f"synthesis: no candidate ({why}); the direct method answered"
    return PlannerOutput(
        candidates=out.candidates,
        stats={**out.stats, "synthesis_seconds": seconds, "synthesis_candidates": 0},
        message=f"{msg}: {out.message}" if out.message else msg,
        extras={**out.extras, **extra, "answered_by": "direct"},
        failure=out.failure,
        warnings=(*out.warnings, msg),
    )


def _controls(glider: LoadFactorGlider, path: Path, samples: int = 400) -> tuple[dict, dict]:
    """The arc classification and a control history thinned to about `samples` nodes."""
    from glideplan.analysis.load_factor import classify_controls
    from glideplan.planners.load_factor import control_history

    hist = control_history(glider, path)
    step = max(1, len(hist["s"]) // samples)
    idx = np.unique(np.r_[np.arange(0, len(hist["s"]), step), len(hist["s"]) - 1])
    h = {key: val[idx] for key, val in hist.items()}
    arcs = classify_controls(glider, h["s"], h["v"], h["n"], h["direction"])
    controls = {
        "s": h["s"],
        "v": h["v"],
        "n": h["n"],
        "bank_deg": np.degrees(h["bank"]),
        "label": [str(x) for x in arcs.labels],
    }
    return arcs.to_dict() | {"turn_word": arcs.turn_word}, controls


@register_planner(
    "load-factor-synthesis",
    vehicle=LoadFactorGlider,
    objective="altitude",
    method="synthesis",
    default=False,
    description="Minimum altitude loss, speed and load-factor controls: extremals (locus, "
    "stall and corner arcs, 6.35-6.51) from tabulated orbits; direct method where none",
)
def plan_load_factor_synthesis(problem: Problem) -> PlannerOutput:
    """The cheapest extremal found (checked against the Dubins bound); with none, the
    direct method's answer (said so)."""
    glider = problem.vehicle
    assert isinstance(glider, LoadFactorGlider)
    goal = problem.goal
    t0 = time.perf_counter()
    bound, bound_word = dubins_bound(glider, goal)
    exts = synthesize(glider, goal, bound=bound)
    seconds = time.perf_counter() - t0
    check = {"dubins_bound": bound, "dubins_bound_word": bound_word}
    if not exts:
        why = (
            "this glider's corner lies below the locus-stall intersection or v_max < 1"
            if kernel_parameters(glider) is None
            else "no extremal converged to the goal"
        )
        return _direct_answer(problem, why, seconds, check)
    if exts[0].cost > bound * (1.0 + 1e-9):
        why = (
            f"the cheapest extremal found ({exts[0].cost:.6g}) costs more than a Dubins path "
            f"flown with the best turn ({bound:.6g}, {bound_word}): the search missed the optimum"
        )
        return _direct_answer(problem, why, seconds, check)
    cands = []
    extras: dict = {"answered_by": "synthesis", **check}
    for k, e in enumerate(exts):
        path = extremal_path(glider, e)
        info = {"w0": e.w0, "Py": e.py, "P": e.modulus, "length": e.length}
        word = "E"
        if k == 0:
            arcs, controls = _controls(glider, path)
            word = str(arcs.pop("turn_word")).replace("-", "") or "S"
            extras |= {"arcs": arcs, "controls": controls}
        cands.append(Candidate(word, "E", path.cost("altitude"), path, Status.FEASIBLE, info))
    return PlannerOutput(
        candidates=tuple(cands),
        stats={"synthesis_seconds": seconds, "synthesis_candidates": len(cands)},
        message="",
        extras=extras,
    )
