"""Exported waypoint names survive the round trip (issue 19): every interchange file carries
the straight-leg list's names, each tool's own reader finds them, and `read_route` reads the
list back with its names and coordinates.

Where the names live: GeoJSON `properties.names` of the straight-leg LineString (and `name`
of each waypoint Point), KML ExtendedData `names` of the straight-leg Placemark (and each
waypoint Placemark's `<name>`), GPX `<rtept><name>`, the CSV `name` column. QGC `.plan` and
WPL mission items have no name field (QGroundControl's format), so names are not written
there; Slocum and Seaglider files carry ASCII-safe names (tests/formats/test_writers.py).
"""

from __future__ import annotations

import csv
import json
import pathlib

import numpy as np
import pytest

from glideplan.formats import ExportOptions, export_mission, parse_formats, read_route

from .geojson_checks import check_feature_collection

NAMES = ["Start, dock", "Küste 1", 'Buoy "B"', "End"]


@pytest.fixture(scope="module")
def exported(tmp_path_factory):
    from glideplan.missions import Route, plan_mission

    route = Route.from_geographic(NAMES, [41.50, 41.505, 41.51, 41.50],
                                  [-70.90, -70.89, -70.895, -70.88],
                                  [90.0, np.nan, 0.0, np.nan])
    plan = plan_mission(route, speed=1.0, radius=150.0)
    assert plan.ok
    out = tmp_path_factory.mktemp("names")
    files, legs = export_mission(plan, out, parse_formats("geojson,kml,gpx,csv"),
                                 ExportOptions(acceptance_radius=20.0, max_deviation=5.0))
    assert len(legs.names) > len(NAMES)  # names between the waypoints too (Start_dock_1 ...)
    return plan, files, legs


def test_geojson_names_in_json_and_read_back(exported):
    _, files, legs = exported
    doc = json.loads(pathlib.Path(files["geojson"]).read_text(encoding="utf-8"))
    check_feature_collection(doc)
    legs_f = next(f for f in doc["features"] if f["properties"]["kind"] == "straight_legs")
    assert legs_f["geometry"]["type"] == "LineString"
    assert legs_f["properties"]["names"] == list(legs.names)
    points = [f["properties"]["name"] for f in doc["features"]
              if f["properties"]["kind"] == "waypoint"]
    assert points == NAMES
    r = read_route(files["geojson"])
    assert r.names == legs.names
    np.testing.assert_array_equal(r.lat, legs.lat)


def test_kml_names_by_fastkml_and_read_back(exported):
    from fastkml import kml

    _, files, legs = exported
    doc = kml.KML.from_string(pathlib.Path(files["kml"]).read_bytes())
    marks = list(doc.features[0].features)
    assert [m.name for m in marks if type(m.geometry).__name__ == "Point"] == NAMES
    leg_mark = next(m for m in marks if m.name == "straight legs")
    data = {d.name: d.value for d in leg_mark.extended_data.elements}
    assert json.loads(data["names"]) == list(legs.names)
    r = read_route(files["kml"])
    assert r.names == legs.names
    np.testing.assert_allclose(r.lat, legs.lat, rtol=0, atol=5e-10)  # 9 decimals


def test_gpx_names_by_gpxpy_and_read_back(exported):
    import gpxpy

    _, files, legs = exported
    gpx = gpxpy.parse(pathlib.Path(files["gpx"]).read_text(encoding="utf-8"))
    assert [q.name for q in gpx.routes[0].points] == list(legs.names)
    assert [q.name for q in gpx.waypoints] == NAMES
    assert read_route(files["gpx"]).names == legs.names


def test_csv_names_by_csv_module_and_read_back(exported):
    _, files, legs = exported
    with open(files["csv"], newline="", encoding="utf-8") as fh:
        assert [r["name"] for r in csv.DictReader(fh)] == list(legs.names)
    r = read_route(files["csv"])
    assert r.names == legs.names
    np.testing.assert_allclose(r.lat, legs.lat, rtol=0, atol=5e-10)
