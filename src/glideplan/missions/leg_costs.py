"""Dubins leg lengths between two waypoints for all pairs of candidate headings.

The heading dynamic programme needs, for every leg, the K0 x K1 matrix of Dubins distances
from waypoint p0 with heading a_j to p1 with heading b_k (dissertation section 2.7, eq. 2.11).
The turning-circle centres of each end depend on one heading only, so the vector between
them separates: with D = (p1 - p0) / R and circle offsets o_L(h) = (-sin h, cos h),
o_R(h) = -o_L(h),

    V_{XY}(a, b) = D + o_Y(b) - o_X(a),

and every word follows from V (REFERENCE_NOTES 4.2, circle-centre form, here in the world frame):

- LSL: |V| + M(phi - a) + M(b - phi), phi = atan2(V);
- RSR: |V| + M(a - phi) + M(phi - b);
- LSR: p + M(phi - a) + M(phi - b), p = sqrt(|V|^2 - 4), phi = atan2(V) + atan2(2, p);
- RSL: p + M(a - phi) + M(b - phi), phi = atan2(V) - atan2(2, p);
- LRL / RLR (|V| <= 4): middle arc 2 pi - acos(1 - |V|^2 / 8),

with M the angle modulo 2 pi in [0, 2 pi). The two turns of LSL sum to M(b - a) or to
M(b - a) + 2 pi (when the first turn passes b), and likewise for the other words, so one
modulo per word suffices. The matrix is formed in row blocks that stay in the CPU cache.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["dubins_length_matrix"]

TWO_PI = 2.0 * math.pi
# Angles this many turns below 2 pi k count as 2 pi k (as planners.dubins); words whose squared
# straight length misses feasibility by rounding only are feasible. Per precision.
_SNAP = {np.dtype(np.float64): 1e-11, np.dtype(np.float32): 2e-6}
_FEAS = {np.dtype(np.float64): 1e-10, np.dtype(np.float32): 1e-5}
_BLOCK = 16384  # matrix entries per block (a few arrays of this size fit the L2 cache)


@dataclass(frozen=True)
class _Consts:
    """The kernel's constants in the working precision (float32 arithmetic stays float32)."""

    two_pi: Any
    inv_2pi: Any
    snap: Any
    tiny: Any
    feas: Any
    one: Any

    @classmethod
    def of(cls, dtype: np.dtype[Any]) -> _Consts:
        t = dtype.type
        snap = _SNAP[dtype]
        return cls(t(TWO_PI), t(1.0 / TWO_PI), t(snap), t(TWO_PI * snap), t(_FEAS[dtype]), t(1))


def _mod(a: NDArray[Any], k: _Consts) -> NDArray[Any]:
    """Angles modulo 2 pi in [-tiny, 2 pi - tiny) (rounding noise below zero kept as zero)."""
    out = a * k.inv_2pi
    out += k.snap
    np.floor(out, out=out)
    out *= -k.two_pi
    out += a
    return out


