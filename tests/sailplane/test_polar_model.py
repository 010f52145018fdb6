"""Mass, ballast, bugs and turning flight on the quadratic polar (hand derivations)."""

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.sailplane import GRAVITY, polar_from_file, read_plr


def test_mass_scales_speeds_and_sinks_by_sqrt_weight_ratio(dg_file):
    """At W = 1.2 W0 every polar point (v, w) moves to (k v, k w), k = sqrt(1.2); the best
    glide ratio is unchanged and the best-glide speed grows by k."""
    pf = read_plr(dg_file)
    p0 = polar_from_file(pf)
    p1 = polar_from_file(pf, mass_kg=0.6 * pf.mass_kg, ballast_l=0.0)  # lighter (>= 0.5 W0)
    p2 = polar_from_file(pf, mass_kg=pf.mass_kg + 40.0, ballast_l=0.0)
    for p in (p1, p2):
        k = math.sqrt(p.mass_kg / p0.mass_kg)
        v = np.linspace(20.0, 40.0, 7)
        np.testing.assert_allclose(p.sink(k * v), k * p0.sink(v), rtol=1e-12)
        assert p.best_glide_ratio == pytest.approx(p0.best_glide_ratio, rel=1e-12)
        assert p.v_best_glide == pytest.approx(k * p0.v_best_glide, rel=1e-12)
        assert p.reference_mass_kg == pf.mass_kg


def test_ballast_adds_one_kg_per_litre_and_is_bounded(fixtures_dir):
    pf = read_plr(fixtures_dir / "DG-1001M_tabs_cr.plr")  # max ballast 100 L
    p = polar_from_file(pf, ballast_l=100.0)
    assert p.mass_kg == pf.mass_kg + 100.0
    with pytest.raises(InvalidParameterError, match=r"ballast.*<= the glider's maximum 100"):
        polar_from_file(pf, ballast_l=101.0)


def test_bugs_reduce_the_glide_ratio_by_the_percentage(dg_polar):
    """Convention: w_bugs(v) = w(v) / (1 - p); so L/D(v) drops by p at every speed."""
    b = dg_polar.with_bugs(15.0)
    v = np.linspace(dg_polar.v_min, dg_polar.v_max, 9)
    np.testing.assert_allclose(v / b.sink(v), 0.85 * v / dg_polar.sink(v), rtol=1e-12)
    assert b.best_glide_ratio == pytest.approx(0.85 * dg_polar.best_glide_ratio, rel=1e-12)
    with pytest.raises(InvalidParameterError, match="bugs"):
        dg_polar.with_bugs(60.0)


def test_turning_polar_is_the_scaled_level_polar(dg_polar):
    """w_phi(V) = n^{3/2} w(V / sqrt n): at 45 deg (n = sqrt 2) the minimum sink moves to
    sqrt(n) v_ms with rate n^{3/2} w_ms; the turn rate is g tan(phi) / V."""
    p = dg_polar
    phi = math.radians(45.0)
    n = 1.0 / math.cos(phi)
    v = np.linspace(25.0, 45.0, 11)
    np.testing.assert_allclose(p.sink_turning(v, phi), n**1.5 * p.sink(v / math.sqrt(n)))
    np.testing.assert_allclose(p.sink_turning(v, 0.0), p.sink(v))
    grid = np.linspace(20.0, 50.0, 300001)
    w = p.sink_turning(grid, phi)
    assert grid[np.argmin(w)] == pytest.approx(math.sqrt(n) * p.v_ms, abs=2e-4)
    assert w.min() == pytest.approx(n**1.5 * p.w_ms, rel=1e-9)
    assert float(p.turn_rate(30.0, phi)) == pytest.approx(GRAVITY / 30.0)
    u = float(p.turn_rate(30.0, phi))
    assert float(p.sink_at_turn_rate(30.0, u)) == pytest.approx(float(p.sink_turning(30.0, phi)))
    assert float(p.stall_speed(phi)) == pytest.approx(p.v_min * 2**0.25)
