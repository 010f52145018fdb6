"""Gamma_umax: paths flown at the maximum turn rate throughout (one turn direction).

Normalised units (R = 1, u_max = 1, rho = r/R). A left turn through heading change Delta
reaches P = integral_0^Delta v(psi) (cos psi, sin psi) dpsi with v in [rho, 1], and takes time
Delta whatever the speed profile: the extremal is singular (eta = 0, H = 0 for every speed),
so the speed profile is not unique (B.1 case 4 with kappa = u_max/v kept in H). The reachable
set is convex (a Lyapunov/Aumann integral):

    P in rho P_B(Delta) + (1 - rho) S(Delta),   P_B(Delta) = (sin Delta, 1 - cos Delta),
    S(Delta) = {integral_0^Delta s(psi) t(psi) dpsi : 0 <= s <= 1},

and S(delta + 2 pi k) = S(delta) + disc(2 k) (each full loop adds a disc of radius 2). With
g' = (g - rho P_B(delta)) / (1 - rho) the goal is reachable with k extra loops iff
dist(g', S(delta)) <= 2 k, and dist follows from the support function
h(w) = integral_0^delta max(0, w . t(psi)) dpsi as max_w (w . g' - h(w)). So the cheapest
fixed-turn-rate path of each orientation costs delta + 2 pi k_min, found by one 1-D
maximisation. A representative profile is built from a point of S(delta) (one B or one C
interval, closed form, or the support point when g' is outside) plus k loops with one B arc
each; the pattern it takes (e.g. CBCB) names the Gamma_umax word it realises.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable

import numpy as np

from glideplan.planners.min_time.geometry import compose_one
from glideplan.pose import TWO_PI, wrap_to_pi

__all__ = ["cheapest_fixed_turn_rate", "fixed_turn_rate_cost", "reach_distance", "support"]

PI = math.pi
_SAMPLES = 96


def _cos_plus_integral(x: np.ndarray) -> np.ndarray:
    """G(x) = integral_{-pi/2}^{x - pi/2} max(0, cos u) du (continuous, +2 per period)."""
    n = np.floor(x / TWO_PI)
    r = x - TWO_PI * n
    return 2.0 * n + np.where(r < PI, 1.0 - np.cos(np.minimum(r, PI)), 2.0)


def support(omega: np.ndarray, delta: float) -> np.ndarray:
    """h(omega) = integral_0^delta max(0, cos(psi - omega)) dpsi (support function of S)."""
    omega = np.asarray(omega, dtype=float)
    return _cos_plus_integral(delta - omega + PI / 2) - _cos_plus_integral(-omega + PI / 2)


def _support_point(omega: float, delta: float) -> tuple[np.ndarray, list[tuple[float, float]]]:
    """Point of S(delta) with outward normal omega and its B intervals (s = 1 where w.t > 0)."""
    intervals = []
    for j in range(-1, 2):
        lo = omega - PI / 2 + TWO_PI * j
        hi = omega + PI / 2 + TWO_PI * j
        a, b = max(lo, 0.0), min(hi, delta)
        if b > a:
            intervals.append((a, b))
    p = np.zeros(2)
    for a, b in intervals:
        p += np.array([math.sin(b) - math.sin(a), math.cos(a) - math.cos(b)])
    return p, intervals


def reach_distance(gp: np.ndarray, delta: float) -> tuple[float, float]:
    """max over omega of (w . g' - h(omega)) (= dist(g', S) when > 0) and the maximiser."""
    from scipy.optimize import minimize_scalar  # SciPy is imported where used (start-up time)

    om = np.arange(_SAMPLES) * (TWO_PI / _SAMPLES)
    phi = gp[0] * np.cos(om) + gp[1] * np.sin(om) - support(om, delta)
    i = int(np.argmax(phi))
    step = TWO_PI / _SAMPLES
    res = minimize_scalar(
        lambda w: -(gp[0] * math.cos(w) + gp[1] * math.sin(w) - float(support(w, delta))),
        bounds=(om[i] - step, om[i] + step),
        method="bounded",
        options={"xatol": 1e-12},
    )
    if -res.fun >= phi[i]:
        return float(-res.fun), float(res.x)
    return float(phi[i]), float(om[i])


def _one_interval(e: np.ndarray, delta: float) -> tuple[float, float] | None:
    """(x, beta) with chord of [x, x + beta] inside [0, delta] equal to e, if any."""
    m = math.hypot(e[0], e[1])
    if m > 2.0 + 1e-12:
        return None
    b0 = 2.0 * math.asin(min(1.0, m / 2.0))
    c = math.atan2(e[1], e[0])
    for beta in (b0, TWO_PI - b0):
        for j in range(-1, 3):
            x = c + TWO_PI * j - beta / 2.0
            if x >= -1e-12 and x + beta <= delta + 1e-12:
                return max(x, 0.0), min(beta, delta - max(x, 0.0))
    return None


def _labels_on(
    b_intervals: list[tuple[float, float]], lo: float, hi: float
) -> list[tuple[str, float, float]]:
    """Split [lo, hi] into ('B'|'C', start, end) pieces, B on the given intervals."""
    cuts = {lo, hi}
    for a, b in b_intervals:
        if hi > a and b > lo:
            cuts.update((max(a, lo), min(b, hi)))
    pts = sorted(cuts)
    out = []
    for a, b in itertools.pairwise(pts):
        if b - a <= 0.0:
            continue
        mid = 0.5 * (a + b)
        lab = "B" if any(x <= mid <= y for x, y in b_intervals) else "C"
        out.append((lab, a, b))
    return out


def _merge(pieces: list[tuple[str, float, float]]) -> list[tuple[str, float]]:
    out: list[list] = []
    for lab, a, b in pieces:
        if out and out[-1][0] == lab:
            out[-1][1] += b - a
        else:
            out.append([lab, b - a])
    return [(lab, x) for lab, x in out]


def _loop_b_intervals(c: float, beta: float, lo: float, hi: float) -> list[tuple[float, float]]:
    """B intervals {psi in [lo, hi]: cos(psi - c) > cos(beta/2)} (one per loop)."""
    out = []
    j0 = math.floor((lo - c) / TWO_PI) - 1
    j1 = math.ceil((hi - c) / TWO_PI) + 1
    for j in range(j0, j1 + 1):
        a, b = c + TWO_PI * j - beta / 2.0, c + TWO_PI * j + beta / 2.0
        if b > lo and a < hi:
            out.append((max(a, lo), min(b, hi)))
    return out


def _representative(
    gp: np.ndarray, pb: np.ndarray, delta: float, k: int, omega: float
) -> list[tuple[str, float]] | None:
    """The labelled arcs (B or C, heading change) of a left-turn profile reaching g' with k
    extra loops: a point p of S(delta) (one B or C interval, or the support point of omega)
    and k loops whose B arcs make up the chord q = g' - p; the shorter of the two orders."""
    # a point p of S(delta) and the loops' chord q = g' - p
    if k == 0:
        p = gp
        one = _one_interval(pb - p, delta)
        if one is not None:  # single C interval
            x0, beta = one
            b_int = [(0.0, x0), (x0 + beta, delta)]
        else:
            one = _one_interval(p, delta)
            if one is None:  # pragma: no cover - S(delta) is covered by the two patterns
                return None
            x0, beta = one
            b_int = [(x0, x0 + beta)]
    else:
        p, b_int = _support_point(omega, delta)
    q = gp - p
    qn = math.hypot(q[0], q[1])
    beta_q = 2.0 * math.asin(min(1.0, qn / (2.0 * k))) if k > 0 else 0.0
    c_q = math.atan2(q[1], q[0]) if qn > 0.0 else 0.0
    total = delta + TWO_PI * k
    best: list[tuple[str, float]] | None = None
    for first_part in (True, False):  # the delta part before or after the loops
        if first_part:
            pieces = _labels_on(b_int, 0.0, delta)
            loops = _labels_on(_loop_b_intervals(c_q, beta_q, delta, total), delta, total)
            moves = _merge(pieces + loops)
        else:
            loops = _labels_on(_loop_b_intervals(c_q, beta_q, 0.0, TWO_PI * k), 0.0, TWO_PI * k)
            shifted = [(a + TWO_PI * k, b + TWO_PI * k) for a, b in b_int]
            pieces = _labels_on(shifted, TWO_PI * k, total)
            moves = _merge(loops + pieces)
        if best is None or len(moves) < len(best):
            best = moves
    assert best is not None
    return best or [("B", 0.0)]


