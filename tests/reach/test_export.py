"""GeoJSON and KML of a reach, read back by their readers (json; fastkml)."""

import json

import numpy as np
import pytest

from glideplan.reach import Landable, glide_reach
from glideplan.terrain import Terrain


def shoelace(ring):
    x, y = np.asarray(ring, float).T
    return 0.5 * float(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]))


@pytest.fixture(scope="module")
def holed(polar):
    """Flat ground with a 2500 m block inside the disk: the footprint has a hole."""
    n = 101
    lat = 46.0 + 0.5 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.7 * np.arange(n) / (n - 1)
    z = np.zeros((n, n), np.float32)
    z[45:56, 60:71] = 2500.0
    pts = [Landable("Here & there", 46.25, 7.3, 0.0), Landable("Behind", 46.25, 7.52, 0.0)]
    return glide_reach(Terrain(lat, lon, z), (46.25, 7.35, 900.0), polar, landables=pts,
                       safety_height=300.0)


def test_geojson_reads_back_closed_rings_right_hand_rule(holed, tmp_path):
    path = holed.write_geojson(tmp_path / "reach.geojson")
    data = json.loads(path.read_text())
    assert data["type"] == "FeatureCollection"
    kinds = [f["properties"]["kind"] for f in data["features"]]
    assert kinds.count("footprint") == 1 and kinds.count("landable") == 2
    foot = data["features"][kinds.index("footprint")]["geometry"]
    assert foot["type"] in ("Polygon", "MultiPolygon")
    polys = [foot["coordinates"]] if foot["type"] == "Polygon" else foot["coordinates"]
    holes = 0
    for poly in polys:
        for k, ring in enumerate(poly):
            assert len(ring) >= 4 and ring[0] == ring[-1]  # closed (RFC 7946 3.1.6)
            # exterior counter-clockwise, holes clockwise (right-hand rule)
            assert (shoelace(ring) > 0) == (k == 0)
            holes += k > 0
            lon, lat = np.asarray(ring).T
            assert np.all((lon >= 7.0) & (lon <= 7.7) & (lat >= 46.0) & (lat <= 46.5))
    assert holes >= 1  # the block is a hole in the footprint
    # Points are [lon, lat]
    lands = [f for f in data["features"] if f["properties"]["kind"] == "landable"]
    assert lands[0]["geometry"]["coordinates"] == [7.3, 46.25]
    assert lands[0]["properties"]["name"] == "Here & there"


def test_kml_reads_back_with_fastkml(holed, tmp_path):
    from fastkml import kml

    path = holed.write_kml(tmp_path / "reach.kml")
    doc = kml.KML.parse(str(path))
    document = doc.features[0]
    marks = list(document.features)
    names = [m.name for m in marks]
    assert "Here & there" in names and "Behind" in names and "start" in names
    foot = marks[0]
    geoms = list(foot.kml_geometry.geometry.geoms)
    assert len(geoms) == len(holed.footprint)
    assert sum(len(list(g.interiors)) for g in geoms) >= 1
    point = marks[names.index("Here & there")].kml_geometry.geometry
    assert (point.x, point.y) == pytest.approx((7.3, 46.25))


def test_plot_draws(holed, tmp_path):
    from glideplan.plotting import save_figure

    out = save_figure(holed.plot(), str(tmp_path / "reach.png"))
    assert (tmp_path / "reach.png").stat().st_size > 10000 and out
