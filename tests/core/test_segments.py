"""Segment kinds: closed forms against numerical integration, transforms, validation."""

import math

import numpy as np
import pytest
from scipy.integrate import quad, solve_ivp

from glideplan import Arc, HeadingSpeedArc, InvalidParameterError, Pose, Sampled, Straight

START = Pose(0.7, -1.2, 0.4)


def _integrate(seg, t_end):
    def rhs(t, z):
        v, u = seg.controls(np.array([t]))
        return [v[0] * math.cos(z[2]), v[0] * math.sin(z[2]), u[0]]

    s = seg.start
    sol = solve_ivp(rhs, (0, t_end), [s.x, s.y, s.heading], method="DOP853", rtol=1e-12, atol=1e-12)
    return sol.y[:, -1]


SEGMENTS = [
    Straight(START, 3.0, speed=2.0),
    Arc(START, 2.5, 1.5, 1, speed=0.5),
    Arc(START, 4.0, 0.3, -1, speed=0.3),
    HeadingSpeedArc(START, 3.5, 1, 0.21, 28.0, 1.7, 0.9),
    HeadingSpeedArc(START, 1.2, -1, 0.5, 2.0, -0.6, -2.0),
]


@pytest.mark.parametrize("seg", SEGMENTS, ids=lambda s: s.kind)
def test_closed_form_states_match_integration(seg):
    for frac in (0.3, 1.0):
        t = frac * seg.duration
        x, y, h = seg.states(np.array([t]))
        np.testing.assert_allclose([x[0], y[0], h[0]], _integrate(seg, t), atol=1e-9)


@pytest.mark.parametrize("seg", SEGMENTS, ids=lambda s: s.kind)
def test_length_is_integral_of_speed(seg):
    ref, _ = quad(lambda t: seg.controls(np.array([t]))[0][0], 0, seg.duration, epsabs=1e-13)
    assert seg.length == pytest.approx(ref, rel=1e-11)
    # time_at_length inverts the arc length
    s = np.linspace(0, seg.length, 7)
    t = seg.time_at_length(s)
    back = seg.integrate_rate(lambda v, u: v, t)
    np.testing.assert_allclose(back, s, atol=1e-9)


@pytest.mark.parametrize("seg", SEGMENTS, ids=lambda s: s.kind)
@pytest.mark.parametrize("reflect", [False, True])
def test_transform_commutes_with_motion(seg, reflect):
    frame = Pose(-3.0, 2.0, 2.2)
    moved = seg.transformed(frame, reflect=reflect)
    t = np.linspace(0, seg.duration, 5)
    x, y, h = seg.states(t)
    from glideplan.pose import to_world

    expect = to_world(np.stack([x, y, h], -1), frame.as_array(), reflect=reflect)
    got = np.stack(moved.states(t), -1)
    np.testing.assert_allclose(got, expect, atol=1e-10)
    assert moved.length == pytest.approx(seg.length)


def test_arc_hand_values():
    # a left quarter turn of radius 2 from the origin facing +x ends at (2, 2) facing +y
    a = Arc(Pose(0, 0, 0), math.pi / 2, 2.0, 1, speed=4.0)
    e = a.end
    assert (e.x, e.y, e.heading) == pytest.approx((2.0, 2.0, math.pi / 2))
    assert a.length == pytest.approx(math.pi)  # R * angle
    assert a.duration == pytest.approx(math.pi / 4)  # length / speed
    np.testing.assert_allclose(a.center, [0.0, 2.0])


def test_heading_speed_arc_constant_speed_limit_is_arc():
    # lam = 0: speed v0 everywhere, so it is an Arc of radius v0/u
    h = HeadingSpeedArc(START, 2.0, -1, 0.25, 3.0, 0.0, 1.0)
    a = Arc(START, 2.0, 3.0 / 0.25, -1, speed=3.0)
    assert h.end.distance_to(a.end) < 1e-12
    assert h.length == pytest.approx(a.length)


def test_sampled_segment_interpolates_a_fine_arc():
    arc = Arc(Pose(0, 0, 0), 2.0, 1.0, 1, speed=1.0)
    t = np.linspace(0, arc.duration, 201)
    x, y, h = arc.states(t)
    v, u = arc.controls(t)
    s = Sampled(t, x, y, h, v, u)
    tq = np.linspace(0, arc.duration, 37)
    np.testing.assert_allclose(np.stack(s.states(tq)), np.stack(arc.states(tq)), atol=1e-7)
    assert s.length == pytest.approx(arc.length, rel=1e-12)
    assert s.turn_word() == "L"


def test_sampled_turn_word_runs():
    t = np.linspace(0, 3, 31)
    u = np.where(t < 1, 1.0, np.where(t < 2, 0.0, -1.0))
    s = Sampled(t, t, 0 * t, 0 * t, np.ones_like(t), u)  # states need not be consistent here
    assert s.turn_word() == "LSR"


@pytest.mark.parametrize(
    ("factory", "name"),
    [
        (lambda: Straight(START, -1.0), "length"),
        (lambda: Straight(START, 1.0, speed=0.0), "speed"),
        (lambda: Arc(START, 1.0, -2.0, 1), "radius"),
        (lambda: Arc(START, 1.0, 2.0, 0), "direction"),
        (lambda: Arc(START, math.nan, 2.0, 1), "angle"),
        (lambda: HeadingSpeedArc(START, 6.0, 1, 1.0, 1.0, 2.0, 0.0), "lam"),
        (lambda: Sampled([0, 0], [0, 1], [0, 0], [0, 0], [1, 1], [0, 0]), "t"),
    ],
)
def test_bad_segment_parameters_name_the_parameter(factory, name):
    with pytest.raises(InvalidParameterError) as err:
        factory()
    assert err.value.name == name


def test_heading_speed_arc_time_at_length_inverts_the_arc_length():
    """time_at_length (SciPy bracketed root of S(t) = s) against the arc length integrated
    independently by Gauss-Legendre quadrature of the speed (`integrate_rate`); lengths outside
    [0, length] map to the ends."""
    from glideplan import HeadingSpeedArc

    arc = HeadingSpeedArc(Pose(1.0, 2.0, 0.3), 4.0, -1, 0.7, 2.0, 0.8, 0.4)
    s = np.linspace(0.05, 0.95, 7) * arc.length
    t = arc.time_at_length(s)
    back = np.array([float(arc.integrate_rate(lambda v, u: v, ti)) for ti in t])
    np.testing.assert_allclose(back, s, rtol=1e-12, atol=1e-12)
    ends = arc.time_at_length(np.array([-1.0, 0.0, arc.length, arc.length + 1.0]))
    np.testing.assert_array_equal(ends, [0.0, 0.0, arc.duration, arc.duration])
