"""Feedback steering by the time-to-go map (routing/replay_feedback.py): closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.fields.field import GriddedField
from glideplan.fields.scalar import scalar_gridded
from glideplan.routing.forecasts import Forecast
from glideplan.routing.replay import Mission, ReplaySettings, replay
from glideplan.routing.replay_feedback import time_to_go
from glideplan.routing.sphere import gc_bearing, gc_distance
from glideplan.routing.steering import crab

EPOCH = np.datetime64("2026-03-01T00:00", "s")
DAY = 86400.0


def uniform(u: float, v: float, days: float = 8.0) -> GriddedField:
    """A uniform current (m/s) on a 1/12 deg grid over 29..31 N, 61..59 W."""
    lat = np.linspace(29.0, 31.0, 25)
    lon = np.linspace(-61.0, -59.0, 25)
    shape = (2, lat.size, lon.size)
    return GriddedField(times=np.array([0.0, days * DAY]), lat=lat, lon=lon,
                        u=np.full(shape, u), v=np.full(shape, v), epoch=EPOCH)


@pytest.mark.parametrize("u,v", [(0.0, 0.0), (0.25, 0.0), (0.2, -0.15)])
def test_time_to_go_heading_is_zermelos_in_a_uniform_current(u, v):
    """In a uniform current the time-optimal path is the straight line to the goal flown with
    the crab angle (Zermelo, closed form: `steering.crab`); the map's heading -grad(tau) must
    be that heading at every point it covers. Tolerance 1 deg: the front's arrival on 2 km
    cells, differentiated at 30-90 km from the goal (h/d ~ 1-4 %; measured <= 0.52 deg)."""
    fld = scalar_gridded(uniform(u, v))
    goal, pos, V = (30.4, -60.0), (29.6, -60.3), 0.5
    m = time_to_go(fld, goal, pos, V, 2 * DAY, 0.0, 2000.0)
    assert m is not None
    for p in [pos, (29.8, -60.1), (30.0, -60.4), (29.7, -60.6), (30.2, -59.9)]:
        h = m.heading(*p)
        assert h is not None
        b = float(gc_bearing(*p, *goal))
        exact = crab(math.sin(b), math.cos(b), u, v, V)
        assert math.degrees(abs((h - exact + math.pi) % (2 * math.pi) - math.pi)) < 1.0
    # far outside the front's window: no value (the caller tracks its plan there)
    assert m.heading(29.01, -60.99) is None


def test_feedback_replay_following_current_closed_form():
    """Truth = still-water forecast + a uniform current along the route, steered by the
    still-water time-to-go map: straight at the goal, arriving at the goal radius r at
    (d - r) / (V + c) (closed form; 0.2 %: the map's heading error, <= 1 deg, costs
    1 - cos(1 deg) = 1.5e-4, and the sphere's bearing change 3e-5)."""
    start, goal, V, c, r = (30.0, -60.5), (30.0, -59.5), 0.5, 0.2, 1000.0
    d = float(gc_distance(*start, *goal))
    fcs = [Forecast(EPOCH, uniform(0.0, 0.0, 4.0), ("memory",))]
    m = Mission(start, goal, V, EPOCH, r, 3 * DAY)
    res = replay(uniform(c, 0.0, 4.0), fcs, m,
                 ReplaySettings(bias_length_m=0.0, cells=30, feedback=True))
    assert res.flight.status == "solved"
    assert res.flight.duration_s == pytest.approx((d - r) / (V + c), rel=2e-3)


def test_feedback_replay_cross_current_beats_pursuit():
    """A uniform cross current c the forecast knows (forecast = truth): the map's heading is
    the crab angle all the way, so the arrival is the crab line's (d - r) / sqrt(V^2 - c^2)
    (closed form, 1 %: the grid's one-cell accuracy at the start), well under pure
    pursuit's T = d V / (V^2 - c^2)."""
    start, goal, V, c, r = (29.6, -60.0), (30.4, -60.0), 0.5, 0.25, 1000.0
    d = float(gc_distance(*start, *goal))
    truth = uniform(c, 0.0, 4.0)
    m = Mission(start, goal, V, EPOCH, r, 3 * DAY)
    res = replay(truth, [Forecast(EPOCH, truth, ("memory",))], m,
                 ReplaySettings(bias_length_m=0.0, feedback=True))
    assert res.flight.status == "solved"
    assert res.flight.duration_s == pytest.approx((d - r) / math.sqrt(V * V - c * c), rel=0.01)
    naive = res.baselines["naive"].duration_s
    assert naive is not None and res.flight.duration_s < 0.9 * naive
