"""Route files in: CSV (geographic or local), GPX, KML, GeoJSON; one-line errors (exit 2)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.formats import read_route

GPX_HEAD = '<?xml version="1.0"?><gpx version="1.1" creator="t" ' \
           'xmlns="http://www.topografix.com/GPX/1/1">'


def test_csv_geographic_with_headings(tmp_path):
    p = tmp_path / "r.csv"
    p.write_text("# a comment\nname,lat,lon,heading_deg\nA,41.5,-70.9,90\nB,41.6,-70.8,\n"
                 "C,41.7,-70.85,270\n")
    r = read_route(p)
    assert r.names == ("A", "B", "C") and r.geographic
    assert r.headings[0] == pytest.approx(0.0)  # compass 90 = east = 0 rad
    assert math.isnan(r.headings[1])
    assert r.headings[2] == pytest.approx(math.pi)
    assert r.lat[1] == 41.6 and r.lon[2] == -70.85


def test_csv_local_uses_the_plan_convention(tmp_path):
    p = tmp_path / "r.csv"
    p.write_text("name,x,y,heading_deg\na,0,0,90\nb,100,50,\n")
    r = read_route(p)
    assert not r.geographic
    assert r.headings[0] == pytest.approx(math.pi / 2)  # CCW from +x
    np.testing.assert_array_equal(r.x, [0, 100])


def test_gpx_prefers_route_then_waypoints_then_track(tmp_path):
    body = ('<wpt lat="1" lon="2"><name>W1</name></wpt><wpt lat="1.1" lon="2"><name>W2</name>'
            '</wpt><rte><rtept lat="3" lon="4"><name>R1</name></rtept><rtept lat="3.1" '
            'lon="4"/></rte><trk><trkseg><trkpt lat="5" lon="6"/><trkpt lat="5.1" lon="6"/>'
            '</trkseg></trk></gpx>')
    p = tmp_path / "a.gpx"
    p.write_text(GPX_HEAD + body)
    r = read_route(p)
    assert r.names == ("R1", "WP02") and r.lat[0] == 3.0
    p.write_text(GPX_HEAD + body.split("<rte>")[0] + "</gpx>")
    assert read_route(p).names == ("W1", "W2")
    p.write_text(GPX_HEAD + "<trk>" + body.split("<trk>")[1])
    assert read_route(p).lat[1] == 5.1


def test_kml_linestring_and_points(tmp_path):
    p = tmp_path / "a.kml"
    p.write_text('<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/'
                 'kml/2.2"><Document><Placemark><name>Path</name><LineString><coordinates>'
                 '-70.9,41.5,0 -70.8,41.6,0 -70.7,41.55,0</coordinates></LineString>'
                 '</Placemark></Document></kml>')
    r = read_route(p)
    assert r.n == 3 and r.lon[2] == -70.7 and r.lat[1] == 41.6
    p.write_text('<?xml version="1.0" encoding="UTF-8"?><kml xmlns="http://www.opengis.net/'
                 'kml/2.2"><Document><Placemark><name>A</name><Point><coordinates>-70.9,41.5'
                 '</coordinates></Point></Placemark><Placemark><name>B</name><Point>'
                 '<coordinates>-70.8,41.6</coordinates></Point></Placemark></Document></kml>')
    r = read_route(p)
    assert r.names == ("A", "B") and r.lat[1] == 41.6


def test_geojson_points_with_heading(tmp_path):
    p = tmp_path / "a.geojson"
    feats = [{"type": "Feature", "geometry": {"type": "Point", "coordinates": [-70.9, 41.5]},
              "properties": {"name": "A", "heading_deg": 0}},
             {"type": "Feature", "geometry": {"type": "Point", "coordinates": [-70.8, 41.6]},
              "properties": {"name": "B"}}]
    p.write_text(json.dumps({"type": "FeatureCollection", "features": feats}))
    r = read_route(p)
    assert r.names == ("A", "B") and r.headings[0] == pytest.approx(math.pi / 2)


@pytest.mark.parametrize(
    ("name", "text", "expect"),
    [
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\nB,95.0,-70.8\n", "line 3 latitude"),
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\nB,abc,-70.8\n", "line 3 lat"),
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\nB,41.6\n", "line 3"),
        ("bad.csv", "name,north,east\nA,1,2\n", "line 1"),
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\n", "at least two waypoints"),
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\nB,41.5,-70.9\n", "identical to the previous"),
        ("bad.csv", "name,lat,lon\nA,41.5,-70.9\nB,41.6,nan\n", "line 3 lon"),
        ("bad.gpx", "<gpx><rte><rtept lat=", "not a readable GPX"),
        ("bad.kml", "<html>not kml</html>", "no LineString or Point"),
        ("bad.geojson", '{"type": "FeatureCollection", "features": [{"type": "Feature"}]}',
         "feature 1"),
        ("bad.geojson", "{not json", "not a readable GeoJSON"),
        ("bad.txt", "x", "unknown route file type"),
        ("big.csv", "name,lat,lon\nA,0,0\nB,20,20\n", "split the mission"),
    ],
)
def test_bad_route_files_one_line_exit_2(tmp_path, cli_error, name, text, expect):
    """One line naming the file, the line/feature and the rule; exit 2, no traceback."""
    p = tmp_path / name
    p.write_text(text)
    line = cli_error("mission", "plan", str(p), "--speed", "1", "--radius", "10")
    assert str(p) in line and expect in line
