"""Compiled (numba) heading primitives of the clipped B arc (`extremals.Kernel.primitives`).

The same closed forms as `Kernel._principal` (dissertation appendix C, re-derived in
`extremals`), one heading at a time: the antiderivatives from 0 to phi of v e^{i phi}, w(v)
and v (all times u_max) for v(phi) = clip(v_ms - lam cos phi, v_stall, v_max), over the
stall band |phi| < phi_s, the free band and the v_max band |phi| > pi - phi_m. Where a band
is absent its terms are exactly zero, so evaluating every band for every heading gives the
NumPy kernel's values (which skips a band only when it is absent for the whole batch).
Serial; imported lazily (importing it imports numba).

The loop over headings is branch-free and vectorised (`_row`): sines and cosines from
`planners._dubins_simd._sincos` (polynomial, within 2e-16 of glibc's), the three cases of
e^{i r1}, e^{i r2} as selects, the complex terms in real and imaginary parts, and the whole
periods' G(pi) computed once per lambda.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from glideplan.planners._dubins_simd import _sincos

__all__ = ["primitives"]

TWO_PI = 2.0 * math.pi


@njit(cache=True)
def _principal(r: float, lam: float, phi_s: float, phi_m: float, vms: float, v_stall: float,
               v_max: float, a: float, w_ms: float, w_stall: float,
               w_max: float) -> tuple[complex, float, float]:
    q = a * lam * lam
    e = complex(math.cos(r), math.sin(r))
    r1 = min(max(r, -phi_s), phi_s)
    r2 = min(max(r, phi_m - math.pi), math.pi - phi_m)
    # cos and sin only where a band boundary cuts r (exp(i 0) = 1 + i 0 exactly)
    e1 = complex(1.0, r1) if r1 == 0.0 else (e if r1 == r else complex(math.cos(r1), math.sin(r1)))
    e2 = e if r2 == r else complex(math.cos(r2), math.sin(r2))
    s1, s2 = e1.imag, e2.imag
    P = -1j * vms * (e2 - e1) - lam * (0.5 * (r2 - r1) - 0.25j * (e2 * e2 - e1 * e1))
    W = w_ms * (r2 - r1) + q * (0.5 * (r2 - r1) + 0.5 * (s2 * e2.real - s1 * e1.real))
    S = vms * (r2 - r1) - lam * (s2 - s1)
    if phi_s > 0.0:
        P = P - 1j * v_stall * (e1 - 1.0)
        W = W + w_stall * r1
        S = S + v_stall * r1
    if phi_m > 0.0:
        P = P - 1j * v_max * (e - e2)
        W = W + w_max * (r - r2)
        S = S + v_max * (r - r2)
    return P, W, S


@njit(cache=True, error_model="numpy", fastmath={"contract"}, inline="always")
def _one(phi: float, lm: float, phi_s: float, phi_m: float, per0: float, per1: float,
         per2: float, vms: float, v_stall: float, v_max: float, a: float, w_ms: float,
         w_stall: float, w_max: float) -> tuple[float, float, float, float]:
    """Re P, Im P, W and S at one heading phi for one lambda (bands phi_s, phi_m; per0..2 =
    Re G(pi), W(pi), S(pi) of that lambda): `_principal` plus whole periods, branch-free."""
    k = math.floor((phi + math.pi) / TWO_PI)
    r = phi - TWO_PI * k
    s, c = _sincos(r)
    r1 = min(max(r, -phi_s), phi_s)
    r2 = min(max(r, phi_m - math.pi), math.pi - phi_m)
    t1, u1 = _sincos(r1)
    t2, u2 = _sincos(r2)
    s1 = r1 if r1 == 0.0 else (s if r1 == r else t1)  # exp(i 0) = 1 + i r1 exactly
    c1 = 1.0 if r1 == 0.0 else (c if r1 == r else u1)
    s2 = s if r2 == r else t2
    c2 = c if r2 == r else u2
    d = r2 - r1
    # P = -i vms (e2 - e1) - lam (d/2 - i/4 (e2^2 - e1^2)), e^2 = (c c - s s) + i (c s + s c)
    sq_re = (c2 * c2 - s2 * s2) - (c1 * c1 - s1 * s1)
    sq_im = (c2 * s2 + s2 * c2) - (c1 * s1 + s1 * c1)
    p_re = vms * (s2 - s1) - lm * (0.5 * d + 0.25 * sq_im)
    p_im = -vms * (c2 - c1) + lm * (0.25 * sq_re)
    w = w_ms * d + a * lm * lm * (0.5 * d + 0.5 * (s2 * c2 - s1 * c1))
    sv = vms * d - lm * (s2 - s1)
    # the stall and v_max bands (their terms are exactly zero where a band is absent)
    p_re += v_stall * s1 + v_max * (s - s2)
    p_im -= v_stall * (c1 - 1.0) + v_max * (c - c2)
    w += w_stall * r1 + w_max * (r - r2)
    sv += v_stall * r1 + v_max * (r - r2)
    return p_re + k * 2.0 * per0, p_im, w + k * 2.0 * per1, sv + k * 2.0 * per2


@njit(cache=True)
def _lam_terms(lm: float, vms: float, v_stall: float, v_max: float, a: float, w_ms: float,
               w_stall: float, w_max: float) -> tuple[float, float, float, float, float]:
    """Band half-widths phi_s, phi_m and one period (Re G(pi), W(pi), S(pi)) of lambda."""
    lo = vms - v_stall
    hi = v_max - vms
    phi_s = math.acos(min(max(lo / lm, -1.0), 1.0)) if lm > lo else 0.0
    phi_m = math.acos(min(max(hi / lm, -1.0), 1.0)) if lm > hi else 0.0
    pp, wp, sp = _principal(math.pi, lm, phi_s, phi_m, vms, v_stall, v_max, a, w_ms, w_stall,
                            w_max)
    return phi_s, phi_m, pp.real, wp, sp


@njit(cache=True, error_model="numpy", fastmath={"contract"})
def _row(phi: np.ndarray, lam: np.ndarray, band_s: np.ndarray, band_m: np.ndarray,
         per: np.ndarray, vms: float, v_stall: float, v_max: float, a: float, w_ms: float,
         w_stall: float, w_max: float, out: np.ndarray, W: np.ndarray, S: np.ndarray) -> None:
    """`_one` for phi[j] with lam[j] (vectorised; P into out[2j], out[2j + 1]);
    per[:, j] = Re G(pi), W(pi), S(pi) of lam[j]."""
    for j in range(phi.size):
        p_re, p_im, w, sv = _one(phi[j], lam[j], band_s[j], band_m[j], per[0, j], per[1, j],
                                 per[2, j], vms, v_stall, v_max, a, w_ms, w_stall, w_max)
        out[2 * j] = p_re
        out[2 * j + 1] = p_im
        W[j] = w
        S[j] = sv


@njit(cache=True)
def primitives(phi: np.ndarray, lam: np.ndarray, vms: float, v_stall: float, v_max: float,
               a: float, w_ms: float, w_stall: float, w_max: float, P: np.ndarray,
               W: np.ndarray, S: np.ndarray) -> None:
    """P, W, S (flat, same length as phi) of `Kernel.primitives`; lam[i % lam.size] goes with
    phi[i] (a lam row repeated over the rows of phi is passed once)."""
    m = lam.size
    if m == 0:
        return
    band_s = np.empty(m)
    band_m = np.empty(m)
    per = np.empty((3, m))
    for j in range(m):  # the clip angles and one period once per lambda
        band_s[j], band_m[j], per[0, j], per[1, j], per[2, j] = _lam_terms(
            lam[j], vms, v_stall, v_max, a, w_ms, w_stall, w_max)
    out = P.view(np.float64)
    for row in range(phi.size // m):
        lo_, hi_ = row * m, (row + 1) * m
        _row(phi[lo_:hi_], lam, band_s, band_m, per, vms, v_stall, v_max, a, w_ms, w_stall,
             w_max, out[2 * lo_:2 * hi_], W[lo_:hi_], S[lo_:hi_])
