"""Lines across the antimeridian (issue 18): split per RFC 7946 3.1.9 in GeoJSON and KML,
longitudes in [-180, 180) in GPX and CSV, and read back whole by `read_route`.

Reference: a segment straight in (lat, lon) from (lat_a, lon_a) east across 180 to
(lat_b, lon_b) meets the seam at lat_a + (lat_b - lat_a) (180 - lon_a) / (lon_b + 360 - lon_a)
(closed form, the linear interpolation in unwrapped longitude); exact up to rounding, so the
tolerance is 1e-12 deg.
"""

from __future__ import annotations

import csv
import json
import pathlib

import numpy as np
import pytest

from glideplan.formats import (
    ExportOptions,
    export_mission,
    parse_formats,
    read_route,
    split_at_antimeridian,
    wrap_longitude,
    write_track_geojson,
    write_track_gpx,
    write_track_kml,
)
from glideplan.formats.antimeridian import join_at_antimeridian
from glideplan.formats.tracks import vertex_names

from .geojson_checks import check_feature_collection, check_geometry


def _seam_lat(lat_a, lon_a, lat_b, lon_b):
    """Closed form: latitude where the short eastward segment a -> b crosses 180."""
    return lat_a + (lat_b - lat_a) * (180.0 - lon_a) / (lon_b + 360.0 - lon_a)


def test_179e_to_179w_splits_at_the_interpolated_latitude():
    parts = split_at_antimeridian([10.0, 12.0], [179.0, -179.0])
    assert len(parts) == 2
    (la1, lo1), (la2, lo2) = parts
    np.testing.assert_array_equal(lo1, [179.0, 180.0])
    np.testing.assert_array_equal(lo2, [-180.0, -179.0])
    assert la1[-1] == la2[0] == pytest.approx(_seam_lat(10.0, 179.0, 12.0, -179.0), abs=1e-12)
    assert la1[-1] == pytest.approx(11.0, abs=1e-12)  # halfway: 1 deg of 2 on each side


def test_random_crossings_match_the_closed_form():
    """400 random segments crossing east or west: two parts, meeting at +-180 at the
    closed-form latitude; the vertices keep their own coordinates bit for bit."""
    rng = np.random.default_rng(7)
    for _ in range(400):
        lon_a = rng.uniform(100.0, 179.99)
        lon_b = rng.uniform(-179.99, -100.0)
        if lon_b + 360.0 - lon_a >= 180.0:
            continue  # the short way does not cross 180
        lat_a, lat_b = rng.uniform(-80, 80, 2)
        east = rng.random() < 0.5
        la, lo = ([lat_a, lat_b], [lon_a, lon_b]) if east else ([lat_b, lat_a], [lon_b, lon_a])
        (la1, lo1), (la2, lo2) = split_at_antimeridian(la, lo)
        want = _seam_lat(lat_a, lon_a, lat_b, lon_b)
        assert la1[-1] == pytest.approx(want, abs=1e-12) and la2[0] == la1[-1]
        assert (lo1[-1], lo2[0]) == ((180.0, -180.0) if east else (-180.0, 180.0))
        assert (la1[0], lo1[0], la2[-1], lo2[-1]) == (la[0], lo[0], la[1], lo[1])


def test_no_crossing_is_one_part_unchanged():
    lat = np.array([41.5, 41.6, 41.7])
    lon = np.array([-70.123456789, -70.0, -69.9])
    parts = split_at_antimeridian(lat, lon)
    assert len(parts) == 1
    assert parts[0][0].tolist() == lat.tolist() and parts[0][1].tolist() == lon.tolist()


