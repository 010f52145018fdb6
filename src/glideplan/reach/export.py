"""The reach for other tools: GeoJSON (RFC 7946) and KML 2.2 (Google Earth).

GeoJSON: one FeatureCollection: the footprint as one Polygon or MultiPolygon feature
(rings closed, exteriors counter-clockwise, holes clockwise: RFC 7946 sec. 3.1.6; positions
[lon, lat]; a footprint across 180 deg split there, sec. 3.1.9), the start and every
landable as Point features (properties: name, elevation, reachable, arrival altitude and
margin), and each landable's flown path as a LineString.
KML: the same in a Document (Polygon in a MultiGeometry, Placemarks, LineStrings).
"""

from __future__ import annotations

import json
import math
import pathlib
from typing import TYPE_CHECKING, Any
from xml.sax.saxutils import escape

if TYPE_CHECKING:
    from glideplan.reach.result import ReachResult

__all__ = ["reach_geojson", "write_geojson", "write_kml"]


def _r(x: float | None, nd: int = 1) -> float | None:
    return None if x is None or not math.isfinite(x) else round(float(x), nd)


def reach_geojson(result: ReachResult) -> dict[str, Any]:
    """The FeatureCollection (module docstring)."""
    polys = result.footprint_coordinates()  # split at the antimeridian (RFC 7946 3.1.9)
    if len(polys) == 1:
        geometry: dict[str, Any] = {"type": "Polygon", "coordinates": polys[0]}
    else:
        geometry = {"type": "MultiPolygon", "coordinates": polys}
    lat0, lon0, alt = result.start
    features: list[dict[str, Any]] = [
        {"type": "Feature", "geometry": geometry,
         "properties": {"kind": "footprint", "safety_height_m": result.safety_height,
                        "clipped": list(result.clipped),
                        "area_km2": round(result.footprint_area_km2(), 3)}},
        {"type": "Feature", "geometry": {"type": "Point", "coordinates": [lon0, lat0]},
         "properties": {"kind": "start", "name": "start", "altitude_m": alt}},
    ]
    for p in result.points:
        lnd = p.landable
        features.append({
            "type": "Feature",
            "geometry": {"type": "Point", "coordinates": [lnd.lon, lnd.lat]},
            "properties": {"kind": "landable", "name": lnd.name, "elevation_m": lnd.elevation_m,
                           "reachable": p.reachable,
                           "arrival_altitude_m": _r(p.arrival_altitude_m),
                           "arrival_margin_m": _r(p.arrival_margin_m),
                           "detour": p.detour,
                           "short_by_m": _r(p.short_by_m),
                           "terrain_missing": p.terrain_missing}})
    for p in result.points:
        if p.path is not None and p.reachable:
            coords = [[round(float(x), 7), round(float(y), 7)]
                      for x, y in zip(p.path.waypoints_lon, p.path.waypoints_lat, strict=True)]
            features.append({"type": "Feature",
                             "geometry": {"type": "LineString", "coordinates": coords},
                             "properties": {"kind": "path", "name": p.landable.name,
                                            "distance_m": _r(p.distance_m)}})
    return {"type": "FeatureCollection", "features": features}


def write_geojson(result: ReachResult, path: str | pathlib.Path) -> pathlib.Path:
    p = pathlib.Path(path)
    p.write_text(json.dumps(reach_geojson(result)) + "\n", encoding="utf-8")
    return p


def _coords(lon: Any, lat: Any) -> str:
    return " ".join(f"{float(x):.7f},{float(y):.7f},0" for x, y in zip(lon, lat, strict=True))


def write_kml(result: ReachResult, path: str | pathlib.Path) -> pathlib.Path:
    """KML 2.2: footprint Polygon(s), the start and landables as Placemarks, flown paths."""
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<kml xmlns="http://www.opengis.net/kml/2.2">',
        "<Document>",
        "<name>glideplan glide reach</name>",
        '<Style id="footprint"><LineStyle><color>ff00aa00</color><width>2</width></LineStyle>'
        "<PolyStyle><color>4000ff00</color></PolyStyle></Style>",
        '<Style id="reachable"><IconStyle><color>ff00ff00</color></IconStyle></Style>',
        '<Style id="unreachable"><IconStyle><color>ff0000ff</color></IconStyle></Style>',
        '<Style id="path"><LineStyle><color>ffff0000</color><width>2</width></LineStyle>'
        "</Style>",
    ]
    polys = []
    for poly in result.footprint:
        outer = _coords(poly[0][:, 0], poly[0][:, 1])
        rings = [f"<outerBoundaryIs><LinearRing><coordinates>{outer}"
                 "</coordinates></LinearRing></outerBoundaryIs>"]
        for hole in poly[1:]:
            rings.append(f"<innerBoundaryIs><LinearRing><coordinates>"
                         f"{_coords(hole[:, 0], hole[:, 1])}</coordinates></LinearRing>"
                         "</innerBoundaryIs>")
        polys.append("<Polygon>" + "".join(rings) + "</Polygon>")
    parts.append(
        f"<Placemark><name>footprint (safety height {result.safety_height:g} m)</name>"
        f"<styleUrl>#footprint</styleUrl><MultiGeometry>{''.join(polys)}</MultiGeometry>"
        "</Placemark>")
    lat0, lon0, alt = result.start
    parts.append(f"<Placemark><name>start</name><description>altitude {alt:.0f} m"
                 f"</description><Point><coordinates>{lon0:.7f},{lat0:.7f},0</coordinates>"
                 "</Point></Placemark>")
    for p in result.points:
        lnd = p.landable
        desc = (f"elevation {lnd.elevation_m:.0f} m; "
                + (f"arrival {p.arrival_altitude_m:.0f} m, margin {p.arrival_margin_m:+.0f} m"
                   if p.arrival_altitude_m is not None and p.arrival_margin_m is not None
                   else "out of reach"))
        style = "reachable" if p.reachable else "unreachable"
        parts.append(f"<Placemark><name>{escape(lnd.name)}</name><description>{escape(desc)}"
                     f"</description><styleUrl>#{style}</styleUrl><Point><coordinates>"
                     f"{lnd.lon:.7f},{lnd.lat:.7f},0</coordinates></Point></Placemark>")
    for p in result.points:
        if p.path is not None and p.reachable:
            parts.append(f"<Placemark><name>path to {escape(p.landable.name)}</name>"
                         "<styleUrl>#path</styleUrl><LineString><tessellate>1</tessellate>"
                         f"<coordinates>{_coords(p.path.waypoints_lon, p.path.waypoints_lat)}"
                         "</coordinates></LineString></Placemark>")
    parts += ["</Document>", "</kml>", ""]
    out = pathlib.Path(path)
    out.write_text("\n".join(parts), encoding="utf-8")
    return out
