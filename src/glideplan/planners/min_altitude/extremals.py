"""The extremal arcs of chapter 5 (Table 5.1) in closed form, and as path segments.

Every arc here is flown at the maximum turn rate u_max (or straight), so the heading is an
affine function of time and every integral can be taken over the heading instead:
dt = dpsi / (sgn(delta) u_max). With phi = psi - theta the heading relative to the adjoint
direction theta, the B arc's speed is

    v(phi) = clip(v_ms - lam cos(phi), v_stall, v_max)                 (5.16, clipped)

and the change of position over an arc covering the headings phi in [phi_a, phi_b] is
exp(i theta) / u_max * (G(phi_b) - G(phi_a)) whatever the turn direction, where G is an
antiderivative of v(phi) exp(i phi). With no clipping,

    G(phi) = -i v_ms exp(i phi) - lam (phi / 2 + exp(2 i phi) / 4i),
    W(phi) = w(v_ms) phi + a lam^2 (phi / 2 + sin(2 phi) / 4)          (altitude, b + 2 a v_ms = 0)

and on a clipped piece v is constant. Written out, these give appendix C's closed forms
(C.1)-(C.12); the re-derivation shows that the lambda terms of (C.6) and (C.7) carry a minus
sign where the extracted text shows a plus (REFERENCE_NOTES 5.5), and that the (vanishing,
since b + 2 a v_ms = 0) lambda (b + 2 a v_ms) term of (C.8) has the opposite sign. The tests
check every formula here against numerical integration of (5.1)-(5.4).
"""

from __future__ import annotations

import itertools
import math
import sys
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.pose import TWO_PI, Pose
from glideplan.segments import Arc, HeadingSpeedArc, Segment, Straight
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = [
    "Change",
    "Kernel",
    "b_arc_change",
    "b_arc_change_unclipped",
    "b_arc_pieces",
    "b_arc_segments",
    "constant_speed_arc_change",
    "straight_change",
]

_COMPILED_FROM = 512  # headings per call from which the compiled kernel pays for numba's import
COMPILED = True  # False: always the NumPy kernel (the benchmarks' baseline, the tests' reference)
SATURATED_LABEL = "Bsat"  # the constant-speed piece of a B arc whose speed is clipped


@dataclass(frozen=True)
class Change:
    """Change of state and cost along an extremal: position (m), heading (rad),
    altitude lost (m) and time (s). Fields are arrays (broadcast over the inputs)."""

    dx: np.ndarray
    dy: np.ndarray
    dpsi: np.ndarray
    dh: np.ndarray
    dt: np.ndarray


def _arrays(*values: ArrayLike) -> list[np.ndarray]:
    return list(np.broadcast_arrays(*(np.asarray(q, dtype=float) for q in values)))


# ----- appendix C.1: literal closed forms --------------------------------------------------


def straight_change(length: ArrayLike, psi_i: ArrayLike, glider: QuadraticPolarGlider) -> Change:
    """S segment of `length` (m) at heading psi_i flown at v_stf (C.1)-(C.4)."""
    L = np.asarray(length, dtype=float)
    p = np.asarray(psi_i, dtype=float)
    v = glider.v_stf
    return Change(
        dx=L * np.cos(p),
        dy=L * np.sin(p),
        dpsi=np.zeros(np.broadcast(L, p).shape),
        dh=L * (glider.a * v + glider.b + glider.c / v),
        dt=L / v + 0.0 * p,
    )


