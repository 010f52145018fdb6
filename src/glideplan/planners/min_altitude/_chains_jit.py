"""Compiled (numba) chain solver of the minimum-altitude synthesis (`chains._solve_chains`).

The same computation as the NumPy path of `chains` (`_chain_eval` on the grid, the cell test,
`_newton_2d`, the final evaluation with the cost), in one compiled call per synthesis, so no
NumPy temporaries are built for the ~15,000 grid points and the ~35 Newton starts of a goal.
A chain of n B arcs (first turn L) with switch angle s and first arc a1 = 2 s t has

    lambda = (v_stf - v_ms) / -cos s,  theta = a1 - s,
    a_n = (a1 - psi1 if n even else psi1 - a1 + 2 s) modulo 2 pi into [s - pi, s + pi),
    end = e^{i theta} [(G(s) - G(s - a1)) + (n - 2)(G(s) - G(-s)) + (G(hi) - G(lo))] / u_max

with (lo, hi) = (s - a_n, s) for n even and (-s, -s + a_n) for n odd, G the heading
primitive of the clipped B-arc speed (`_jit._one`; altitude likewise with W). On the grid,
G(s), G(-s) and G(s - a1) are shared by every task and G of the last arc by the tasks of the
same parity and final heading, so a goal's grid costs ~13,000 primitives instead of 77,000.
Serial; imported lazily (importing it imports numba).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from glideplan.planners.min_altitude._jit import _lam_terms, _one

__all__ = ["solve_chains"]

TWO_PI = 2.0 * math.pi
# constants vector c: v_ms, v_stall, v_max, a, w_ms, w_stall, w_max, u_max, lam_s, scale


@njit(cache=True)
def _g(phi: float, lm: float, t: tuple, c: np.ndarray) -> tuple[float, float, float]:
    """Re G, Im G, W at heading phi for lambda lm with its `_lam_terms` t."""
    p_re, p_im, w, _ = _one(phi, lm, t[0], t[1], t[2], t[3], t[4], c[0], c[1], c[2], c[3],
                            c[4], c[5], c[6])
    return p_re, p_im, w


@njit(cache=True)
def _wrap(x: float, low: float) -> float:
    """x modulo 2 pi into [low, low + 2 pi) (as `_tasks._wrap`)."""
    r = (x - low) % TWO_PI
    return (0.0 if r >= TWO_PI else r) + low


@njit(cache=True)
def _last(n: int, s: float, a1: float, gpsi: float) -> tuple[float, float, float]:
    """The last arc's angle a_n and its heading interval (lo, hi)."""
    if n % 2 == 0:  # the last arc turns R from +s
        an = _wrap(a1 - gpsi, s - math.pi)
        return an, s - an, s
    an = _wrap(gpsi - a1 + 2.0 * s, s - math.pi)  # it turns L from -s
    return an, -s, -s + an


@njit(cache=True)
def _point(n: int, s: float, t: float, gx: float, gy: float, gpsi: float,
           c: np.ndarray) -> tuple[float, float, float, float, float, float]:
    """Residual (end - goal)/R_stf (re, im), a_n, lambda, theta and cost (m) of one chain."""
    lm = c[8] / -math.cos(s)
    a1 = 2.0 * s * t
    theta = a1 - s
    an, lo, hi = _last(n, s, a1, gpsi)
    tl = _lam_terms(lm, c[0], c[1], c[2], c[3], c[4], c[5], c[6])
    p0r, p0i, w0 = _g(s, lm, tl, c)
    p1r, p1i, w1 = _g(-s, lm, tl, c)
    p2r, p2i, w2 = _g(s - a1, lm, tl, c)
    p3r, p3i, w3 = _g(lo, lm, tl, c)
    p4r, p4i, w4 = _g(hi, lm, tl, c)
    inner = n - 2
    tr = (p0r - p2r) + inner * (p0r - p1r) + (p4r - p3r)
    ti = (p0i - p2i) + inner * (p0i - p1i) + (p4i - p3i)
    ct, st = math.cos(theta), math.sin(theta)
    u = c[7]
    zr = (ct * tr - st * ti) / u
    zi = (st * tr + ct * ti) / u
    cost = ((w0 - w2) + inner * (w0 - w1) + (w4 - w3)) / u
    return (zr - gx) / c[9], (zi - gy) / c[9], an, lm, theta, cost


@njit(cache=True)
def _res(n: int, s: float, t: float, g: np.ndarray, c: np.ndarray) -> tuple[float, float]:
    """The residual (re, im) of `_point`."""
    r = _point(n, s, t, g[0], g[1], g[2], c)
    return r[0], r[1]