def test_vertex_on_the_seam_and_several_crossings():
    parts = split_at_antimeridian([0.0, 1.0, 2.0], [170.0, 180.0, -170.0])
    assert [p[1].tolist() for p in parts] == [[170.0, 180.0], [-180.0, -170.0]]
    parts = split_at_antimeridian([0, 1, 2, 3], [170.0, -170.0, 170.0, -170.0])
    assert len(parts) == 4
    lat, _, seam = join_at_antimeridian(parts)
    assert sum(seam) == 3 and len(lat) == 4 + 3
    assert vertex_names([0, 1, 2, 3], [170.0, -170.0, 170.0, -170.0], "abcd") == [
        "a", None, "b", None, "c", None, "d"]


def test_wrap_longitude():
    np.testing.assert_array_equal(wrap_longitude([-180.0, 180.0, 190.0, 359.75, -73.5]),
                                  [-180.0, -180.0, -170.0, -0.25, -73.5])


# ----- track files -------------------------------------------------------------------------
LAT = [10.0, 11.0, 12.0, 13.0]
LON = [178.0, 179.0, -179.0, -178.0]  # crosses 180 between the 2nd and 3rd points at 12.0 ...
SEAM = _seam_lat(11.0, 179.0, 12.0, -179.0)  # ... = 11.5


def test_track_geojson_split_and_read_back(tmp_path):
    p = write_track_geojson(tmp_path / "t.geojson", LAT, LON, {"duration_s": 3600.0})
    doc = json.loads(p.read_text())
    check_feature_collection(doc)
    g = doc["features"][0]["geometry"]
    assert g["type"] == "MultiLineString"
    assert g["coordinates"] == [[[178.0, 10.0], [179.0, 11.0], [180.0, SEAM]],
                                [[-180.0, SEAM], [-179.0, 12.0], [-178.0, 13.0]]]
    assert doc["features"][0]["properties"] == {"duration_s": 3600.0}
    r = read_route(p)  # the parts joined; the seam point (no names given) kept once
    np.testing.assert_array_equal(r.lat, [10.0, 11.0, SEAM, 12.0, 13.0])


def test_track_geojson_refuses_nan_properties(tmp_path):
    with pytest.raises(ValueError, match="properties"):
        write_track_geojson(tmp_path / "t.geojson", LAT, LON, {"x": float("nan")})


def test_track_kml_read_by_fastkml(tmp_path):
    from fastkml import kml

    p = write_track_kml(tmp_path / "t.kml", LAT, LON, name="route <1>")
    doc = kml.KML.from_string(p.read_bytes())
    pm = doc.features[0].features[0]
    assert pm.name == "route <1>"
    assert type(pm.geometry).__name__ == "MultiLineString"
    parts = [[(c[0], c[1]) for c in g.coords] for g in pm.geometry.geoms]
    assert parts == [[(178.0, 10.0), (179.0, 11.0), (180.0, SEAM)],
                     [(-180.0, SEAM), (-179.0, 12.0), (-178.0, 13.0)]]
    np.testing.assert_array_equal(read_route(p).lat, [10.0, 11.0, SEAM, 12.0, 13.0])


def test_track_gpx_read_by_gpxpy(tmp_path):
    import datetime as dt

    import gpxpy

    t0 = dt.datetime(2026, 1, 1, tzinfo=dt.UTC)
    p = write_track_gpx(tmp_path / "t.gpx", LAT, [178.0, 179.0, 181.0, 182.0],
                        times_s=[0, 60, 120, 180], start_time=t0)
    pts = gpxpy.parse(p.read_text()).tracks[0].segments[0].points
    assert [q.longitude for q in pts] == [178.0, 179.0, -179.0, -178.0]
    assert pts[3].time == t0 + dt.timedelta(seconds=180)


