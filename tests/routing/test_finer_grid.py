"""A grid too coarse for a current stronger than the vehicle (`routing.finer_grid`).

The field: a steady eastward Gaussian jet u(y) = U exp(-(y / w)^2), U = 1 m/s, w = 3 km, along
40.5 N, crossed northwards by a 0.3 m/s vehicle from (40.4, -70.2) to (40.6, -70.1). On a
1800-3200 m grid the front's characteristic cannot be flown (its controls leave the field;
before `finer_grid` the answer was not_verified with a duration of ~1,800 h).

Reference (closed form, independent of the router): Zermelo's problem in a parallel shear
flow u(y). The Hamiltonian does not depend on x, so along the optimal path
cos(theta) / (V + u(y) cos(theta)) = k is constant (theta the heading from east), i.e.
cos(theta) = k V / (1 - k u(y)); then T = int dy / (V sin theta) and the eastward
displacement X = int (V cos theta + u) / (V sin theta) dy, with k found by Brent's method so
that X is the goal's (a local plane at the jet's latitude: over 22 km north the metric
changes by < 0.2 %, a few metres here). Tolerance of a routed duration: h / V, the time to
swim one grid spacing h of the grid that answered (as in test_strong_currents.py).
"""

from __future__ import annotations

import functools
import json
import math

import numpy as np
import pytest

from glideplan.fields import AnalyticField
from glideplan.fields.field import Extent
from glideplan.routing import route
from glideplan.routing.sphere import EARTH_RADIUS_M

U, W, V = 1.0, 3000.0, 0.3
LAT_C = 40.5
START, GOAL = (40.4, -70.2), (40.6, -70.1)


def _y(lat):
    return (np.asarray(lat) - LAT_C) * math.radians(1.0) * EARTH_RADIUS_M


def _jet() -> AnalyticField:
    def fn(t, lat, lon):
        return U * np.exp(-(_y(lat) / W) ** 2) + 0 * lon, 0 * lat + 0 * lon

    return AnalyticField(fn=fn, extent=Extent(39.5, 41.5, -71.0, -69.0), name="jet")


@functools.cache
def _crossing_time() -> float:
    """The closed form of the module docstring (s)."""
    from scipy.integrate import quad
    from scipy.optimize import brentq

    y0, y1 = float(_y(START[0])), float(_y(GOAL[0]))
    X = math.radians(GOAL[1] - START[1]) * EARTH_RADIUS_M * math.cos(math.radians(LAT_C))

    def u(y):
        return U * math.exp(-(y / W) ** 2)

    def integrals(k):
        def c(y):
            return k * V / (1 - k * u(y))

        def s(y):
            return math.sqrt(1 - c(y) ** 2)

        T = quad(lambda y: 1 / (V * s(y)), y0, y1, points=[0.0], limit=200)[0]
        dx = quad(lambda y: (V * c(y) + u(y)) / (V * s(y)), y0, y1, points=[0.0], limit=200)[0]
        return T, dx

    # |cos theta| < 1 on the whole crossing for k in (-1 / (V + U), 1 / (V + U)) ... wider
    # for k < 0; the bracket [-3, -0.5] holds the one root (X changes sign across it)
    k = brentq(lambda k: integrals(k)[1] - X, -3.0, -0.5, xtol=1e-12)
    return integrals(k)[0]


def test_closed_form_crossing():
    """The reference itself: a straight crossing with no jet would take 22.2 km / V = 20.6 h
    plus the jet's set; the solved k gives 22.69 h (hand check of the quadrature above)."""
    assert _crossing_time() / 3600 == pytest.approx(22.692, abs=1e-3)


def test_coarse_grid_in_a_jet_faster_than_the_vehicle_runs_again_finer():
    """resolution 3000 m (11 cells across 33 km; the first grid fails from 1800 m up,
    measured 1800-3200 m): the route the front finds cannot be flown; route() runs again at
    half the spacing and answers solved there (measured: 1500 m), with the closed form's time
    within h / V of the grid that answered, a warning naming both grids, and the grids tried
    in stats. On main: not_verified, duration ~1,800 h."""
    r = route(_jet(), START, GOAL, V, resolution=3000.0)
    assert r.status == "solved", r.message
    h = r.stats["spacing_m"]
    tried = r.stats["grids"]
    assert [g["spacing_m"] for g in tried] == [3000.0 / 2**k for k in range(len(tried))]
    assert [g["status"] for g in tried] == ["not_verified"] * (len(tried) - 1) + ["solved"]
    assert h == tried[-1]["spacing_m"] < 3000.0
    assert r.duration_s == pytest.approx(_crossing_time(), abs=h / V)
    assert r.endpoint_error_m <= r.endpoint_tolerance_m == pytest.approx(h)
    (warning,) = [w for w in r.warnings if "too coarse" in w]
    assert "the 3000 m routing grid" in warning and "faster than the vehicle's 0.3 m/s" in warning
    assert f"--resolution {h:.0f} gives" in warning


def test_when_no_grid_flies_it_says_why_and_gives_no_duration(monkeypatch):
    """With no finer grid to try, the answer stays not_verified, its one sentence names the
    grid, the current against the vehicle and a --resolution to try (half the grid), and it
    claims no duration (the held legs' time is no flown time); the front's arrival stays in
    grid_duration_s."""
    monkeypatch.setattr("glideplan.routing.finer_grid.ladder", lambda h0, floor: [])
    r = route(_jet(), START, GOAL, V, resolution=3000.0)
    assert r.status == "not_verified" and not r.ok
    assert r.duration_s is None and r.arrive is None
    assert r.grid_duration_s is not None and r.grid_duration_s < 2 * _crossing_time()
    assert "\n" not in r.message and r.message.count(";") == 1
    assert r.message.startswith("the route the front found on the 3000 m grid cannot be flown")
    assert "faster than the vehicle's 0.3 m/s" in r.message
    assert "--resolution of 1500 m or finer" in r.message
    d = r.to_dict()
    assert d["duration_s"] is None and d["arrive"] is None


