"""The glider-scale path along a route: feasible radius and closed-loop following."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.fields import AnalyticField, UniformField
from glideplan.routing import route
from glideplan.routing.glider import follow_route, trochoid_chain


def test_follow_route_in_uniform_current():
    """R0' = R0 (1 + eps)^2 with eps = |c| / V (eq. 3.3); the follower stays within R0 of the
    path and ends within R0 of the goal (the path is trackable under |c| <= eps V)."""
    c = (0.1, 0.05)
    r = route(UniformField(*c), (30.0, -40.0), (30.05, -39.95), 0.3, cells=60)
    g = follow_route(r, UniformField(*c), 0.3, 30.0)
    eps = math.hypot(*c) / 0.3
    assert g.status == "solved"
    assert g.disturbance_ratio == pytest.approx(eps, rel=1e-9)
    assert g.feasible_radius_m == pytest.approx(30.0 * (1 + eps) ** 2, rel=1e-12)
    assert g.max_cross_track_m < 30.0
    assert g.final_distance_m < 30.0
    assert g.path_length_m >= r.distance_m * 0.999


def test_current_as_fast_as_the_vehicle_has_no_feasible_radius():
    r = route(UniformField(0.3, 0.0), (30.0, -40.0), (30.0, -39.95), 0.3, cells=40)
    g = follow_route(r, UniformField(0.3, 0.0), 0.3, 30.0)
    assert g.status == "infeasible" and g.feasible_radius_m is None


def test_follower_feels_the_field_where_the_vehicle_is():
    """The route is planned in a uniform current but flown through a field with land (NaN)
    east of the route's midpoint: the follower (simulation.follow_paths with the field as a
    FieldDisturbance at the vehicle's position) stops there and says it reached land; the
    same field without the land band is followed to the goal's finish line."""
    c = (0.1, 0.0)
    r = route(UniformField(*c), (30.0, -40.0), (30.0, -39.95), 0.3, cells=40)
    assert r.duration_s is not None
    mid = -39.975

    def with_land(t, lat, lon):
        land = lon > mid
        return np.where(land, np.nan, c[0]), np.where(land, np.nan, 0.0)

    g = follow_route(r, AnalyticField(with_land), 0.3, 30.0)
    assert g.status == "lost" and "reached land" in g.message
    # stopped near the midpoint: half the track at the ground speed V + c along +x
    half_time = 0.5 * g.path_length_m / (0.3 + c[0])
    assert g.duration_s == pytest.approx(half_time, rel=0.05)
    ok = follow_route(r, AnalyticField(lambda t, lat, lon: (c[0] + 0 * lat, 0 * lat)), 0.3, 30.0)
    assert ok.status == "solved" and ok.final_distance_m is not None
    assert ok.final_distance_m < 1.0
    assert ok.duration_s == pytest.approx(ok.path_length_m / (0.3 + c[0]), rel=0.02)


def test_trochoid_pieces_in_a_uniform_current():
    """In a uniform current the mean current of every piece is the current itself, so the
    residual eps' is ~0 and R0' = R0 (the known-wind planner needs no margin, Corollary A.2),
    against R0 (1 + |c| / V)^2 for the Dubins pieces; the chain's time is the closed form
    |d - c t| = V t (the route's straight ground track) within the routing's 1e-3, and each
    piece's controls integrated through its current end on its goal pose."""
    c = (0.1, 0.05)
    fld = UniformField(*c)
    r = route(fld, (30.0, -40.0), (30.05, -39.95), 0.3, cells=60)
    tc = trochoid_chain(r, fld, 0.3, 30.0)
    assert tc.status == "solved"
    # local_current rotates (east, north) into the aeqd plane: ~1e-5 of |c| away from the start
    assert tc.residual_ratio < 1e-4
    assert tc.feasible_radius_m == pytest.approx(30.0, rel=1e-3)
    gx, gy = float(r.x[-1]), float(r.y[-1])
    dc = gx * c[0] + gy * c[1]
    k = 0.3**2 - c[0] ** 2 - c[1] ** 2
    t_star = (-dc + math.sqrt(dc * dc + k * (gx * gx + gy * gy))) / k
    assert tc.duration_s == pytest.approx(t_star, rel=1e-3)
    assert tc.max_piece_error_m is not None and tc.max_piece_error_m < 1e-6
    # flown open loop through the field the chain ends near the goal (route endpoint scale)
    assert tc.field_endpoint_error_m is not None and tc.field_endpoint_error_m < 30.0


def test_trochoid_residual_in_a_time_varying_current():
    """A current that turns with time: each piece's mean differs from the samples, so eps' > 0
    and R0' = R0 (1 + eps')^2 > R0, still below the Dubins pieces' R0 (1 + max|c| / V)^2."""
    def fn(t, lat, lon):
        a = 2 * math.pi * t / 20000.0
        return 0.12 * np.cos(a) + 0 * lat, 0.12 * np.sin(a) + 0 * lat

    fld = AnalyticField(fn)
    r = route(fld, (30.0, -40.0), (30.05, -39.95), 0.3, cells=50)
    tc = trochoid_chain(r, fld, 0.3, 30.0)
    assert tc.status == "solved" and tc.residual_ratio > 0.0
    assert tc.feasible_radius_m == pytest.approx(30.0 * (1 + tc.residual_ratio) ** 2, rel=1e-12)
    assert tc.feasible_radius_m < 30.0 * (1 + 0.12 / 0.3) ** 2
    assert tc.duration_s is not None and r.duration_s is not None
    assert tc.duration_s >= r.duration_s * (1 - 1e-3)  # no faster than the optimal route
