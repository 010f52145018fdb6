"""Short legs through a gridded field by local Zermelo shooting (`missions.field_legs`).

References: the router (`glideplan.routing.route`: front, backtrack, Zermelo refinement;
its stated accuracy after refinement 1e-3 relative) on the same legs, and the sphere's own
verification (`routing.sphere.fly_headings`: SciPy RK45 through the field's SciPy
interpolator, an integrator independent of the local RK4 and its cube).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.routing.sphere import fly_headings

V = 0.5


@pytest.fixture(scope="module")
def tidal_field():
    """1/12 deg, hourly for 2 days: an M2 current <= 0.15 m/s east and 0.05 m/s north that
    varies over a few cells; a block of land (NaN) in the north-east corner."""
    from glideplan.fields.field import GriddedField

    lat = np.arange(39.5, 41.5001, 1 / 12)
    lon = np.arange(-71.0, -68.999, 1 / 12)
    t = np.arange(0, 2 * 86400 + 1, 3600.0)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ph = 2 * np.pi * t / 44712.0
    u = 0.15 * np.sin(ph)[:, None, None] * np.cos((LA - 40) * 3)[None]
    v = 0.05 * np.cos(ph)[:, None, None] * np.sin((LO + 70) * 2)[None]
    u[:, -5:, -5:] = np.nan
    v = np.where(np.isnan(u), np.nan, v)
    return GriddedField(times=t, lat=lat, lon=lon, u=u, v=v,
                        epoch=np.datetime64("2026-01-01T00:00", "ns"))


LEGS = [((40.50, -70.00), (40.52, -69.97)), ((40.52, -69.97), (40.51, -70.02))]


def test_local_shooting_equals_the_router(tidal_field):
    """The local leg's duration equals the router's within 1e-3 (the router's accuracy); its
    headings flown by the sphere's verification end within the router's tolerance (one
    spacing) and within 1 m of where the local verification says."""
    from glideplan.missions.field_legs import fast_leg
    from glideplan.routing import route

    a, b = LEGS[1]
    fast = fast_leg(tidal_field, a, b, V, 7200.0, None, None)
    assert fast is not None and fast.status == "solved" and fast.method == "zermelo-local"
    ref = route(tidal_field, a, b, V, depart=7200.0)
    assert ref.status == "solved"
    assert fast.duration_s == pytest.approx(ref.duration_s, rel=1e-3)
    chi = np.radians(np.asarray(fast.heading_deg, dtype=float))
    flown = fly_headings(tidal_field, V, fast.depart_s + fast.t, chi, a, b)
    assert flown.endpoint_error_m <= fast.endpoint_tolerance_m
    assert flown.endpoint_error_m == pytest.approx(fast.endpoint_error_m, abs=1.0)


def test_the_router_takes_legs_near_land_long_or_in_strong_currents(tidal_field):
    """No local shortcut where the router's checks matter: land (NaN) within the leg's
    cube, a leg longer than FAST_MAX_DISTANCE_M, a current >= 0.9 V."""
    from glideplan.missions.field_legs import FAST_MAX_DISTANCE_M, fast_leg

    near_land = ((41.05, -69.45), (41.07, -69.42))
    assert fast_leg(tidal_field, *near_land, V, 0.0, None, None) is None
    far = math.degrees(1.5 * FAST_MAX_DISTANCE_M / 6_371_008.8)
    assert fast_leg(tidal_field, (40.0, -70.5), (40.0 + far, -70.5), V, 0.0, None, None) is None
    assert fast_leg(tidal_field, *LEGS[0], 0.01, 0.0, None, None) is None  # |c| ~ 0.0106


def test_mission_counts_its_legs(tidal_field, capsys):
    """A 4-leg mission: every leg local, chained in time (leg i + 1 departs when leg i
    arrives), the progress bar drawn on stderr counting 4 legs."""
    from glideplan.missions import plan_mission_in_field
    from glideplan.missions.route import Route

    lat = [40.50, 40.52, 40.51, 40.53, 40.50]
    lon = [-70.00, -69.97, -70.02, -70.04, -70.01]
    m = plan_mission_in_field(Route.from_geographic(list("ABCDE"), lat, lon), tidal_field,
                              speed=V, progress=True)
    assert m.ok and [leg.result.method for leg in m.legs] == ["zermelo-local"] * 4
    for prev, nxt in zip(m.legs[:-1], m.legs[1:], strict=True):
        assert nxt.result.depart_s == pytest.approx(prev.result.depart_s + prev.duration_s)
    assert "4/4" in capsys.readouterr().err
