"""Every closed form of the chapter 5 extremals (C.1-C.12, re-derived) against integration.

The reference integrates x' = v cos psi, y' = v sin psi, psi' = u, h' = w(v) (5.1)-(5.4)
with SciPy's DOP853 for the speed law of each extremal, independently of the segment code.
The clipped speed law has kinks (where the free speed crosses v_stall or v_max); the
reference integrates piecewise between them, the kink times computed in closed form, so
each piece is smooth and the integrator's error control holds on it.

Tolerances follow from the reference's accuracy. psi is affine in t (u is constant), so x, y
and h are plain quadratures of known functions of t: an error made in one step is not
amplified later, and the global error of each component is at most the sum of the local
errors. DOP853 keeps each step's error norm (RMS over the 4 components of
err_i / (ATOL + RTOL |z_i|)) below 1, so each component's local error is below
2 (ATOL + RTOL |z_i|), and the bound is `bound = sum over steps of 2 (ATOL + RTOL max|z|)`
(`reference_bound`), plus the closed form's own round-off (`ROUNDOFF`, relative).
"""

import itertools
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from glideplan.path import Path
from glideplan.planners.min_altitude import (
    Kernel,
    b_arc_change,
    b_arc_change_unclipped,
    b_arc_segments,
    constant_speed_arc_change,
    straight_change,
)
from glideplan.pose import Pose
from glideplan.vehicles import dg1001m

G = dg1001m()
RTOL, ATOL = 1e-12, 1e-12
# the closed forms sum a handful of terms of size ~|z| in double precision
ROUNDOFF = 1e-13


def dop853_piecewise(rhs, times, z0):
    """Integrate `rhs` over the consecutive intervals of `times` (smooth on each).

    Returns the end state and, per component, the bound on its global error: the sum over
    accepted steps of 2 (ATOL + RTOL max|z_i|) (see the module docstring)."""
    z = np.asarray(z0, dtype=float)
    bound = np.zeros_like(z)
    for a, b in itertools.pairwise(times):
        if b <= a:
            continue
        sol = solve_ivp(rhs, (a, b), z, method="DOP853", rtol=RTOL, atol=ATOL)
        assert sol.success, sol.message
        steps = sol.t.size - 1
        bound += steps * 2.0 * (ATOL + RTOL * np.max(np.abs(sol.y), axis=1))
        z = sol.y[:, -1]
    return z, bound + ROUNDOFF * np.maximum(1.0, np.abs(z))


def kink_times(psi_i, delta, theta, lam):
    """Times in (0, T) of a max-rate turn where v_ms - lam cos(psi - theta) crosses v_stall or
    v_max (psi = psi_i + sgn(delta) u_max t): cos(psi - theta) = (v_ms - v_edge) / lam."""
    T = abs(delta) / G.u_max
    out = [0.0, T]
    for edge in (G.v_stall, G.v_max):
        c = (G.v_ms - edge) / lam
        if abs(c) > 1.0:
            continue
        for base in (math.acos(c), -math.acos(c)):
            # headings theta + base + 2 pi k inside the turn
            lo, hi = sorted((psi_i, psi_i + delta))
            k0 = math.ceil((lo - theta - base) / (2 * math.pi))
            k1 = math.floor((hi - theta - base) / (2 * math.pi))
            for k in range(k0, k1 + 1):
                psi = theta + base + 2 * math.pi * k
                out.append(abs(psi - psi_i) / G.u_max)
    return sorted(t for t in out if 0.0 <= t <= T)


def integrate(psi_i, delta, speed_of_heading, turn=True, kinks=None):
    """Integrate (5.1)-(5.4) over a max-rate turn of signed angle delta (or a straight of
    length `delta` when turn is False); speed_of_heading(psi) gives v. `kinks`: the times
    where the speed law is not smooth (default: none). Returns (state, T, error bound)."""
    u = math.copysign(G.u_max, delta) if turn else 0.0
    T = abs(delta) / G.u_max if turn else delta / speed_of_heading(psi_i)

    def rhs(t, z):
        v = speed_of_heading(z[2])
        return [v * math.cos(z[2]), v * math.sin(z[2]), u, float(G.sink_rate(v, 0.0))]

    z, bound = dop853_piecewise(rhs, kinks if kinks is not None else [0.0, T], [0, 0, psi_i, 0])
    return z, T, bound


