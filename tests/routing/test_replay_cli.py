"""`glideplan route replay` and `glideplan study replay` end to end on a small QG twin."""

from __future__ import annotations

import json

import pytest


@pytest.fixture(scope="module")
def twin(tmp_path_factory):
    """A 32 x 32, 1/12 deg twin: 4 days, 3 daily forecasts of 2 days; two missions."""
    from glideplan.fields.twin import TwinConfig, write_twin
    from glideplan.studies.replay import write_missions

    out = tmp_path_factory.mktemp("twin")
    files = write_twin(out, TwinConfig(n=32, days=4.0, forecasts=3, lead_days=2.0,
                                       spinup_days=30.0, seed=5))
    rows = [{"id": "a", "start_lat": 29.5, "start_lon": -60.5, "goal_lat": 30.1,
             "goal_lon": -59.7, "depart": "2026-03-01T00:00:00Z", "speed_mps": 0.5,
             "goal_radius_m": 2000.0, "max_hours": 60.0},
            {"id": "b", "start_lat": 30.3, "start_lon": -59.5, "goal_lat": 29.7,
             "goal_lon": -60.3, "depart": "2026-03-01T12:00:00Z", "speed_mps": 0.5,
             "goal_radius_m": 2000.0, "max_hours": 60.0}]
    write_missions(out / "missions.csv", rows)
    return files


def test_route_replay_cli_json_plot_geojson(twin, run_cli, tmp_path):
    fc = str(twin.truth.parent / "forecasts" / "*.nc")
    code, out, err = run_cli("route", "replay", "--truth", str(twin.truth), "--forecasts", fc,
                             "--from", "29.5", "-60.5", "--to", "30.1", "-59.7", "--speed",
                             "0.5", "--depart", "2026-03-01T00:00Z", "--max-duration", "60",
                             "--json", "--plot", str(tmp_path / "r.png"), "--geojson",
                             str(tmp_path / "r.geojson"))
    d = json.loads(out)
    assert code == (0 if d["status"] == "solved" else 1), err
    assert d["status"] in ("solved", "unreachable")
    assert set(d["baselines"]) == {"naive", "plan_once", "hindsight"}
    assert d["replans"][0]["forecast_reference_time"] == "2026-03-01T00:00:00Z"
    assert (tmp_path / "r.png").stat().st_size > 10_000
    gj = json.loads((tmp_path / "r.geojson").read_text())
    kinds = [f["properties"]["kind"] for f in gj["features"]]
    assert kinds[0] == "flown" and "plan" in kinds and "baseline" in kinds
    # the flown track in the GeoJSON is the JSON's track
    assert gj["features"][0]["geometry"]["coordinates"][-1] == pytest.approx(
        [d["track"]["lon"][-1], d["track"]["lat"][-1]])


def test_route_replay_bad_input(twin, cli_error, tmp_path):
    fc = str(twin.truth.parent / "forecasts" / "*.nc")
    base = ["route", "replay", "--truth", str(twin.truth), "--from", "29.5", "-60.5", "--to",
            "30.1", "-59.7", "--speed", "0.5", "--max-duration", "20"]
    line = cli_error(*base, "--forecasts", str(tmp_path / "*.nc"), "--depart",
                     "2026-03-01T00:00Z")
    assert "--forecasts" in line and "matches no file" in line
    line = cli_error(*base, "--forecasts", fc, "--depart", "2026-02-28T00:00Z")
    assert "--truth" in line and "does not cover the mission" in line
    late = str(twin.truth.parent / "forecasts" / "fc_00[12].nc")
    line = cli_error(*base, "--forecasts", late, "--depart", "2026-03-01T06:00Z")
    assert "fc_001.nc" in line and "no forecast is issued at or before" in line


def test_route_example_still_works(run_cli):
    """`route` keeps its options: the dispatch only rewrites `route replay`."""
    code, out, _ = run_cli("route", "--example", "double-gyre", "--from", "0.2", "0.2",
                             "--to", "0.5", "1.2", "--speed", "0.9", "--help")
    assert code == 0 and "--example" in out


