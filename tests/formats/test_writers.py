"""Every exported file read back by an independent reader (issue 13: files out).

Readers: pymavlink `mavwp.MAVWPLoader` (QGC WPL), `json` + the .plan structure of FORMATS.md,
gpxpy and GPSBabel (GPX/KML/GeoJSON), fastkml (KML), and `vehicle_checks` (Slocum, Seaglider).
Coordinates must survive within each format's precision: DDMM.MMMM at 4 decimals is
0.5e-4 / 60 deg; WPL and KML print 8-9 decimals; GPSBabel's unicsv prints 6.
"""

from __future__ import annotations

import csv
import io
import itertools
import json
import math
import pathlib
import shutil
import subprocess

import numpy as np
import pytest

from glideplan.formats import (
    ExportOptions,
    ddmm_to_degrees,
    degrees_to_ddmm,
    export_mission,
    parse_formats,
    read_route,
)
from glideplan.missions import plan_mission

from .vehicle_checks import check_seaglider, check_slocum, ddmm

DATA = pathlib.Path(__file__).parents[2] / "src/glideplan/missions/data/buzzards_bay.gpx"
DDMM_TOL = 0.5e-4 / 60 + 1e-12


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    out = tmp_path_factory.mktemp("export")
    plan = plan_mission(read_route(DATA), speed=0.5, radius=400.0)
    opts = ExportOptions(acceptance_radius=60.0, altitude=80.0, goto_number=20,
                         max_goto_waypoints=5)
    files, legs = export_mission(plan, out, parse_formats(None), opts)
    return plan, files, legs


def _coords(legs):
    return np.column_stack([legs.lat, legs.lon])


def test_ddmm_examples_and_carry():
    """FORMATS.md examples; 59.99995' at 4 decimals carries into the next degree."""
    assert degrees_to_ddmm(40 + 22.552 / 60) == "4022.5520"
    assert degrees_to_ddmm(-(73 + 53.7601 / 60)) == "-7353.7601"
    assert degrees_to_ddmm(40 + 59.99996 / 60) == "4100.0000"
    assert degrees_to_ddmm(-(40 + 59.99996 / 60)) == "-4100.0000"
    assert degrees_to_ddmm(40 + 59.99994 / 60) == "4059.9999"
    rng = np.random.default_rng(0)
    for v in np.concatenate([rng.uniform(-180, 180, 500), [0.0, 1e-9, -1e-9, 89.99999999]]):
        s = degrees_to_ddmm(float(v))
        assert abs(ddmm(s) - v) <= DDMM_TOL  # the independent decoder
        assert ddmm_to_degrees(s) == pytest.approx(ddmm(s), abs=1e-12)


def test_slocum_files_split_and_resolve(exported):
    _, files, legs = exported
    paths = [pathlib.Path(p) for p in files["slocum"]]
    assert [p.name for p in paths] == [f"goto_l{20 + k}.ma" for k in range(len(paths))]
    got = []
    for k, p in enumerate(paths):
        pts = check_slocum(p)
        assert len(pts) <= 5
        if k:  # consecutive files share their boundary waypoint
            assert pts[0] == got[-1]
            pts = pts[1:]
        got += pts
    assert len(paths) > 1, "the fixture's list is longer than 5 waypoints: the files split"
    np.testing.assert_allclose(np.array(got), _coords(legs), atol=DDMM_TOL)


def test_seaglider_targets(exported):
    plan, files, legs = exported
    targets = check_seaglider(pathlib.Path(files["seaglider"]))
    assert len(targets) == len(legs.names)
    latlon = np.array([(a, b) for a, b, _ in targets.values()])
    np.testing.assert_allclose(latlon, _coords(legs), atol=DDMM_TOL)
    names = list(targets)
    for name in plan.route.names:  # names from the route
        assert name in names
    assert all(targets[a][2] == b for a, b in itertools.pairwise(names))


