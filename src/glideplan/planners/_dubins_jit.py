"""Compiled (numba) Dubins lengths: `dubins_kernel`'s six words, one query at a time, pruned.

The word formulas are `dubins_kernel`'s (dissertation eq. 2.11, circle-centre form) written
for scalars with the same operations in the same order, the same 2 pi snap (1e-11 turns) and
feasibility margin (1e-10), so a word's length equals the NumPy kernel's to rounding (the
tests compare them). What is new is the order of work: each word first gets a lower bound
from square roots only (no arc tangent),

    LSL: |V| + psi,   RSR: |V| + (2 pi - psi),   LSR, RSL: p + min(psi, 2 pi - psi),
    RLR, LRL: pi (the middle arc is at least pi; only when |V| <= 4),

(t + q is psi or psi + 2 pi for LSL, -psi mod 2 pi or that + 2 pi for RSR; t - q = +-psi for
the mixed words, so t + q >= min(psi, 2 pi - psi)), and words are evaluated in full (one
atan2) in order of their bounds only while a bound is below the best length so far: usually
one word. A word is skipped only when its bound exceeds the best by more than rounding, so
ties still go to the first word in `WORDS`.

`dp_leg` is one step of the heading dynamic programme (missions.headings): for each goal
heading b, min over start headings a of V(a) + c(a, b), scanning a in increasing V(a) + a
lower bound of every leg from a (`_to_point`), stopping once that exceeds the best, and asking
each entry only whether it beats the best so far (`_may_beat`, then `min_total` with the cap).
Flat batches and the DP's inner blocks now run the vectorised kernels (`_dubins_simd`,
`_dubins_dp`), which call `min_total` for the queries they flag; `dp_leg` here is the previous
DP step (`missions.leg_costs.DP_BLOCKS = False`, the benchmark's baseline).

Serial kernels (no prange): callers run them one per process. Imported lazily: importing
this module imports numba (`glideplan` itself does not).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["dp_leg", "min_lengths", "word_total"]

TWO_PI = 2.0 * math.pi
PI = math.pi
_INV_2PI = 1.0 / TWO_PI
SNAP = 1e-11  # dubins_kernel.NUMPY64.snap
FEAS = 1e-10  # dubins_kernel.NUMPY64.feas
ZERO = 2.0 * TWO_PI * SNAP  # turns shorter than this are rounding (dubins_kernel._zero_turn)
INF = np.inf
_NEAR = 16.0 + 8.0 * FEAS  # |V|^2 at most this: the CCC words exist


@njit(cache=True)
def _mod(a: float) -> float:
    return a - TWO_PI * math.floor(a * _INV_2PI + SNAP)


@njit(cache=True)
def _tot(t: float, p: float, q: float) -> float:
    return (max(t, 0.0) + p) + max(q, 0.0)


@njit(cache=True)
def word_total(k: int, x: float, y: float, psi: float, sp: float, cp: float) -> float:
    """Total length t + p + q of word k (`WORDS` order; unit radius), inf where infeasible."""
    if k == 0:  # LSL
        vx, vy = x - sp, y + cp - 1.0
        phi = math.atan2(vy, vx)
        return _tot(_mod(phi), math.sqrt(vx * vx + vy * vy), _mod(psi - phi))
    if k == 3:  # RSR
        vx, vy = x + sp, y - cp + 1.0
        phi = math.atan2(vy, vx)
        return _tot(_mod(-phi), math.sqrt(vx * vx + vy * vy), _mod(phi - psi))
    if k == 1:  # LSR
        vx, vy = x + sp, y - cp - 1.0
        p2 = vx * vx + vy * vy - 4.0
        if p2 + FEAS < 0.0:
            return INF
        p = math.sqrt(max(p2, 0.0))
        phi = math.atan2(vy * p + 2.0 * vx, vx * p - 2.0 * vy)
        return _tot(_mod(phi), p, _mod(phi - psi))
    if k == 2:  # RSL
        vx, vy = x - sp, y + cp + 1.0
        p2 = vx * vx + vy * vy - 4.0
        if p2 + FEAS < 0.0:
            return INF
        p = math.sqrt(max(p2, 0.0))
        phi = math.atan2(vy * p - 2.0 * vx, vx * p + 2.0 * vy)
        return _tot(_mod(-phi), p, _mod(psi - phi))
    if k == 4:  # RLR
        vx, vy = x + sp, y - cp + 1.0
        v2 = vx * vx + vy * vy
        if not v2 <= _NEAR:
            return INF
        c = 1.0 - 0.125 * v2
        pm = TWO_PI - math.acos(min(max(c, -1.0), 1.0))
        t = _mod(0.5 * pm - math.atan2(vy, vx))
        return _tot(t, pm, _mod(pm - t - psi))
    vx, vy = x - sp, y + cp - 1.0  # LRL
    v2 = vx * vx + vy * vy
    if not v2 <= _NEAR:
        return INF
    c = 1.0 - 0.125 * v2
    pm = TWO_PI - math.acos(min(max(c, -1.0), 1.0))
    t = _mod(math.atan2(vy, vx) + 0.5 * pm)
    return _tot(t, pm, _mod(psi - t + pm))


@njit(cache=True)
def _atan2_near(y: float, x: float) -> float:
    """atan2(y, x) within 3e-8 rad (odd series of atan to t^15 on |t| <= tan(pi/8), after
    atan a = pi/4 + atan((a - 1)/(a + 1)); the first term left out is below 2e-8)."""
    ax, ay = abs(x), abs(y)
    hi, lo = max(ax, ay), min(ax, ay)
    if hi == 0.0:
        return 0.0
    a = lo / hi
    off = 0.0
    if a > 0.41421356237309503:
        a = (a - 1.0) / (a + 1.0)
        off = 0.25 * PI
    t2 = a * a
    r = t2 * (1.0 / 13.0 - t2 / 15.0) - 1.0 / 11.0
    r = t2 * (1.0 / 9.0 + t2 * r) - 1.0 / 7.0
    r = t2 * (1.0 / 5.0 + t2 * r) - 1.0 / 3.0
    r = off + a * (1.0 + t2 * r)
    if ay > ax:
        r = 0.5 * PI - r
    if x < 0.0:
        r = PI - r
    return -r if y < 0.0 else r


_DELTA = 1e-7  # bound on |_atan2_near - atan2| (3e-8) with room for rounding


@njit(cache=True)
def _mod_low(a: float) -> float:
    """A lower bound of mod(b) for every b within _DELTA of a (0 where b may wrap)."""
    u = _mod(a - _DELTA)
    return 0.0 if u > TWO_PI - 4.0 * _DELTA else u


@njit(cache=True)
def _in_sweep(vx: float, vy: float, p: float, psi: float, sp: float, cp: float) -> int:
    """Whether the direction of V lies in [0, psi] (CCW): 1 yes, 0 no, -1 too close to say."""
    tol = 1e-9 * p
    s1 = vy  # cross(e_x, V)
    s2 = vx * sp - vy * cp  # cross(V, (cos psi, sin psi))
    if p < 1e-9 or abs(s1) <= tol or abs(s2) <= tol or psi < 1e-9 or psi > TWO_PI - 1e-9:
        return -1
    if psi <= PI:
        return 1 if (s1 > 0.0 and s2 > 0.0) else 0
    return 1 if (s1 > 0.0 or s2 > 0.0) else 0


@njit(cache=True)
def _bounds(x: float, y: float, psi: float, sp: float, cp: float,
            cap: float) -> tuple[float, ...]:
    """Lower bounds of the six words' totals (module docstring), inf where infeasible.

    LSL and RSR: t + q from which side of the goal heading V points (exact unless V is
    within 1e-9 of a boundary); LSR and RSL: p + min(psi, 2 pi - psi), and when that is
    not above `cap`, t and q from `_atan2_near`."""
    slack = 1e-9
    lx, ly = x - sp, y + cp - 1.0  # left circles (LSL, LRL)
    rx, ry = x + sp, y - cp + 1.0  # right circles (RSR, RLR)
    l2 = lx * lx + ly * ly
    r2 = rx * rx + ry * ry
    pl = math.sqrt(l2) * (1.0 - 1e-15)
    side = _in_sweep(lx, ly, pl, psi, sp, cp)
    b0 = pl + (psi + TWO_PI if side == 0 else psi) - slack
    pr = math.sqrt(r2) * (1.0 - 1e-15)
    side = _in_sweep(rx, ry, pr, psi, sp, cp)  # theta >= psi: 2 pi - psi, else 4 pi - psi
    if side < 0:
        b3 = pr + (TWO_PI - psi if psi > 1e-6 else 0.0) - slack
    else:
        b3 = pr + (2.0 * TWO_PI - psi if side == 1 else TWO_PI - psi) - slack
    ax, ay = x + sp, y - cp - 1.0
    p2 = ax * ax + ay * ay - 4.0
    mixed = min(psi, TWO_PI - psi) - slack
    b1 = INF
    if p2 + FEAS >= 0.0:
        p = math.sqrt(max(p2, 0.0))
        b1 = p * (1.0 - 1e-15) + mixed
        if b1 <= cap:
            phi = _atan2_near(ay * p + 2.0 * ax, ax * p - 2.0 * ay)
            b1 = _mod_low(phi) + p * (1.0 - 1e-15) + _mod_low(phi - psi) - slack
    bx, by = x - sp, y + cp + 1.0
    q2 = bx * bx + by * by - 4.0
    b2 = INF
    if q2 + FEAS >= 0.0:
        p = math.sqrt(max(q2, 0.0))
        b2 = p * (1.0 - 1e-15) + mixed
        if b2 <= cap:
            phi = _atan2_near(by * p - 2.0 * bx, bx * p + 2.0 * by)
            b2 = _mod_low(-phi) + p * (1.0 - 1e-15) + _mod_low(psi - phi) - slack
    b4 = _ccc_low(rx, ry, r2, psi, cap, True)
    b5 = _ccc_low(lx, ly, l2, psi, cap, False)
    return (b0, b1, b2, b3, b4, b5)


@njit(cache=True)
def _ccc_low(vx: float, vy: float, v2: float, psi: float, cap: float, right: bool) -> float:
    """Lower bound of RLR (`right`) or LRL: pi, and when that is not above `cap`, the middle
    arc pm exactly plus t and q from `_atan2_near` (inf where the word does not exist)."""
    if not v2 <= _NEAR:
        return INF
    if PI > cap:
        return PI - 1e-9
    pm = TWO_PI - math.acos(min(max(1.0 - 0.125 * v2, -1.0), 1.0))
    phi = _atan2_near(vy, vx)
    if right:
        t = _mod(0.5 * pm - phi)
        low_q = _mod_low(pm - t - psi) if t < TWO_PI - 4.0 * _DELTA else 0.0
    else:
        t = _mod(phi + 0.5 * pm)
        low_q = _mod_low(psi - t + pm) if t < TWO_PI - 4.0 * _DELTA else 0.0
    low_t = 0.0 if t > TWO_PI - 4.0 * _DELTA else max(t - _DELTA, 0.0)
    return low_t + pm * (1.0 - 1e-15) + low_q - 1e-9


@njit(cache=True)
def _may_beat(x: float, y: float, psi: float, sp: float, cp: float, cap: float) -> bool:
    """Whether any word's bound (`_bounds`) is <= cap, stopping at the first that is."""
    slack = 1e-9
    lx, ly = x - sp, y + cp - 1.0
    l2 = lx * lx + ly * ly
    pl = math.sqrt(l2) * (1.0 - 1e-15)
    if pl + psi - slack <= cap:  # LSL: t + q is psi or psi + 2 pi
        if _in_sweep(lx, ly, pl, psi, sp, cp) != 0 or pl + psi + TWO_PI - slack <= cap:
            return True
    rx, ry = x + sp, y - cp + 1.0
    r2 = rx * rx + ry * ry
    pr = math.sqrt(r2) * (1.0 - 1e-15)
    low = TWO_PI - psi if psi > 1e-6 else 0.0
    if pr + low - slack <= cap:  # RSR: 2 pi - psi or 4 pi - psi
        if _in_sweep(rx, ry, pr, psi, sp, cp) != 1 or pr + low + TWO_PI - slack <= cap:
            return True
    mixed = min(psi, TWO_PI - psi) - slack
    ax, ay = x + sp, y - cp - 1.0
    p2 = ax * ax + ay * ay - 4.0
    if p2 + FEAS >= 0.0:
        p = math.sqrt(max(p2, 0.0))
        if p * (1.0 - 1e-15) + mixed <= cap:
            phi = _atan2_near(ay * p + 2.0 * ax, ax * p - 2.0 * ay)
            if _mod_low(phi) + p * (1.0 - 1e-15) + _mod_low(phi - psi) - slack <= cap:
                return True
    bx, by = x - sp, y + cp + 1.0
    q2 = bx * bx + by * by - 4.0
    if q2 + FEAS >= 0.0:
        p = math.sqrt(max(q2, 0.0))
        if p * (1.0 - 1e-15) + mixed <= cap:
            phi = _atan2_near(by * p - 2.0 * bx, bx * p + 2.0 * by)
            if _mod_low(-phi) + p * (1.0 - 1e-15) + _mod_low(psi - phi) - slack <= cap:
                return True
    if PI - slack > cap:
        return False
    return (_ccc_low(rx, ry, r2, psi, cap, True) <= cap
            or _ccc_low(lx, ly, l2, psi, cap, False) <= cap)


