"""The glider-scale path along a route: feasible radius and closed-loop following."""

from __future__ import annotations

import math

import pytest

from glideplan.fields import UniformField
from glideplan.routing import route
from glideplan.routing.glider import follow_route


def test_follow_route_in_uniform_current():
    """R0' = R0 (1 + eps)^2 with eps = |c| / V (eq. 3.3); the follower stays within R0 of the
    path and ends within R0 of the goal (the path is trackable under |c| <= eps V)."""
    c = (0.1, 0.05)
    r = route(UniformField(*c), (30.0, -40.0), (30.05, -39.95), 0.3, cells=60)
    g = follow_route(r, UniformField(*c), 0.3, 30.0)
    eps = math.hypot(*c) / 0.3
    assert g.status == "followed"
    assert g.disturbance_ratio == pytest.approx(eps, rel=1e-9)
    assert g.feasible_radius_m == pytest.approx(30.0 * (1 + eps) ** 2, rel=1e-12)
    assert g.max_cross_track_m < 30.0
    assert g.final_distance_m < 30.0
    assert g.path_length_m >= r.distance_m * 0.999


def test_current_as_fast_as_the_vehicle_has_no_feasible_radius():
    r = route(UniformField(0.3, 0.0), (30.0, -40.0), (30.0, -39.95), 0.3, cells=40)
    g = follow_route(r, UniformField(0.3, 0.0), 0.3, 30.0)
    assert g.status == "infeasible" and g.feasible_radius_m is None
