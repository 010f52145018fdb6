"""Every closed form of the chapter 5 extremals (C.1-C.12, re-derived) against integration.

The reference integrates x' = v cos psi, y' = v sin psi, psi' = u, h' = w(v) (5.1)-(5.4)
with SciPy's DOP853 for the speed law of each extremal, independently of the segment code.
"""

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
from glideplan.verify import integrate_path

G = dg1001m()


def integrate(psi_i, delta, speed_of_heading, turn=True):
    """Integrate (5.1)-(5.4) over a max-rate turn of signed angle delta (or a straight of
    length `delta` when turn is False); speed_of_heading(psi) gives v."""
    u = math.copysign(G.u_max, delta) if turn else 0.0
    T = abs(delta) / G.u_max if turn else delta / speed_of_heading(psi_i)

    def rhs(t, z):
        v = speed_of_heading(z[2])
        return [v * math.cos(z[2]), v * math.sin(z[2]), u, float(G.sink_rate(v, 0.0))]

    sol = solve_ivp(
        rhs,
        (0.0, T),
        [0.0, 0.0, psi_i, 0.0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-10,
        max_step=T / 50,
    )
    return sol.y[:, -1], T


def free_speed(theta, lam):
    return lambda psi: G.v_ms - lam * math.cos(psi - theta)


def clipped_speed(theta, lam):
    return lambda psi: min(max(G.v_ms - lam * math.cos(psi - theta), G.v_stall), G.v_max)


CASES = [  # psi_i, delta, theta, lam (m/s)
    (0.0, 2.0, 1.0, 2.0),
    (0.3, -5.0, -2.0, 3.9),
    (1.0, 8.0, 0.5, 4.2),  # more than a full turn
    (-2.0, -1.0, 2.5, 0.5),
    (2.5, 4.4, -3.0, 3.0),
]


@pytest.mark.parametrize(("psi_i", "delta", "theta", "lam"), CASES)
def test_b_arc_unclipped_c5_to_c8(psi_i, delta, theta, lam):
    (x, y, psi, h), T = integrate(psi_i, delta, free_speed(theta, lam))
    c = b_arc_change_unclipped(psi_i, delta, theta, lam, G)
    assert float(c.dx) == pytest.approx(x, abs=1e-7)
    assert float(c.dy) == pytest.approx(y, abs=1e-7)
    assert float(c.dpsi) == pytest.approx(psi - psi_i, abs=1e-12)
    assert float(c.dh) == pytest.approx(h, abs=1e-8)
    assert float(c.dt) == pytest.approx(T)


def test_extracted_c6_c7_sign_is_an_erratum():
    """The extracted (C.6)/(C.7) show '+' before the lambda term; that does not integrate."""
    psi_i, d, th, lam = 0.3, 2.0, 1.0, 3.0
    (x, y, _, _), _ = integrate(psi_i, d, free_speed(th, lam))
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
    assert abs(x_plus - x) > 1.0 and abs(y_plus - y) > 1.0
    c = b_arc_change_unclipped(psi_i, d, th, lam, G)
    assert float(c.dx) == pytest.approx(x, abs=1e-7) and float(c.dy) == pytest.approx(y, abs=1e-7)


CLIPPED = [(0.0, 6.0, 3.0), (1.0, -9.0, 0.2), (-0.5, 2.5, 0.7), (2.0, -3.5, 1.0)]


@pytest.mark.parametrize(("psi_i", "delta", "theta"), CLIPPED)
@pytest.mark.parametrize("lam", [2.0, 4.28, 6.6, 25.0, 120.0])  # stall band, v_max band
def test_b_arc_clipped(psi_i, delta, theta, lam):
    (x, y, psi, h), T = integrate(psi_i, delta, clipped_speed(theta, lam))
    c = b_arc_change(psi_i, delta, theta, lam, G)
    assert float(c.dx) == pytest.approx(x, abs=2e-7)
    assert float(c.dy) == pytest.approx(y, abs=2e-7)
    assert float(c.dh) == pytest.approx(h, abs=1e-8)
    assert float(c.dt) == pytest.approx(T)
    # the same arc as path segments (HeadingSpeedArc + constant-speed Arc pieces)
    d = 1 if delta > 0 else -1
    path = Path(tuple(b_arc_segments(Pose(0, 0, psi_i), d, abs(delta), lam, theta, G)), G)
    assert path.end.x == pytest.approx(x, abs=2e-7) and path.end.y == pytest.approx(y, abs=2e-7)
    assert path.end.heading == pytest.approx(psi, abs=1e-9)
    assert path.cost("altitude") == pytest.approx(h, abs=1e-8)
    assert path.duration == pytest.approx(T)
    free = G.v_ms - lam * np.cos(np.linspace(psi_i, psi_i + delta, 4001) - theta)
    clipped = bool(np.any((free < G.v_stall) | (free > G.v_max)))
    assert any(s.label == "Bsat" for s in path.segments) == clipped
    ends = integrate_path(path, "altitude")  # the segments' controls, integrated by the core
    assert ends.end.distance_to(path.end) < 1e-7 and ends.cost == pytest.approx(h, abs=1e-8)


def test_unclipped_and_clipped_agree_inside_the_speed_range():
    psi_i, delta, theta = np.meshgrid(np.linspace(-3, 3, 5), np.linspace(-7, 7, 6), [0.4])
    lam = 0.999 * (G.v_ms - G.v_stall)
    a = b_arc_change(psi_i, delta, theta, lam, G)
    b = b_arc_change_unclipped(psi_i, delta, theta, lam, G)
    for f in ("dx", "dy", "dpsi", "dh", "dt"):
        np.testing.assert_allclose(getattr(a, f), getattr(b, f), atol=1e-9)


@pytest.mark.parametrize("speed", [G.v_stall, G.v_ms])
@pytest.mark.parametrize(("psi_i", "delta"), [(0.0, 1.0), (0.7, -2.5), (-1.0, 5.9)])
def test_constant_speed_arcs_c9_to_c12(speed, psi_i, delta):
    (x, y, psi, h), T = integrate(psi_i, delta, lambda p: speed)
    c = constant_speed_arc_change(psi_i, delta, speed, G)
    assert float(c.dx) == pytest.approx(x, abs=1e-7)
    assert float(c.dy) == pytest.approx(y, abs=1e-7)
    assert float(c.dpsi) == pytest.approx(psi - psi_i)
    assert float(c.dh) == pytest.approx(h, abs=1e-9)
    assert float(c.dt) == pytest.approx(T)


@pytest.mark.parametrize(("length", "psi_i"), [(100.0, 0.3), (250.0, -2.0)])
def test_straight_c1_to_c4(length, psi_i):
    (x, y, _, h), T = integrate(psi_i, length, lambda p: G.v_stf, turn=False)
    c = straight_change(length, psi_i, G)
    assert float(c.dx) == pytest.approx(x) and float(c.dy) == pytest.approx(y)
    assert float(c.dpsi) == 0.0 and float(c.dt) == pytest.approx(T)
    assert float(c.dh) == pytest.approx(h, rel=1e-10)  # (C.4): L (a v_stf + b + c / v_stf)


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
