"""Speed to fly and the straight final glide: hand checks and brute-force minimisation."""

import math

import numpy as np
import pytest

from glideplan.sailplane import speed_to_fly, straight_final_glide


def _brute(p, mc, wt, wc):
    """Independent: minimise (w + MC) / ground speed on a fine grid of airspeeds."""
    v = np.linspace(max(p.v_min, abs(wc) + 1e-6), p.v_max, 400001)
    g = np.sqrt(v**2 - wc**2) + wt
    f = np.where(g > 0, (p.sink(v) + mc) / np.where(g > 0, g, 1.0), np.inf)
    return v[np.argmin(f)]


def test_still_air_mc0_loss_is_d_times_2_sqrt_ac_plus_b(dg_polar):
    """MC = 0, no wind: v = sqrt(c/a) and loss = D w(v)/v = D (2 sqrt(ac) + b)."""
    p, D = dg_polar, 25_000.0
    g = straight_final_glide(p, D, 0.3, start_altitude=2000.0, goal_elevation=400.0)
    assert float(g.speed) == pytest.approx(math.sqrt(p.c / p.a), rel=1e-12)
    loss = D * (2.0 * math.sqrt(p.a * p.c) + p.b)
    assert float(g.altitude_loss) == pytest.approx(loss, rel=1e-12)
    assert float(g.altitude_required) == pytest.approx(400.0 + 300.0 + loss, rel=1e-12)
    assert float(g.arrival_margin) == pytest.approx(2000.0 - 700.0 - loss, rel=1e-12)
    assert float(g.glide_ratio_required) == pytest.approx(D / 1300.0)
    assert float(g.duration) == pytest.approx(D / math.sqrt(p.c / p.a))


@pytest.mark.parametrize(("head", "mc"), [(5.0, 0.0), (10.0, 1.5), (-4.0, 0.5)])
def test_headwind_speed_closed_form(dg_polar, head, mc):
    """Headwind W (negative: tailwind): v = W + sqrt(W^2 + (b W + c + MC) / a), and it
    minimises (w + MC) / (v - W) on a fine grid too."""
    p = dg_polar
    v = float(speed_to_fly(p, mc, tailwind=-head))
    hand = head + math.sqrt(head**2 + (p.b * head + p.c + mc) / p.a)
    assert v == pytest.approx(min(max(hand, p.v_min), p.v_max), rel=1e-12)
    assert v == pytest.approx(_brute(p, mc, -head, 0.0), abs=2e-4)


@pytest.mark.parametrize(("wt", "wc", "mc"), [(-6.0, 8.0, 0.0), (3.0, -9.0, 1.0), (0.0, 12.0, 2.0)])
def test_crosswind_speed_matches_brute_force(dg_polar, wt, wc, mc):
    assert float(speed_to_fly(dg_polar, mc, wt, wc)) == pytest.approx(
        _brute(dg_polar, mc, wt, wc), abs=2e-4
    )


def test_crab_keeps_the_ground_track_on_the_line(dg_polar):
    """Air velocity v (cos, sin)(chi + crab) plus the wind points along the track chi."""
    chi = np.radians([10.0, 100.0, 250.0])
    wind = (6.0, -4.0)
    g = straight_final_glide(dg_polar, 10_000.0, chi, wind=wind)
    gx = g.speed * np.cos(chi + g.crab) + wind[0]
    gy = g.speed * np.sin(chi + g.crab) + wind[1]
    np.testing.assert_allclose(-gx * np.sin(chi) + gy * np.cos(chi), 0.0, atol=1e-12)
    np.testing.assert_allclose(gx * np.cos(chi) + gy * np.sin(chi), g.ground_speed, rtol=1e-12)


def test_vectorised_over_many_goals_equals_one_at_a_time(dg_polar):
    rng = np.random.default_rng(7)
    d = rng.uniform(1e3, 8e4, 2000)
    chi = rng.uniform(-math.pi, math.pi, 2000)
    many = straight_final_glide(dg_polar, d, chi, wind=(7.0, 3.0), mc=1.0, start_altitude=1500.0)
    for i in (0, 777, 1999):
        one = straight_final_glide(
            dg_polar, d[i], chi[i], wind=(7.0, 3.0), mc=1.0, start_altitude=1500.0
        )
        assert float(one.altitude_loss) == pytest.approx(many.altitude_loss[i], rel=1e-12)


def test_wind_faster_than_the_glider_makes_the_goal_unreachable(dg_polar):
    g = straight_final_glide(dg_polar, 5000.0, 0.0, wind=(-60.0, 0.0), start_altitude=5000.0)
    assert math.isinf(float(g.altitude_loss)) and not bool(g.reachable)


def test_speed_to_fly_is_a_minimum_for_any_wind(dg_polar):
    """Property (Hypothesis): no feasible airspeed nearby does better than the speed to fly."""
    from hypothesis import given, settings
    from hypothesis import strategies as st

    p = dg_polar

    def f(v, mc, wt, wc):
        return (p.sink(v) + mc) / (math.sqrt(v * v - wc * wc) + wt)

    @settings(max_examples=200, deadline=None)
    @given(st.floats(-15.0, 15.0), st.floats(-15.0, 15.0), st.floats(0.0, 5.0))
    def check(wt, wc, mc):
        v = float(speed_to_fly(p, mc, wt, wc))
        if not math.isfinite(v):
            return
        for dv in (-0.05, 0.05):
            u = v + dv
            if p.v_min <= u <= p.v_max and u > abs(wc) and math.sqrt(u * u - wc * wc) + wt > 0:
                assert f(v, mc, wt, wc) <= f(u, mc, wt, wc) * (1 + 1e-12)

    check()
