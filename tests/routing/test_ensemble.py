"""`glideplan route --ensemble` and `--depart-range` (issue 25 parts 3-4): closed forms, bad input.

Members are NetCDF files written with `glideplan.fields.synthetic.copernicus_dataset` (nothing
downloaded), on the equator, where a uniform eastward current W is along the route's great
circle: the time-optimal route is the equator itself and its duration is t = D / (V + W) with
D = R dlon (the router's sphere), a closed form. Routes are solved by Zermelo shooting to
~1e-6 relative here; the tolerances below are the router's own claim, GRID_TIME_TOLERANCE
(5e-3 relative).
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.fields.synthetic import copernicus_dataset
from glideplan.routing.ensemble import ensemble_quantile
from glideplan.routing.route import GRID_TIME_TOLERANCE
from glideplan.routing.sphere import gc_distance

T0 = np.datetime64("2026-03-01T00:00", "ns")
TIMES = T0 + np.arange(49) * np.timedelta64(3600, "s")
LAT = np.arange(-0.5, 0.5 + 1e-9, 0.05)
LON = np.arange(0.0, 1.0 + 1e-9, 0.05)
START, GOAL = ("0", "0.1"), ("0", "0.6")
V = 0.5
D = float(gc_distance(0.0, 0.1, 0.0, 0.6))
W = (0.0, 0.1, 0.2, 0.3, 0.4)
COMMON = ("--from", *START, "--to", *GOAL, "--speed", str(V), "--resolution", "2000",
          "--workers", "1", "--json")


def _write(path, u, lat=LAT, times=TIMES):
    shape = (times.size, 1, lat.size, LON.size)
    uu = np.broadcast_to(np.asarray(u, dtype=float).reshape(-1, 1, 1, 1)
                         if np.ndim(u) else u, shape)
    copernicus_dataset(lat, LON, times, [0.494], uu, np.zeros(shape)).to_netcdf(path)


@pytest.fixture(scope="module")
def family(tmp_path_factory):
    """Uniform eastward currents W_i (m/s), one member each; and three identical members."""
    d = tmp_path_factory.mktemp("ens")
    (d / "uniform").mkdir()
    (d / "equal").mkdir()
    for i, w in enumerate(W):
        _write(d / "uniform" / f"member_{i:02d}.nc", w)
    for i in range(3):
        _write(d / "equal" / f"member_{i:02d}.nc", 0.2)
    return d


def test_quantile_is_numpys_linear_and_none_past_the_arrivals():
    """Reference: numpy.quantile (method 'linear') on finite durations."""
    d = [5.0, 1.0, 3.0, 2.0, 8.0]
    for q in (0.1, 0.5, 0.9):
        assert ensemble_quantile(d, q) == pytest.approx(float(np.quantile(d, q)))
    assert ensemble_quantile([1.0, 2.0, math.inf], 0.5) == pytest.approx(2.0)
    assert ensemble_quantile([1.0, 2.0, math.inf], 0.9) is None


def test_uniform_family_quantiles_match_the_closed_form(family, run_cli, tmp_path):
    """t_i = D / (V + W_i); P10/P50/P90 = numpy's linear quantiles of those; the route to
    fly, flown through member j in closed loop, arrives at t_j (the same straight line)."""
    png, gj = tmp_path / "ens.png", tmp_path / "ens.geojson"
    code, out, err = run_cli("route", "--ensemble", str(family / "uniform" / "member_*.nc"),
                             *COMMON, "--plot", str(png), "--geojson", str(gj))
    assert code == 0, err
    e = json.loads(out)["ensemble"]
    exact = np.array([D / (V + w) for w in W])
    assert e["members"] == len(W)
    assert e["duration_s"] == pytest.approx(list(exact), rel=GRID_TIME_TOLERANCE)
    assert e["p_arrival"] == 1.0
    for key, q in (("p10_h", 0.1), ("p50_h", 0.5), ("p90_h", 0.9)):
        assert e[key] == pytest.approx(np.quantile(exact, q) / 3600.0, rel=GRID_TIME_TOLERANCE)
    c = e["chosen"]
    assert c["p_arrival"] == 1.0
    assert c["closed_loop_duration_s"] == pytest.approx(list(exact), rel=GRID_TIME_TOLERANCE)
    assert png.stat().st_size > 10_000
    data = json.loads(gj.read_text())
    kinds = [f["properties"]["kind"] for f in data["features"]]
    assert kinds.count("member") == len(W) and kinds.count("route") == 1
    ring = next(f for f in data["features"] if f["properties"]["kind"] == "corridor")
    coords = ring["geometry"]["coordinates"][0]
    assert coords[0] == coords[-1]  # a closed GeoJSON ring, lon first
    lons = [p[0] for p in coords]
    assert min(lons) == pytest.approx(0.1, abs=0.02) and max(lons) == pytest.approx(0.6, abs=0.02)


def test_equal_members_give_equal_quantiles(family, run_cli):
    """All members equal: P10 = P50 = P90 = every member's duration; p_arrival 1, and 0 with
    a duration limit below the closed-form time (every member then unreachable, exit 1)."""
    pattern = str(family / "equal" / "member_*.nc")
    code, out, err = run_cli("route", "--ensemble", pattern, *COMMON)
    assert code == 0, err
    e = json.loads(out)["ensemble"]
    assert e["p_arrival"] == 1.0
    assert e["p10_h"] == e["p50_h"] == e["p90_h"]
    assert len(set(e["duration_s"])) == 1
    assert e["p50_h"] * 3600 == pytest.approx(D / (V + 0.2), rel=GRID_TIME_TOLERANCE)
    short = 0.5 * D / (V + 0.2) / 3600.0
    code, out, err = run_cli("route", "--ensemble", pattern, *COMMON, "--max-duration",
                             f"{short:.3f}")
    assert code == 1, err
    e = json.loads(out)["ensemble"]
    assert e["p_arrival"] == 0.0
    assert e["p10_h"] is e["p50_h"] is e["p90_h"] is None
    assert e["duration_s"] == [None, None, None] and e["chosen"] is None


@pytest.fixture(scope="module")
def switch_on(tmp_path_factory):
    """No current until 10 h, then 0.5 m/s east from 11 h (linear between the two levels)."""
    d = tmp_path_factory.mktemp("switch")
    hours = (TIMES - T0) / np.timedelta64(1, "h")
    u = np.where(hours >= 11.0, 0.5, 0.0)
    for i in range(2):
        _write(d / f"member_{i}.nc", u)
    return d


def test_depart_range_best_departure_matches_the_closed_form(switch_on, run_cli, tmp_path):
    """Departing at t_d >= 11 h takes D / (V + W) (the shortest); departing earlier crawls at V
    until the switch: longer. The best departure is the first of the range at or after 11 h
    (12 h), and the durations are the closed form's there."""
    png = tmp_path / "dep.png"
    code, out, err = run_cli("route", "--field", str(switch_on / "member_0.nc"),
                             "--depart-range", "2026-03-01T00:00Z", "2026-03-01T20:00Z", "4",
                             *COMMON, "--plot", str(png))
    assert code == 0, err
    data = json.loads(out)
    rows = data["departures"]
    assert [r["depart"][11:16] for r in rows] == ["00:00", "04:00", "08:00", "12:00", "16:00",
                                                  "20:00"]
    assert data["best_departure"] == "2026-03-01T12:00:00Z"
    fast = D / (V + 0.5)
    for r in rows[3:]:
        assert r["duration_s"] == pytest.approx(fast, rel=GRID_TIME_TOLERANCE)
    for r in rows[:3]:  # before the switch: at least the wait's loss over the crawl
        assert r["duration_s"] > fast * (1 + 4 * GRID_TIME_TOLERANCE)
    # departing at 0 h: 10 h at V (18 km), the ramp 10-11 h (mean current 0.25 m/s: 2.7 km),
    # then the rest at V + W
    rest = D - V * 10 * 3600 - (V + 0.25) * 3600
    assert rows[0]["duration_s"] == pytest.approx(11 * 3600 + rest / (V + 0.5),
                                                  rel=GRID_TIME_TOLERANCE)
    assert png.stat().st_size > 10_000


