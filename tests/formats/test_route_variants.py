"""Route files as other tools write them (issue 19): GeoJSON null geometries (skipped with a
warning), MultiLineString/MultiPoint, KML MultiGeometry, KMZ, the older Google Earth KML
namespaces, CSV header and delimiter variants, decimal commas and degrees-and-minutes.

Every file is built here; the expected coordinates are the numbers written into it (decimal
degrees exactly, degrees and minutes by d + m/60, hand-derived in each case).
"""

from __future__ import annotations

import json
import math
import zipfile

import numpy as np
import pytest

from glideplan.formats import read_route

# 40 deg 22.552' N, 73 deg 53.7601' W (FORMATS.md's DDMM example) and a second point
LAT1, LON1 = 40 + 22.552 / 60, -(73 + 53.7601 / 60)
LAT2, LON2 = 40 + 25.0 / 60, -(73 + 50.5 / 60)


def _fc(*features):
    return json.dumps({"type": "FeatureCollection", "features": list(features)})


def _point(lon, lat, name=None):
    return {"type": "Feature", "geometry": {"type": "Point", "coordinates": [lon, lat]},
            "properties": {} if name is None else {"name": name}}


# ----- GeoJSON ------------------------------------------------------------------------------
def test_geojson_null_geometry_is_skipped_with_a_warning(tmp_path):
    p = tmp_path / "a.geojson"
    p.write_text(_fc(_point(-70.9, 41.5, "A"),
                     {"type": "Feature", "geometry": None, "properties": {"name": "note"}},
                     _point(-70.8, 41.6, "B")))
    r = read_route(p)
    assert r.names == ("A", "B")
    assert len(r.warnings) == 1
    assert str(p) in r.warnings[0] and "feature 2" in r.warnings[0] and "null" in r.warnings[0]


def test_geojson_only_null_geometries_is_refused(tmp_path):
    p = tmp_path / "a.geojson"
    p.write_text(_fc({"type": "Feature", "geometry": None, "properties": {}}))
    with pytest.raises(ValueError, match="without geometry were skipped"):
        read_route(p)


def test_null_geometry_warning_reaches_the_cli_user(tmp_path, run_cli):
    """`mission plan` prints the reader's warning as one `glideplan: warning:` line."""
    p = tmp_path / "a.geojson"
    p.write_text(_fc(_point(-70.9, 41.5, "A"),
                     {"type": "Feature", "geometry": None, "properties": {}},
                     _point(-70.89, 41.51, "B")))
    code, _, err = run_cli("mission", "plan", str(p), "--speed", "1", "--radius", "50")
    assert code == 0, err
    lines = [ln for ln in err.splitlines() if ln.startswith("glideplan: warning:")]
    assert len(lines) == 1 and "feature 2 has no geometry (null): skipped" in lines[0]


def test_geojson_multilinestring_parts_joined_in_order(tmp_path):
    """Two parts meeting at the antimeridian (RFC 7946 3.1.9): the shared seam point (180 and
    -180 at latitude 11) is kept once; without `names` it is a waypoint of the route."""
    p = tmp_path / "a.geojson"
    geom = {"type": "MultiLineString",
            "coordinates": [[[179.0, 10.0], [180.0, 11.0]], [[-180.0, 11.0], [-179.0, 12.0]]]}
    p.write_text(_fc({"type": "Feature", "geometry": geom, "properties": {}}))
    r = read_route(p)
    np.testing.assert_array_equal(r.lat, [10.0, 11.0, 12.0])
    assert r.lon[0] == 179.0 and abs(r.lon[1]) == 180.0 and r.lon[2] == -179.0
    assert r.warnings == ()


def test_geojson_multilinestring_names_drop_interpolated_seam_points(tmp_path):
    """`names` with null at a seam point glideplan interpolated: the point is dropped."""
    p = tmp_path / "a.geojson"
    geom = {"type": "MultiLineString",
            "coordinates": [[[179.0, 10.0], [180.0, 11.0]], [[-180.0, 11.0], [-179.0, 12.0]]]}
    p.write_text(_fc({"type": "Feature", "geometry": geom,
                      "properties": {"names": ["West", None, "East"]}}))
    r = read_route(p)
    assert r.names == ("West", "East")
    np.testing.assert_array_equal(r.lat, [10.0, 12.0])


