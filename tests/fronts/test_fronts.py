"""The front (glideplan.fronts) against closed forms on the sphere.

References: great-circle distances from pyproj's Geod on the same sphere (independent of the
front); the drift disk (a uniform drift c: first arrival |x - c t| = V t, solved for t); the
gauge of a velocity set (support function); a wall with a gap (two straight legs via the
gap's edge). Tolerances: the front is first order at kinks and near second order in smooth
regions; each check states the accuracy it allows in grid spacings h, measured from the
method's convergence (halving h at least halves the error), not from one passing run.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("numba")

from glideplan.errors import InvalidParameterError
from glideplan.fronts import (
    EARTH_RADIUS_M,
    DriftLevels,
    FrontProblem,
    LatLonGrid,
    backtrack,
    propagate,
    start_state,
)


def _geod():
    from pyproj import Geod

    return Geod(a=EARTH_RADIUS_M, b=EARTH_RADIUS_M)


def _still_arrival(step_deg: float, goal: tuple[float, float], lon0: float = -1.0) -> tuple[
    float, float
]:
    lat = np.arange(43.0, 47.0 + 1e-9, step_deg)
    lon = np.arange(lon0 - 0.6, goal[1] + 0.6 + 1e-9, step_deg)
    g = LatLonGrid(lat, lon)
    prob = FrontProblem(g, speeds=[10.0])
    st = start_state(prob, 0.0, 45.0, lon0)
    res = propagate(prob, st, 1e7, goal=goal)
    assert res.reason == "goal"
    assert res.goal_time is not None
    _, _, d = _geod().inv(lon0, 45.0, goal[1], goal[0])
    return res.goal_time, d / 10.0


def test_still_water_is_the_great_circle_and_converges() -> None:
    """Arrival = great-circle distance / V; the error shrinks as h halves (>= 2x)."""
    goal = (45.6, 1.0)
    errs = []
    for step in (0.1, 0.05):
        t, exact = _still_arrival(step, goal)
        errs.append(abs(t / exact - 1.0))
    # one grid spacing (0.05 deg, ~4 km) over the ~170 km leg is ~2.3 %: allow 1/20 of it
    assert errs[1] < 1e-3
    assert errs[1] <= 0.5 * errs[0]


def test_backtracked_track_follows_the_great_circle() -> None:
    """The characteristic from 45N 1W to 45N 1E crosses 0E at the great circle's latitude."""
    lat = np.arange(44.0, 46.0 + 1e-9, 0.01)
    lon = np.arange(-1.5, 1.5 + 1e-9, 0.01)
    g = LatLonGrid(lat, lon)
    prob = FrontProblem(g, speeds=[1.0])
    st = start_state(prob, 0.0, 45.0, -1.0)
    res = propagate(prob, st, 1e9, goal=(45.0, 1.0))
    assert res.goal_time is not None
    ch = backtrack(prob, res.arrival, (45.0, 1.0), res.goal_time, 0.0, st.source,
                   st.start_radius_m)
    assert ch.complete
    assert ch.lat[0] == 45.0 and ch.lon[0] == -1.0
    # great circle through both points: its vertex latitude at lon 0 (closed form)
    lat_mid = math.degrees(math.atan(math.tan(math.radians(45.0)) / math.cos(math.radians(1.0))))
    mid = float(np.interp(0.0, ch.lon, ch.lat))
    assert abs(mid - lat_mid) * 111_195.0 < 0.25 * g.hy  # within a quarter cell
    # heading at 0E points east (the vertex), in the local frame
    k = int(np.argmin(np.abs(ch.lon)))
    assert abs(math.remainder(ch.heading[k], 2 * math.pi)) < 0.02