# ----- a mission across the antimeridian, every export ---------------------------------------
@pytest.fixture(scope="module")
def across(tmp_path_factory):
    """Four waypoints either side of 180 E/W near Fiji; headings given so the legs curve and
    the straight-leg list has points between the waypoints."""
    from glideplan.missions import Route, plan_mission

    route = Route.from_geographic(["Suva", "Seam", "Taveuni", "Lau"],
                                  [-17.0, -16.99, -16.97, -16.96],
                                  [179.985, -179.995, -179.99, -179.975],
                                  [0.0, np.nan, 90.0, np.nan])
    plan = plan_mission(route, speed=1.0, radius=300.0)
    assert plan.ok
    out = tmp_path_factory.mktemp("across")
    files, legs = export_mission(plan, out, parse_formats(None),
                                 ExportOptions(acceptance_radius=30.0, max_deviation=10.0))
    assert len(legs.names) > route.n  # points between the waypoints
    return plan, files, legs


def _same_lon(a, b, atol):
    d = (np.asarray(a) - np.asarray(b) + 180.0) % 360.0 - 180.0
    return np.all(np.abs(d) <= atol)


def test_exported_geojson_split_valid_and_read_back(across):
    _, files, legs = across
    doc = json.loads(pathlib.Path(files["geojson"]).read_text())
    check_feature_collection(doc)
    lines = {f["properties"]["kind"]: f for f in doc["features"]
             if f["properties"]["kind"] != "waypoint"}
    for kind in ("straight_legs", "track"):
        g = lines[kind]["geometry"]
        assert g["type"] == "MultiLineString", kind
        for a, b in zip(g["coordinates"], g["coordinates"][1:], strict=False):
            assert abs(a[-1][0]) == 180.0 and b[0][0] == -a[-1][0] and b[0][1] == a[-1][1]
    r = read_route(files["geojson"])
    assert r.names == legs.names and r.warnings == ()
    np.testing.assert_allclose(r.lat, legs.lat, rtol=0, atol=1e-12)
    assert _same_lon(r.lon, legs.lon, 1e-12)


def test_exported_kml_split_and_read_back(across):
    from fastkml import kml

    _, files, legs = across
    doc = kml.KML.from_string(pathlib.Path(files["kml"]).read_bytes())
    marks = {m.name: m for m in doc.features[0].features}
    for name in ("straight legs", "track"):
        g = marks[name].geometry
        assert type(g).__name__ == "MultiLineString", name
        for line in g.geoms:
            lon = [c[0] for c in line.coords]
            assert max(abs(np.diff(lon))) <= 180.0 and min(lon) >= -180 and max(lon) <= 180
    names = json.loads(marks["straight legs"].extended_data.elements[0].value)
    assert [n for n in names if n is not None] == list(legs.names)
    r = read_route(files["kml"])
    assert r.names == legs.names
    np.testing.assert_allclose(r.lat, legs.lat, rtol=0, atol=5e-10)  # 9 decimals
    assert _same_lon(r.lon, legs.lon, 5e-10)


def test_exported_gpx_and_csv_keep_longitudes_in_range(across):
    import gpxpy

    _, files, legs = across
    gpx = gpxpy.parse(pathlib.Path(files["gpx"]).read_text())
    lons = [q.longitude for q in gpx.routes[0].points]
    lons += [q.longitude for q in gpx.tracks[0].segments[0].points]
    lons += [q.longitude for q in gpx.waypoints]
    assert min(lons) >= -180.0 and max(lons) < 180.0
    assert min(lons) < -179.0 and max(lons) > 179.0  # both sides
    with open(files["csv"], newline="") as fh:
        rows = list(csv.DictReader(fh))
    assert [r["name"] for r in rows] == list(legs.names)
    assert all(-180.0 <= float(r["lon"]) < 180.0 for r in rows)
    for fmt in ("gpx", "csv"):
        r = read_route(files[fmt])
        assert r.names == legs.names
        assert _same_lon(r.lon, legs.lon, 5e-10)


def test_exported_points_are_valid_geometries(across):
    plan, files, _ = across
    doc = json.loads(pathlib.Path(files["geojson"]).read_text())
    pts = [f for f in doc["features"] if f["properties"]["kind"] == "waypoint"]
    assert [f["properties"]["name"] for f in pts] == list(plan.route.names)
    for f in pts:
        check_geometry(f["geometry"])
