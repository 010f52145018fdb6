"""The arrival-heading final glide (direct method, steady wind, turning polar), checked
against the straight final glide, a hand estimate of a turn, and chapter 5's synthesis."""

import math

import numpy as np
import pytest

from glideplan.planners.final_glide import best_start_heading
from glideplan.planning import plan
from glideplan.pose import Pose
from glideplan.sailplane import GRAVITY, SailplanePolar, straight_final_glide
from glideplan.vehicles.quadratic_polar_glider import dg1001m
from glideplan.vehicles.sailplane import Sailplane


def _glide(vehicle, goal, start_heading=None):
    psi0 = best_start_heading((0.0, 0.0), goal, vehicle) if start_heading is None else start_heading
    sol = plan(Pose(0.0, 0.0, psi0), goal, vehicle, "altitude")
    assert sol.ok, sol.message
    # plan() verified the path by integrating its controls through the wind
    assert sol.endpoint_error.position < 1e-4 * vehicle.length_scale
    return sol


@pytest.mark.parametrize("wind", [(0.0, 0.0), (-8.0, 0.0), (0.0, 6.0)])
def test_far_goal_on_the_bearing_is_the_straight_final_glide(dg_polar, wind):
    """Goal 20 km away, arrival heading = bearing, start heading free: the path is the
    straight final glide (MacCready speed with wind) within 0.1 %. Headwind and crosswind
    included (in a crosswind the heading differs from the track by the crab angle, so the
    glider ends with a small turn to the arrival heading: still within 0.1 %)."""
    v = Sailplane(dg_polar, wind=wind)
    bearing = math.radians(30.0)
    D = 20_000.0
    goal = Pose(D * math.cos(bearing), D * math.sin(bearing), bearing)
    sol = _glide(v, goal)
    ref = float(straight_final_glide(dg_polar, D, bearing, wind=wind).altitude_loss)
    assert sol.cost == pytest.approx(ref, rel=1e-3)
    assert sol.cost >= ref * (1 - 1e-6)  # the straight line is the optimum


def test_reversed_arrival_costs_about_one_turn_more(dg_polar):
    """Arriving at a goal 10 km ahead pointing back at the start costs more than arriving on
    the bearing by about a 180-degree turn. Hand estimate: the least altitude a half turn
    can cost, min over V and phi <= 45 deg (above the stall speed v_min sqrt n) of
    pi V / (g tan phi) * w_phi(V); the straight part is the same length to first order
    ((2R)^2 / 2D ~ 1 m here)."""
    v = Sailplane(dg_polar)
    D = 10_000.0
    on = _glide(v, Pose(D, 0.0, 0.0)).cost
    back = _glide(v, Pose(D, 0.0, math.pi)).cost
    V = np.linspace(dg_polar.v_min, dg_polar.v_max, 2001)[:, None]
    phi = np.linspace(0.05, v.bank_max, 401)[None, :]
    ok = V**2 * np.cos(phi) >= dg_polar.v_min**2
    half_turn = np.where(
        ok, math.pi * V / (GRAVITY * np.tan(phi)) * dg_polar.sink_turning(V, phi), np.inf
    )
    estimate = float(half_turn.min())
    assert back > on
    assert back - on == pytest.approx(estimate, rel=0.25)


@pytest.mark.parametrize("goal_r", [(-3.0, 4.0, 0.0), (0.0, 2.0, 7 * math.pi / 4)])
def test_small_bank_model_matches_plan_min_altitude(goal_r):
    """Zero wind, sink independent of bank, turn rate bounded by the DG-1001M's u_max = pi/15
    (bank free up to 60 deg): the vehicle is chapter 5's glider, so the direct method's
    altitude loss equals `plan min-altitude`'s synthesis (section 5.9 goals) within 0.1 %."""
    g = dg1001m()
    polar = SailplanePolar(g.a, g.b, g.c, g.v_stall, g.v_max, 614.0, 614.0, name="DG-1001M")
    v = Sailplane(polar, bank_max=math.radians(60.0), turn_rate_max=g.u_max, turning_polar=False)
    R = g.radius_stf
    goal = Pose(goal_r[0] * R, goal_r[1] * R, goal_r[2])
    ref = plan(Pose(), goal, g, "altitude")
    ours = _glide(v, goal, start_heading=0.0)
    assert ours.cost == pytest.approx(ref.cost, rel=1e-3)


def test_turning_polar_costs_more_than_chapter_5_at_the_same_turn_rate_bound():
    """Same goal, same turn-rate bound u_max = pi/15, zero wind, but the sink rate of the
    turning polar: on every admissible control (|u| <= u_max, V >= v_min sqrt n) it sinks
    at least as fast as the level polar (checked on a grid below), and its stall limit only
    removes controls, so its optimum cannot beat `plan min-altitude`'s."""
    g = dg1001m()
    polar = SailplanePolar(g.a, g.b, g.c, g.v_stall, g.v_max, 614.0, 614.0, name="DG-1001M")
    V = np.linspace(g.v_stall, g.v_max, 401)[:, None]
    u = np.linspace(0.0, g.u_max, 101)[None, :]
    n = np.sqrt(1.0 + (u * V / GRAVITY) ** 2)
    excess = polar.sink_at_turn_rate(V, u) - polar.sink(V)
    assert np.min(np.where(V >= g.v_stall * np.sqrt(n), excess, np.inf)) > -1e-12
    v = Sailplane(polar, bank_max=math.radians(60.0), turn_rate_max=g.u_max)
    R = g.radius_stf
    goal = Pose(-3.0 * R, 4.0 * R, 0.0)
    ref = plan(Pose(), goal, g, "altitude")
    ours = _glide(v, goal, start_heading=0.0)
    assert ours.cost > ref.cost * (1 + 1e-3)
