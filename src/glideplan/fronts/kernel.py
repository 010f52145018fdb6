"""Compiled (numba) narrow-band kernels of the front: one TVD-RK2 stage, the active set.

The level set phi on a `LatLonGrid` solves

    d phi/dt + H(grad phi; x, t) = 0,   H(p) = max_k ( a_k |p| + d_k(x, t) . p ),

with p the physical gradient (hx_i = R cos(lat_i) dlon, hy = R dlat), d_k = b_k + s_k c(x, t)
(constant drifts b_k, a drift field c linear between two time levels). Each term is
discretised monotonically -- Osher-Sethian/Godunov upwinding of a_k |p| on ENO2 one-sided
differences (Osher & Fedkiw 2003, sec. 3.3 and 6.4), upwind differences for d_k . p -- and the
max of monotone consistent numerical Hamiltonians is monotone and consistent, so the scheme
converges to the viscosity solution (Barles-Souganidis). Blocked nodes (obstacles, or nodes
not yet reached after their block time) hold +B; second differences that touch them are
dropped (first order there) and advection never differences across them.

Only the active nodes are updated: those within two nodes (the ENO2 stencil) of the band
|phi| < B. Every other node has a zero rate exactly (its stencil is flat at +-B), so the
narrow band costs O(band) per step instead of O(grid).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

__all__ = ["next_active", "rk_stage", "rk_stage_parallel", "stage_two", "stage_two_parallel"]

INF = np.inf
SNAP = 0.97


@njit(cache=True, inline="always")
def _col(j: int, dj: int, nx: int, periodic: bool) -> int:
    jj = j + dj
    if periodic:
        jj = jj % nx
    elif jj < 0:
        jj = 0
    elif jj > nx - 1:
        jj = nx - 1
    return jj


@njit(cache=True, inline="always")
def _row(i: int, di: int, ny: int) -> int:
    ii = i + di
    if ii < 0:
        return 0
    if ii > ny - 1:
        return ny - 1
    return ii


@njit(cache=True, inline="always")
def _blocked(idx: int, t: float, arrival: np.ndarray, tb: np.ndarray, lo: np.ndarray,
             has_drift: bool, may: np.ndarray) -> bool:
    if may[idx] == 0:  # one byte: open water/air, never blocked (most nodes)
        return False
    if t > tb[idx] and arrival[idx] == INF:  # tb first: +inf (open water) ends it at once
        return True
    if has_drift and (lo[0, idx] != lo[0, idx]):
        return True
    return False


@njit(cache=True, inline="always")
def _minmod(a: float, b: float) -> float:
    if a * b <= 0.0:
        return 0.0
    if abs(a) < abs(b):
        return a
    return b


@njit(cache=True, inline="always")
def _one_sided(c: float, vm1: float, vm2: float, vp1: float, vp2: float, bm1: bool, bm2: bool,
               bp1: bool, bp2: bool, h: float) -> tuple[float, float]:
    """ENO2 (D-, D+) at a node from values at -2..+2; second differences touching blocks dropped."""
    h2 = h * h
    d2c = 0.0 if (bm1 or bp1) else (vp1 - 2.0 * c + vm1) / h2
    d2m = 0.0 if (bm1 or bm2) else (c - 2.0 * vm1 + vm2) / h2
    d2p = 0.0 if (bp1 or bp2) else (vp2 - 2.0 * vp1 + c) / h2
    dm = (c - vm1) / h + 0.5 * h * _minmod(d2m, d2c)
    dp = (vp1 - c) / h - 0.5 * h * _minmod(d2c, d2p)
    return dm, dp


@njit(cache=True)
def _rate(idx: int, p: np.ndarray, t: float, w: float, ny: int, nx: int, periodic: bool,
          hx: np.ndarray, hy: float, a: np.ndarray, b: np.ndarray, s: np.ndarray,
          arrival: np.ndarray, tb: np.ndarray, lo: np.ndarray, hi: np.ndarray,
          has_drift: bool, may: np.ndarray) -> tuple[float, float]:
    """(d phi/dt, largest characteristic speed / spacing) at node idx (module docstring)."""
    i = idx // nx
    j = idx - i * nx
    c = p[idx]
    # x neighbours
    jm1 = i * nx + _col(j, -1, nx, periodic)
    jm2 = i * nx + _col(j, -2, nx, periodic)
    jp1 = i * nx + _col(j, 1, nx, periodic)
    jp2 = i * nx + _col(j, 2, nx, periodic)
    bxm1 = _blocked(jm1, t, arrival, tb, lo, has_drift, may)
    bxm2 = _blocked(jm2, t, arrival, tb, lo, has_drift, may)
    bxp1 = _blocked(jp1, t, arrival, tb, lo, has_drift, may)
    bxp2 = _blocked(jp2, t, arrival, tb, lo, has_drift, may)
    dxm, dxp = _one_sided(c, p[jm1], p[jm2], p[jp1], p[jp2], bxm1, bxm2, bxp1, bxp2, hx[i])
    # y neighbours
    im1 = _row(i, -1, ny) * nx + j
    im2 = _row(i, -2, ny) * nx + j
    ip1 = _row(i, 1, ny) * nx + j
    ip2 = _row(i, 2, ny) * nx + j
    bym1 = _blocked(im1, t, arrival, tb, lo, has_drift, may)
    bym2 = _blocked(im2, t, arrival, tb, lo, has_drift, may)
    byp1 = _blocked(ip1, t, arrival, tb, lo, has_drift, may)
    byp2 = _blocked(ip2, t, arrival, tb, lo, has_drift, may)
    dym, dyp = _one_sided(c, p[im1], p[im2], p[ip1], p[ip2], bym1, bym2, byp1, byp2, hy)
    g2 = (max(dxm, 0.0) ** 2 + min(dxp, 0.0) ** 2 + max(dym, 0.0) ** 2 + min(dyp, 0.0) ** 2)
    grad = np.sqrt(g2)
    # advection: upwind, never across a blocked neighbour (the other side, else 0)
    axm, axp, aym, ayp = dxm, dxp, dym, dyp
    if bxm1:
        axm = 0.0 if bxp1 else dxp
    if bxp1:
        axp = 0.0 if bxm1 else dxm
    if bym1:
        aym = 0.0 if byp1 else dyp
    if byp1:
        ayp = 0.0 if bym1 else dym
    cu = 0.0
    cv = 0.0
    if has_drift:
        cu = (1.0 - w) * lo[0, idx] + w * hi[0, idx]
        cv = (1.0 - w) * lo[1, idx] + w * hi[1, idx]
        if cu != cu or cv != cv:
            cu = 0.0
            cv = 0.0
    best = -INF
    smax = 0.0
    inv_h = 1.0 / min(hx[i], hy)
    for k in range(a.size):
        bx = b[k, 0] + s[k] * cu
        by = b[k, 1] + s[k] * cv
        adv = (max(bx, 0.0) * axm + min(bx, 0.0) * axp + max(by, 0.0) * aym
               + min(by, 0.0) * ayp)
        r = a[k] * grad + adv
        if r > best:
            best = r
        sp = (a[k] + abs(bx) + abs(by)) * inv_h
        if sp > smax:
            smax = sp
    return best, smax


def _rk_stage(phi: np.ndarray, out: np.ndarray, act: np.ndarray, t: float, w: float, dt_cap: float,
             band: float, ny: int, nx: int, periodic: bool, hx: np.ndarray, hy: float,
             a: np.ndarray, b: np.ndarray, s: np.ndarray, arrival: np.ndarray, tb: np.ndarray,
             lo: np.ndarray, hi: np.ndarray, has_drift: bool, cfl: float,
             may: np.ndarray) -> float:
    """Stage 1: out = phi - dt L(phi) on the active nodes, dt = min(cfl / max(speed / spacing)
    over the active nodes, dt_cap) (the CFL condition); returns the dt used."""
    n = act.size
    rates = np.empty(n)
    speeds = np.empty(n)
    for m in prange(n):  # nodes are independent: both cores share the band
        r, sp = _rate(act[m], phi, t, w, ny, nx, periodic, hx, hy, a, b, s, arrival, tb, lo, hi,
                      has_drift, may)
        rates[m] = r
        speeds[m] = sp
    smax = 1e-300
    for m in range(n):
        if speeds[m] > smax:
            smax = speeds[m]
    dt = min(cfl / smax, dt_cap)
    for m in prange(n):
        idx = act[m]
        if _blocked(idx, t, arrival, tb, lo, has_drift, may):
            out[idx] = band
        else:
            v = phi[idx] - dt * rates[m]
            out[idx] = min(max(v, -band), band)
    return dt


def _stage_two(phi: np.ndarray, p1: np.ndarray, act: np.ndarray, t: float, t1: float, w1: float,
              dt: float, band: float, ny: int, nx: int, periodic: bool, hx: np.ndarray,
              hy: float, a: np.ndarray, b: np.ndarray, s: np.ndarray, arrival: np.ndarray,
              tb: np.ndarray, lo: np.ndarray, hi: np.ndarray, has_drift: bool,
              may: np.ndarray) -> tuple[int, float]:
    """Stage 2 of TVD-RK2 (Heun): phi <- (phi + p1 - dt L(p1; t1)) / 2, arrival times recorded.

    A node whose phi crosses from > 0 to <= 0 gets arrival t + dt phi_old / (phi_old - phi_new)
    (linear in time). Returns (newly reached nodes, largest decrease of phi on the outside).
    """
    n = act.size
    new = np.empty(n)
    for m in prange(n):
        idx = act[m]
        if _blocked(idx, t1, arrival, tb, lo, has_drift, may):
            new[m] = band
            continue
        r, _ = _rate(idx, p1, t1, w1, ny, nx, periodic, hx, hy, a, b, s, arrival, tb, lo, hi,
                     has_drift, may)
        v = 0.5 * (phi[idx] + p1[idx] - dt * r)
        # Snap the band's tails to +-B: the clipped profile rounds off under ENO2 and would
        # otherwise keep a wide fringe of nodes a hair inside the band (they are >= 5.8 cells
        # from the zero level, upwind information never comes from there).
        if v > SNAP * band:
            v = band
        elif v < -SNAP * band:
            v = -band
        new[m] = v
    reached = 0
    dmax = 0.0
    for m in range(n):
        idx = act[m]
        old = phi[idx]
        v = new[m]
        if old > 0.0 and old - v > dmax:
            dmax = old - v
        if old > 0.0 and v <= 0.0 and arrival[idx] == INF:
            arrival[idx] = t + dt * old / (old - v)
            reached += 1
        phi[idx] = v
    for m in range(n):
        idx = act[m]
        p1[idx] = phi[idx]
    return reached, dmax


@njit(cache=True)
def next_active(phi: np.ndarray, act: np.ndarray, band: float, mark: np.ndarray, stamp: int,
                ny: int, nx: int, periodic: bool, edge_margin: int) -> tuple[np.ndarray, int, int]:
    """Active nodes for the next step: the band |phi| < B grown by 2 nodes along rows/columns.

    Returns (active indices, band size, edge bits: 1 south, 2 north, 4 west, 8 east -- the band
    lies within `edge_margin` nodes of that side of a non-periodic grid).
    """
    out = np.empty(act.size * 9 + 9, dtype=np.int64)
    cnt = 0
    nband = 0
    edges = 0
    for m in range(act.size):
        idx = act[m]
        if not (abs(phi[idx]) < band):
            continue
        nband += 1
        i = idx // nx
        j = idx - i * nx
        if i < edge_margin:
            edges |= 1
        if i > ny - 1 - edge_margin:
            edges |= 2
        if not periodic:
            if j < edge_margin:
                edges |= 4
            if j > nx - 1 - edge_margin:
                edges |= 8
        for d in range(-2, 3):
            jj = j + d
            if periodic:
                jj = jj % nx
            if 0 <= jj < nx:
                q = i * nx + jj
                if mark[q] != stamp:
                    mark[q] = stamp
                    out[cnt] = q
                    cnt += 1
            ii = i + d
            if d != 0 and 0 <= ii < ny:
                q = ii * nx + j
                if mark[q] != stamp:
                    mark[q] = stamp
                    out[cnt] = q
                    cnt += 1
    res = out[:cnt].copy()
    res.sort()  # row-major order: neighbours in cache (random order costs ~10x here)
    return res, nband, edges


# Each stage compiled twice: serial, and with the nodes split over the cores (numba prange).
# The driver picks the parallel one for large bands only (thread start-up costs ~10-50 us per
# call, and oversubscribed cores -- e.g. pytest -n 2 -- stall at the barrier).
rk_stage = njit(cache=True)(_rk_stage)
rk_stage_parallel = njit(cache=True, parallel=True)(_rk_stage)
stage_two = njit(cache=True)(_stage_two)
stage_two_parallel = njit(cache=True, parallel=True)(_stage_two)
