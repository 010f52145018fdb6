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

# The threading layer (TBB if present: thread- and fork-safe; else numba's work queue, whose
# launches `glideplan.compute.kernel_section` serialises) is chosen before any kernel runs.
from glideplan.compute import configure_threading

configure_threading()

__all__ = ["next_active", "rk_stage", "stage_two"]

INF = np.inf
SNAP = 0.97


@njit(cache=True)
def _blk(t: float, tb: float, arr: float, lo: float, has_drift: bool) -> bool:
    """Blocked, from scalars: not reached and past its block time, or no drift data (NaN)."""
    if t > tb and arr == INF:
        return True
    return has_drift and lo != lo


@njit(cache=True)
def _minmod(a: float, b: float) -> float:
    if a * b <= 0.0:
        return 0.0
    if abs(a) < abs(b):
        return a
    return b


@njit(cache=True)
def _one_sided(c: float, vm1: float, vm2: float, vp1: float, vp2: float, bm1: bool, bm2: bool,
               bp1: bool, bp2: bool, ih: float, ih2: float, hh: float) -> tuple[float, float]:
    """ENO2 (D-, D+) at a node from values at -2..+2 (ih = 1/h, ih2 = 1/h^2, hh = h/2);
    second differences that touch a blocked node are dropped."""
    d2c = 0.0 if (bm1 or bp1) else (vp1 - 2.0 * c + vm1) * ih2
    d2m = 0.0 if (bm1 or bm2) else (c - 2.0 * vm1 + vm2) * ih2
    d2p = 0.0 if (bp1 or bp2) else (vp2 - 2.0 * vp1 + c) * ih2
    dm = (c - vm1) * ih + hh * _minmod(d2m, d2c)
    dp = (vp1 - c) * ih - hh * _minmod(d2c, d2p)
    return dm, dp


def _rates(p: np.ndarray, act: np.ndarray, rates: np.ndarray, speeds: np.ndarray, t: float,
           w: float, ny: int, nx: int, periodic: bool, ihx: np.ndarray, ihx2: np.ndarray,
           hxh: np.ndarray, ihy: float, ihy2: float, hyh: float, ihmin: np.ndarray,
           a: np.ndarray, b: np.ndarray, s: np.ndarray, arrival: np.ndarray, tb: np.ndarray,
           lo: np.ndarray, hi: np.ndarray, has_drift: bool, may: np.ndarray) -> None:
    """rates[m] = d phi/dt at node act[m] (module docstring); speeds[m] = its largest
    characteristic speed / spacing (the CFL bound). The loop body is written out in full:
    helpers that take arrays would cost reference counting per node (~10x here)."""
    for m in prange(act.size):
        idx = act[m]
        i = idx // nx
        j = idx - i * nx
        row = i * nx
        c = p[idx]
        if periodic:
            jm1 = row + (j - 1) % nx
            jm2 = row + (j - 2) % nx
            jp1 = row + (j + 1) % nx
            jp2 = row + (j + 2) % nx
        else:
            jm1 = row + max(j - 1, 0)
            jm2 = row + max(j - 2, 0)
            jp1 = row + min(j + 1, nx - 1)
            jp2 = row + min(j + 2, nx - 1)
        im1 = max(i - 1, 0) * nx + j
        im2 = max(i - 2, 0) * nx + j
        ip1 = min(i + 1, ny - 1) * nx + j
        ip2 = min(i + 2, ny - 1) * nx + j
        bxm1 = may[jm1] != 0 and _blk(t, tb[jm1], arrival[jm1], lo[0, jm1], has_drift)
        bxm2 = may[jm2] != 0 and _blk(t, tb[jm2], arrival[jm2], lo[0, jm2], has_drift)
        bxp1 = may[jp1] != 0 and _blk(t, tb[jp1], arrival[jp1], lo[0, jp1], has_drift)
        bxp2 = may[jp2] != 0 and _blk(t, tb[jp2], arrival[jp2], lo[0, jp2], has_drift)
        bym1 = may[im1] != 0 and _blk(t, tb[im1], arrival[im1], lo[0, im1], has_drift)
        bym2 = may[im2] != 0 and _blk(t, tb[im2], arrival[im2], lo[0, im2], has_drift)
        byp1 = may[ip1] != 0 and _blk(t, tb[ip1], arrival[ip1], lo[0, ip1], has_drift)
        byp2 = may[ip2] != 0 and _blk(t, tb[ip2], arrival[ip2], lo[0, ip2], has_drift)
        dxm, dxp = _one_sided(c, p[jm1], p[jm2], p[jp1], p[jp2], bxm1, bxm2, bxp1, bxp2,
                              ihx[i], ihx2[i], hxh[i])
        dym, dyp = _one_sided(c, p[im1], p[im2], p[ip1], p[ip2], bym1, bym2, byp1, byp2,
                              ihy, ihy2, hyh)
        g2 = (max(dxm, 0.0) ** 2 + min(dxp, 0.0) ** 2 + max(dym, 0.0) ** 2
              + min(dyp, 0.0) ** 2)
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
        for k in range(a.size):
            bx = b[k, 0] + s[k] * cu
            by = b[k, 1] + s[k] * cv
            r = a[k] * grad + (max(bx, 0.0) * axm + min(bx, 0.0) * axp + max(by, 0.0) * aym
                               + min(by, 0.0) * ayp)
            if r > best:
                best = r
            sp = a[k] + abs(bx) + abs(by)
            if sp > smax:
                smax = sp
        rates[m] = best
        speeds[m] = smax * ihmin[i]


