"""Compiled kernels of the chapter 6 extremals (numba, cached): the canonical system in s.

Arc length s is the independent variable (6.15, 6.22). The hodograph's lower boundary, the
least sink per unit length for a curvature kappa (the extremal locus, then the stall
boundary, up to the corner; `glideplan.analysis.load_factor.best_turn`), is, over 2 p1,

    G(k) = sqrt(1 + k^2)                   |k| <= k_lim   (locus v^4 + n^2 = 2, 6.35)
    G(k) = a / sqrt(p2^2 - k^2)            k_lim <= |k| <= k_c   (stall n = p2 v^2),

a = (1 + p2^2) / 2: convex and C^1 (no relaxation is needed, 6.4-6.6). With the adjoint
(lx, ly) = -2 p1 (Px, Py) and w = -l_psi / (2 p1), minimising H over the controls gives

    kappa = k*(w):  G'(k) = w, i.e. k = w / sqrt(1 - w^2) on the locus, the stall inverse
                    a k (p2^2 - k^2)^(-3/2) = w, saturated at +-k_c (the corner) for |w| >= w_c,
    x' = cos psi,  y' = sin psi,  psi' = kappa,  w' = Px sin psi - Py cos psi,

and H = 0 (free length) is G(k) - w k - (Px cos psi + Py sin psi) = 0, so that from the start
(psi = 0) Px = G*(w0) = G(k0) - w0 k0: an extremal is fixed by (w0, Py).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = [
    "crossed",
    "extend_parameters",
    "g_star",
    "integrate",
    "kappa_newton",
    "kappa_of",
    "kink_nodes",
    "nodes",
    "shoot",
    "w_newton",
    "w_of_g_star",
]


@njit(cache=True)
def _table(x: float, x0: float, x1: float, base: int, prm: np.ndarray) -> float:
    """Cubic Hermite interpolation of a tabulated function (values, then slopes) on
    [x0, x1]; n = prm[8] uniform nodes stored from prm[base]."""
    n = int(prm[8])
    hx = (x1 - x0) / (n - 1)
    u = (x - x0) / hx
    i = min(max(int(u), 0), n - 2)
    t = u - i
    t2 = t * t
    t3 = t2 * t
    f0, f1 = prm[base + i], prm[base + i + 1]
    d0, d1 = prm[base + n + i], prm[base + n + i + 1]
    return (
        (2.0 * t3 - 3.0 * t2 + 1.0) * f0
        + (t3 - 2.0 * t2 + t) * hx * d0
        + (-2.0 * t3 + 3.0 * t2) * f1
        + (t3 - t2) * hx * d1
    )


@njit(cache=True)
def extend_parameters(prm: np.ndarray, n: int) -> np.ndarray:
    """(p2, a, k_lim, k_c, w_lim, w_c, q_lim, q_c, n) and tables of W(q) on the stall part
    [q_c, q_lim] (slope -1/k) and of k*(w) on [w_lim, w_c] (slope 1/G''(k)), n nodes each,
    for `kappa_of` and `w_of_g_star` (cubic Hermite: about 1e-12 at n = 2048)."""
    p2, a, _kl, kc, wl, wc = prm[0], prm[1], prm[2], prm[3], prm[4], prm[5]
    out = np.zeros(9 + 4 * n)
    out[:6] = prm[:6]
    q_lim = math.sqrt(1.0 - wl * wl)
    q_c = a / math.sqrt(p2 * p2 - kc * kc) - wc * kc
    out[6], out[7], out[8] = q_lim, q_c, n
    for i in range(n):
        q = q_c + (q_lim - q_c) * i / (n - 1)
        w = w_newton(q, prm)
        out[9 + i] = w
        out[9 + n + i] = -1.0 / kappa_newton(w, prm)
        w = wl + (wc - wl) * i / (n - 1)
        k = kappa_newton(w, prm)
        out[9 + 2 * n + i] = k
        out[9 + 3 * n + i] = (p2 * p2 - k * k) ** 2.5 / (a * (p2 * p2 + 2.0 * k * k))
    return out


@njit(cache=True)
def kappa_of(w: float, prm: np.ndarray) -> float:
    """k*(w) (signed); prm as `extend_parameters` (or its first six entries: Newton)."""
    if prm.size > 9:
        aw = abs(w)
        if prm[4] < aw < prm[5]:
            k = _table(aw, prm[4], prm[5], 9 + 2 * int(prm[8]), prm)
            return k if w >= 0.0 else -k
    return kappa_newton(w, prm)


@njit(cache=True)
def kappa_newton(w: float, prm: np.ndarray) -> float:
    """k*(w) (signed) by Newton's method; prm = (p2, a, k_lim, k_c, w_lim, w_c)."""
    p2, a, kl, kc, wl, wc = prm[0], prm[1], prm[2], prm[3], prm[4], prm[5]
    aw = abs(w)
    if aw <= wl:
        k = aw / math.sqrt(1.0 - aw * aw)
    elif aw >= wc:
        k = kc
    else:  # safeguarded Newton on f(k) = a k - w (p2^2 - k^2)^(3/2), increasing in k
        lo, hi = kl, kc
        k = kl + (kc - kl) * (aw - wl) / (wc - wl)
        for _ in range(50):
            r = math.sqrt(p2 * p2 - k * k)
            f = a * k - aw * r * r * r
            if f > 0.0:
                hi = k
            else:
                lo = k
            step = f / (a + 3.0 * aw * k * r)
            kn = k - step
            if abs(step) < 1e-9:  # quadratic convergence: the error is now ~1e-18
                k = kn
                break
            if kn <= lo or kn >= hi:
                kn = 0.5 * (lo + hi)
            k = kn
    return k if w >= 0.0 else -k