def test_study_replay_cli_resumes_and_reports(twin, run_cli, cli_error, tmp_path):
    fc = str(twin.truth.parent / "forecasts" / "*.nc")
    args = ["study", "replay", "--truth", str(twin.truth), "--forecasts", fc, "--missions",
            str(twin.truth.parent / "missions.csv"), "--out", str(tmp_path / "s"),
            "--workers", "1", "--json"]
    code, out, err = run_cli(*args)
    assert code == 0, err
    d = json.loads(out)
    assert [m["id"] for m in d["missions"]] == ["a", "b"]
    s = d["summary"]
    assert s["missions"] == 2
    assert s["feasible"] == sum(m["baselines"]["hindsight"]["status"] == "solved"
                                for m in d["missions"])
    assert set(s["success_rate"]) == {"replan", "plan_once", "naive"}
    for name in ("summary.json", "outcomes.csv", "summary.png", "results.sqlite"):
        assert (tmp_path / "s" / name).exists()
    code, out2, err = run_cli(*args)  # resumed: nothing runs again, same answer
    d2 = json.loads(out2)
    assert d2["run"]["ran"] == 0 and d2["run"]["skipped"] == 2
    assert d2["summary"] == s
    bad = tmp_path / "bad.csv"
    bad.write_text("id,start_lat,start_lon,goal_lat,goal_lon,depart,speed_mps,max_hours\n"
                   "x,29.5,-60.5,30,-60,2026-03-01T00:00Z,0.5,10\n")
    line = cli_error(*args[:6], "--missions", str(bad), "--out", str(tmp_path / "t"))
    assert "bad.csv" in line and "goal_radius_m" in line


def test_route_replay_help_reads_as_documented(run_cli):
    """`route replay --help` names the command as the user types it (was `route-replay`)."""
    code, out, _ = run_cli("route", "replay", "--help")
    assert code == 0
    assert "glideplan route replay" in out and "route-replay" not in out
    # --follow track (the default) steers by the time-to-go map (ReplaySettings.feedback)
    assert "time-to-go" in " ".join(out.replace("│", " ").split())


def test_study_replay_missions_file_as_saved_by_a_spreadsheet_or_wrong(twin, cli_error,
                                                                       tmp_path):
    """A binary file given as --missions is bad input (exit 2, one line naming it), not an
    internal error; a CSV saved with a UTF-8 byte-order mark (Excel's "CSV UTF-8") reads."""
    from glideplan.studies.replay import read_missions

    fc = str(twin.truth.parent / "forecasts" / "*.nc")
    png = tmp_path / "map.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR" + bytes(range(256)))
    line = cli_error("study", "replay", "--truth", str(twin.truth), "--forecasts", fc,
                     "--missions", str(png), "--out", str(tmp_path / "s"))
    assert "--missions" in line and "map.png" in line and "not a UTF-8 text CSV" in line
    text = (twin.truth.parent / "missions.csv").read_text(encoding="utf-8")
    bom = tmp_path / "excel.csv"
    bom.write_bytes(b"\xef\xbb\xbf" + text.encode("utf-8"))
    assert read_missions(bom) == read_missions(twin.truth.parent / "missions.csv")


def test_route_replay_forecasts_wrong_file_or_elsewhere(twin, cli_error, tmp_path):
    """A forecast that is not NetCDF/GRIB says so as the truth does; a forecast that does not
    cover the start or goal is named as the forecast (was: "position latitude=...")."""
    import numpy as np

    from glideplan.fields.synthetic import copernicus_dataset

    base = ["route", "replay", "--truth", str(twin.truth), "--from", "29.5", "-60.5", "--to",
            "30.1", "-59.7", "--speed", "0.5", "--max-duration", "20", "--depart",
            "2026-03-01T00:00Z"]
    png = tmp_path / "fc.png"
    png.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(64))
    line = cli_error(*base, "--forecasts", str(png))
    assert "--forecasts" in line and "fc.png" in line and "not a NetCDF or GRIB file" in line
    lat, lon = np.arange(44.0, 45.01, 0.25), np.arange(-9.0, -7.99, 0.25)
    times = np.datetime64("2026-03-01T00") + np.arange(3) * np.timedelta64(1, "D")
    zero = np.zeros((3, 1, lat.size, lon.size))
    copernicus_dataset(lat, lon, times, [0.5], zero, zero).to_netcdf(tmp_path / "far.nc")
    line = cli_error(*base, "--forecasts", str(tmp_path / "far.nc"))
    assert line.startswith("glideplan: error: --forecasts") and "far.nc" in line
    assert "--from latitude=29.5" in line and "south bound 44" in line
    (tmp_path / "d" / "sub").mkdir(parents=True)  # a glob that matches a folder
    line = cli_error(*base, "--forecasts", str(tmp_path / "d" / "*"))
    assert "--forecasts" in line and "sub" in line and "directory" in line