def test_geojson_multilinestring_with_a_gap_is_joined_with_a_warning(tmp_path):
    p = tmp_path / "a.geojson"
    geom = {"type": "MultiLineString",
            "coordinates": [[[-70.9, 41.5], [-70.8, 41.55]], [[-70.7, 41.6], [-70.6, 41.6]]]}
    p.write_text(_fc({"type": "Feature", "geometry": geom, "properties": {}}))
    r = read_route(p)
    np.testing.assert_array_equal(r.lon, [-70.9, -70.8, -70.7, -70.6])
    assert len(r.warnings) == 1 and "joined in order" in r.warnings[0]


def test_geojson_multipoint(tmp_path):
    p = tmp_path / "a.geojson"
    p.write_text(json.dumps({"type": "Feature", "properties": {"name": "G"}, "geometry": {
        "type": "MultiPoint", "coordinates": [[-70.9, 41.5], [-70.8, 41.6]]}}))
    r = read_route(p)
    assert r.names == ("G-1", "G-2") and r.lat[1] == 41.6


# ----- KML / KMZ ----------------------------------------------------------------------------
KML_LINES = ("<Placemark><name>Leg</name><MultiGeometry>"
             "<LineString><coordinates>179,10,0 180,11,0</coordinates></LineString>"
             "<LineString><coordinates>-180,11,0 -179,12,0</coordinates></LineString>"
             "</MultiGeometry></Placemark>")
KML_POINTS = ("<Placemark><name>P</name><MultiGeometry>"
              "<Point><coordinates>-70.9,41.5</coordinates></Point>"
              "<Point><coordinates>-70.8,41.6</coordinates></Point>"
              "</MultiGeometry></Placemark>")


def _kml(body, ns='xmlns="http://www.opengis.net/kml/2.2"'):
    return f'<?xml version="1.0" encoding="UTF-8"?><kml {ns}><Document>{body}</Document></kml>'


def test_kml_multigeometry_lines_and_points(tmp_path):
    p = tmp_path / "a.kml"
    p.write_text(_kml(KML_LINES))
    r = read_route(p)
    np.testing.assert_array_equal(r.lat, [10.0, 11.0, 12.0])
    assert r.names == ("Leg-1", "Leg-2", "Leg-3")
    p.write_text(_kml(KML_POINTS))
    r = read_route(p)
    assert r.names == ("P-1", "P-2") and r.lon[1] == -70.8


@pytest.mark.parametrize("ns", ['xmlns="http://earth.google.com/kml/2.0"',
                                'xmlns="http://earth.google.com/kml/2.1"',
                                'xmlns="http://earth.google.com/kml/2.2"', ""])
def test_kml_older_google_earth_namespaces_and_none(tmp_path, ns):
    p = tmp_path / "a.kml"
    p.write_text(_kml("<Placemark><name>Path</name><LineString><coordinates>-70.9,41.5,0 "
                      "-70.8,41.6,0</coordinates></LineString></Placemark>", ns))
    r = read_route(p)
    assert r.n == 2 and r.lat[1] == 41.6 and r.lon[0] == -70.9