def test_qgc_wpl_read_by_pymavlink(exported):
    """pymavlink's loader (it rejects lines without 12 fields); home = first waypoint."""
    from pymavlink import mavwp

    plan, files, legs = exported
    loader = mavwp.MAVWPLoader()
    n = loader.load(files["qgc-wpl"])
    assert n == len(legs.names) + 1
    home = loader.wp(0)
    assert (home.x, home.y) == pytest.approx((plan.route.lat[0], plan.route.lon[0]), abs=1e-8)
    for i in range(1, n):
        wp = loader.wp(i)
        assert wp.command == 16 and wp.frame == 3
        assert wp.z == pytest.approx(80.0) and wp.param2 == pytest.approx(60.0)
        assert (wp.x, wp.y) == pytest.approx((legs.lat[i - 1], legs.lon[i - 1]), abs=1e-8)


PLAN_SCHEMA = {  # FORMATS.md, QGC .plan: key -> type (nested dicts are sub-schemas)
    "fileType": str, "version": int, "groundStation": str,
    "mission": {"version": int, "firmwareType": int, "vehicleType": int,
                "cruiseSpeed": (int, float), "hoverSpeed": (int, float),
                "plannedHomePosition": list, "items": list},
    "geoFence": {"version": int, "polygons": list, "circles": list},
    "rallyPoints": {"version": int, "points": list},
}
ITEM_SCHEMA = {"type": str, "command": int, "frame": int, "params": list,
               "autoContinue": bool, "doJumpId": int}


def _check_schema(obj, schema, where="plan"):
    for key, typ in schema.items():
        assert key in obj, f"{where}.{key} missing"
        if isinstance(typ, dict):
            _check_schema(obj[key], typ, f"{where}.{key}")
        else:
            assert isinstance(obj[key], typ), f"{where}.{key} is {type(obj[key]).__name__}"


def test_qgc_plan_json(exported):
    plan, files, legs = exported
    text = pathlib.Path(files["qgc-plan"]).read_text()
    doc = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-JSON constant {c}"))
    _check_schema(doc, PLAN_SCHEMA)
    assert doc["fileType"] == "Plan" and doc["mission"]["version"] == 2
    home = doc["mission"]["plannedHomePosition"]
    assert home[:2] == pytest.approx([plan.route.lat[0], plan.route.lon[0]], abs=1e-12)
    items = doc["mission"]["items"]
    assert len(items) == len(legs.names)
    for k, item in enumerate(items):
        _check_schema(item, ITEM_SCHEMA, f"items[{k}]")
        assert item["type"] == "SimpleItem" and item["command"] == 16 and item["frame"] == 3
        assert len(item["params"]) == 7 and item["doJumpId"] == k + 1
        assert item["params"][4:6] == pytest.approx([legs.lat[k], legs.lon[k]], abs=1e-12)
        assert item["params"][6] == 80.0


def test_gpx_read_by_gpxpy(exported):
    import gpxpy

    plan, files, legs = exported
    gpx = gpxpy.parse(pathlib.Path(files["gpx"]).read_text())
    rte = gpx.routes[0].points
    np.testing.assert_allclose([(p.latitude, p.longitude) for p in rte], _coords(legs),
                               atol=1e-9)
    assert [p.name for p in gpx.waypoints] == list(plan.route.names)
    trk = gpx.tracks[0].segments[0].points
    assert len(trk) > 10 * len(rte)  # the dense track
    # glideplan reads its own GPX back as a route (route points first)
    assert read_route(files["gpx"]).names == legs.names


def _gpsbabel(kind: str, fmt: str, path: str) -> list[list[str]]:
    out = subprocess.run(["gpsbabel", kind, "-i", fmt, "-f", path, "-o", "unicsv", "-F", "-"],
                         capture_output=True, text=True, check=True, timeout=30).stdout
    return list(csv.reader(io.StringIO(out)))[1:]


