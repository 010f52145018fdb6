"""`footprint.polygons` in the reach JSON holds the polygons (GeoJSON MultiPolygon
coordinates), not a count, split at the antimeridian (RFC 7946 3.1.9) (issue 26).

References: a square 179.5..180.5 E with a hole splits into two pieces at 180 whose areas
(shoelace, deg^2) add up to the square's minus the hole's (closed form); a real reach over
tiles S17E179 + S17W180 gives parts inside [-180, 180] (checked by the independent RFC 7946
check `geojson_checks` and pygeoif) whose total area equals the unsplit footprint's.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.formats.antimeridian import split_polygon_at_antimeridian
from glideplan.reach.footprint import ring_area


def _square(x0, x1, y0, y1, ccw=True):
    r = np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]], dtype=float)
    return r if ccw else r[::-1]


def test_square_with_hole_splits_at_180():
    outer = _square(179.5, 180.5, -17.0, -16.0)
    hole = _square(179.6, 179.8, -16.6, -16.4, ccw=False)  # west of 180
    parts = split_polygon_at_antimeridian([outer, hole])
    assert len(parts) == 2
    west, east = parts
    assert len(west) == 2 and len(east) == 1  # the hole stays on its side
    assert west[0][:, 0].max() == 180.0 and east[0][:, 0].min() == -180.0
    assert ring_area(west[0]) == pytest.approx(0.5) and ring_area(east[0]) == pytest.approx(0.5)
    assert ring_area(west[1]) == pytest.approx(-0.04)
    for part in parts:
        for ring in part:
            assert np.array_equal(ring[0], ring[-1])
            assert np.all(np.abs(ring[:, 0]) <= 180.0)
    inside = _square(10.0, 11.0, 0.0, 1.0)
    assert [p[0].tolist() for p in split_polygon_at_antimeridian([inside])] == [inside.tolist()]


def test_reach_json_holds_the_split_polygons(polar, tmp_path):
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).parents[1] / "formats"))
    from geojson_checks import check_geometry

    from glideplan.reach import glide_reach
    from glideplan.terrain import read_terrain, write_hgt

    paths = []
    for name in ("S17E179.hgt", "S17W180.hgt"):
        p = tmp_path / name
        write_hgt(p, np.zeros((1201, 1201), dtype=np.int16))
        paths.append(p)
    r = glide_reach(read_terrain(paths), (-16.5, 179.98, 450.0), polar, landables=[])
    data = json.loads(json.dumps(r.to_dict()))
    polys = data["footprint"]["polygons"]
    assert isinstance(polys, list) and len(polys) >= 2 and data["footprint"]["count"] == 1
    check_geometry({"type": "MultiPolygon", "coordinates": polys})
    lons = [x for poly in polys for ring in poly for x, _ in ring]
    assert max(lons) == 180.0 and min(lons) < -179.9 and max(lons) <= 180.0
    total = sum(ring_area(np.array(poly[0])) for poly in polys)
    unsplit = ring_area(r.footprint[0][0])
    assert total == pytest.approx(unsplit, rel=1e-6)
    # the file the CLI writes holds the same split geometry
    geom = r.to_geojson()["features"][0]["geometry"]
    assert geom["type"] == "MultiPolygon" and geom["coordinates"] == polys
    assert math.isfinite(data["footprint"]["area_km2"])
