"""`glideplan mission plan`: JSON keys of issue 13, exports, plot, wind, bad input."""

from __future__ import annotations

import json
import math
import pathlib

import pytest

DATA = pathlib.Path(__file__).parents[2] / "src/glideplan/missions/data/buzzards_bay.gpx"


def test_json_keys_and_exports(run_cli, tmp_path):
    out = tmp_path / "out"
    fig = tmp_path / "m.png"
    code, stdout, err = run_cli("mission", "plan", str(DATA), "--speed", "0.5", "--radius",
                                "400", "--json", "--export", str(out), "--formats",
                                "slocum,seaglider,qgc-plan", "--plot", str(fig))
    assert code == 0, err
    d = json.loads(stdout)
    for key in ("status", "total_length_m", "total_duration_s", "headings_deg", "legs",
                "track", "files", "stats"):
        assert key in d
    assert d["status"] == "solved"
    assert len(d["headings_deg"]) == 8 and len(d["legs"]) == 7
    assert set(d["legs"][0]) >= {"from", "to", "word", "length_m", "duration_s"}
    assert d["legs"][0]["from"] == "LAUNCH" and d["legs"][-1]["to"] == "RECV"
    assert sum(leg["length_m"] for leg in d["legs"]) == pytest.approx(d["total_length_m"])
    assert d["total_duration_s"] == pytest.approx(d["total_length_m"] / 0.5)
    assert set(d["track"]) == {"lat", "lon"}
    assert d["track"]["lat"][0] == pytest.approx(41.495, abs=1e-9)
    assert d["track"]["lon"][-1] == pytest.approx(-70.865, abs=1e-9)
    assert set(d["files"]) == {"slocum", "seaglider", "qgc-plan", "plot"}
    assert (out / "targets").is_file() and (out / "goto_l10.ma").is_file()
    assert fig.stat().st_size > 10_000
    assert d["stats"]["projection"]["roundtrip_error_deg"] < 1e-9
    assert d["stats"]["straight_legs"]["max_deviation_m"] <= 50.0  # half the 100 m default
    assert d["stats"]["max_endpoint_error"] < 1e-6


def test_local_route_with_wind(run_cli, tmp_path):
    """Local metres: track as x/y; wind 0.2 m/s from the west pushes east (time objective)."""
    p = tmp_path / "r.csv"
    p.write_text("name,x,y,heading_deg\na,0,0,0\nb,600,400,\nc,1200,0,\n")
    code, stdout, err = run_cli("mission", "plan", str(p), "--speed", "1", "--radius", "100",
                                "--wind", "0.2", "270", "--headings", "8", "--json")
    assert code == 0, err
    d = json.loads(stdout)
    assert set(d["track"]) == {"x", "y"} and d["objective"] == "time"
    assert d["wind"] == {"speed": 0.2, "from_deg": 270.0}
    assert d["headings_deg"][0] == pytest.approx(90.0)  # 0 deg CCW from +x = compass 90
    # downwind (eastward) the ground speed exceeds the airspeed: the time is below length / v
    assert d["total_duration_s"] < d["total_length_m"] / 1.0
    assert math.isfinite(d["stats"]["max_endpoint_error"])


@pytest.mark.parametrize(
    ("args", "expect"),
    [
        (["--speed", "-1", "--radius", "10"], "--speed"),
        (["--speed", "1", "--radius", "nan"], "--radius"),
        (["--speed", "1", "--radius", "10", "--objective", "fuel"], "--objective"),
        (["--speed", "1", "--radius", "10", "--wind", "0.2", "0", "--objective", "length"],
         "--objective"),
        (["--speed", "1", "--radius", "10", "--formats", "gpx"], "--formats"),
        (["--speed", "1", "--radius", "10", "--field", "missing.nc"], "--field"),
        (["--speed", "1", "--radius", "10", "--plot", "m.txt"], "--plot"),
    ],
)
def test_bad_options(cli_error, args, expect):
    assert expect in cli_error("mission", "plan", str(DATA), *args)


def test_geographic_formats_need_a_geographic_route(cli_error, tmp_path):
    p = tmp_path / "r.csv"
    p.write_text("name,x,y\na,0,0\nb,600,400\n")
    line = cli_error("mission", "plan", str(p), "--speed", "1", "--radius", "100", "--export",
                     str(tmp_path / "o"), "--formats", "slocum")
    assert "geographic route" in line


@pytest.mark.parametrize(
    ("flag", "value"),
    [("--goto-number", "120"), ("--max-goto-waypoints", "1"), ("--acceptance-radius", "0"),
     ("--max-deviation", "-5")],
)
def test_bad_export_options_fail_before_planning(cli_error, tmp_path, flag, value):
    line = cli_error("mission", "plan", str(DATA), "--speed", "1", "--radius", "10",
                     "--export", str(tmp_path), flag, value)
    assert flag in line


def test_demo_mission_example(tmp_path):
    """`make demo`'s mission product: planned, not longer than the heuristics, files written."""
    from glideplan.demos.products import PRODUCTS, run_product

    case = next(p for p in PRODUCTS if p.key == "mission")
    run = run_product(case, tmp_path, plots=False)
    assert run.ok and run.check.met
    best = float(run.check.reference.split()[1])  # "<= 10126.6 m heading heuristics"
    assert run.result.total_length_m <= best + 0.05
    for name in ("goto_l10.ma", "targets", "buzzards_bay.plan", "buzzards_bay.kml"):
        assert (tmp_path / name).is_file()