@pytest.mark.skipif(shutil.which("gpsbabel") is None, reason="gpsbabel not installed")
@pytest.mark.parametrize(("fmt", "kind"), [("gpx", "-r"), ("geojson", "-r"), ("kml", "-t")])
def test_gpsbabel_reads_the_straight_legs(exported, fmt, kind):
    """GPSBabel (independent C++ reader): GPX routes, GeoJSON LineStrings (routes) and KML
    LineStrings (tracks; the straight legs come first) within its 6 printed decimals."""
    plan, files, legs = exported
    rows = _gpsbabel(kind, fmt, files[fmt])
    got = np.array([(float(r[1]), float(r[2])) for r in rows[: len(legs.names)]])
    np.testing.assert_allclose(got, _coords(legs), atol=5.1e-7)
    waypoints = _gpsbabel("-w", fmt, files[fmt])
    assert [r[3] for r in waypoints] == list(plan.route.names)
    np.testing.assert_allclose([(float(r[1]), float(r[2])) for r in waypoints],
                               np.column_stack([plan.route.lat, plan.route.lon]), atol=5.1e-7)


def test_kml_read_by_fastkml(exported):
    from fastkml import kml

    plan, files, legs = exported
    doc = kml.KML.from_string(pathlib.Path(files["kml"]).read_bytes())
    marks = list(doc.features[0].features)
    points = [m for m in marks if type(m.geometry).__name__ == "Point"]
    lines = {m.name: m.geometry for m in marks if type(m.geometry).__name__ == "LineString"}
    assert [m.name for m in points] == list(plan.route.names)
    np.testing.assert_allclose([(c[1], c[0]) for c in lines["straight legs"].coords],
                               _coords(legs), atol=1e-9)
    assert len(lines["track"].coords) > 10 * len(legs.names)


def test_geojson_and_csv(exported):
    plan, files, legs = exported
    doc = json.loads(pathlib.Path(files["geojson"]).read_text())
    assert doc["type"] == "FeatureCollection"
    kinds = [f["properties"]["kind"] for f in doc["features"]]
    assert kinds.count("waypoint") == plan.route.n and "track" in kinds
    pts = [f for f in doc["features"] if f["properties"]["kind"] == "waypoint"]
    for f, lat, lon, h in zip(pts, plan.route.lat, plan.route.lon, plan.headings_deg,
                              strict=True):
        assert f["geometry"]["coordinates"] == [lon, lat]  # longitude first, exact
        assert f["properties"]["heading_deg"] == pytest.approx(h)
    with open(files["csv"], newline="") as fh:
        rows = list(csv.DictReader(fh))
    np.testing.assert_allclose([(float(r["lat"]), float(r["lon"])) for r in rows],
                               _coords(legs), atol=1e-9)
    assert all(0 <= float(r["heading_deg"]) < 360 for r in rows)
    assert not math.isnan(float(rows[0]["heading_deg"]))


def test_carry_through_the_vehicle_files(tmp_path):
    """A waypoint 0.00004' below a whole degree is written as the next degree, 00.0000'
    (FORMATS.md), in both the Slocum and the Seaglider file, and decodes within DDMM precision."""
    from glideplan.missions import Route

    lat = 40 + 59.99996 / 60
    lon = -(70 + 59.99996 / 60)
    route = Route.from_geographic(["P", "Q"], [lat, lat + 0.01], [lon, lon + 0.01])
    plan = plan_mission(route, speed=1.0, radius=50.0)
    files, _ = export_mission(plan, tmp_path, ("slocum", "seaglider"),
                                 ExportOptions(max_deviation=5.0))
    goto = pathlib.Path(files["slocum"][0])
    assert "-7100.0000   4100.0000" in goto.read_text()
    assert check_slocum(goto)[0] == pytest.approx((41.0, -71.0), abs=1e-12)
    targets = check_seaglider(pathlib.Path(files["seaglider"]))
    assert targets["P"][:2] == pytest.approx((41.0, -71.0), abs=1e-12)
    assert abs(targets["P"][0] - lat) <= DDMM_TOL and abs(targets["P"][1] - lon) <= DDMM_TOL
