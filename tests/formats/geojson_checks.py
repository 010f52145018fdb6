"""An RFC 7946 structural check of GeoJSON written by glideplan, independent of its writer.

Checks what RFC 7946 requires of the geometries glideplan writes (sections 3.1.1-3.1.5,
3.1.9, 3.2, 3.3): object types and members, positions [lon, lat] with lon in [-180, 180] and
lat in [-90, 90], LineStrings of >= 2 positions, and no line segment jumping across the
antimeridian (|dlon| > 180: such a line must be split, 3.1.9). Each geometry is then built by
pygeoif (`pygeoif.shape`, the geometry library fastkml uses), a second reader.
"""

from __future__ import annotations

import math
from typing import Any

GEOMETRIES = {"Point", "MultiPoint", "LineString", "MultiLineString", "Polygon",
              "MultiPolygon", "GeometryCollection"}


def _position(c: Any, where: str) -> tuple[float, float]:
    assert isinstance(c, list) and 2 <= len(c) <= 3, f"{where}: position {c!r}"
    assert all(isinstance(v, int | float) and math.isfinite(v) for v in c), where
    lon, lat = float(c[0]), float(c[1])
    assert -180.0 <= lon <= 180.0, f"{where}: longitude {lon}"
    assert -90.0 <= lat <= 90.0, f"{where}: latitude {lat}"
    return lon, lat


def _line(coords: Any, where: str) -> list[tuple[float, float]]:
    assert isinstance(coords, list) and len(coords) >= 2, f"{where}: a line needs 2 positions"
    pts = [_position(c, f"{where}[{i}]") for i, c in enumerate(coords)]
    for i in range(1, len(pts)):
        assert abs(pts[i][0] - pts[i - 1][0]) <= 180.0, (
            f"{where}: segment {i} jumps {pts[i][0] - pts[i - 1][0]:+.3f} deg in longitude "
            "(crosses the antimeridian unsplit, RFC 7946 3.1.9)")
    return pts


def check_geometry(g: Any, where: str = "geometry") -> None:
    """Assert `g` is a valid GeoJSON geometry of the kinds above and pygeoif reads it."""
    import pygeoif

    assert isinstance(g, dict) and g.get("type") in GEOMETRIES, f"{where}: {g!r:.80}"
    kind = g["type"]
    c = g.get("coordinates")
    if kind == "Point":
        _position(c, where)
    elif kind == "MultiPoint":
        for i, q in enumerate(c):
            _position(q, f"{where}[{i}]")
    elif kind == "LineString":
        _line(c, where)
    elif kind == "MultiLineString":
        assert isinstance(c, list) and c, f"{where}: MultiLineString needs parts"
        for i, q in enumerate(c):
            _line(q, f"{where}[{i}]")
    shape = pygeoif.shape(g)
    assert type(shape).__name__ == kind


def check_feature_collection(doc: Any) -> None:
    """Assert `doc` is a FeatureCollection of Features with geometry and properties."""
    assert isinstance(doc, dict) and doc.get("type") == "FeatureCollection"
    assert isinstance(doc.get("features"), list)
    for k, f in enumerate(doc["features"]):
        assert f.get("type") == "Feature", f"feature {k}"
        assert "geometry" in f and "properties" in f, f"feature {k}"
        assert f["properties"] is None or isinstance(f["properties"], dict)
        if f["geometry"] is not None:
            check_geometry(f["geometry"], f"feature {k}")