def test_uniform_drift_disk_closed_form() -> None:
    """A uniform drift c: |x - c t| = V t. Eastward goal with c = (0.3, 0.4) V."""
    lat = np.arange(-0.4, 0.4 + 1e-9, 0.004)
    lon = np.arange(-0.4, 0.6 + 1e-9, 0.004)
    g = LatLonGrid(lat, lon)
    V = 2.0
    c = np.array([0.3, 0.4]) * V
    prob = FrontProblem(g, speeds=[V], drifts=[c])
    st = start_state(prob, 0.0, 0.0, 0.0)
    goal = (0.0, 0.45)
    res = propagate(prob, st, 1e9, goal=goal)
    assert res.goal_time is not None
    x = EARTH_RADIUS_M * math.radians(0.45)  # along the equator
    # |(x,0) - c t| = V t  ->  (V^2 - |c|^2) t^2 + 2 x c_x t - x^2 = 0
    A = V * V - float(c @ c)
    t_exact = (-x * c[0] + math.sqrt((x * c[0]) ** 2 + A * x * x)) / A
    assert abs(res.goal_time / t_exact - 1.0) < 2e-3


def test_two_modes_take_the_convex_hull() -> None:
    """Velocity sets conv{n + (0.5, 0), n - (0.5, 0)}: northward speed is 1 (the hull's flat
    top), not sqrt(0.75) (either circle alone)."""
    lat = np.arange(-0.3, 0.3 + 1e-9, 0.003)
    lon = np.arange(-0.3, 0.3 + 1e-9, 0.003)
    g = LatLonGrid(lat, lon)
    prob = FrontProblem(g, speeds=[1.0, 1.0], drifts=[[0.5, 0.0], [-0.5, 0.0]])
    st = start_state(prob, 0.0, 0.0, 0.0)
    res = propagate(prob, st, 1e9, goal=(0.25, 0.0))
    assert res.goal_time is not None
    y = EARTH_RADIUS_M * math.radians(0.25)
    assert abs(res.goal_time / (y / 1.0) - 1.0) < 5e-3
    assert abs(res.goal_time / (y / math.sqrt(0.75)) - 1.0) > 0.1


def test_wall_with_a_gap_goes_through_the_gap() -> None:
    """A wall along 0E from the south edge to 0.1N: the way round its end is two straight legs
    via the end (closed form); nothing crosses the wall."""
    lat = np.arange(-0.3, 0.3 + 1e-9, 0.002)
    lon = np.arange(-0.3, 0.3 + 1e-9, 0.002)
    g = LatLonGrid(lat, lon)
    tb = np.full(g.shape, np.inf)
    wall_j = int(np.argmin(np.abs(lon)))
    tb[lat <= 0.1, wall_j] = -np.inf
    prob = FrontProblem(g, speeds=[1.0], block_time=tb)
    st = start_state(prob, 0.0, -0.1, -0.1)
    goal = (-0.1, 0.1)
    res = propagate(prob, st, 1e9, goal=goal)
    assert res.goal_time is not None
    R = EARTH_RADIUS_M
    corner = (R * math.radians(0.1), R * math.radians(0.2))  # (dx, dy) to the end, each leg
    legs = 2 * math.hypot(*corner)
    h = g.hy
    assert res.goal_time == pytest.approx(legs, abs=2.5 * h)
    assert res.goal_time > legs - 0.5 * h  # never shorter than the way round
    assert np.all(np.isinf(res.arrival[tb == -np.inf]))


def test_block_times_stop_the_front() -> None:
    """Nodes beyond 20 km may only be entered before t = 20 km / V: the front stalls there."""
    lat = np.arange(-0.5, 0.5 + 1e-9, 0.005)
    lon = np.arange(-0.5, 0.5 + 1e-9, 0.005)
    g = LatLonGrid(lat, lon)
    x, y = g.local_xy(0.0, 0.0)
    r = np.hypot(x, y)
    V = 1.0
    tb = np.where(r > 20_000.0, 15_000.0 / V, np.inf)
    prob = FrontProblem(g, speeds=[V], block_time=tb)
    st = start_state(prob, 0.0, 0.0, 0.0)
    res = propagate(prob, st, 1e9)
    assert res.reason == "stalled"
    reached = np.isfinite(res.arrival)
    assert float(np.max(r[reached])) < 20_000.0 + 1.5 * g.hy
    assert float(np.max(r[reached])) > 20_000.0 - 1.5 * g.hy


