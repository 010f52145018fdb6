"""The K x K leg-cost kernel against the core Dubins kernel, and the vectorised wind times
against the known-wind planner."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.missions.leg_costs import dubins_length_matrix
from glideplan.missions.wind_costs import convected_times
from glideplan.planners.dubins import dubins_distance
from glideplan.planners.wind import convected_dubins


def _reference(p0, p1, a, b, r):
    s = np.zeros((a.size, 1, 3))
    s[:, 0, :2], s[:, 0, 2] = p0, a
    g = np.zeros((1, b.size, 3))
    g[0, :, :2], g[0, :, 2] = p1, b
    return dubins_distance(s, g, r)


@pytest.mark.parametrize("seed", range(6))
def test_matrix_equals_core_kernel(seed):
    """Independent method: `planners.dubins.dubins_distance` (start-frame closed forms) on the
    broadcast poses; equal to rounding (1e-12 relative) in double precision, including the
    straight-ahead cases (zero turns) and waypoints closer than 4 R (CCC words)."""
    rng = np.random.default_rng(seed)
    a = np.concatenate([[0.0, math.pi], rng.uniform(-7, 7, 40)])
    b = np.concatenate([[0.0, math.pi], rng.uniform(-7, 7, 37)])
    for scale in (0.3, 1.5, 3.0, 12.0):
        p0 = rng.normal(size=2) * 5
        p1 = p0 + scale * np.array([1.0, 0.0]) if seed % 2 else p0 + rng.normal(size=2) * scale
        r = rng.uniform(0.5, 2.0)
        got = dubins_length_matrix(p0, p1, a, b, r)
        ref = _reference(p0, p1, a, b, r)
        np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12 * r)
        got32 = dubins_length_matrix(p0, p1, a, b, r, np.float32)
        assert got32.dtype == np.float32
        # single precision: relative rounding of the trigonometry, a few 1e-6 (stated bound 1e-5)
        np.testing.assert_allclose(got32, ref, rtol=1e-5, atol=1e-5 * r)


def test_wind_times_match_the_planner():
    """Reference: `planners.wind.convected_dubins` (scalar root polishing with Brent, the
    planner `plan()` uses). The vectorised scan + bisection finds the same minimum time to
    1e-6 relative on random legs (it may only overestimate, when two roots share a cell)."""
    rng = np.random.default_rng(4)
    v, r, wind = 1.0, 1.0, (0.3, -0.2)
    m = 60  # goals at 0.5-6 R: short legs, where arcs wrap and words jump by 2 pi R
    starts = np.zeros((m, 3))
    starts[:, 2] = rng.uniform(-math.pi, math.pi, m)
    dist, bearing = rng.uniform(0.5, 6.0, m), rng.uniform(-math.pi, math.pi, m)
    goals = np.column_stack([dist * np.cos(bearing), dist * np.sin(bearing),
                             rng.uniform(-math.pi, math.pi, m)])
    got = convected_times(starts, goals, speed=v, radius=r, wind=wind)
    for s, g, t in zip(starts, goals, got, strict=True):
        c, sn = math.cos(s[2]), math.sin(s[2])
        local = (c * g[0] + sn * g[1], -sn * g[0] + c * g[1], g[2] - s[2])
        w_local = (c * wind[0] + sn * wind[1], -sn * wind[0] + c * wind[1])
        ref = convected_dubins(local, speed=v, radius=r, wind=w_local).time
        assert t == pytest.approx(ref, rel=1e-6)