@njit(cache=True)
def _g(k: float, prm: np.ndarray) -> float:
    ak = abs(k)
    if ak <= prm[2]:
        return math.sqrt(1.0 + k * k)
    return prm[1] / math.sqrt(prm[0] * prm[0] - k * k)


@njit(cache=True)
def _speed(k: float, prm: np.ndarray) -> float:
    ak = abs(k)
    if ak <= prm[2]:
        return (1.0 + k * k) ** -0.25
    return (prm[0] * prm[0] - k * k) ** -0.25


@njit(cache=True)
def _rhs(st: np.ndarray, px: float, py: float, prm: np.ndarray, out: np.ndarray) -> None:
    """(x, y, psi, w, cost / 2 p1, t)' at st."""
    k = kappa_of(st[3], prm)
    c, s = math.cos(st[2]), math.sin(st[2])
    out[0] = c
    out[1] = s
    out[2] = k
    out[3] = px * s - py * c
    out[4] = _g(k, prm)
    out[5] = 1.0 / _speed(k, prm)


@njit(cache=True)
def _region(w: float, prm: np.ndarray) -> int:
    aw = abs(w)
    return 0 if aw <= prm[4] else (2 if aw >= prm[5] else 1)


@njit(cache=True)
def _signed_region(w: float, prm: np.ndarray) -> int:
    return _region(w, prm) * (1 if w >= 0.0 else -1)


@njit(cache=True)
def crossed(wa: float, wb: float, da: float, db: float, h: float, prm: np.ndarray) -> bool:
    """Whether w, a cubic Hermite between (wa, da) and (wb, db) over a step h, leaves the
    region of k*(w) it starts in (the end or a quarter point elsewhere: grazes count)."""
    r0 = _signed_region(wa, prm)
    if _signed_region(wb, prm) != r0:
        return True
    for t in (0.25, 0.5, 0.75):
        t2 = t * t
        t3 = t2 * t
        w = (
            (2.0 * t3 - 3.0 * t2 + 1.0) * wa
            + (t3 - 2.0 * t2 + t) * h * da
            + (-2.0 * t3 + 3.0 * t2) * wb
            + (t3 - t2) * h * db
        )
        if _signed_region(w, prm) != r0:
            return True
    return False


@njit(cache=True)
def _step(st: np.ndarray, h: float, px: float, py: float, prm: np.ndarray, k1, k2, k3, k4, tmp):
    """One RK4 step; where w crosses (or grazes) a junction of G (locus, stall, corner:
    kappa*(w) has a kink there), the step is redone in 64 sub-steps (RK4 is only first
    order across a kink)."""
    s0, s1, s2, s3, s4, s5 = st[0], st[1], st[2], st[3], st[4], st[5]
    _rk4(st, h, px, py, prm, k1, k2, k3, k4, tmp)
    da = px * math.sin(s2) - py * math.cos(s2)
    db = px * math.sin(st[2]) - py * math.cos(st[2])
    if crossed(s3, st[3], da, db, h, prm):
        st[0], st[1], st[2], st[3], st[4], st[5] = s0, s1, s2, s3, s4, s5
        for _ in range(64):
            _rk4(st, h / 64.0, px, py, prm, k1, k2, k3, k4, tmp)