@njit(cache=True)
def _grid(n: np.ndarray, goals: np.ndarray, S: np.ndarray, T: np.ndarray,
          c: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Residuals (re, im) of every task on the grid S x T, shape (tasks, len S, len T)."""
    K, ns, nt = n.size, S.size, T.size
    re = np.empty((K, ns, nt))
    im = np.empty((K, ns, nt))
    last = np.empty((K, nt, 3))  # G of the last arc's free end, per task (shared if equal)
    u, scale = c[7], c[9]
    for i in range(ns):
        s = S[i]
        lm = c[8] / -math.cos(s)
        tl = _lam_terms(lm, c[0], c[1], c[2], c[3], c[4], c[5], c[6])
        p0r, p0i, _ = _g(s, lm, tl, c)
        p1r, p1i, _ = _g(-s, lm, tl, c)
        for k in range(K):
            src = k
            for k2 in range(k):  # a task of the same parity and final heading: its values
                if n[k2] % 2 == n[k] % 2 and goals[k2, 2] == goals[k, 2]:
                    src = k2
                    break
            for j in range(nt):
                if src != k:
                    last[k, j, 0], last[k, j, 1] = last[src, j, 0], last[src, j, 1]
                    continue
                _, lo, hi = _last(n[k], s, 2.0 * s * T[j], goals[k, 2])
                free = lo if n[k] % 2 == 0 else hi
                last[k, j, 0], last[k, j, 1], last[k, j, 2] = _g(free, lm, tl, c)
        for j in range(nt):
            a1 = 2.0 * s * T[j]
            theta = a1 - s
            p2r, p2i, _ = _g(s - a1, lm, tl, c)
            ct, st = math.cos(theta), math.sin(theta)
            for k in range(K):
                inner = n[k] - 2
                if n[k] % 2 == 0:  # (G(s) - G(lo)); n odd: (G(hi) - G(-s))
                    er, ei = p0r - last[k, j, 0], p0i - last[k, j, 1]
                else:
                    er, ei = last[k, j, 0] - p1r, last[k, j, 1] - p1i
                tr = (p0r - p2r) + inner * (p0r - p1r) + er
                ti = (p0i - p2i) + inner * (p0i - p1i) + ei
                re[k, i, j] = ((ct * tr - st * ti) / u - goals[k, 0]) / scale
                im[k, i, j] = ((st * tr + ct * ti) / u - goals[k, 1]) / scale
    return re, im


@njit(cache=True)
def _straddles(v: np.ndarray, k: int, i: int, j: int) -> bool:
    """The cell (i, j) of task k may hold a zero of v (corners' range widened by half)."""
    a, b, e, f = v[k, i, j], v[k, i + 1, j], v[k, i, j + 1], v[k, i + 1, j + 1]
    lo = min(min(a, b), min(e, f))
    hi = max(max(a, b), max(e, f))
    margin = 0.5 * (hi - lo)  # allow for curvature inside the cell
    return lo - margin <= 0.0 and hi + margin >= 0.0


@njit(cache=True)
def _newton(n: int, s: float, t: float, g: np.ndarray, c: np.ndarray, lower: np.ndarray,
            upper: np.ndarray) -> tuple[float, float, float]:
    """`chains._newton_2d` for one start: central differences, steps limited to 0.25,
    clipped to the box, stopped when converged or clearly not converging."""
    h, max_step = 1e-7, 0.25
    err = np.inf
    for it in range(40):
        f0r, f0i = _res(n, s, t, g, c)
        err = math.hypot(f0r, f0i)
        ar, ai = _res(n, s + h, t, g, c)
        br, bi = _res(n, s - h, t, g, c)
        cr, ci = _res(n, s, t + h, g, c)
        dr, di = _res(n, s, t - h, g, c)
        a, b = (ar - br) / (2 * h), (cr - dr) / (2 * h)
        cc, d = (ai - bi) / (2 * h), (ci - di) / (2 * h)
        det = a * d - b * cc
        ok = abs(det) > 1e-300
        sp = -(d * f0r - b * f0i) / det if ok else 0.0
        sq = -(-cc * f0r + a * f0i) / det if ok else 0.0
        big = max(max(abs(sp), abs(sq)) / max_step, 1.0)
        s = min(max(s + sp / big, lower[0]), upper[0])
        t = min(max(t + sq / big, lower[1]), upper[1])
        done = err < 1e-14 or (abs(sp) + abs(sq)) < 1e-14 or not ok
        if it >= 12 and err > 1e-4:
            done = True
        if done:
            break
    fr, fi = _res(n, s, t, g, c)
    final = math.hypot(fr, fi)
    return s, t, min(final, err if math.isfinite(err) else final)


@njit(cache=True)
def solve_chains(n: np.ndarray, goals: np.ndarray, S: np.ndarray, T: np.ndarray,
                 c: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """Every Newton-polished chain from the grid cells that may hold a root.

    Returns rows (task, s, t, Newton residual, |residual| at t clipped to [0, 1], a_n,
    lambda, theta, cost), in the NumPy path's order (task, then s cell, then t cell).
    """
    re, im = _grid(n, goals, S, T, c)
    K, ns, nt = n.size, S.size, T.size
    rows = []
    for k in range(K):
        for i in range(ns - 1):
            for j in range(nt - 1):
                if not (_straddles(re, k, i, j) and _straddles(im, k, i, j)):
                    continue
                s0 = 0.5 * (S[i] + S[i + 1])
                t0 = 0.5 * (T[j] + T[j + 1])
                s1, t1, err = _newton(n[k], s0, t0, goals[k], c, lower, upper)
                tc = min(max(t1, 0.0), 1.0)
                r_re, r_im, an, lm, theta, cost = _point(n[k], s1, tc, goals[k, 0],
                                                         goals[k, 1], goals[k, 2], c)
                rows.append((float(k), s1, t1, err, math.hypot(r_re, r_im), an, lm, theta,
                             cost))
    out = np.empty((len(rows), 9))
    for m in range(len(rows)):
        for q in range(9):
            out[m, q] = rows[m][q]
    return out
