"""Turn-back point against closed forms: still air and a head/tailwind along the course."""

import math

import numpy as np
import pytest

from glideplan.reach import Glide, turnback
from glideplan.solution import Status
from glideplan.terrain import Terrain

from .conftest import flat_terrain
from .test_model import brute

START = (46.3, 7.4)
ALT, ELEV, SAFETY = 1500.0, 200.0, 300.0


def test_still_air_flat_ground(polar):
    """Closed form: out and back at (L/D)max, ALT - d/E = ELEV + safety + d/E, so
    d = (ALT - ELEV - safety) E / 2 (home under the start)."""
    E = polar.best_glide_ratio
    r = turnback((*START, ALT), 90.0, (*START, ELEV), polar, safety_height=SAFETY)
    assert r.status is Status.SOLVED and r.ok
    assert r.distance_m == pytest.approx((ALT - ELEV - SAFETY) * E / 2, abs=1.0)
    assert r.arrival_margin_m >= -1e-6
    assert r.arrival_altitude_m == pytest.approx(ELEV + SAFETY, abs=1.0 / E + 1e-6)
    assert r.back is not None and r.back.endpoint_error_m < 1e-3


@pytest.mark.parametrize("course,wind", [(0.0, (0.0, -8.0)), (0.0, (0.0, 8.0)),
                                         (90.0, (-6.0, 0.0))])
def test_head_and_tailwind_along_the_course(polar, course, wind):
    """Closed form: d = (ALT - ELEV - safety) / (1/r_out + 1/r_back) with the ground glide
    ratios out and back from brute force over the polar (head- or tailwind, no crab)."""
    chi = math.radians(90.0 - course)
    r_out = brute(polar, wind, chi)
    r_back = brute(polar, wind, chi + math.pi)
    r = turnback((*START, ALT), course, (*START, ELEV), polar, safety_height=SAFETY,
                 wind=wind)
    d = (ALT - ELEV - SAFETY) / (1 / r_out + 1 / r_back)
    assert r.distance_m == pytest.approx(d, abs=1.0)
    assert r.altitude_m == pytest.approx(ALT - d / r_out, abs=1.0)


def test_with_terrain_uses_the_front_and_agrees(polar):
    """Flat terrain given as data (the front probes run): the same closed form, to the
    refinement's 1 m."""
    E = polar.best_glide_ratio
    alt = 900.0
    t = flat_terrain(81, span_lat=0.4, span_lon=0.5, elevation=ELEV)
    r = turnback((46.2, 7.25, alt), 45.0, (46.2, 7.25, ELEV), polar, terrain=t,
                 safety_height=SAFETY)
    assert r.ok and len(r.probes) >= 2
    assert r.distance_m == pytest.approx((alt - ELEV - SAFETY) * E / 2, abs=1.0)


def test_ridge_behind_limits_the_turnback(polar):
    """A ridge across the way home, between the home and the outbound course: the glide home
    must clear it, so the turn-back point comes earlier than over flat ground (and the
    return, flown, keeps the safety height over the ridge)."""
    n = 101
    lat = 46.0 + 0.3 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.5 * np.arange(n) / (n - 1)
    z = np.full((n, n), ELEV, np.float32)
    z[:, 40:43] = 600.0  # a ridge along a meridian at lon ~7.2
    home = (46.15, 7.15, ELEV)
    t = Terrain(lat, lon, z)
    alt = 1100.0
    flat = turnback((46.15, 7.25, alt), 90.0, home, polar, safety_height=SAFETY)
    r = turnback((46.15, 7.25, alt), 90.0, home, polar, terrain=t, safety_height=SAFETY)
    assert r.ok and r.distance_m < flat.distance_m - 1000
    assert r.limited_by == "terrain on the way home"
    assert r.back is not None and r.back.min_clearance_m >= SAFETY - 1e-6
    # at the turn-back point the return crosses the ridge with just the safety height
    # (the ridge binds, not the arrival): within the 1 m refinement's glide
    assert r.back.min_clearance_m - SAFETY <= 2.0 / Glide(polar).still_air_ratio + 1e-6


def test_home_out_of_reach_is_unreachable(polar):
    r = turnback((*START, 400.0), 0.0, (START[0] + 0.3, START[1], ELEV), polar,
                 safety_height=SAFETY)
    assert r.status is Status.UNREACHABLE and not r.ok
    assert r.to_dict()["status"] == "unreachable"