@njit(cache=True)
def _rk4(st: np.ndarray, h: float, px: float, py: float, prm: np.ndarray, k1, k2, k3, k4, tmp):
    _rhs(st, px, py, prm, k1)
    for i in range(6):
        tmp[i] = st[i] + 0.5 * h * k1[i]
    _rhs(tmp, px, py, prm, k2)
    for i in range(6):
        tmp[i] = st[i] + 0.5 * h * k2[i]
    _rhs(tmp, px, py, prm, k3)
    for i in range(6):
        tmp[i] = st[i] + h * k3[i]
    _rhs(tmp, px, py, prm, k4)
    for i in range(6):
        st[i] += h * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]) / 6.0


@njit(cache=True)
def g_star(w: float, prm: np.ndarray) -> float:
    """G*(w) = min_k G(k) - w k (= Px at the start, from H = 0)."""
    k = kappa_of(w, prm)
    return _g(k, prm) - w * k


@njit(cache=True)
def integrate(w0: float, py: float, length: float, n: int, prm: np.ndarray) -> np.ndarray:
    """End state (x, y, psi, w, cost / 2 p1, t) after `length` in n RK4 steps from the origin."""
    px = g_star(w0, prm)
    st = np.zeros(6)
    st[3] = w0
    k1, k2, k3, k4, tmp = np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6)
    h = length / n
    for _ in range(n):
        _step(st, h, px, py, prm, k1, k2, k3, k4, tmp)
    return st


@njit(cache=True)
def nodes(w0: float, py: float, length: float, n: int, prm: np.ndarray) -> np.ndarray:
    """States at the n + 1 nodes (columns x, y, psi, w, cost / 2 p1, t, kappa, v)."""
    px = g_star(w0, prm)
    out = np.zeros((n + 1, 8))
    st = np.zeros(6)
    st[3] = w0
    k1, k2, k3, k4, tmp = np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6)
    h = length / n
    for j in range(n + 1):
        if j > 0:
            _step(st, h, px, py, prm, k1, k2, k3, k4, tmp)
        out[j, :6] = st
        k = kappa_of(st[3], prm)
        out[j, 6] = k
        out[j, 7] = _speed(k, prm)
    return out


@njit(cache=True)
def w_of_g_star(q: float, prm: np.ndarray) -> float:
    """|w| >= 0 with G*(w) = q (q <= 1), tabulated on the stall part (`extend_parameters`)."""
    if prm.size > 9 and prm[7] < q < prm[6]:
        return _table(q, prm[7], prm[6], 9, prm)
    return w_newton(q, prm)


@njit(cache=True)
def w_newton(q: float, prm: np.ndarray) -> float:
    """|w| >= 0 with G*(w) = q (q <= 1; G* is even and decreasing in |w|, G*' = -kappa):

    locus  G* = sqrt(1 - w^2)                      (|w| <= w_lim)
    stall  G* = a (p2^2 - 2 k^2) / (p2^2 - k^2)^1.5, w = a k (p2^2 - k^2)^-1.5  (k in [k_lim, k_c])
    corner G* = G(k_c) - |w| k_c                   (|w| >= w_c)."""
    p2, a, kl, kc, wl, wc = prm[0], prm[1], prm[2], prm[3], prm[4], prm[5]
    if q >= 1.0:
        return 0.0
    q_lim = math.sqrt(1.0 - wl * wl)
    if q >= q_lim:
        return math.sqrt(1.0 - q * q)
    q_c = a / math.sqrt(p2 * p2 - kc * kc) - wc * kc
    if q <= q_c:
        return wc + (q_c - q) / kc
    lo, hi = kl, kc  # q(k) decreasing on [k_lim, k_c]: safeguarded Newton
    k = kl + (kc - kl) * (q_lim - q) / (q_lim - q_c)
    for _ in range(60):
        r2 = p2 * p2 - k * k
        r3 = r2 * math.sqrt(r2)
        qk = a * (p2 * p2 - 2.0 * k * k) / r3
        if qk > q:
            lo = k
        else:
            hi = k
        step = (qk - q) / (-k * a * (p2 * p2 + 2.0 * k * k) / (r3 * r2))  # dq/dk = -k dw/dk
        kn = k - step
        if abs(step) < 1e-9:  # quadratic convergence: the error is now ~1e-18
            k = kn
            break
        if kn <= lo or kn >= hi:
            kn = 0.5 * (lo + hi)
        k = kn
    r2 = p2 * p2 - k * k
    return a * k / (r2 * math.sqrt(r2))