def free_speed(theta, lam):
    return lambda psi: G.v_ms - lam * math.cos(psi - theta)


def clipped_speed(theta, lam):
    return lambda psi: min(max(G.v_ms - lam * math.cos(psi - theta), G.v_stall), G.v_max)


def integrate_segments(path):
    """Integrate (5.1)-(5.4) along the path's controls (`Segment.controls`, never its closed
    form states), piecewise between each segment's breakpoints. Returns (state, bound)."""
    z, bound = np.array([path.start.x, path.start.y, path.start.heading, 0.0]), 0.0
    for seg in path.segments:

        def rhs(t, s, seg=seg):
            v, u = (float(q[0]) for q in seg.controls(np.array([t])))
            return [v * math.cos(s[2]), v * math.sin(s[2]), u, float(G.sink_rate(v, 0.0))]

        z, b = dop853_piecewise(rhs, list(seg.breakpoints()), z)
        bound = bound + b
    return z, bound


def assert_within(value, reference, bound):
    assert abs(float(value) - reference) <= bound, (float(value), reference, bound)


CASES = [  # psi_i, delta, theta, lam (m/s)
    (0.0, 2.0, 1.0, 2.0),
    (0.3, -5.0, -2.0, 3.9),
    (1.0, 8.0, 0.5, 4.2),  # more than a full turn
    (-2.0, -1.0, 2.5, 0.5),
    (2.5, 4.4, -3.0, 3.0),
]


@pytest.mark.parametrize(("psi_i", "delta", "theta", "lam"), CASES)
def test_b_arc_unclipped_c5_to_c8(psi_i, delta, theta, lam):
    (x, y, psi, h), T, (ex, ey, epsi, eh) = integrate(psi_i, delta, free_speed(theta, lam))
    c = b_arc_change_unclipped(psi_i, delta, theta, lam, G)
    assert_within(c.dx, x, ex)
    assert_within(c.dy, y, ey)
    assert_within(c.dpsi, psi - psi_i, epsi)
    assert_within(c.dh, h, eh)
    assert float(c.dt) == pytest.approx(T, rel=ROUNDOFF)  # both |delta| / u_max


def test_extracted_c6_c7_sign_is_an_erratum():
    """The extracted (C.6)/(C.7) show '+' before the lambda term; that does not integrate."""
    psi_i, d, th, lam = 0.3, 2.0, 1.0, 3.0
    (x, y, _, _), _, (ex, ey, _, _) = integrate(psi_i, d, free_speed(th, lam))
    sg, u = 1.0, G.u_max
    x_plus = (
        sg
        * (
            G.v_ms * (math.sin(psi_i + d) - math.sin(psi_i))
            + 0.5 * lam * (d * math.cos(th) + math.cos(2 * psi_i - th + d) * math.sin(d))
        )
        / u
    )
    y_plus = (
        sg
        * (
            G.v_ms * (math.cos(psi_i) - math.cos(psi_i + d))
            + 0.5 * lam * (d * math.sin(th) + math.sin(2 * psi_i - th + d) * math.sin(d))
        )
        / u
    )
    assert abs(x_plus - x) > 1.0 and abs(y_plus - y) > 1.0  # bounds are ~1e-9 m
    c = b_arc_change_unclipped(psi_i, d, th, lam, G)
    assert_within(c.dx, x, ex)
    assert_within(c.dy, y, ey)


CLIPPED = [(0.0, 6.0, 3.0), (1.0, -9.0, 0.2), (-0.5, 2.5, 0.7), (2.0, -3.5, 1.0)]


