"""Route edge cases a new user hit (issue 26): crossing 180 deg westward with a turn radius,
start = goal with --plot / --geojson.

References: still water, so the route is the great circle (duration = D / V on the router's
sphere) and the flyable glider path of a straight route stays on it.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from glideplan.fields import UniformField
from glideplan.routing import route
from glideplan.routing.glider import follow_route
from glideplan.routing.sphere import gc_distance


def test_route_west_across_180_has_finite_plane_track_and_a_flyable_glider_path():
    start, goal = (-17.0, -179.95), (-17.0, 179.9)
    flow = UniformField(0.0, 0.0)
    r = route(flow, start, goal, 1.0)
    assert r.ok, r.message
    assert np.all(np.isfinite(r.x)) and np.all(np.isfinite(r.y))
    # the plane track ends west of the start, the great-circle distance away (aeqd: exact
    # distance from the projection's centre)
    d = float(gc_distance(*start, *goal))
    assert r.x[-1] < 0.0
    assert float(np.hypot(r.x[-1], r.y[-1])) == pytest.approx(d, rel=5e-3)
    g = follow_route(r, flow, 1.0, 200.0)
    assert g.ok, g.message
    assert np.all(np.isfinite(g.track.lat)) and np.all(np.isfinite(g.track.lon))


def test_start_equal_goal_plots_and_exports(run_cli, tmp_path):
    png, gj = tmp_path / "r.png", tmp_path / "r.geojson"
    code, _out, err = run_cli("route", "--example", "double-gyre", "--from", "30.45", "-39.8",
                             "--to", "30.45", "-39.8", "--speed", "0.5", "--plot", str(png),
                             "--geojson", str(gj))
    assert code == 0, err
    assert png.stat().st_size > 0
    geom = json.loads(gj.read_text())["features"][0]["geometry"]
    assert geom["type"] == "LineString"
    assert geom["coordinates"][0] == geom["coordinates"][-1] == [-39.8, 30.45]


def test_route_over_the_pole_names_the_latitude_limit():
    """(80 N, 0) -> (80 N, 180): the great circle passes the pole (90 deg, closed form: the
    two meridians 0 and 180 form one great circle); the router's lattice stops at 85 deg."""
    r = route(UniformField(0.0, 0.0), (80.0, 0.0), (80.0, 180.0), 1.0, max_duration=48 * 3600.0)
    assert r.status == "unreachable"
    assert r.unreachable_reason == "polar_limit"
    assert "90.0 deg latitude" in r.message and "85" in r.message