def test_depart_range_with_an_ensemble(switch_on, run_cli):
    """Per departure the ensemble statistics; the best departure is the same closed-form one."""
    code, out, err = run_cli("route", "--ensemble", str(switch_on / "member_*.nc"),
                             "--depart-range", "2026-03-01T04:00Z", "2026-03-01T12:00Z", "8",
                             *COMMON)
    assert code == 0, err
    data = json.loads(out)
    assert [r["p_arrival"] for r in data["departures"]] == [1.0, 1.0]
    assert data["best_departure"] == "2026-03-01T12:00:00Z"
    assert data["ensemble"]["p50_h"] * 3600 == pytest.approx(D / (V + 0.5),
                                                             rel=GRID_TIME_TOLERANCE)
    assert data["ensemble"]["chosen"]["p_arrival"] == 1.0


def test_local_process_pool_gives_the_same_answer(family, run_cli):
    """Two local processes (run_batch's pool) against in-process: the same durations."""
    pattern = str(family / "equal" / "member_*.nc")
    args = [a if a != "1" else "2" for a in COMMON]
    code, out, err = run_cli("route", "--ensemble", pattern, *args)
    assert code == 0, err
    assert json.loads(out)["ensemble"]["duration_s"][0] == pytest.approx(
        D / (V + 0.2), rel=GRID_TIME_TOLERANCE)