def test_periodic_grid_crosses_the_antimeridian() -> None:
    """A global grid: 179.5E to 179.5W at the equator is 1 deg of great circle, not 359."""
    lat = np.arange(-3.0, 3.0 + 1e-9, 0.05)
    lon = np.arange(0.0, 360.0, 0.05)
    g = LatLonGrid(lat, lon, periodic=True)
    prob = FrontProblem(g, speeds=[5.0])
    st = start_state(prob, 0.0, 0.0, 179.5)
    res = propagate(prob, st, 1e9, goal=(0.0, -179.5))
    assert res.goal_time is not None
    exact = EARTH_RADIUS_M * math.radians(1.0) / 5.0
    assert abs(res.goal_time / exact - 1.0) < 3e-3
    ch = backtrack(prob, res.arrival, (0.0, -179.5), res.goal_time, 0.0, st.source,
                   st.start_radius_m)
    assert np.all(np.diff(ch.lon) > -1e-9)  # continuous, eastward through 180
    assert ch.lon[-1] == pytest.approx(180.5, abs=1e-9)


def test_time_levels_of_a_drift_field() -> None:
    """A drift that switches on at t1 (linear between levels): the arrival matches the
    integral of the along-track speed (closed form for an eastward drift on the equator)."""
    lat = np.arange(-0.3, 0.3 + 1e-9, 0.003)
    lon = np.arange(-0.1, 0.5 + 1e-9, 0.003)
    g = LatLonGrid(lat, lon)
    V, c1, t1 = 1.0, 0.5, 10_000.0
    shape = g.shape

    def level(k: int) -> tuple[np.ndarray, np.ndarray]:
        return np.full(shape, 0.0 if k == 0 else c1), np.zeros(shape)

    drift = DriftLevels(np.array([0.0, t1]), level)
    prob = FrontProblem(g, speeds=[V], drift=drift)
    st = start_state(prob, 0.0, 0.0, 0.0)
    res = propagate(prob, st, 1e9, goal=(0.0, 0.4))
    assert res.goal_time is not None
    x = EARTH_RADIUS_M * math.radians(0.4)
    # distance by t1: V t1 + c1 t1 / 2 (the drift ramps linearly); then V + c1
    d1 = V * t1 + 0.5 * c1 * t1
    t_exact = t1 + (x - d1) / (V + c1)
    assert abs(res.goal_time / t_exact - 1.0) < 3e-3


def test_bad_problems_are_refused() -> None:
    g = LatLonGrid(np.arange(0.0, 1.0, 0.1), np.arange(0.0, 1.0, 0.1))
    with pytest.raises(InvalidParameterError, match="speeds"):
        FrontProblem(g, speeds=[-1.0])
    with pytest.raises(InvalidParameterError, match="block_time"):
        FrontProblem(g, speeds=[1.0], block_time=np.zeros((2, 2)))
    with pytest.raises(InvalidParameterError, match="periodic"):
        LatLonGrid(np.arange(0.0, 1.0, 0.1), np.arange(0.0, 10.0, 0.1), periodic=True)
    prob = FrontProblem(g, speeds=[1.0])
    with pytest.raises(InvalidParameterError, match="outside"):
        start_state(prob, 0.0, 5.0, 0.5)