@pytest.mark.parametrize(("psi_i", "delta", "theta"), CLIPPED)
@pytest.mark.parametrize("lam", [2.0, 4.28, 6.6, 25.0, 120.0])  # stall band, v_max band
def test_b_arc_clipped(psi_i, delta, theta, lam):
    kinks = kink_times(psi_i, delta, theta, lam)
    (x, y, psi, h), T, (ex, ey, epsi, eh) = integrate(
        psi_i, delta, clipped_speed(theta, lam), kinks=kinks
    )
    c = b_arc_change(psi_i, delta, theta, lam, G)
    assert_within(c.dx, x, ex)
    assert_within(c.dy, y, ey)
    assert_within(c.dh, h, eh)
    assert float(c.dt) == pytest.approx(T, rel=ROUNDOFF)
    # the same arc as path segments (HeadingSpeedArc + constant-speed Arc pieces)
    d = 1 if delta > 0 else -1
    path = Path(tuple(b_arc_segments(Pose(0, 0, psi_i), d, abs(delta), lam, theta, G)), G)
    assert_within(path.end.x, x, ex)
    assert_within(path.end.y, y, ey)
    assert_within(path.end.heading, psi, epsi)
    assert_within(path.cost("altitude"), h, eh)
    assert path.duration == pytest.approx(T, rel=ROUNDOFF)
    # a saturated piece exactly when the free speed leaves [v_stall, v_max] (a kink inside)
    free = G.v_ms - lam * math.cos(psi_i - theta)
    clipped = len(kinks) > 2 or not G.v_stall <= free <= G.v_max
    assert any(s.label == "Bsat" for s in path.segments) == clipped
    # the segments' controls, integrated: they fly to the segments' own closed-form end
    (sx, sy, spsi, sh), (bx, by, bpsi, bh) = integrate_segments(path)
    assert_within(path.end.x, sx, bx)
    assert_within(path.end.y, sy, by)
    assert_within(path.end.heading, spsi, bpsi)
    assert_within(h, sh, bh + eh)


def test_unclipped_and_clipped_agree_inside_the_speed_range():
    """Two closed forms of the same integral: they differ by round-off only (|z| <= ~600 m)."""
    psi_i, delta, theta = np.meshgrid(np.linspace(-3, 3, 5), np.linspace(-7, 7, 6), [0.4])
    lam = 0.999 * (G.v_ms - G.v_stall)
    a = b_arc_change(psi_i, delta, theta, lam, G)
    b = b_arc_change_unclipped(psi_i, delta, theta, lam, G)
    for f in ("dx", "dy", "dpsi", "dh", "dt"):
        np.testing.assert_allclose(getattr(a, f), getattr(b, f), rtol=0, atol=1e-10)


@pytest.mark.parametrize("speed", [G.v_stall, G.v_ms])
@pytest.mark.parametrize(("psi_i", "delta"), [(0.0, 1.0), (0.7, -2.5), (-1.0, 5.9)])
def test_constant_speed_arcs_c9_to_c12(speed, psi_i, delta):
    (x, y, psi, h), T, (ex, ey, epsi, eh) = integrate(psi_i, delta, lambda p: speed)
    c = constant_speed_arc_change(psi_i, delta, speed, G)
    assert_within(c.dx, x, ex)
    assert_within(c.dy, y, ey)
    assert_within(c.dpsi, psi - psi_i, epsi)
    assert_within(c.dh, h, eh)
    assert float(c.dt) == pytest.approx(T, rel=ROUNDOFF)


@pytest.mark.parametrize(("length", "psi_i"), [(100.0, 0.3), (250.0, -2.0)])
def test_straight_c1_to_c4(length, psi_i):
    (x, y, _, h), T, (ex, ey, _, eh) = integrate(psi_i, length, lambda p: G.v_stf, turn=False)
    c = straight_change(length, psi_i, G)
    assert_within(c.dx, x, ex)
    assert_within(c.dy, y, ey)
    assert float(c.dpsi) == 0.0 and float(c.dt) == pytest.approx(T, rel=ROUNDOFF)
    assert_within(c.dh, h, eh)  # (C.4): L (a v_stf + b + c / v_stf)


def test_primitives_are_periodic_and_odd():
    k = Kernel.of(G)
    phi = np.linspace(-3.0, 3.0, 13)
    for lam in (1.0, 6.0, 40.0):
        P, W, S = k.primitives(phi, lam)
        Pn, Wn, _ = k.primitives(-phi, lam)
        np.testing.assert_allclose(Pn, -np.conj(P), atol=1e-12)  # v even in phi
        np.testing.assert_allclose(Wn, -W, atol=1e-12)
        P2, W2, S2 = k.primitives(phi + 2 * math.pi, lam)
        Pp, Wp, Sp = k.primitives(np.array([math.pi, -math.pi]), lam)
        np.testing.assert_allclose(P2 - P, Pp[0] - Pp[1], atol=1e-10)
        np.testing.assert_allclose(W2 - W, Wp[0] - Wp[1], atol=1e-10)
        np.testing.assert_allclose(S2 - S, Sp[0] - Sp[1], atol=1e-10)