def test_bad_input(family, cli_error, tmp_path):
    """Empty glob, members on different grids, END < START, a step <= 0: one line, exit 2."""
    line = cli_error("route", "--ensemble", str(tmp_path / "none_*.nc"), *COMMON)
    assert "--ensemble" in line and "matches no file" in line
    mixed = tmp_path / "mixed"
    mixed.mkdir()
    _write(mixed / "member_0.nc", 0.1)
    _write(mixed / "member_1.nc", 0.1, lat=np.arange(-0.5, 0.5 + 1e-9, 0.1))
    line = cli_error("route", "--ensemble", str(mixed / "member_*.nc"), *COMMON)
    assert "--ensemble" in line and "member_1.nc" in line and "one grid" in line
    field = str(family / "uniform" / "member_00.nc")
    line = cli_error("route", "--field", field, "--depart-range", "2026-03-01T10:00Z",
                     "2026-03-01T04:00Z", "2", *COMMON)
    assert "--depart-range" in line and "END" in line
    for step in ("0", "-1"):
        line = cli_error("route", "--field", field, "--depart-range", "2026-03-01T00:00Z",
                         "2026-03-01T04:00Z", step, *COMMON)
        assert "--depart-range" in line and "step" in line
    line = cli_error("route", "--field", field, "--depart-range", "2026-03-01T00:00Z",
                     "2026-03-09T04:00Z", "2", *COMMON)
    assert "--depart-range" in line
    line = cli_error("route", "--field", field, *COMMON)  # --workers alone
    assert "--workers" in line and "--ensemble" in line


def test_one_file_with_a_member_dimension(tmp_path, run_cli):
    """CF `realization` in one file = the same ensemble as one file per member (FORMATS.md):
    durations t_i = D / (V + W_i) for the members W = 0.1, 0.3."""
    import xarray as xr

    parts = []
    for w in (0.1, 0.3):
        path = tmp_path / f"m{w}.nc"
        _write(path, w)
        with xr.open_dataset(path) as ds:
            parts.append(ds.load())
    one = tmp_path / "one"
    one.mkdir()
    xr.concat(parts, dim="realization").assign_coords(realization=[0, 1]).to_netcdf(
        one / "ens.nc")
    code, out, err = run_cli("route", "--ensemble", str(one), *COMMON)  # a folder works too
    assert code == 0, err
    e = json.loads(out)["ensemble"]
    assert e["members"] == 2 and e["files"][1].endswith("ens.nc[realization=1]")
    assert e["duration_s"] == pytest.approx([D / (V + 0.1), D / (V + 0.3)],
                                            rel=GRID_TIME_TOLERANCE)


def test_library_steady_members_and_start_equal_goal():
    """`route_ensemble` on steady FlowFields (no time span, no limit: route()'s own default
    applies to the closed loop too): t_i = D / (V + W_i); start = goal: zero durations."""
    from glideplan.fields.field import UniformField
    from glideplan.routing import RouteSettings
    from glideplan.routing.ensemble import route_ensemble

    fields = [UniformField(w, 0.0) for w in (0.1, 0.3)]
    res = route_ensemble(fields, (0.0, 0.1), (0.0, 0.6), V, processes=1,
                         settings=RouteSettings(resolution=2000.0))
    assert res.ok and res.p_arrival == 1.0 and res.chosen_p_arrival == 1.0
    assert res.durations == pytest.approx([D / 0.6, D / 0.8], rel=GRID_TIME_TOLERANCE)
    same = route_ensemble(fields, (0.0, 0.1), (0.0, 0.1), V, processes=1)
    assert same.ok and list(same.durations) == [0.0, 0.0] and same.quantile_h(0.5) == 0.0