def dubins_length_matrix(
    p0: ArrayLike,
    p1: ArrayLike,
    headings0: ArrayLike,
    headings1: ArrayLike,
    radius: float,
    dtype: type[np.floating[Any]] = np.float64,
) -> NDArray[Any]:
    """Dubins distances (m) from (p0, a_j) to (p1, b_k): a `(len(headings0), len(headings1))` array.

    `p0`, `p1`: (x, y) in m; headings in rad (CCW from +x); `radius` the minimum turn radius
    (m). In float64 equal to `planners.dubins.dubins_distance` on the broadcast poses (section
    2.7) to rounding; `dtype=np.float32` is about twice as fast, with relative errors of a few
    1e-6 (turns within 1.3e-5 rad of a multiple of 2 pi count as that multiple).
    """
    dt = np.dtype(dtype)
    k = _Consts.of(dt)
    p0a = np.asarray(p0, dtype=float)
    p1a = np.asarray(p1, dtype=float)
    a = np.mod(np.asarray(headings0, dtype=float).ravel(), TWO_PI).astype(dt)
    b = np.mod(np.asarray(headings1, dtype=float).ravel(), TWO_PI).astype(dt)
    inv = 1.0 / float(radius)
    dx = dt.type((p1a[0] - p0a[0]) * inv)
    dy = dt.type((p1a[1] - p0a[1]) * inv)
    out = np.empty((a.size, b.size), dtype=dt)
    rows = max(1, _BLOCK // max(1, b.size))
    sb, cb = np.sin(b), np.cos(b)
    for i in range(0, a.size, rows):
        _block(a[i : i + rows], b, sb, cb, dx, dy, out[i : i + rows], k)
    out *= dt.type(radius)
    return out


def _block(
    a: NDArray[Any],
    b: NDArray[Any],
    sb: NDArray[Any],
    cb: NDArray[Any],
    dx: Any,
    dy: Any,
    out: NDArray[Any],
    k: _Consts,
) -> None:
    """Fill `out` (len(a), len(b)) with unit-radius Dubins distances (see module docstring)."""
    sa, ca = np.sin(a)[:, None], np.cos(a)[:, None]
    ac = a[:, None]
    beta = _mod(b[None, :] - ac, k)  # M(b - a) in [-tiny, 2 pi - tiny)
    np.maximum(beta, 0.0, out=beta)
    beta_neg = k.two_pi - beta  # M(a - b)
    beta_neg[beta <= k.tiny] = 0.0

    # LSL: V = D + o_L(b) - o_L(a)
    vx = (dx - sb)[None, :] + sa
    vy = (dy + cb)[None, :] - ca
    d2_ll = vx * vx
    d2_ll += vy * vy
    phi_ll = np.arctan2(vy, vx)
    t = _mod(phi_ll - ac, k)
    np.maximum(t, 0.0, out=t)
    np.sqrt(d2_ll, out=out)
    out += beta
    out += k.two_pi * k.one * (t > beta + k.tiny)

    # RSR: V = D + o_R(b) - o_R(a)
    vx = (dx + sb)[None, :] - sa
    vy = (dy - cb)[None, :] + ca
    d2_rr = vx * vx
    d2_rr += vy * vy
    phi_rr = np.arctan2(vy, vx)
    t = _mod(ac - phi_rr, k)
    np.maximum(t, 0.0, out=t)
    tot = np.sqrt(d2_rr)
    tot += beta_neg
    tot += k.two_pi * k.one * (t > beta_neg + k.tiny)
    np.minimum(out, tot, out=out)

    # LSR: V = D + o_R(b) - o_L(a); straight heading atan2(V) + atan2(2, p)
    vx = (dx + sb)[None, :] + sa
    vy = (dy - cb)[None, :] - ca
    p = vx * vx
    p += vy * vy
    p -= 4.0
    ok = p >= -k.feas
    np.maximum(p, 0.0, out=p)
    np.sqrt(p, out=p)
    phi = np.arctan2(vy * p + 2.0 * vx, vx * p - 2.0 * vy)
    t = _mod(phi - ac, k)
    np.maximum(t, 0.0, out=t)
    # turns M(phi - a) + M(phi - b) = 2 t - M(b - a) (+ 2 pi when t < M(b - a))
    tot = p
    tot += 2.0 * t
    tot -= beta
    tot += k.two_pi * k.one * (t < beta - k.tiny)
    np.putmask(out, ok & (tot < out), tot)

    # RSL: V = D + o_L(b) - o_R(a); straight heading atan2(V) - atan2(2, p)
    vx = (dx - sb)[None, :] - sa
    vy = (dy + cb)[None, :] + ca
    p = vx * vx
    p += vy * vy
    p -= 4.0
    ok = p >= -k.feas
    np.maximum(p, 0.0, out=p)
    np.sqrt(p, out=p)
    phi = np.arctan2(vy * p - 2.0 * vx, vx * p + 2.0 * vy)
    t = _mod(ac - phi, k)  # first (right) turn
    np.maximum(t, 0.0, out=t)
    # turns M(a - phi) + M(b - phi) = 2 t + M(b - a) (- 2 pi when that reaches 2 pi... twice)
    s = t + beta
    s -= k.two_pi * k.one * (s >= k.two_pi - k.tiny)
    tot = p
    tot += t
    tot += s
    np.putmask(out, ok & (tot < out), tot)

    # LRL / RLR where the circle centres are at most 4 R apart
    for d2, phi_c, sign in ((d2_rr, phi_rr, -1.0), (d2_ll, phi_ll, 1.0)):
        near = d2 <= 16.0 + 8.0 * k.feas
        count = int(np.count_nonzero(near))
        if count == 0:
            continue
        if 4 * count < near.size:  # few: evaluate where needed only
            idx = np.nonzero(near)
            d2 = d2[idx]
            phi_c = phi_c[idx] - np.broadcast_to(ac, out.shape)[idx]
            psi = np.broadcast_to(beta, out.shape)[idx]
        else:  # most: evaluate everywhere, mask after
            phi_c = phi_c - ac
            psi = beta
        c = 1.0 - k.one * 0.125 * d2
        np.clip(c, -1.0, 1.0, out=c)
        pm = np.arccos(c)
        np.subtract(k.two_pi, pm, out=pm)
        tt = 0.5 * pm
        tt += sign * phi_c
        tt = _mod(tt, k)
        np.maximum(tt, 0.0, out=tt)
        last = pm - tt
        last += sign * psi
        last = _mod(last, k)
        np.maximum(last, 0.0, out=last)
        last += pm
        last += tt
        if 4 * count < near.size:
            out[idx] = np.minimum(out[idx], last)
        else:
            np.putmask(out, near & (last < out), last)
