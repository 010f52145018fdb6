"""Lines for GIS tools: GeoJSON and KML geometry split at the antimeridian, and track files.

`geojson_line` and `kml_line` give the geometry of a line in WGS84 degrees, one part when it
stays inside [-180, 180] and several (MultiLineString / MultiGeometry) meeting at +-180 when
it crosses (`formats.antimeridian`, RFC 7946 section 3.1.9). `vertex_names` lists names along
the written line, None at the crossing points the split added, which `read_route` drops.

`write_track_geojson`, `write_track_kml` and `write_track_gpx` write one track (a route's, a
reach boundary's) for `glideplan route --geojson FILE` and the like.
"""

from __future__ import annotations

import json
import pathlib
from collections.abc import Mapping, Sequence
from typing import Any
from xml.sax.saxutils import escape

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.formats.antimeridian import (
    join_at_antimeridian,
    split_at_antimeridian,
    wrap_longitude,
)

__all__ = [
    "geojson_line",
    "kml_line",
    "vertex_names",
    "write_track_geojson",
    "write_track_gpx",
    "write_track_kml",
]

KML_HEAD = ('<?xml version="1.0" encoding="UTF-8"?>\n'
            '<kml xmlns="http://www.opengis.net/kml/2.2">')


def _checked(lat: ArrayLike, lon: ArrayLike, name: str) -> tuple[NDArray[np.float64],
                                                                 NDArray[np.float64]]:
    la = np.atleast_1d(np.asarray(lat, dtype=float))
    lo = np.atleast_1d(np.asarray(lon, dtype=float))
    if la.ndim == 1 and la.shape == lo.shape and la.size == 1:
        # a zero-length track (start = goal): RFC 7946 lines need two positions
        la, lo = np.repeat(la, 2), np.repeat(lo, 2)
    if la.ndim != 1 or la.shape != lo.shape or la.size < 2:
        raise InvalidParameterError(name, la.shape,
                                    "a line needs lat and lon of equal length >= 2")
    if not (np.all(np.isfinite(la)) and np.all(np.isfinite(lo))):
        raise InvalidParameterError(name, "NaN/inf", "coordinates must be finite")
    if np.any(np.abs(la) > 90.0):
        raise InvalidParameterError(name, float(np.max(np.abs(la))),
                                    "latitudes must be in [-90, 90] degrees")
    return la, lo


def geojson_line(lat: ArrayLike, lon: ArrayLike) -> dict[str, Any]:
    """A GeoJSON LineString of the line, or a MultiLineString split at the antimeridian."""
    la, lo = _checked(lat, lon, "line")
    parts = split_at_antimeridian(la, lo)
    coords = [[[float(b), float(a)] for a, b in zip(pl, po, strict=True)] for pl, po in parts]
    if len(coords) == 1:
        return {"type": "LineString", "coordinates": coords[0]}
    return {"type": "MultiLineString", "coordinates": coords}


def _kml_coords(lat: NDArray[np.float64], lon: NDArray[np.float64]) -> str:
    return " ".join(f"{b:.9f},{a:.9f},0" for a, b in zip(lat, lon, strict=True))


def kml_line(lat: ArrayLike, lon: ArrayLike, tessellate: bool = True) -> str:
    """KML of the line: a LineString, or a MultiGeometry of LineStrings split at +-180."""
    la, lo = _checked(lat, lon, "line")
    tess = "<tessellate>1</tessellate>" if tessellate else ""
    parts = [f"<LineString>{tess}<coordinates>{_kml_coords(pl, po)}</coordinates></LineString>"
             for pl, po in split_at_antimeridian(la, lo)]
    return parts[0] if len(parts) == 1 else "<MultiGeometry>" + "".join(parts) + (
        "</MultiGeometry>")


def vertex_names(lat: ArrayLike, lon: ArrayLike, names: Sequence[str]) -> list[str | None]:
    """`names` of the line's vertices along the written (split, then joined) line, None at
    the crossing points the split added (what `read_route` reads back)."""
    la, lo = _checked(lat, lon, "line")
    if len(names) != la.size:
        raise InvalidParameterError("names", len(names), f"needs one name per vertex ({la.size})")
    jl, jo, _ = join_at_antimeridian(split_at_antimeridian(la, lo))
    out: list[str | None] = []
    i = 0
    for a, b in zip(jl, jo, strict=True):
        same = i < la.size and a == la[i] and abs((b - lo[i] + 180.0) % 360.0 - 180.0) < 1e-9
        if same:
            out.append(str(names[i]))
            i += 1
        else:
            out.append(None)
    return out


def write_track_geojson(path: str | pathlib.Path, lat: ArrayLike, lon: ArrayLike,
                        properties: Mapping[str, Any] | None = None) -> pathlib.Path:
    """A GeoJSON FeatureCollection of one line feature (split at the antimeridian).

    `properties` must be JSON-serialisable (NaN/inf are refused: JSON has no such values).
    """
    p = pathlib.Path(path)
    feature = {"type": "Feature", "geometry": geojson_line(lat, lon),
               "properties": dict(properties or {})}
    try:
        text = json.dumps({"type": "FeatureCollection", "features": [feature]}, indent=1,
                          allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError("properties", str(exc), "must be finite JSON values"
                                    ) from None
    p.write_text(text + "\n", encoding="utf-8")
    return p


def write_track_kml(path: str | pathlib.Path, lat: ArrayLike, lon: ArrayLike,
                    name: str = "track", description: str = "") -> pathlib.Path:
    """A KML 2.2 Document with one line Placemark (a MultiGeometry when split at +-180)."""
    p = pathlib.Path(path)
    geometry = kml_line(lat, lon)
    desc = f"<description>{escape(description)}</description>" if description else ""
    text = "\n".join([
        KML_HEAD, "<Document>", f"<name>{escape(name)}</name>",
        '<Style id="track"><LineStyle><color>ff0000ff</color><width>2</width></LineStyle>'
        "</Style>",
        f"<Placemark><name>{escape(name)}</name>{desc}<styleUrl>#track</styleUrl>"
        f"{geometry}</Placemark>",
        "</Document>", "</kml>", ""])
    p.write_text(text, encoding="utf-8")
    return p


def write_track_gpx(path: str | pathlib.Path, lat: ArrayLike, lon: ArrayLike,
                    name: str = "track", times_s: ArrayLike | None = None,
                    start_time: Any = None) -> pathlib.Path:
    """A GPX 1.1 track (one segment; longitudes in [-180, 180) as GPX requires). With
    `times_s` (s since `start_time`, a timezone-aware datetime) each point gets its time."""
    import datetime as dt

    import gpxpy.gpx

    la, lo = _checked(lat, lon, "line")
    lo = wrap_longitude(lo)
    gpx = gpxpy.gpx.GPX()
    gpx.creator = "glideplan"
    trk = gpxpy.gpx.GPXTrack(name=name)
    seg = gpxpy.gpx.GPXTrackSegment()
    t = None if times_s is None else np.asarray(times_s, dtype=float)
    if t is not None and (t.shape != la.shape or start_time is None):
        raise InvalidParameterError("times_s", t.shape,
                                    "needs one time per point and a start_time")
    for i, (a, b) in enumerate(zip(la, lo, strict=True)):
        when = None if t is None else start_time + dt.timedelta(seconds=float(t[i]))
        seg.points.append(gpxpy.gpx.GPXTrackPoint(float(a), float(b), time=when))
    trk.segments.append(seg)
    gpx.tracks.append(trk)
    p = pathlib.Path(path)
    p.write_text(gpx.to_xml(version="1.1"), encoding="utf-8")
    return p
