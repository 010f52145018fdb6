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


def test_steady_field_legs_run_on_the_batch_runner(monkeypatch):
    """A steady field and 8 legs (the batch threshold lowered to 4 here): the legs run on
    the batch runner (independent), then are chained in time; the same legs and times as
    routed one after the other."""
    from glideplan.fields.field import GriddedField
    from glideplan.missions import field_legs, plan_mission_in_field
    from glideplan.missions.route import Route

    lat = np.arange(39.5, 41.5001, 1 / 12)
    lon = np.arange(-71.0, -68.999, 1 / 12)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    fld = GriddedField(times=np.array([0.0]), lat=lat, lon=lon,
                       u=(0.1 * np.cos((LA - 40) * 3))[None], v=(0.05 * np.sin(LO + 70))[None],
                       epoch=np.datetime64("2026-01-01T00:00", "ns"))
    rng = np.random.default_rng(3)
    wl = 40.5 + np.cumsum(rng.uniform(-0.02, 0.02, 9))
    wo = -70.0 + np.cumsum(rng.uniform(-0.03, 0.03, 9))
    route = Route.from_geographic([f"W{i}" for i in range(9)], wl, wo)
    monkeypatch.setattr(field_legs, "BATCH_MIN_LEGS", 4)
    monkeypatch.setattr(field_legs, "LEGS_PER_TASK", 4)
    calls = []
    real = field_legs.steady_legs
    monkeypatch.setattr(field_legs, "steady_legs", lambda *a, **k: calls.append(1) or real(
        *a, **k))
    batch = plan_mission_in_field(route, fld, speed=V, depart=3600.0)
    monkeypatch.setattr(field_legs, "BATCH_MIN_LEGS", 10**6)
    seq = plan_mission_in_field(route, fld, speed=V, depart=3600.0)
    assert calls == [1] and batch.ok and seq.ok and len(batch.legs) == 8
    for a, b in zip(batch.legs, seq.legs, strict=True):
        assert a.duration_s == pytest.approx(b.duration_s, rel=1e-9)
        assert a.result.depart_s == pytest.approx(b.result.depart_s, rel=1e-12)
    assert batch.legs[0].result.depart_s == 3600.0