@njit(cache=True)
def min_total(x: float, y: float, psi: float, sp: float, cp: float,
              cap: float) -> tuple[float, int]:
    """Shortest total length (unit radius) and its word (ties: first in `WORDS`); (inf, -1)
    when no word is shorter than or equal to `cap` (pass inf for the plain minimum)."""
    lb = _bounds(x, y, psi, sp, cp, cap)
    best, bk = cap, -1
    done = 0
    for _ in range(6):
        k, low = -1, INF
        for j in range(6):
            if not (done >> j) & 1 and lb[j] < low:
                k, low = j, lb[j]
        if k < 0 or low > best:
            break
        done |= 1 << k
        tot = word_total(k, x, y, psi, sp, cp)
        if tot < best or (tot == best and (bk < 0 or k < bk)):
            best, bk = tot, k
    if bk < 0:
        return INF, -1
    return best, bk


@njit(cache=True)
def min_lengths(start: np.ndarray, goal: np.ndarray, inv: np.ndarray, out: np.ndarray,
                idx: np.ndarray) -> None:
    """Shortest total (units of R, >= 0) and word of each `(m, 3)` start/goal pair into `out`,
    `idx`; `inv` = 1 / R, `(m,)` or `(1,)`. The frame change of `dubins_kernel.flat_word_totals`."""
    m = start.shape[0]
    scalar = inv.shape[0] == 1
    for i in range(m):
        h0 = start[i, 2]
        c0, s0 = math.cos(h0), math.sin(h0)
        dx, dy = goal[i, 0] - start[i, 0], goal[i, 1] - start[i, 1]
        r = inv[0] if scalar else inv[i]
        x = (c0 * dx + s0 * dy) * r
        y = (c0 * dy - s0 * dx) * r
        psi = _mod(goal[i, 2] - h0)
        tot, k = min_total(x, y, psi, math.sin(psi), math.cos(psi), INF)
        out[i] = max(tot, 0.0)
        idx[i] = k