@pytest.mark.parametrize("inner", ["doc.kml", "files/route.kml"])
def test_kmz(tmp_path, inner):
    """A KMZ is a zip: `doc.kml`, else the first .kml in it (here with an image first)."""
    p = tmp_path / "a.kmz"
    with zipfile.ZipFile(p, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("files/icon.png", b"\x89PNG")
        z.writestr(inner, _kml(KML_POINTS))
    r = read_route(p)
    assert r.names == ("P-1", "P-2") and r.lat[0] == 41.5


@pytest.mark.parametrize(("content", "rule"), [
    (b"not a zip", "not a readable KMZ"),
    (None, "holds no .kml file"),
])
def test_bad_kmz_one_line(tmp_path, cli_error, content, rule):
    p = tmp_path / "a.kmz"
    if content is None:
        with zipfile.ZipFile(p, "w") as z:
            z.writestr("readme.txt", "no kml")
    else:
        p.write_bytes(content)
    line = cli_error("mission", "plan", str(p), "--speed", "1", "--radius", "10")
    assert str(p) in line and rule in line


# ----- CSV ----------------------------------------------------------------------------------
@pytest.mark.parametrize("header", [
    "name,Latitude,Longitude", "name,lat,lng", "name,LAT,LON", "name,lat,long",
    "Name,Lat,Lng", "NAME,latitude,longitude", "name,lat_deg,lon_deg",
])
def test_csv_header_variants(tmp_path, header):
    p = tmp_path / "a.csv"
    p.write_text(f"{header}\nA,41.5,-70.9\nB,41.6,-70.8\n")
    r = read_route(p)
    assert r.names == ("A", "B") and r.lat[1] == 41.6 and r.lon[0] == -70.9


@pytest.mark.parametrize(("delim", "decimal"), [(";", "."), ("\t", "."), (";", ","),
                                                ("\t", ",")])
def test_csv_delimiters_sniffed_and_decimal_commas(tmp_path, delim, decimal):
    p = tmp_path / "a.csv"
    rows = [["name", "lat", "lon", "heading_deg"], ["A", "41.5", "-70.9", "90.5"],
            ["B", "41.6", "-70.8", ""]]
    p.write_text("\n".join(delim.join(c.replace(".", decimal) for c in r) for r in rows) + "\n")
    r = read_route(p)
    assert r.names == ("A", "B") and r.lat[1] == 41.6 and r.lon[0] == -70.9
    assert r.headings[0] == pytest.approx(math.radians(90.0 - 90.5))  # compass 90.5
    assert (len(r.warnings) == 1 and "decimal mark" in r.warnings[0]) == (decimal == ",")


def test_csv_quoted_decimal_commas(tmp_path):
    p = tmp_path / "a.csv"
    p.write_text('name,lat,lon\nA,"41,5","-70,9"\nB,"41,6","-70,8"\n')
    r = read_route(p)
    assert r.lat[0] == 41.5 and r.lon[1] == -70.8 and "decimal mark" in r.warnings[0]


def test_csv_semicolons_mixing_decimal_marks_refused(tmp_path):
    p = tmp_path / "a.csv"
    p.write_text("name;lat;lon\nA;41,5;-70.9\nB;41.6;-70,8\n")
    with pytest.raises(ValueError, match=r"mix '\.' and ','"):
        read_route(p)


def test_csv_ddmm_column(tmp_path):
    """A header saying DDMM: packed DDMM.MMMM, 4022.5520 = 40 + 22.552/60."""
    p = tmp_path / "a.csv"
    p.write_text("name,lat_ddmm,lon_ddmm\nA,4022.5520,-7353.7601\nB,4025.0000,-7350.5000\n")
    r = read_route(p)
    np.testing.assert_allclose(r.lat, [LAT1, LAT2], rtol=0, atol=1e-12)
    np.testing.assert_allclose(r.lon, [LON1, LON2], rtol=0, atol=1e-12)


@pytest.mark.parametrize(("a", "b"), [
    ("40 22.552 N", "73 53.7601 W"),
    ("N40 22.552", "W73 53.7601"),
    ("40°22.552'N", "73°53.7601'W"),
    ("40 22.552", "-73 53.7601"),
    ("40 22 33.12 N", "73 53 45.606 W"),  # 22' 33.12" = 22.552', 53' 45.606" = 53.7601'
])
def test_csv_degrees_and_minutes_apart(tmp_path, a, b):
    p = tmp_path / "a.csv"
    p.write_text(f'name,lat,lon\nA,"{a}","{b}"\nB,40.5,-73.5\n')
    r = read_route(p)
    assert r.lat[0] == pytest.approx(LAT1, abs=1e-12)
    assert r.lon[0] == pytest.approx(LON1, abs=1e-12)


@pytest.mark.parametrize(("text", "expect"), [
    # a DDMM number in a column that does not say so: refused with the hint
    ("name,lat,lon\nA,4022.5520,-7353.7601\nB,4025.0,-7350.5\n", "lat_ddmm"),
    ("name,lat,lon\nA,40 22.552 E,73 53.7601 W\nB,40.5,-73.5\n", "hemisphere N or S"),
    ("name,lat,lon\nA,40 62.5 N,73 53.7601 W\nB,40.5,-73.5\n", "below 60"),
    ("name,lat_ddmm,lon_ddmm\nA,4075.0,-7353.7601\nB,4025.0,-7350.5\n", "below 60"),
    ("name,lat,lon\nA,-40 22.5 S,73 53.7601 W\nB,40.5,-73.5\n", "not both"),
    ("name,lat,latitude,lon\nA,1,1,2\nB,1,1,3\n", "more than one latitude"),
])
def test_csv_ambiguous_or_wrong_coordinates_refused(tmp_path, cli_error, text, expect):
    p = tmp_path / "bad.csv"
    p.write_text(text)
    line = cli_error("mission", "plan", str(p), "--speed", "1", "--radius", "10")
    assert str(p) in line and expect in line