def b_arc_change_unclipped(
    psi_i: ArrayLike,
    delta: ArrayLike,
    theta: ArrayLike,
    lam: ArrayLike,
    glider: QuadraticPolarGlider,
) -> Change:
    """B arc with speed v_ms - lam cos(psi - theta), no clipping (C.5)-(C.8), re-derived.

    With s = sgn(d) / u_max, p = psi_i and h = 2 p - th + d:
    dx = s {v_ms [sin(p + d) - sin p] - lam/2 [d cos th + cos(h) sin d]}
    dy = s {v_ms [cos p - cos(p + d)] - lam/2 [d sin th + sin(h) sin d]}
    dh = s {(w(v_ms) + a lam^2/2) d + a lam^2/2 cos(h - th) sin d
            + lam (b + 2 a v_ms) [sin(p - th) - sin(p - th + d)]}

    Args: initial heading psi_i (rad), signed heading change delta (rad; > 0 left),
    adjoint direction theta (rad), multiplier lam (m/s).
    """
    p, d, th, lam = _arrays(psi_i, delta, theta, lam)
    g, u = glider, glider.u_max
    s = np.sign(d) / u
    h = 2 * p - th + d
    vms = g.v_ms
    dx = s * (
        vms * (np.sin(p + d) - np.sin(p)) - 0.5 * lam * (d * np.cos(th) + np.cos(h) * np.sin(d))
    )
    dy = s * (
        vms * (np.cos(p) - np.cos(p + d)) - 0.5 * lam * (d * np.sin(th) + np.sin(h) * np.sin(d))
    )
    half = 0.5 * g.a * lam**2
    cross = lam * (g.b + 2 * g.a * vms) * (np.sin(p - th) - np.sin(p - th + d))
    dh = s * ((g.w_ms + half) * d + half * np.cos(h - th) * np.sin(d) + cross)
    return Change(dx, dy, d.copy(), dh, np.abs(d) / u)


def constant_speed_arc_change(
    psi_i: ArrayLike, delta: ArrayLike, speed: ArrayLike, glider: QuadraticPolarGlider
) -> Change:
    """B_stall or B_ms arc: maximum turn rate at constant `speed` (m/s) (C.9)-(C.12)."""
    p, d, v = np.broadcast_arrays(*(np.asarray(q, dtype=float) for q in (psi_i, delta, speed)))
    u, sg = glider.u_max, np.sign(d)
    return Change(
        dx=sg * v * (np.sin(p + d) - np.sin(p)) / u,
        dy=sg * v * (np.cos(p) - np.cos(p + d)) / u,
        dpsi=d.copy(),
        dh=np.abs(d) * glider.sink_rate(v, 0.0) / u,
        dt=np.abs(d) / u,
    )


# ----- the clipped B arc: heading primitives ------------------------------------------------