@njit(cache=True)
def _to_point(x: float, y: float) -> float:
    """A lower bound (unit radius) of the shortest path from the origin, heading 0, to the
    point (x, y) with any final heading: the shorter turn-then-straight path when the point
    is outside both turning circles (that path is then optimal: Bui, Soueres, Boissonnat
    and Laumond 1994), else the distance."""
    d = math.sqrt(x * x + y * y)
    best = INF
    for sgn in (1.0, -1.0):  # left circle (0, 1); the right one by mirroring y
        yy = sgn * y
        rho2 = x * x + (yy - 1.0) * (yy - 1.0)
        if rho2 < 1.0 + 1e-9:
            return d * (1.0 - 1e-12)
        rho = math.sqrt(rho2)
        turn = _mod(math.atan2(yy - 1.0, x) - math.acos(1.0 / rho) + 0.5 * PI)
        if turn > TWO_PI - 1e-9:
            turn = 0.0
        best = min(best, max(turn, 0.0) + math.sqrt(rho2 - 1.0))
    return max(d, best * (1.0 - 1e-12) - 1e-9)


@njit(cache=True)
def dp_leg(value: np.ndarray, x: np.ndarray, y: np.ndarray, a: np.ndarray, b: np.ndarray,
           dx: float, dy: float, radius: float, scale: float, new: np.ndarray,
           arg: np.ndarray) -> None:
    """new[j] = min_i value[i] + c(a_i, b_j), arg[j] its first minimiser i (eq. in
    missions.headings), c = scale * R * Dubins total from heading a_i (goal at x[i], y[i] in
    that start's frame, units of R) to heading b_j; (dx, dy) the leg in units of R.

    Each start heading gets a lower bound of every leg from it (`_to_point`), each goal
    heading one of every leg to it (the reversed path); start headings are scanned by
    value + bound, from the previous goal heading's minimiser, until the bound exceeds the
    best. Only entries whose bounds are below the best are evaluated."""
    rs = radius * scale
    sa, ca = np.sin(a), np.cos(a)
    sb, cb = np.sin(b), np.cos(b)
    key = np.empty(a.size)
    for i in range(a.size):
        key[i] = value[i] + _to_point(x[i], y[i]) * rs
    low_b = np.empty(b.size)
    for j in range(b.size):  # reversed: from (p1, b + pi) to the point p0
        c, s = -cb[j], -sb[j]
        low_b[j] = _to_point(-(c * dx + s * dy), -(c * dy - s * dx)) * rs
    order = np.argsort(key, kind="mergesort")
    prev = -1
    for j in range(b.size):
        best, bi = INF, -1
        bj = b[j]
        for r in range(-1, order.size):
            i = prev if r < 0 else order[r]
            if i < 0:
                continue
            v = value[i]
            if r >= 0 and key[i] > best:
                break  # sorted by key: no later start heading can do better
            if v + low_b[j] > best:
                continue
            cap = INF if bi < 0 else (best - v) / rs * (1.0 + 1e-12) + 1e-12
            sp = sb[j] * ca[i] - cb[j] * sa[i]  # sin(b - a), cos(b - a) as in leg_costs
            cp = cb[j] * ca[i] + sb[j] * sa[i]
            psi = _mod(bj - a[i])
            if bi >= 0 and not _may_beat(x[i], y[i], psi, sp, cp, cap):
                continue
            tot, _ = min_total(x[i], y[i], psi, sp, cp, cap)
            if tot == INF:
                continue
            c = tot * radius
            if scale != 1.0:
                c = c * scale
            t = v + c
            if t < best or (t == best and i < bi):
                best, bi = t, i
        new[j] = best
        arg[j] = bi
        prev = bi
