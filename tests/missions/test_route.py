"""Routes: the local projection (round trip, distortion, refusal) and the waypoint rules."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import geodesic_distance_bearing
from glideplan.missions import Route


def test_projection_round_trip_and_distances():
    """lat/lon -> local -> lat/lon within 1e-9 deg (issue 13); distances from the first
    waypoint equal the WGS84 geodesic distance (pyproj Geod, independent of the projection:
    aeqd is exact along lines from its origin) to 1e-6 relative."""
    lat = np.array([41.52, 41.60, 41.30, 42.1])
    lon = np.array([-70.9, -70.5, -71.2, -70.0])
    r = Route.from_geographic(["a", "b", "c", "d"], lat, lon)
    assert r.roundtrip_error_deg < 1e-9
    x, y = r.x, r.y
    dist, _ = geodesic_distance_bearing(np.full(3, lat[0]), np.full(3, lon[0]), lat[1:], lon[1:])
    np.testing.assert_allclose(np.hypot(x[1:], y[1:]), dist, rtol=1e-6)
    # the distortion at ~70 km is (d/R)^2/6 ~ 2e-5 (aeqd on a sphere); reported, below 1e-3
    assert 1e-6 < r.distortion < 1e-4
    # heading convention: a compass bearing of 90 (east) is 0 rad inside
    r2 = Route.from_geographic(["a", "b"], lat[:2], lon[:2], [90.0, math.nan])
    assert r2.headings[0] == pytest.approx(0.0)
    assert math.isnan(r2.headings[1])


def test_too_large_mission_is_refused():
    """A route spanning 2000 km exceeds the 1e-3 scale-distortion limit (geodesy)."""
    with pytest.raises(InvalidParameterError, match="split the mission"):
        Route.from_geographic(["a", "b"], [0.0, 15.0], [0.0, 10.0], source="big.csv")


def test_antipodal_waypoint_is_refused():
    """At the first waypoint's antipode the azimuthal equidistant scale is infinite (the
    projection is singular); it was reported as 0 distortion and the mission was planned."""
    with pytest.raises(InvalidParameterError, match="split the mission"):
        Route.from_geographic(["a", "b"], [47.0, -47.0], [8.0, -172.0], source="far.csv")


def test_identical_consecutive_free_waypoints_are_an_error():
    with pytest.raises(InvalidParameterError, match="identical to the previous"):
        Route.from_local(["a", "b", "c"], [0, 5, 5], [0, 0, 0])
    # with both headings given the leg is well defined (a full turn or nothing)
    r = Route.from_local(["a", "b", "c"], [0, 5, 5], [0, 0, 0], [0.0, 0.0, 1.0])
    assert r.n == 3


def test_fewer_than_two_waypoints():
    with pytest.raises(InvalidParameterError, match="at least two"):
        Route.from_local(["a"], [0.0], [0.0])
