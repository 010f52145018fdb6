"""The chain solver of the minimum-altitude synthesis: n B arcs switching where v = v_stf.

H = 0 puts every switch at phi = psi - theta = +-s with cos s = -(v_stf - v_ms)/lambda, so
interior arcs turn exactly 2 s and the chain is fixed by (s, first arc angle); the two
position equations are solved by a grid scan and a vectorised 2-D Newton polish.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from glideplan.planners.min_altitude._tasks import (
    _ANGLE_TOL,
    _S_MIN,
    _Found,
    _saturated_time,
    _Setup,
    _Task,
    _wrap,
)

__all__: list[str] = []


# ----- chains of B arcs: 2-D root finding over (s, first-arc fraction) -----------------------


def _chain_eval(
    st: _Setup,
    n: np.ndarray,
    s: np.ndarray,
    t: np.ndarray,
    goal: np.ndarray,
    with_cost: bool = False,
) -> tuple[np.ndarray, ...]:
    """Chains of n B arcs (first turn L) with switch angle s and first arc 2 s t.

    All inputs broadcast (`goal` has a last axis (x, y, psi)). Returns the residual
    (end - goal)/R_stf (complex), the last arc's angle, lambda, theta [and the cost, m].
    """
    kern = st.kern
    n, s, t = np.broadcast_arrays(np.asarray(n), np.asarray(s, dtype=float), np.asarray(t))
    gx, gy, gpsi = goal[..., 0], goal[..., 1], goal[..., 2]
    lam = st.lam_s / -np.cos(s)
    a1 = 2.0 * s * t
    theta = a1 - s
    even = n % 2 == 0
    # n even: the last arc turns R from +s; n odd: it turns L from -s
    an = _wrap(np.where(even, a1 - gpsi, gpsi - a1 + 2.0 * s), s - math.pi)
    last_lo = np.where(even, s - an, -s)
    last_hi = np.where(even, s, -s + an)
    phi = np.stack(np.broadcast_arrays(s, -s, s - a1, last_lo, last_hi))
    P, W, _ = kern.primitives(phi, np.broadcast_to(lam, phi.shape))
    inner = n - 2
    tot = (P[0] - P[2]) + inner * (P[0] - P[1]) + (P[4] - P[3])
    z = np.exp(1j * theta) * tot / kern.u_max
    res = (z - (gx + 1j * gy)) / st.scale
    if not with_cost:
        return res, an, lam, theta
    cost = ((W[0] - W[2]) + inner * (W[0] - W[1]) + (W[4] - W[3])) / kern.u_max
    return res, an, lam, theta, cost


def _newton_2d(
    fun: Callable[[np.ndarray, np.ndarray, np.ndarray], np.ndarray],
    p: np.ndarray,
    q: np.ndarray,
    *,
    lower: tuple[float, float],
    upper: tuple[float, float],
    iterations: int = 40,
    step: float = 1e-7,
    max_step: float = 0.25,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vectorised Newton on a complex residual fun(p, q, index) of two real unknowns
    (central differences; `index` selects the start's data). Each start is clipped to the
    box and retired once converged or clearly not converging; returns (p, q, |residual|)."""
    p, q = p.astype(float).copy(), q.astype(float).copy()
    active = np.arange(p.size)
    err = np.full(p.size, np.inf)
    for it in range(iterations):
        if active.size == 0:
            break
        m = active.size
        pa, qa = p[active], q[active]
        idx = np.tile(active, 5)
        hp = np.concatenate([pa, pa + step, pa - step, pa, pa])
        hq = np.concatenate([qa, qa, qa, qa + step, qa - step])
        f = fun(hp, hq, idx)
        f0 = f[:m]
        err[active] = np.abs(f0)
        dp = (f[m : 2 * m] - f[2 * m : 3 * m]) / (2 * step)
        dq = (f[3 * m : 4 * m] - f[4 * m :]) / (2 * step)
        a, b, c, d = dp.real, dq.real, dp.imag, dq.imag
        det = a * d - b * c
        ok = np.abs(det) > 1e-300
        safe = np.where(ok, det, 1.0)
        sp = np.where(ok, -(d * f0.real - b * f0.imag) / safe, 0.0)
        sq = np.where(ok, -(-c * f0.real + a * f0.imag) / safe, 0.0)
        big = np.maximum(np.maximum(np.abs(sp), np.abs(sq)) / max_step, 1.0)
        p[active] = np.clip(pa + sp / big, lower[0], upper[0])
        q[active] = np.clip(qa + sq / big, lower[1], upper[1])
        done = (np.abs(f0) < 1e-14) | ((np.abs(sp) + np.abs(sq)) < 1e-14) | ~ok
        if it >= 12:
            done |= np.abs(f0) > 1e-4
        active = active[~done]
    final = np.abs(fun(p, q, np.arange(p.size)))
    return p, q, np.minimum(final, np.where(np.isfinite(err), final, err))


