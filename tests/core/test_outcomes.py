"""The outcome contract (`glideplan.results.Outcome`) on every product: status, ok, message,
warnings, to_dict() with the status's value and the message, plot()."""

from __future__ import annotations

import numpy as np
import pytest

import glideplan
from glideplan.results import Outcome
from glideplan.solution import Status
from glideplan.vehicles.sailplane import dg1001m_sailplane

# 10 km due north of the start (the geodesic length of 0.08993 deg of latitude at 47 N is
# 10,004 m; the result reports its own distance, used below).
START, GOAL = (47.0, 8.0, 1500.0), (47.08993, 8.0, 400.0)


def _contract(result: object) -> dict:
    assert isinstance(result, Outcome)
    assert isinstance(result.status, Status)
    assert result.ok is (result.status is Status.SOLVED)
    assert isinstance(result.message, str) and result.message
    assert isinstance(result.warnings, tuple)
    d = result.to_dict()
    assert d["status"] == result.status.value and d["message"] == result.message
    return d


def test_final_glide_straight_still_air_is_distance_over_best_glide_ratio():
    """Still air, MC 0: the speed to fly is the best-glide speed, so the altitude loss is
    D / (L/D)max (closed form of the quadratic polar); the margin is start - goal - safety -
    loss; status SOLVED when the margin is >= 0."""
    polar = dg1001m_sailplane().polar
    res = glideplan.final_glide(polar, START, GOAL, safety_height=300.0)
    d = _contract(res)
    loss = res.distance_m / polar.best_glide_ratio
    assert res.altitude_loss_m == pytest.approx(loss, rel=1e-9)
    assert res.arrival_margin_m == pytest.approx(1500.0 - 400.0 - 300.0 - loss, rel=1e-9)
    assert res.status is Status.SOLVED and d["altitude_loss_m"] == res.altitude_loss_m
    # the track: straight, geographic, with the altitude profile from start to arrival
    assert res.track.geographic and res.track.alt[0] == 1500.0
    assert res.track.alt[-1] == pytest.approx(1500.0 - loss, rel=1e-9)


def test_final_glide_below_glide_and_unreachable():
    """Lower start: the margin is negative (BELOW_GLIDE). A 60 m/s headwind (the polar's top
    speed is 160 km/h = 44 m/s) makes no progress at any airspeed: UNREACHABLE."""
    polar = dg1001m_sailplane().polar
    low = glideplan.final_glide(polar, (47.0, 8.0, 800.0), GOAL)
    _contract(low)
    assert low.status is Status.BELOW_GLIDE and low.arrival_margin_m < 0
    # a wind blowing towards the south (north = -60 m/s) is a headwind on a northbound glide
    blown = glideplan.final_glide(polar, START, GOAL, wind=(0.0, -60.0))
    d = _contract(blown)
    assert blown.status is Status.UNREACHABLE and blown.altitude_loss_m is None
    assert d["wind"]["from_deg"] == pytest.approx(0.0, abs=1e-9)  # from the north
    assert "headwind 60.0 m/s" in blown.message


def test_final_glide_start_equal_goal_is_zero_loss():
    """Start = goal is answered, not refused: nothing to fly, zero altitude loss."""
    polar = dg1001m_sailplane().polar
    res = glideplan.final_glide(polar, START, (START[0], START[1], 400.0))
    assert res.ok and res.altitude_loss_m == 0.0 and res.distance_m == 0.0


def test_final_glide_to_an_arrival_heading_is_a_verified_plan():
    """With an arrival heading the path is plan()'s (verified by integration through the
    wind); it cannot lose less altitude than the unconstrained straight glide."""
    polar = dg1001m_sailplane().polar
    res = glideplan.final_glide(polar, START, GOAL, arrival_heading=190.0, wind=(3.0, -2.0))
    d = _contract(res)
    assert res.solution is not None and res.solution.ok
    assert d["endpoint_error"]["position"] < 1e-3
    assert res.altitude_loss_m >= d["straight"]["altitude_loss_m"] - 1e-6
    assert res.track.t[-1] == pytest.approx(d["duration_s"], rel=1e-12)
    assert res.track.alt[-1] == pytest.approx(START[2] - res.altitude_loss_m, rel=1e-9)


def test_final_glide_errors_name_parameters_not_flags():
    polar = dg1001m_sailplane().polar
    with pytest.raises(glideplan.InvalidParameterError) as err:
        glideplan.final_glide(polar, START, GOAL, mc=-1.0)
    assert err.value.name == "mc"
    with pytest.raises(glideplan.InvalidParameterError) as err:
        glideplan.final_glide(polar, (95.0, 8.0, 1500.0), GOAL)
    assert err.value.name == "start latitude"


def test_mission_plan_is_an_outcome():
    """Two legs in still air: each leg is a Dubins path verified by plan(); the mission's
    length is the legs' sum."""
    from glideplan.missions import Route

    r = Route.from_local(["a", "b", "c"], [0.0, 800.0, 900.0], [0.0, 300.0, -500.0])
    mission = glideplan.plan_mission(r, speed=1.0, radius=150.0, headings=8)
    d = _contract(mission)
    assert mission.status is Status.SOLVED
    assert d["total_length_m"] == pytest.approx(sum(leg["length_m"] for leg in d["legs"]))
    track = mission.track()
    assert isinstance(track, glideplan.Track) and set(np.unique(track.leg)) == {0, 1}
    assert track.t[-1] == pytest.approx(mission.total_duration_s, rel=1e-9)


def test_following_results_are_outcomes():
    """The following and trochoid-chain results carry the one Status (built by keyword)."""
    from glideplan.routing.glider import GliderFollow, TrochoidChain

    lost = GliderFollow(status=Status.LOST, radius_m=30.0, disturbance_ratio=0.2,
                        feasible_radius_m=43.2, message="the vehicle reached land")
    assert _contract(lost)["track"] == {} and not lost.ok
    chain = TrochoidChain(status="infeasible", residual_ratio=1.2, feasible_radius_m=None,
                          message="no feasible radius")
    assert chain.status is Status.INFEASIBLE and _contract(chain)["status"] == "infeasible"