def _rk_stage(phi: np.ndarray, out: np.ndarray, act: np.ndarray, t: float, w: float,
              dt_cap: float, band: float, ny: int, nx: int, periodic: bool, ihx: np.ndarray,
              ihx2: np.ndarray, hxh: np.ndarray, ihy: float, ihy2: float, hyh: float,
              ihmin: np.ndarray, a: np.ndarray, b: np.ndarray, s: np.ndarray,
              arrival: np.ndarray, tb: np.ndarray, lo: np.ndarray, hi: np.ndarray,
              has_drift: bool, cfl: float, may: np.ndarray) -> float:
    """Stage 1: out = phi - dt L(phi) on the active nodes, dt = min(cfl / max(speed / spacing)
    over the active nodes, dt_cap) (the CFL condition); returns the dt used."""
    n = act.size
    rates = np.empty(n)
    speeds = np.empty(n)
    _rates_inner(phi, act, rates, speeds, t, w, ny, nx, periodic, ihx, ihx2, hxh, ihy, ihy2,
                 hyh, ihmin, a, b, s, arrival, tb, lo, hi, has_drift, may)
    smax = 1e-300
    for m in range(n):
        if speeds[m] > smax:
            smax = speeds[m]
    dt = min(cfl / smax, dt_cap)
    for m in range(n):
        idx = act[m]
        if may[idx] != 0 and _blk(t, tb[idx], arrival[idx], lo[0, idx], has_drift):
            out[idx] = band
        else:
            v = phi[idx] - dt * rates[m]
            out[idx] = min(max(v, -band), band)
    return dt


def _stage_two(phi: np.ndarray, p1: np.ndarray, act: np.ndarray, t: float, t1: float,
               w1: float, dt: float, band: float, ny: int, nx: int, periodic: bool,
               ihx: np.ndarray, ihx2: np.ndarray, hxh: np.ndarray, ihy: float, ihy2: float,
               hyh: float, ihmin: np.ndarray, a: np.ndarray, b: np.ndarray, s: np.ndarray,
               arrival: np.ndarray, tb: np.ndarray, lo: np.ndarray, hi: np.ndarray,
               has_drift: bool, may: np.ndarray) -> tuple[int, float]:
    """Stage 2 of TVD-RK2 (Heun): phi <- (phi + p1 - dt L(p1; t1)) / 2, arrival times recorded.

    A node whose phi crosses from > 0 to <= 0 gets arrival t + dt phi_old / (phi_old - phi_new)
    (linear in time). Returns (newly reached nodes, largest decrease of phi on the outside).
    """
    n = act.size
    rates = np.empty(n)
    speeds = np.empty(n)
    _rates_inner(p1, act, rates, speeds, t1, w1, ny, nx, periodic, ihx, ihx2, hxh, ihy, ihy2,
                 hyh, ihmin, a, b, s, arrival, tb, lo, hi, has_drift, may)
    new = np.empty(n)
    for m in range(n):
        idx = act[m]
        if may[idx] != 0 and _blk(t1, tb[idx], arrival[idx], lo[0, idx], has_drift):
            new[m] = band
            continue
        v = 0.5 * (phi[idx] + p1[idx] - dt * rates[m])
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
# One compiled version, parallel over the active nodes (numba prange). The driver sets the
# thread count per step (`numba.set_num_threads`): one thread for small bands, where starting
# threads costs more than it saves, and under pytest -n 2 (NUMBA_NUM_THREADS=1).
_rates_inner = njit(cache=True, parallel=True)(_rates)
rk_stage = njit(cache=True)(_rk_stage)
stage_two = njit(cache=True)(_stage_two)