def _solve_chains(
    tasks: list[_Task], st: _Setup, grid: tuple[int, int]
) -> list[tuple[_Task, _Found]]:
    """All chains of all tasks at once: one grid scan and one Newton run (vectorised NumPy;
    compiled in one call unless `extremals.COMPILED` is False)."""
    if not tasks:
        return []
    from glideplan.planners.min_altitude import extremals

    if extremals.COMPILED:
        return _solve_chains_compiled(tasks, st, grid)
    ns, nt = grid
    n = np.array([task.family.arcs for task in tasks])[:, None, None]
    goals = np.array([task.goal.as_array() for task in tasks])[:, None, None, :]
    S = np.linspace(_S_MIN, math.pi, ns)[None, :, None]
    T = np.linspace(-0.05, 1.05, nt)[None, None, :]
    res = _chain_eval(st, n, S, T, goals)[0]
    cells = np.ones((len(tasks), ns - 1, nt - 1), dtype=bool)
    for comp in (res.real, res.imag):
        corners = np.stack([comp[:, :-1, :-1], comp[:, 1:, :-1], comp[:, :-1, 1:], comp[:, 1:, 1:]])
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        margin = 0.5 * (hi - lo)  # allow for curvature inside the cell
        cells &= (lo - margin <= 0.0) & (hi + margin >= 0.0)
    k, i, j = np.nonzero(cells)
    if k.size == 0:
        return []
    s0 = 0.5 * (S[0, i, 0] + S[0, i + 1, 0])
    t0 = 0.5 * (T[0, 0, j] + T[0, 0, j + 1])
    nk, gk = n[k, 0, 0], goals[k, 0, 0, :]

    def fun(s: np.ndarray, t: np.ndarray, idx: np.ndarray) -> np.ndarray:
        return _chain_eval(st, nk[idx], s, t, gk[idx])[0]

    s1, t1, err = _newton_2d(fun, s0, t0, lower=(_S_MIN * 0.999, -0.3), upper=(math.pi, 1.3))
    keep = (err < 1e-9) & (t1 >= -1e-9) & (t1 <= 1 + 1e-9)
    k, s1, t1 = k[keep], s1[keep], np.clip(t1[keep], 0.0, 1.0)
    res, an, lam, theta, cost = _chain_eval(st, nk[keep], s1, t1, gk[keep], with_cost=True)
    out: list[tuple[_Task, _Found]] = []
    seen: set[tuple] = set()
    for m in range(k.size):
        s, a_n = float(s1[m]), float(an[m])
        key = (int(k[m]), round(s, 7), round(float(t1[m]), 7))
        if key in seen or abs(res[m]) > 1e-9 or not -_ANGLE_TOL <= a_n <= 2 * s + _ANGLE_TOL:
            continue
        seen.add(key)
        task = tasks[int(k[m])]
        a_n = min(max(a_n, 0.0), 2 * s)
        found = _chain_found(
            task, st, s, 2 * s * float(t1[m]), a_n, float(lam[m]), float(theta[m]), float(cost[m])
        )
        out.append((task, found))
    return out


def _solve_chains_compiled(
    tasks: list[_Task], st: _Setup, grid: tuple[int, int]
) -> list[tuple[_Task, _Found]]:
    """`_solve_chains` by the compiled kernel (`_chains_jit.solve_chains`): the same grid,
    cell test, Newton polish and acceptance rules."""
    from glideplan.planners.min_altitude._chains_jit import solve_chains

    ns, nt = grid
    k = st.kern
    consts = np.array([k.v_ms, k.v_stall, k.v_max, k.a, k.w_ms, k.w_stall, k.w_max, k.u_max,
                       st.lam_s, st.scale])  # fmt: skip
    rows = solve_chains(
        np.array([task.family.arcs for task in tasks], dtype=np.int64),
        np.array([task.goal.as_array() for task in tasks], dtype=float),
        np.linspace(_S_MIN, math.pi, ns),
        np.linspace(-0.05, 1.05, nt),
        consts,
        np.array([_S_MIN * 0.999, -0.3]),
        np.array([math.pi, 1.3]),
    )
    out: list[tuple[_Task, _Found]] = []
    seen: set[tuple] = set()
    for kk, s, t, err, res, an, lam, theta, cost in rows.tolist():
        if not (err < 1e-9 and -1e-9 <= t <= 1 + 1e-9):
            continue
        t = min(max(t, 0.0), 1.0)
        key = (int(kk), round(s, 7), round(t, 7))
        if key in seen or res > 1e-9 or not -_ANGLE_TOL <= an <= 2 * s + _ANGLE_TOL:
            continue
        seen.add(key)
        task = tasks[int(kk)]
        an = min(max(an, 0.0), 2 * s)
        out.append((task, _chain_found(task, st, s, 2 * s * t, an, lam, theta, cost)))
    return out


def _chain_found(
    task: _Task,
    st: _Setup,
    s: float,
    a1: float,
    an: float,
    lam: float,
    theta: float,
    cost: float,
) -> _Found:
    n, g = task.family.arcs, st.glider
    angles = [a1, *([2.0 * s] * (n - 2)), an]
    dirs = [1 if k % 2 == 0 else -1 for k in range(n)]
    stall, phi0 = 0.0, -theta
    for d, angle in zip(dirs, angles, strict=True):
        stall += _saturated_time(phi0, d, angle, lam, g)
        phi0 += d * angle
    info = {
        "lambda": lam,
        "switch_angle": s,
        "angles": [a * d for d, a in zip(dirs, angles, strict=True)],
        "saturated_time": float(stall),
    }
    moves = tuple(("B", d, a) for d, a in zip(dirs, angles, strict=True))
    return _Found(moves, cost, info, theta=theta)