Reach = Callable[[np.ndarray, float], tuple[float, float]]


def _loops(
    goal: np.ndarray, rho: float, direction: int, reach: Reach | None
) -> tuple[float, np.ndarray, np.ndarray, float, int]:
    """(delta, P_B(delta), g', maximiser omega, extra loops k) of a goal (rho < 1)."""
    x, y, psi = float(goal[0]), direction * float(goal[1]), direction * float(goal[2])
    delta = psi % TWO_PI
    if delta > TWO_PI - 1e-12:
        delta = 0.0
    pb = np.array([math.sin(delta), 1.0 - math.cos(delta)])
    gp = (np.array([x, y]) - rho * pb) / (1.0 - rho)
    dist, omega = (reach or reach_distance)(gp, delta)
    k = 0 if dist <= 1e-12 else math.ceil(dist / 2.0 - 1e-12)
    return delta, pb, gp, omega, k


def fixed_turn_rate_cost(
    goal: np.ndarray, rho: float, direction: int, *, max_loops: int = 6, reach: Reach | None = None
) -> float | None:
    """The cost delta + 2 pi k that `cheapest_fixed_turn_rate` returns, without building the
    path (so without its end check): None when rho >= 1 or more than `max_loops` loops."""
    if rho >= 1.0:
        return None
    delta, _, _, _, k = _loops(goal, rho, direction, reach)
    return None if k > max_loops else delta + TWO_PI * k


def cheapest_fixed_turn_rate(
    goal: np.ndarray,
    rho: float,
    direction: int,
    *,
    max_loops: int = 6,
    reach: Reach | None = None,
) -> tuple[list[tuple[str, int, float]], float, int] | None:
    """Cheapest path of constant turn direction to `goal`: (moves, cost, loops) or None.

    `goal` is (x, y, heading) in normalised units; right turns are solved as mirrored left
    turns. Returns None when more than `max_loops` extra loops would be needed or rho >= 1.
    `reach` replaces `reach_distance` (the compiled one: `compiled.reach_distance`).
    """
    if rho >= 1.0:
        return None
    delta, pb, gp, omega, k = _loops(goal, rho, direction, reach)
    if k > max_loops:
        return None
    best = _representative(gp, pb, delta, k, omega)
    if best is None:  # pragma: no cover - S(delta) is covered by the two patterns
        return None
    total = delta + TWO_PI * k
    out = [(lab, direction, ang) for lab, ang in best]
    px, py, he = compose_one(out, rho)
    err = max(math.hypot(px - goal[0], py - goal[1]), abs(float(wrap_to_pi(he - goal[2]))))
    if err > 1e-8:
        return None
    return out, total, k
