"""Compiled (numba) heading primitives of the clipped B arc (`extremals.Kernel.primitives`).

The same closed forms as `Kernel._principal` (dissertation appendix C, re-derived in
`extremals`), one heading at a time: the antiderivatives from 0 to phi of v e^{i phi}, w(v)
and v (all times u_max) for v(phi) = clip(v_ms - lam cos phi, v_stall, v_max), over the
stall band |phi| < phi_s, the free band and the v_max band |phi| > pi - phi_m. Where a band
is absent its terms are exactly zero, so evaluating every band for every heading gives the
NumPy kernel's values (which skips a band only when it is absent for the whole batch).
Serial; imported lazily (importing it imports numba).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

__all__ = ["primitives"]

TWO_PI = 2.0 * math.pi


@njit(cache=True, inline="always")
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


@njit(cache=True)
def primitives(phi: np.ndarray, lam: np.ndarray, vms: float, v_stall: float, v_max: float,
               a: float, w_ms: float, w_stall: float, w_max: float, P: np.ndarray,
               W: np.ndarray, S: np.ndarray) -> None:
    """P, W, S (flat, same length as phi) of `Kernel.primitives`; lam[i % lam.size] goes with
    phi[i] (a lam row repeated over the rows of phi is passed once)."""
    lo = vms - v_stall
    hi = v_max - vms
    m = lam.size
    band_s = np.empty(m)
    band_m = np.empty(m)
    for j in range(m):  # the clip angles once per lambda (the same expressions as before)
        lm = lam[j]
        band_s[j] = math.acos(min(max(lo / lm, -1.0), 1.0)) if lm > lo else 0.0
        band_m[j] = math.acos(min(max(hi / lm, -1.0), 1.0)) if lm > hi else 0.0
    for i in range(phi.size):
        j = i % m
        lm = lam[j]
        phi_s = band_s[j]
        phi_m = band_m[j]
        k = math.floor((phi[i] + math.pi) / TWO_PI)
        r = phi[i] - TWO_PI * k
        p, w, s = _principal(r, lm, phi_s, phi_m, vms, v_stall, v_max, a, w_ms, w_stall, w_max)
        if k != 0:  # whole periods: G(pi) - G(-pi) = 2 Re G(pi), W and S likewise
            pp, wp, sp = _principal(math.pi, lm, phi_s, phi_m, vms, v_stall, v_max, a, w_ms,
                                    w_stall, w_max)
            p = p + k * 2.0 * pp.real
            w = w + k * 2.0 * wp
            s = s + k * 2.0 * sp
        P[i] = p
        W[i] = w
        S[i] = s
