"""The closed-loop waypoint follower of the ensemble's route choice: closed forms, stops."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.fields.field import UniformField
from glideplan.routing.follow_waypoints import REASONS, follow_waypoints
from glideplan.routing.sphere import gc_distance

V = 0.5
LON = np.linspace(0.0, 0.5, 26)
LAT = np.zeros(LON.size)
D = float(gc_distance(0.0, 0.0, 0.0, 0.5))


def test_crab_angle_in_a_cross_current_gives_the_closed_form():
    """A 0.3 m/s northward current across an eastward track along the equator: holding the
    line takes the crab angle asin(0.3 / V) and the ground speed sqrt(V^2 - 0.3^2) = 0.4 m/s;
    t = D / 0.4 (closed form; the follower arrives at its closest approach, located exactly
    within the last step). Along-track currents W: t = D / (V + W)."""
    fields = [UniformField(0.0, 0.3), UniformField(0.2, 0.0), UniformField(-0.2, 0.0)]
    res = follow_waypoints(fields, [0, 1, 2], [(LAT, LON)] * 3, V, (0.0, 0.5), 0.0, 1e7,
                           radius_m=500.0)
    assert res.arrived.all()
    # the sphere's meridian convergence bends a held crab line by < 1 m over 55 km here; the
    # explicit midpoint step is exact for uniform currents
    assert res.duration_s == pytest.approx([D / 0.4, D / 0.7, D / 0.3], rel=1e-4)
    assert np.all(res.miss_m < 500.0)


def test_stops_say_why():
    """Time runs out against a current as fast as the vehicle; an off-field box is left."""
    from glideplan.fields.io import from_xarray
    from glideplan.fields.synthetic import copernicus_dataset

    t = np.datetime64("2026-01-01T00", "ns") + np.arange(3) * np.timedelta64(1, "D")
    lat, lon = np.linspace(-0.2, 0.2, 5), np.linspace(-0.1, 0.6, 15)
    ds = copernicus_dataset(lat, lon, t, [0.5], 0.0, 1.0)  # 1 m/s north: swept off the box
    boxed = from_xarray(ds)
    res = follow_waypoints([UniformField(-V, 0.0), boxed], [0, 1], [(LAT, LON)] * 2, V,
                           (0.0, 0.5), 0.0, 86400.0, radius_m=500.0)
    assert [REASONS[k] for k in res.reason] == ["time ran out", "left the field"]
    assert not res.arrived.any() and np.all(np.isnan(res.duration_s))
    assert res.miss_m[0] == pytest.approx(D, rel=1e-3) and math.isfinite(res.miss_m[1])