@njit(cache=True)
def _residual(z: np.ndarray, gx: float, gy: float, gpsi: float, n: int, prm: np.ndarray, out):
    st = integrate(z[0], z[1], z[2], n, prm)
    out[0] = st[0] - gx
    out[1] = st[1] - gy
    out[2] = (st[2] - gpsi + math.pi) % (2.0 * math.pi) - math.pi
    return math.sqrt(out[0] ** 2 + out[1] ** 2 + out[2] ** 2)


@njit(cache=True)
def shoot(
    z0: np.ndarray, gx: float, gy: float, gpsi: float, n: int, prm: np.ndarray, iters: int
) -> np.ndarray:
    """Damped Newton on (w0, Py, L): the extremal's end (n RK4 steps) at the goal pose.

    Forward-difference Jacobian; returns (w0, Py, L, |residual|)."""
    z = z0.copy()
    r = np.zeros(3)
    rn = np.zeros(3)
    jac = np.zeros((3, 3))
    norm = _residual(z, gx, gy, gpsi, n, prm, r)
    for _ in range(iters):
        if norm < 1e-12:
            break
        for j in range(3):
            dz = 1e-7 * max(1.0, abs(z[j]))
            zz = z.copy()
            zz[j] += dz
            _residual(zz, gx, gy, gpsi, n, prm, rn)
            for i in range(3):
                jac[i, j] = (rn[i] - r[i]) / dz
        if abs(np.linalg.det(jac)) < 1e-300:
            break
        step = np.linalg.solve(jac, -r)
        lam = 1.0
        improved = False
        while lam > 1e-4:
            zn = z + lam * step
            if zn[2] > 0.0:
                nn = _residual(zn, gx, gy, gpsi, n, prm, rn)
                if nn < norm:
                    z, norm = zn, nn
                    r[:] = rn
                    improved = True
                    break
            lam *= 0.5
        if not improved:
            break
    out = np.zeros(4)
    out[:3] = z
    out[3] = norm
    return out


@njit(cache=True)
def _put(out: np.ndarray, m: int, st: np.ndarray, kink: float, prm: np.ndarray) -> np.ndarray:
    if m == out.shape[0]:
        grown = np.zeros((2 * m, 9))
        grown[:m] = out
        out = grown
    out[m, :6] = st
    k = kappa_of(st[3], prm)
    out[m, 6] = k
    out[m, 7] = _speed(k, prm)
    out[m, 8] = kink
    return out


@njit(cache=True)
def kink_nodes(w0: float, py: float, length: float, n: int, prm: np.ndarray) -> np.ndarray:
    """As `nodes` (the same RK4 steps, so the same end state), plus a node (flag 1 in a 9th
    column) within h / 64 after each kink of k*(w) (w crossing w_lim or w_c), so that the
    controls are smooth between nodes."""
    px = g_star(w0, prm)
    out = np.zeros((n + 64, 9))
    st = np.zeros(6)
    save = np.zeros(6)
    st[3] = w0
    k1, k2, k3, k4, tmp = np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6), np.zeros(6)
    h = length / n
    out = _put(out, 0, st, 0.0, prm)
    m = 1
    for _ in range(n):
        save[:] = st
        r0 = _signed_region(st[3], prm)
        _rk4(st, h, px, py, prm, k1, k2, k3, k4, tmp)
        da = px * math.sin(save[2]) - py * math.cos(save[2])
        db = px * math.sin(st[2]) - py * math.cos(st[2])
        last = 0.0
        if crossed(save[3], st[3], da, db, h, prm):
            st[:] = save
            for i in range(64):
                _rk4(st, h / 64.0, px, py, prm, k1, k2, k3, k4, tmp)
                r1 = _signed_region(st[3], prm)
                if r1 != r0:
                    if i < 63:
                        out = _put(out, m, st, 1.0, prm)
                        m += 1
                    else:
                        last = 1.0
                r0 = r1
        out = _put(out, m, st, last, prm)
        m += 1
    return out[:m]