@dataclass(frozen=True)
class Kernel:
    """Heading primitives of the clipped B-arc speed for one glider (vectorised)."""

    v_ms: float
    v_stall: float
    v_max: float
    u_max: float
    a: float
    w_ms: float
    w_stall: float
    w_max: float

    @classmethod
    def of(cls, glider: QuadraticPolarGlider) -> Kernel:
        return cls(
            glider.v_ms,
            glider.v_stall,
            glider.v_max,
            glider.u_max,
            glider.a,
            glider.w_ms,
            glider.w_stall,
            float(glider.sink_rate(glider.v_max, 0.0)),
        )

    def clip_angles(self, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Half-widths of the stall-clipped band |phi| < phi_s and of the v_max band
        |phi| > pi - phi_m (0 when the speed does not reach the limit)."""
        lo = self.v_ms - self.v_stall
        hi = self.v_max - self.v_ms
        with np.errstate(divide="ignore", invalid="ignore"):
            phi_s = np.where(lam > lo, np.arccos(np.clip(lo / lam, -1.0, 1.0)), 0.0)
            phi_m = np.where(lam > hi, np.arccos(np.clip(hi / lam, -1.0, 1.0)), 0.0)
        return phi_s, phi_m

    def speed(self, phi: ArrayLike, lam: ArrayLike) -> np.ndarray:
        """v(phi) = clip(v_ms - lam cos phi, v_stall, v_max) (m/s)."""
        v = self.v_ms - np.asarray(lam, dtype=float) * np.cos(np.asarray(phi, dtype=float))
        return np.clip(v, self.v_stall, self.v_max)

    def _principal(
        self, r: np.ndarray, lam: np.ndarray, phi_s: np.ndarray, phi_m: np.ndarray
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        # integrals from 0 to r, |r| <= pi, over the stall band |phi| < phi_s, the free band
        # and the v_max band |phi| > pi - phi_m (bands absent everywhere are skipped)
        vms, q = self.v_ms, self.a * lam * lam
        e = np.exp(1j * r)
        stall = bool(np.any(phi_s > 0.0))
        fast = bool(np.any(phi_m > 0.0) and np.any(np.abs(r) > math.pi - phi_m))
        r1 = np.clip(r, -phi_s, phi_s) if stall else np.zeros_like(r)
        r2 = np.clip(r, phi_m - math.pi, math.pi - phi_m) if fast else r
        e1 = np.exp(1j * r1) if stall else np.ones_like(e)
        e2 = np.exp(1j * r2) if fast else e
        s1, s2 = e1.imag, e2.imag
        # free band: v = v_ms - lam cos(phi)
        P = -1j * vms * (e2 - e1) - lam * (0.5 * (r2 - r1) - 0.25j * (e2 * e2 - e1 * e1))
        W = self.w_ms * (r2 - r1) + q * (0.5 * (r2 - r1) + 0.5 * (s2 * e2.real - s1 * e1.real))
        S = vms * (r2 - r1) - lam * (s2 - s1)
        if stall:
            P = P - 1j * self.v_stall * (e1 - 1.0)
            W = W + self.w_stall * r1
            S = S + self.v_stall * r1
        if fast:
            P = P - 1j * self.v_max * (e - e2)
            W = W + self.w_max * (r - r2)
            S = S + self.v_max * (r - r2)
        return P, W, S

    def primitives(
        self, phi: ArrayLike, lam: ArrayLike
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Antiderivatives from 0 to phi of v e^{i phi} (complex), w(v) and v (all x u_max).

        Displacement, altitude lost and arc length over headings [phi_a, phi_b] are the
        differences divided by u_max (the first rotated by e^{i theta}).
        """
        phi, lam = np.broadcast_arrays(np.asarray(phi, dtype=float), np.asarray(lam, dtype=float))
        shape = phi.shape
        if COMPILED and (phi.size >= _COMPILED_FROM or "numba" in sys.modules):
            # a lambda row repeated over the leading axis (chains) is passed once
            row = lam.ndim > 1 and lam.strides[0] == 0
            return self._compiled(phi.reshape(-1), lam[0].reshape(-1) if row else
                                  lam.reshape(-1), shape)
        phi, lam = phi.reshape(-1), lam.reshape(-1)
        phi_s, phi_m = self.clip_angles(lam)
        k = np.floor((phi + math.pi) / TWO_PI)
        r = phi - TWO_PI * k
        P, W, S = self._principal(r, lam, phi_s, phi_m)
        wrapped = k != 0
        if np.any(wrapped):
            # one period: v is even in phi, so G(pi) - G(-pi) = 2 Re G(pi), W and S likewise
            kk = k[wrapped]
            pi = np.full(kk.shape, math.pi)
            Pp, Wp, Sp = self._principal(pi, lam[wrapped], phi_s[wrapped], phi_m[wrapped])
            P[wrapped] += kk * 2.0 * Pp.real
            W[wrapped] += kk * 2.0 * Wp
            S[wrapped] += kk * 2.0 * Sp
        return P.reshape(shape), W.reshape(shape), S.reshape(shape)


    def _compiled(
        self, phi: np.ndarray, lam: np.ndarray, shape: tuple[int, ...]
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """`primitives` by the compiled kernel (`min_altitude._jit`): the same values."""
        from glideplan.planners.min_altitude._jit import primitives

        P = np.empty(phi.size, dtype=complex)
        W = np.empty(phi.size)
        S = np.empty(phi.size)
        primitives(np.ascontiguousarray(phi), np.ascontiguousarray(lam), self.v_ms,
                   self.v_stall, self.v_max, self.a, self.w_ms, self.w_stall, self.w_max,
                   P, W, S)
        return P.reshape(shape), W.reshape(shape), S.reshape(shape)


def b_arc_change(
    psi_i: ArrayLike,
    delta: ArrayLike,
    theta: ArrayLike,
    lam: ArrayLike,
    glider: QuadraticPolarGlider,
) -> Change:
    """B arc with speed clip(v_ms - lam cos(psi - theta), v_stall, v_max), any lam >= 0.

    Equals `b_arc_change_unclipped` while v_ms - lam <= ... stays inside the speed range;
    otherwise the clipped pieces are flown at constant speed (the saturated B arc).
    """
    p, d, th, lam = _arrays(psi_i, delta, theta, lam)
    kern = Kernel.of(glider)
    phi0 = p - th
    P0, W0, _ = kern.primitives(phi0, lam)
    P1, W1, _ = kern.primitives(phi0 + d, lam)
    s = np.sign(d) / glider.u_max  # a right turn covers its headings backwards in time
    z = s * np.exp(1j * th) * (P1 - P0)
    return Change(z.real, z.imag, d.copy(), s * (W1 - W0), np.abs(d) / glider.u_max)


# ----- segments -----------------------------------------------------------------------------


def b_arc_pieces(
    phi0: float, direction: int, angle: float, lam: float, glider: QuadraticPolarGlider
) -> list[tuple[float, float, float]]:
    """The pieces of a B arc from phi0 = psi0 - theta turning `angle` >= 0 in `direction`:
    (a0, a1, v) with a0, a1 the heading change from the start at the piece's ends and v the
    clipped speed (v_stall or v_max) of a constant-speed piece, 0.0 where v_ms - lam cos(phi)
    is inside the speed range. The cuts are the band edges +-phi_s, +-(pi - phi_m) of
    `Kernel.clip_angles` (modulo 2 pi)."""
    v_ms, v_stall, v_max = glider.v_ms, glider.v_stall, glider.v_max
    lo_v, hi_v = v_ms - v_stall, v_max - v_ms
    phi_s = math.acos(min(max(lo_v / lam, -1.0), 1.0)) if lam > lo_v else 0.0
    phi_m = math.acos(min(max(hi_v / lam, -1.0), 1.0)) if lam > hi_v else 0.0
    lo, hi = sorted((phi0, phi0 + direction * angle))
    bands = ([phi_s, -phi_s] if phi_s > 0.0 else []) + (
        [math.pi - phi_m, phi_m - math.pi] if phi_m > 0.0 else []
    )
    cuts = [
        c + TWO_PI * k
        for c in bands
        for k in range(math.ceil((lo - c) / TWO_PI), math.floor((hi - c) / TWO_PI) + 1)
    ]
    # distances along the arc (heading change from the start) at which the law changes
    marks = sorted({abs(c - phi0) for c in cuts if lo < c < hi})
    bounds = [0.0, *[m for m in marks if 1e-12 < m < angle - 1e-12], angle]
    pieces = []
    for a0, a1 in itertools.pairwise(bounds):
        v_free = v_ms - lam * math.cos(phi0 + direction * 0.5 * (a0 + a1))
        v = v_stall if v_free < v_stall else (v_max if v_free > v_max else 0.0)
        pieces.append((a0, a1, v))
    return pieces


def b_arc_segments(
    start: Pose,
    direction: int,
    angle: float,
    lam: float,
    theta: float,
    glider: QuadraticPolarGlider,
    *,
    label: str = "B",
) -> list[Segment]:
    """The B arc as segments: `HeadingSpeedArc` pieces and constant-speed `Arc` pieces
    (label "Bsat") where the speed v_ms - lam cos(psi - theta) is clipped at v_stall or v_max.

    Args: start pose, direction (+1 left, -1 right), heading change `angle` >= 0 (rad),
    multiplier lam (m/s) and adjoint direction theta (rad, absolute).
    """
    if angle <= 0.0:
        return []
    u, v_ms = glider.u_max, glider.v_ms
    segments: list[Segment] = []
    pose = start
    for a0, a1, v in b_arc_pieces(start.heading - theta, direction, angle, lam, glider):
        seg: Segment
        if v > 0.0:
            seg = Arc(pose, a1 - a0, v / u, direction, v, SATURATED_LABEL)
        else:
            seg = HeadingSpeedArc(pose, a1 - a0, direction, u, v_ms, lam, theta, label)
        segments.append(seg)
        pose = seg.end
    return segments


def straight_segment(
    start: Pose, length: float, glider: QuadraticPolarGlider, *, keep_empty: bool = False
) -> list[Segment]:
    """The S extremal (v = v_stf, u = 0) as a segment list (empty for zero length unless
    `keep_empty`)."""
    return [Straight(start, length, glider.v_stf)] if length > 0.0 or keep_empty else []


def constant_speed_segment(
    start: Pose,
    direction: int,
    angle: float,
    speed: float,
    glider: QuadraticPolarGlider,
    label: str,
) -> list[Segment]:
    """A B_stall or B_ms arc (constant speed, maximum turn rate) as a segment list."""
    if angle <= 0.0:
        return []
    return [Arc(start, angle, speed / glider.u_max, direction, speed, label)]
