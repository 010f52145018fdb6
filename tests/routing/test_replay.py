"""Replay on forecasts through a truth (issue 25 part 1): closed forms, physics, bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import GriddedField
from glideplan.fields.scalar import scalar_gridded
from glideplan.routing.forecasts import Forecast, open_forecasts
from glideplan.routing.replay import Mission, ReplaySettings, replay
from glideplan.routing.sphere import gc_distance

EPOCH = np.datetime64("2026-03-01T00:00", "s")
DAY = 86400.0


def uniform(u: float, v: float, days: float = 4.0) -> GriddedField:
    """A uniform current (m/s) on a 1/12 deg grid over 29..31 N, 61..59 W, `days` long."""
    lat = np.linspace(29.0, 31.0, 25)
    lon = np.linspace(-61.0, -59.0, 25)
    times = np.array([0.0, days * DAY])
    shape = (2, lat.size, lon.size)
    return GriddedField(times=times, lat=lat, lon=lon, u=np.full(shape, u),
                        v=np.full(shape, v), epoch=EPOCH)


def forecast_of(fld: GriddedField, day: int = 0) -> Forecast:
    return Forecast(EPOCH + np.timedelta64(day * 86400, "s"), fld, ("memory",))


def test_following_current_matches_closed_form():
    """Truth = forecast (still water) + a uniform current along the route: every plan (made in
    still water) heads straight at the goal, which is optimal, so the arrival at the goal
    radius r is exactly (d - r) / (V + c) (closed form; tolerance: the integration step's
    interpolation of the crossing, << 1 s)."""
    start, goal, V, c, r = (30.0, -60.5), (30.0, -59.5), 0.5, 0.2, 1000.0
    d = float(gc_distance(*start, *goal))  # due east along a parallel: bearing changes a bit
    truth = uniform(c, 0.0)
    fcs = [forecast_of(uniform(0.0, 0.0))]
    m = Mission(start, goal, V, EPOCH, r, 3 * DAY)
    res = replay(truth, fcs, m, ReplaySettings(bias_length_m=0.0, cells=30))
    expected = (d - r) / (V + c)
    assert res.flight.status == "solved"
    # the great circle's bearing is not due east: the current's along-track share is
    # cos(dbearing) ~ 1 - 3e-5 here, hence 0.1 % tolerance.
    assert res.flight.duration_s == pytest.approx(expected, rel=1e-3)
    assert res.baselines["naive"].duration_s == pytest.approx(expected, rel=1e-3)


def test_cross_current_pure_pursuit_closed_form():
    """naive (heading always at the goal) in a uniform current c perpendicular to the initial
    line of sight: the classic river-crossing pursuit, T = d V / (V^2 - c^2) to reach the
    goal (closed form, planar: on the sphere over 90 km it holds to ~(d/R)^2 ~ 2e-4, and
    the grid's cos(lat) varies: 0.1 %); a goal radius r shortens it by at most r / (V - c)."""
    start, goal, V, c, r = (29.6, -60.0), (30.4, -60.0), 0.5, 0.25, 200.0
    d = float(gc_distance(*start, *goal))
    truth = uniform(c, 0.0)
    m = Mission(start, goal, V, EPOCH, r, 3 * DAY)
    res = replay(truth, [forecast_of(uniform(0.0, 0.0))], m, ReplaySettings(cells=30))
    T = d * V / (V * V - c * c)
    naive = res.baselines["naive"].duration_s
    assert naive is not None
    assert T * (1 - 1e-3) - r / (V - c) <= naive <= T * (1 + 1e-3)


def test_measured_current_replanning_against_closed_form():
    """Truth = forecast (still water) + uniform cross current c. Replanning every hour with
    the measured current applied everywhere (bias length and time >> the mission): the first
    hour is flown on the still-water plan, then each plan is the crab-angle straight line,
    whose ground speed along the line to the goal e is s = c.e + sqrt(V^2 - (c x e)^2)
    (closed form). Reference: 1 h + (distance after 1 h - r) / s, to the grid planner's
    accuracy (one cell, 2 km, of 30-km-scale geometry: 1 %)."""
    start, goal, V, c, r = (29.6, -60.0), (30.4, -60.0), 0.5, 0.25, 1000.0
    truth = uniform(c, 0.0)
    m = Mission(start, goal, V, EPOCH, r, 3 * DAY, replan_every_s=3600.0)
    s = ReplaySettings(bias_length_m=1e8, bias_time_s=1e9, fix_every_s=3600.0)
    res = replay(truth, [forecast_of(uniform(0.0, 0.0))], m, s)
    f = res.flight
    k = int(np.searchsorted(f.t, 3600.0))
    assert f.t[k] == pytest.approx(3600.0)
    la, lo = f.lat[k], f.lon[k]
    d1 = float(gc_distance(la, lo, *goal))
    from glideplan.routing.sphere import gc_bearing

    b = float(gc_bearing(la, lo, *goal))
    e = np.array([math.sin(b), math.cos(b)])  # east, north
    cvec = np.array([c, 0.0])
    cross = cvec[0] * e[1] - cvec[1] * e[0]
    ground = float(cvec @ e) + math.sqrt(V * V - cross * cross)
    expected = 3600.0 + (d1 - r) / ground
    assert f.status == "solved"
    assert f.duration_s == pytest.approx(expected, rel=0.01)
    # and far better than not correcting: pure pursuit's T = d V / (V^2 - c^2)
    assert f.duration_s < res.baselines["naive"].duration_s


@pytest.fixture(scope="module")
def twin(tmp_path_factory):
    """A small QG twin: 32 x 32 at 1/12 deg, 4 days, 3 daily forecasts of 2 days."""
    from glideplan.fields.twin import TwinConfig, write_twin

    out = tmp_path_factory.mktemp("twin")
    cfg = TwinConfig(n=32, days=4.0, forecasts=3, lead_days=2.0, spinup_days=30.0, seed=3)
    return write_twin(out, cfg)


def test_forecasts_equal_truth_replay_is_the_route_on_the_truth(twin):
    """Forecasts equal to the truth: replanning on the truth itself gives the hindsight route
    (within the grid route's discretisation: each replan is a new grid route, one cell of
    ~2 km at 0.5 m/s is ~1 h in 60 h; 2 %), and plan_once = replay likewise."""
    from glideplan.fields import open_field

    truth = open_field(twin.truth)
    fcs = [Forecast(EPOCH + np.timedelta64(d * 86400, "s"), truth, ("truth",)) for d in
           range(3)]
    m = Mission((29.6, -60.5), (30.4, -59.6), 0.5, EPOCH, 2000.0, 3.5 * DAY)
    res = replay(truth, fcs, m, ReplaySettings(bias_length_m=0.0))
    hind = res.baselines["hindsight"]
    assert res.flight.status == hind.status == res.baselines["plan_once"].status == "solved"
    assert res.flight.duration_s == pytest.approx(hind.duration_s, rel=0.02)
    assert res.baselines["plan_once"].duration_s == pytest.approx(res.flight.duration_s,
                                                                  rel=0.02)


def test_twin_replay_track_is_physical_and_json_complete(twin):
    """Between consecutive track points the through-water velocity (ground velocity minus the
    truth's current at the segment's middle) never exceeds V (to the midpoint rule's
    accuracy, 1 %); points at most 15 min apart; the JSON keys of the issue."""
    from glideplan.fields import open_field

    truth = scalar_gridded(open_field(twin.truth))
    fcs = open_forecasts(str(twin.truth.parent / "forecasts" / "*.nc"))
    assert [str(f.issued) for f in fcs] == ["2026-03-01T00:00:00", "2026-03-02T00:00:00",
                                            "2026-03-03T00:00:00"]
    V = 0.5
    m = Mission((29.5, -60.5), (30.3, -59.5), V, EPOCH + np.timedelta64(3600, "s"), 2000.0,
                2.9 * DAY)
    res = replay(truth, fcs, m)
    d = json.loads(json.dumps(res.to_dict()))
    for key in ("status", "duration_s", "arrival_time", "track", "replans", "baselines"):
        assert key in d
    assert set(d["baselines"]) == {"naive", "plan_once", "hindsight"}
    assert {"time_s", "forecast_reference_time", "planned_duration_s"} <= set(d["replans"][0])
    assert len(d["replans"]) >= 3  # departure + the forecasts of day 1 and day 2
    t = np.asarray(d["track"]["time_s"])
    la, lo = np.asarray(d["track"]["lat"]), np.asarray(d["track"]["lon"])
    assert np.diff(t).max() <= 900.0 + 1e-6
    t0 = 3600.0
    R = 6_371_000.0
    for k in range(t.size - 1):
        dt = t[k + 1] - t[k]
        if dt < 1.0:
            continue
        mid_la, mid_lo = 0.5 * (la[k] + la[k + 1]), 0.5 * (lo[k] + lo[k + 1])
        cu, cv = truth.velocity(t0 + t[k] + dt / 2, mid_la, mid_lo)
        gx = math.radians(lo[k + 1] - lo[k]) * R * math.cos(math.radians(mid_la)) / dt
        gy = math.radians(la[k + 1] - la[k]) * R / dt
        assert math.hypot(gx - float(cu), gy - float(cv)) <= V * 1.01


def test_bad_inputs_name_the_file(twin, tmp_path):
    from glideplan.fields import open_field

    truth = open_field(twin.truth)
    fcs = open_forecasts(str(twin.truth.parent / "forecasts" / "*.nc"))
    late = [f for f in fcs if f.issued > EPOCH]
    with pytest.raises(InvalidParameterError, match="no forecast is issued at or before"):
        replay(truth, late, Mission((29.5, -60.5), (30.3, -59.5), 0.5, EPOCH, 2000.0, DAY))
    with pytest.raises(InvalidParameterError, match="does not cover the mission"):
        replay(truth, fcs, Mission((29.5, -60.5), (30.3, -59.5), 0.5, EPOCH, 2000.0, 9 * DAY))
    with pytest.raises(InvalidParameterError, match="matches no file"):
        open_forecasts(str(tmp_path / "none" / "*.nc"))


def test_scalar_gridded_equals_scipy_interpolation(twin):
    """The scalar fast path is the parent's trilinear interpolation (same values to 1e-12),
    NaN where the cell touches a NaN node, and the parent's error outside the field."""
    from glideplan.fields import open_field

    fld = open_field(twin.truth)
    u = fld.u.copy()
    u[:, 10, 10] = np.nan
    fld = GriddedField(times=fld.times, lat=fld.lat, lon=fld.lon, u=u, v=fld.v, epoch=fld.epoch)
    fast = scalar_gridded(fld)
    rng = np.random.default_rng(0)
    for _ in range(300):
        t = rng.uniform(*fld.time_span)
        la = rng.uniform(fld.lat[0], fld.lat[-1])
        lo = rng.uniform(fld.lon[0], fld.lon[-1])
        a, b = GriddedField.velocity(fld, t, la, lo), fast.velocity(t, la, lo)
        for x, y in zip(a, b, strict=True):
            assert (math.isnan(float(x)) and math.isnan(float(y))) or \
                float(x) == pytest.approx(float(y), abs=1e-12)
    assert math.isnan(float(fast.velocity(100.0, float(fld.lat[10]), float(fld.lon[10]))[0]))
    with pytest.raises(InvalidParameterError):
        fast.velocity(100.0, 0.0, 0.0)


def test_lateness_and_front_schedule_closed_forms():
    """`_lateness`: a plan due east along the equator at 1 m/s, the vehicle 3.6 km short of
    where the plan is at 2 h -> 1 h late (to 1 s: the local plane at the equator is exact to
    1e-6 over 10 km); `_front_schedule`: an arrival map linear in longitude is interpolated
    exactly at the track's vertices, ending at the front's arrival."""
    from types import SimpleNamespace

    from glideplan.routing.replay import Plan, _Flyer, _front_schedule, _lateness

    k = math.radians(1.0) * 6_371_000.0  # metres per degree at the equator
    t = np.linspace(0.0, 10_000.0, 11)
    plan = Plan(0.0, "x", "solved", 10_000.0, t, 0 * t, t / k, 0 * t + math.pi / 2)
    m = Mission((0.0, 0.0), (0.0, 0.2), 1.0, np.datetime64("2026-01-01"))
    fl = _Flyer(None, m, 0.0, 1e6, 600.0)  # type: ignore[arg-type]
    fl.t.append(7200.0)
    fl.lat.append(0.0)
    fl.lon.append(3600.0 / k)
    assert _lateness(plan, fl) == pytest.approx(3600.0, abs=1.0)
    lon = np.linspace(0.0, 1.0, 11)
    front = SimpleNamespace(lat=np.array([-1.0, 1.0]), lon=lon,
                            arrival=np.tile(lon * 36_000.0, (2, 1)))
    r = SimpleNamespace(front=front, grid_duration_s=36_000.0,
                        lat=np.zeros(5), lon=np.array([0.0, 0.25, 0.5, 0.7, 1.0]))
    sched, dur = _front_schedule(r, np.zeros(5), 1e9)
    assert dur == 36_000.0
    assert sched == pytest.approx([0.0, 9_000.0, 18_000.0, 25_200.0, 36_000.0], abs=1e-6)