def test_home_beyond_any_glide_over_terrain_is_unreachable(polar):
    t = flat_terrain(121, span_lat=0.6, span_lon=0.8, elevation=ELEV)
    r = turnback((46.05, 7.05, ELEV + 400.0), 0.0, (46.55, 7.75, ELEV), polar, terrain=t,
                 safety_height=SAFETY)
    assert r.status is Status.UNREACHABLE


@pytest.mark.parametrize("clearance,arrival", [(150.0, 300.0), (0.0, 300.0), (150.0, 200.0),
                                               (200.0, 450.0)])
@pytest.mark.parametrize("with_terrain", [False, True])
def test_two_heights_flat_ground_closed_form(polar, clearance, arrival, with_terrain):
    """Closed form with two heights (XCSoar's): over flat ground the clearance en route
    (<= the arrival height) never binds (the glider is above home + arrival height until
    it turns), so d = (ALT - ELEV - arrival height) E / 2 whatever the clearance; without
    terrain and with flat terrain data (the backward search runs), to the 1 m refinement."""
    E = polar.best_glide_ratio
    alt = 900.0 if with_terrain else ALT
    t = flat_terrain(81, span_lat=0.4, span_lon=0.5, elevation=ELEV) if with_terrain else None
    start = (46.2, 7.25) if with_terrain else START
    r = turnback((*start, alt), 45.0, (*start, ELEV), polar, terrain=t,
                 terrain_clearance=clearance, arrival_height=arrival)
    assert r.ok
    assert r.distance_m == pytest.approx((alt - ELEV - arrival) * E / 2, abs=1.0)
    assert r.arrival_margin_m == pytest.approx(r.arrival_altitude_m - ELEV - arrival)
    assert r.arrival_margin_m >= -1e-6
    d = r.to_dict()
    assert d["terrain_clearance_m"] == clearance and d["arrival_height_m"] == arrival
    assert d["safety_height_m"] == arrival  # compatibility: the arrival height, as reach


def test_two_heights_defaults_and_the_old_single_height(polar):
    """Defaults 150 m en route, 300 m on arrival; `safety_height` alone sets both (the same
    answer as both given explicitly); an explicit height wins over it."""
    E = polar.best_glide_ratio
    home = (*START, ELEV)
    r = turnback((*START, ALT), 90.0, home, polar)
    assert (r.terrain_clearance, r.arrival_height) == (150.0, 300.0)
    assert r.distance_m == pytest.approx((ALT - ELEV - 300.0) * E / 2, abs=1.0)
    one = turnback((*START, ALT), 90.0, home, polar, safety_height=250.0)
    both = turnback((*START, ALT), 90.0, home, polar, terrain_clearance=250.0,
                    arrival_height=250.0)
    assert (one.terrain_clearance, one.arrival_height) == (250.0, 250.0)
    assert one.distance_m == both.distance_m
    assert one.distance_m == pytest.approx((ALT - ELEV - 250.0) * E / 2, abs=1.0)
    mixed = turnback((*START, ALT), 90.0, home, polar, safety_height=250.0,
                     arrival_height=400.0)
    assert (mixed.terrain_clearance, mixed.arrival_height) == (250.0, 400.0)
    from glideplan.errors import InvalidParameterError

    with pytest.raises(InvalidParameterError, match="terrain_clearance"):
        turnback((*START, ALT), 90.0, home, polar, terrain_clearance=-1.0)


def test_ridge_clearance_en_route_acts_over_the_ridge(polar):
    """Over the ridge of `test_ridge_behind_limits_the_turnback` the en-route clearance
    binds, not the arrival height: 150 m clearance (arrival 300 m) turns back later than
    300 m, and the return, flown, keeps the 150 m over the ridge."""
    n = 101
    lat = 46.0 + 0.3 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.5 * np.arange(n) / (n - 1)
    z = np.full((n, n), ELEV, np.float32)
    z[:, 40:43] = 600.0
    t = Terrain(lat, lon, z)
    home, start = (46.15, 7.15, ELEV), (46.15, 7.25, 1100.0)
    high = turnback(start, 90.0, home, polar, terrain=t, safety_height=SAFETY)
    low = turnback(start, 90.0, home, polar, terrain=t, terrain_clearance=150.0,
                   arrival_height=SAFETY)
    assert low.ok and low.distance_m > high.distance_m + 500.0
    assert low.back is not None and low.back.min_clearance_m >= 150.0 - 1e-6
    assert low.arrival_margin_m >= -1e-6
