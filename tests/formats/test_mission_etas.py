"""Mission exports with per-waypoint ETAs (issue 26), read back by each format's own reader.

Reference: in still air a Dubins leg takes its path length over the speed, so waypoint i is
reached at sum_{k<i} L_k / V (the legs' lengths from their verified paths' segments, not
from the exporter's sampled track). With a departure time the ETAs are UTC times.
"""

from __future__ import annotations

import csv
import dataclasses
import datetime as dt
import json
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

from glideplan.formats import ExportOptions, export_mission, parse_formats, read_route
from glideplan.missions import plan_mission

DEPART = np.datetime64("2026-05-01T08:00:00", "ms")
SPEED = 1.0


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    d = tmp_path_factory.mktemp("etas")
    src = d / "wp.csv"
    src.write_text("name,lat,lon\nA,41.50,-70.70\nB,41.52,-70.66\nC,41.55,-70.67\n")
    plan = plan_mission(read_route(src), speed=SPEED, radius=200.0, headings=36)
    plan = dataclasses.replace(plan, depart=DEPART)
    files, legs = export_mission(plan, d / "out",
                                 parse_formats("geojson,kml,gpx,csv,slocum,seaglider,qgc-plan,qgc-wpl"),
                                 ExportOptions(name="m"))
    lengths = [sum(seg.length for seg in leg.path.segments) for leg in plan.legs]
    eta = np.concatenate([[0.0], np.cumsum(lengths) / SPEED])
    return plan, files, legs, eta


def _utc(seconds: float) -> dt.datetime:
    base = DEPART.astype("datetime64[ms]").item().replace(tzinfo=dt.UTC)
    return base + dt.timedelta(seconds=float(seconds))


def test_etas_are_the_legs_times(exported):
    plan, _, legs, eta = exported
    np.testing.assert_allclose(plan.waypoint_eta_s, eta, rtol=1e-9)
    # the straight-leg list's mission waypoints carry the same ETAs (from the track's t)
    np.testing.assert_allclose(legs.eta_s[legs.mission], eta, rtol=1e-9, atol=1e-6)
    assert np.all(np.diff(legs.eta_s) > 0)
    wps = plan.to_dict()["waypoints"]
    assert [w["eta"] for w in wps][-1] == str(DEPART + np.timedelta64(
        round(eta[-1] * 1e3), "ms")) + "Z"


def test_geojson_and_csv_etas(exported):
    _, files, _, eta = exported
    doc = json.loads(pathlib.Path(files["geojson"]).read_text())
    pts = [f["properties"] for f in doc["features"] if f["properties"]["kind"] == "waypoint"]
    np.testing.assert_allclose([p["eta_s"] for p in pts], eta, rtol=1e-9)
    assert [dt.datetime.fromisoformat(p["eta"]) for p in pts] == [
        _utc(round(e, 3)) for e in eta]
    with open(files["csv"], newline="") as fh:
        rows = list(csv.DictReader(fh))
    mission = [r for r in rows if r["mission"] == "1"]
    np.testing.assert_allclose([float(r["eta_s"]) for r in mission], eta, atol=1e-3)
    assert all(dt.datetime.fromisoformat(r["eta_utc"]) - _utc(e) < dt.timedelta(seconds=1e-3)
               for r, e in zip(mission, eta, strict=True))


def test_gpx_and_kml_etas(exported):
    import gpxpy
    from fastkml import kml

    _, files, _, eta = exported
    gpx = gpxpy.parse(pathlib.Path(files["gpx"]).read_text())
    got = [w.time for w in gpx.waypoints]
    assert all(abs(g - _utc(e)) < dt.timedelta(milliseconds=1) for g, e in
               zip(got, eta, strict=True))
    doc = kml.KML.from_string(pathlib.Path(files["kml"]).read_bytes())
    marks = [m for m in doc.features[0].features if type(m.geometry).__name__ == "Point"]
    stamps = [m.times.timestamp.dt for m in marks]
    assert all(abs(s - _utc(e)) < dt.timedelta(milliseconds=1) for s, e in
               zip(stamps, eta, strict=True))


