"""The simulator with a disturbance that depends on position and time (`FieldDisturbance`)."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError
from glideplan.simulation import (
    FieldDisturbance,
    PathArrays,
    SteadyDisturbance,
    closed_loop,
    follow_paths,
)

R0 = 20.0 / 0.3


def _paths(n: int = 12, seed: int = 5) -> PathArrays:
    rng = np.random.default_rng(seed)
    goals = np.column_stack([rng.uniform(-4, 4, (n, 2)) * R0, rng.uniform(-3, 3, n)])
    return PathArrays.dubins(goals, np.full(n, 1.5 * R0))


def test_uniform_field_equals_steady_disturbance_exactly():
    """A field that is the same constant everywhere is the steady disturbance: same floats in,
    same floats out (the simulator's arithmetic does not depend on where delta comes from)."""
    paths = _paths()
    n = paths.count
    speed, direction = 5.0, 0.7
    ux, uy = speed * np.cos(direction), speed * np.sin(direction)
    steady = follow_paths(paths, SteadyDisturbance((ux, uy)).stream(n, 0.05),
                          disturbance_bound=speed, record=True)
    field = FieldDisturbance(lambda t, x, y: (np.full(x.shape, ux), np.full(x.shape, uy)))
    moved = follow_paths(paths, field.stream(n, 0.05), disturbance_bound=speed, record=True)
    np.testing.assert_array_equal(moved.error, steady.error)
    np.testing.assert_array_equal(moved.time, steady.time)
    np.testing.assert_array_equal(moved.tracks, steady.tracks)
    assert moved.stopped is not None and not moved.stopped.any()
    assert steady.stopped is None
    # the recorded cross-track error is |e| <= the distance to the path's start at step 0
    assert moved.cross_track is not None and moved.cross_track.shape[1] == n
    np.testing.assert_allclose(moved.cross_track[0], 0.0, atol=1e-9)


def test_field_is_evaluated_at_each_vehicle_position_and_time():
    """A current along +y that exists only for x < 0 and t0 + t < 1000 s: every call sees the
    vehicles' current positions (checked against the recorded tracks) and the offset time."""
    paths = PathArrays.from_segments(np.array([[-200.0, 0.0, 0.0], [-200.0, 50.0, 0.0]]),
                                     np.zeros((2, 1)), np.full((2, 1), 400.0), R0)
    seen: list[tuple[float, np.ndarray]] = []

    def velocity(t, x, y):
        seen.append((t, np.column_stack([x, y]).copy()))
        v = np.where(x < 0.0, 2.0, 0.0)
        return np.zeros_like(x), v

    res = follow_paths(paths, FieldDisturbance(velocity, t0=990.0).stream(2, 0.05),
                       disturbance_bound=2.0, record=True)
    assert res.tracks is not None
    for k, (t, xy) in enumerate(seen[:50]):
        assert t == pytest.approx(990.0 + 0.05 * k, abs=1e-9)
        np.testing.assert_array_equal(xy, res.tracks[k])
    assert res.crossed.all()


def test_vehicle_stops_where_the_field_is_undefined():
    """NaN (land, off the field) beyond x = 100 m: that vehicle stops as a failure, flagged
    in `stopped`; the other one, which stays on the field, finishes normally."""
    paths = PathArrays.from_segments(np.array([[0.0, 0.0, 0.0], [0.0, 0.0, np.pi]]),
                                     np.zeros((2, 1)), np.full((2, 1), 300.0), R0)

    def velocity(t, x, y):
        return np.where(x > 100.0, np.nan, 0.0), np.zeros_like(x)

    res = follow_paths(paths, FieldDisturbance(velocity).stream(2, 0.05), record=True)
    assert res.stopped is not None
    assert res.stopped.tolist() == [True, False]
    assert res.crossed.tolist() == [False, True]
    assert np.isnan(res.error[0]) and res.error[1] < 1e-6
    # reported at the end of the first step that starts beyond x = 100 m (20 m/s, dt 0.05 s)
    assert 100.0 / 20.0 < res.time[0] <= 100.0 / 20.0 + 2 * 0.05 + 1e-9


def test_walked_segment_index_equals_the_scan(monkeypatch):
    """Long chained paths use the walked segment index; it must give what the scan over every
    break point gives (bit for bit) on paths with many segments, zero lengths included."""
    rng = np.random.default_rng(2)
    n, k = 6, 15
    dirs = rng.choice([-1.0, 0.0, 1.0], size=(n, k))
    lens = rng.uniform(0.0, 2.0 * R0, size=(n, k))
    lens[:, 3] = 0.0
    paths = PathArrays.from_segments(np.zeros((n, 3)), dirs, lens, 2.0 * R0)
    stream = SteadyDisturbance((4.0 * math.cos(1.0), 4.0 * math.sin(1.0)))
    walked = follow_paths(paths, stream.stream(n, 0.05), disturbance_bound=4.0)
    monkeypatch.setattr(closed_loop, "_SCAN_BREAKS", 10**6)
    scanned = follow_paths(paths, stream.stream(n, 0.05), disturbance_bound=4.0)
    np.testing.assert_array_equal(walked.error, scanned.error)
    np.testing.assert_array_equal(walked.time, scanned.time)
    assert walked.crossed.sum() >= n - 1


def test_bad_field_disturbance():
    with pytest.raises(InvalidParameterError, match="velocity"):
        FieldDisturbance(3.0)  # type: ignore[arg-type]
    with pytest.raises(InvalidParameterError, match="t0"):
        FieldDisturbance(lambda t, x, y: (x, y), t0=float("nan"))