def test_a_route_that_flies_on_its_grid_is_not_rerun():
    """Resolution 600 m (finer than 750 m, coarser than the default 133 m): solved on its
    own grid, one grid in the answer, no warning (routes that verify pay nothing new)."""
    r = route(_jet(), START, GOAL, V, resolution=600.0)
    assert r.status == "solved", r.message
    assert r.stats["spacing_m"] == 600.0 and "grids" not in r.stats
    assert not any("too coarse" in w for w in r.warnings)


def _jet_file(path) -> None:
    """The jet as a Copernicus-like file: 0.005 deg in latitude (555 m), 0.01 in longitude,
    steady (two levels)."""
    from glideplan.fields.synthetic import copernicus_dataset

    lat = np.arange(40.2, 40.8001, 0.005)
    lon = np.arange(-70.4, -69.9001, 0.01)
    times = np.array(["2026-01-01T00:00", "2026-01-03T00:00"], dtype="datetime64[ns]")
    u = U * np.exp(-(_y(lat) / W) ** 2)[None, None, :, None] * np.ones((2, 1, 1, lon.size))
    copernicus_dataset(lat, lon, times, [0.5], u, 0 * u).to_netcdf(path)


def test_cli_warns_of_the_finer_grid_or_fails_in_one_line(tmp_path, run_cli, error_line,
                                                         monkeypatch):
    """`glideplan route --field jet.nc ... --resolution 3000`: exit 0, solved on 1500 m
    within h / V of the closed form (the file's bilinear jet differs from the Gaussian by
    < 1 %), one warning line naming the 3000 m grid and --resolution 1500. With no finer
    grid to try: exit 1, one error line naming --resolution, no duration in the JSON, and the
    summary prints no infinite miss."""
    jet = tmp_path / "jet.nc"
    _jet_file(jet)
    args = ("route", "--field", str(jet), "--from", *map(str, START), "--to", *map(str, GOAL),
            "--speed", str(V), "--resolution", "3000")
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved" and data["stats"]["spacing_m"] == 1500.0
    assert data["duration_s"] == pytest.approx(_crossing_time(), abs=1500.0 / V)
    warned = [ln for ln in err.splitlines() if "too coarse" in ln]
    assert len(warned) == 1 and warned[0].startswith("glideplan: warning: the 3000 m routing")
    assert "--resolution 1500" in warned[0] and warned[0] in [
        f"glideplan: warning: {w}" for w in data["warnings"]]

    monkeypatch.setattr("glideplan.routing.finer_grid.ladder", lambda h0, floor: [])
    code, out, err = run_cli(*args, "--json")
    assert code == 1
    line = error_line(err)
    assert line.startswith("glideplan: error: route: not_verified: the route the front found "
                           "on the 3000 m grid cannot be flown")
    assert "--resolution of 1500 m or finer" in line
    data = json.loads(out)
    assert data["duration_s"] is None and data["arrive"] is None
    code, out, err = run_cli(*args)
    assert code == 1 and "status: not_verified" in out and "inf" not in out


def _fake(status: str, spacing: float, reason: str | None = None):
    from glideplan.results import Reason
    from glideplan.routing.result import RouteResult

    return RouteResult(status=status, reason=None if reason is None else Reason(reason),
                       duration_s=None if status == "unreachable" else 3600.0,
                       grid_duration_s=3000.0, stats={"spacing_m": spacing})


def test_ladder_halves_down_to_the_default_grid_and_unreachable_is_advised_not_rerun():
    """The ladder (by hand): 3000 m to a 617 m default -> 1500, 750, 617; none from the
    default itself. An unreachable answer by the front's own limit (max_duration) on a
    coarse grid is not rerun (a default-grid front to the time limit costs a minute): its
    message advises the default grid's --resolution; a window_limit (no finer grid helps)
    and the same answer on the default grid come back untouched."""
    from glideplan.routing.finer_grid import Attempt, finer, ladder
    from glideplan.routing.problem import RouteProblem
    from glideplan.routing.settings import RouteSettings

    assert ladder(3000.0, 617.0) == [1500.0, 750.0, 617.0]
    assert ladder(617.0, 617.0) == [] and ladder(1000.0, 617.0) == [617.0]
    problem = RouteProblem(None, START, GOAL, 0.05, 0.0, 3.6e6, "max_duration",
                           154_250.0, RouteSettings(resolution=3000.0), None)  # default 617 m
    ran: list[float] = []

    def run(p):
        ran.append(p.settings.resolution)
        raise AssertionError("no rerun for an unreachable answer")

    first = Attempt(_fake("unreachable", 3000.0, "max_duration"), True, 0.45)
    r = finer(problem, first, run)
    assert ran == [] and r.unreachable_reason == "max_duration"
    assert r.message.endswith("can stall it short of a reachable goal: --resolution 617 (the "
                              "default grid) checks")
    assert "3000 m grid" in r.message and "0.45 against 0.05 m/s" in r.message
    limited = Attempt(_fake("unreachable", 3000.0, "window_limit"), True, 0.45)
    assert finer(problem, limited, run) is limited.result
    default = Attempt(_fake("unreachable", 617.0, "max_duration"), True, 0.45)
    assert finer(problem, default, run) is default.result