def test_vehicle_files_carry_the_etas_as_comments(exported):
    """Slocum goto and Seaglider targets have no time field: each waypoint's ETA goes in its
    comment; the files still parse (the independent checks of `vehicle_checks`)."""
    from .vehicle_checks import check_seaglider, check_slocum

    _, files, legs, eta = exported
    when = [_utc(e).strftime("%Y-%m-%dT%H:%M:%S") for e in eta]
    targets = pathlib.Path(files["seaglider"])
    assert len(check_seaglider(targets)) == len(legs.names)
    comments = [ln for ln in targets.read_text().splitlines() if " ETA +" in ln]
    assert len(comments) == len(legs.names)
    assert comments[-1].startswith("/ C ETA +") and when[-1] in comments[-1]
    text = "".join(pathlib.Path(p).read_text() for p in files["slocum"])
    assert sum(len(check_slocum(pathlib.Path(p))) for p in files["slocum"]) >= len(eta)
    for name, w in zip(("A", "B", "C"), when, strict=True):
        assert f"# {name} ETA +" in text and w in text


def test_qgc_plan_carries_the_etas_per_item(exported):
    """QGC `.plan` has no time field: each SimpleItem carries its ETA in an extra `glideplan`
    key, which QGroundControl's item reader ignores (it validates only the keys it knows);
    the file still passes the .plan checks of test_writers (json + FORMATS.md schema) and the
    QGC WPL file is unchanged (QGC rejects any line that is not 12 fields: no place there)."""
    from pymavlink import mavwp

    from .test_writers import ITEM_SCHEMA, PLAN_SCHEMA, _check_schema

    _, files, legs, eta = exported
    doc = json.loads(pathlib.Path(files["qgc-plan"]).read_text(),
                     parse_constant=lambda c: pytest.fail(f"non-JSON constant {c}"))
    _check_schema(doc, PLAN_SCHEMA)
    items = doc["mission"]["items"]
    for k, item in enumerate(items):
        _check_schema(item, ITEM_SCHEMA, f"items[{k}]")
        assert item["doJumpId"] == k + 1 and len(item["params"]) == 7
    extra = [item["glideplan"] for item in items]
    assert [x["name"] for x in extra] == list(legs.names)
    np.testing.assert_allclose([x["eta_s"] for x in extra], legs.eta_s, rtol=1e-12)
    mission = [extra[i] for i in np.flatnonzero(legs.mission)]
    np.testing.assert_allclose([x["eta_s"] for x in mission], eta, rtol=1e-9, atol=1e-6)
    assert all(abs(dt.datetime.fromisoformat(x["eta"]) - _utc(e)) < dt.timedelta(milliseconds=1)
               for x, e in zip(mission, eta, strict=True))
    loader = mavwp.MAVWPLoader()
    assert loader.load(files["qgc-wpl"]) == len(legs.names) + 1


@pytest.mark.skipif(shutil.which("gpsbabel") is None, reason="gpsbabel not installed")
def test_gpsbabel_reads_the_waypoint_times(exported):
    _, files, _, eta = exported
    out = subprocess.run(["gpsbabel", "-w", "-i", "gpx", "-f", files["gpx"], "-o", "unicsv",
                          "-F", "-"], capture_output=True, text=True, check=True,
                         timeout=30).stdout
    rows = list(csv.DictReader(out.splitlines()))
    assert [r["Name"] for r in rows] == ["A", "B", "C"]
    when = _utc(eta[-1])
    assert rows[-1]["Date"] == when.strftime("%Y/%m/%d")
    assert rows[-1]["Time"][:8] == when.strftime("%H:%M:%S")


def test_local_route_names_the_skipped_formats(run_cli, tmp_path):
    """Local x,y waypoints: `--export` writes the CSV and a warning names the other formats
    (it said nothing before); the JSON carries the same warning and per-waypoint ETAs."""
    src = tmp_path / "local.csv"
    src.write_text("name,x,y\nA,0,0\nB,600,0\n")
    code, out, err = run_cli("mission", "plan", str(src), "--speed", "1", "--radius", "100",
                             "--headings", "8", "--export", str(tmp_path / "o"), "--json")
    assert code == 0, err
    data = json.loads(out)
    assert list(data["files"]) == ["csv"]
    warning = [w for w in data["warnings"] if w.startswith("not written")]
    assert warning and all(f in warning[0] for f in ("geojson", "kml", "gpx", "qgc-wpl",
                                                     "qgc-plan", "slocum", "seaglider"))
    assert err.count("not written: geojson") == 1  # once (it was printed twice)
    assert data["waypoints"][1]["eta_s"] == pytest.approx(data["total_duration_s"])