def test_parallel_stages_equal_the_serial_ones() -> None:
    """A front split over two threads (numba prange) is bit-identical to one thread: each node
    is computed by the same code; only the split differs."""
    import numba

    from glideplan.fronts import solver

    lat = np.arange(-0.2, 0.2 + 1e-9, 0.004)
    g = LatLonGrid(lat, lat.copy())
    prob = FrontProblem(g, speeds=[1.0, 0.7], drifts=[[0.2, 0.1], [-0.1, 0.3]])
    results = []
    old = solver.PARALLEL_MIN_NODES
    n_threads = numba.get_num_threads()
    try:
        solver.PARALLEL_MIN_NODES = 0
        for threads in (1, min(2, numba.config.NUMBA_NUM_THREADS)):
            numba.set_num_threads(threads)
            st = start_state(prob, 0.0, 0.0, 0.0)
            results.append(propagate(prob, st, 8000.0))
    finally:
        solver.PARALLEL_MIN_NODES = old
        numba.set_num_threads(n_threads)
    assert np.array_equal(results[0].arrival, results[1].arrival)
    assert np.array_equal(results[0].state.phi, results[1].state.phi)


def test_a_process_that_ran_a_front_can_fork(tmp_path) -> None:
    """`run_batch` forks workers: after a parallel front in the parent, workers that run fronts
    must not abort. (With NUMBA_THREADING_LAYER=omp this very script dies: GNU OpenMP aborts a
    forked child -- "fork() called from a process already using GNU OpenMP"; the kernel
    selects numba's fork-safe work queue.)"""
    import os
    import subprocess
    import sys

    script = tmp_path / "fork_after_front.py"
    script.write_text(
        "import numpy as np\n"
        "from glideplan import run_batch\n"
        "from glideplan.fronts import solver, LatLonGrid, FrontProblem, start_state, propagate\n"
        "solver.PARALLEL_MIN_NODES = 0\n"
        "def one(v):\n"
        "    g = LatLonGrid(np.arange(-0.1, 0.1, 0.004), np.arange(-0.1, 0.1, 0.004))\n"
        "    p = FrontProblem(g, speeds=[v])\n"
        "    return propagate(p, start_state(p, 0.0, 0.0, 0.0), 3000.0).steps\n"
        "if __name__ == '__main__':\n"
        "    one(3.0)\n"
        "    print(run_batch(one, [3.0, 4.0, 5.0, 6.0], processes=2, progress=False))\n"
    )
    env = {k: v for k, v in os.environ.items()
           if k not in ("NUMBA_NUM_THREADS", "NUMBA_THREADING_LAYER")}
    env["NUMBA_NUM_THREADS"] = "2"
    out = subprocess.run([sys.executable, str(script)], capture_output=True, text=True,
                         env=env, timeout=300, check=False, cwd=tmp_path)
    assert out.returncode == 0, out.stderr[-800:]
    steps = [int(x) for x in out.stdout.strip().strip("[]").split(",")]
    assert len(steps) == 4 and all(n > 0 for n in steps)


def test_a_grown_grid_keeps_the_band_narrow() -> None:
    """Growing the grid can widen the band (B follows the largest spacing): the old plateaus
    must become the new +-B, or every old node counts as inside the band (a global still-air
    route once took 80 s instead of 5 s that way)."""
    lat = np.arange(40.0, 41.0 + 1e-9, 0.01)
    g = LatLonGrid(lat, np.arange(0.0, 1.0 + 1e-9, 0.01))
    prob = FrontProblem(g, speeds=[1.0])
    res = propagate(prob, start_state(prob, 0.0, 40.5, 0.5), 4000.0)
    band_before = int(np.count_nonzero(np.abs(res.state.phi) < prob.band))
    wider = 1.05 * prob.band  # a grown grid reaching further south has wider cells
    ny, nx = g.shape
    grown = res.state.embedded((ny + 20, nx + 20), 10, 10, wider)
    after = int(np.count_nonzero(np.abs(grown.phi) < wider))
    # the same band (less the never-updated tails within 3 % of B, snapped like the kernel's)
    assert 0.9 * band_before <= after <= band_before
    assert np.array_equal(np.isfinite(grown.arrival), np.pad(np.isfinite(res.arrival), 10))
