"""A route's files for other tools: GeoJSON, KML, GPX and CSV, each vertex with its UTC time.

Pure functions from a `RouteResult` to a file. The vertices are the route's track with the
heading-switch copies dropped: the router writes each inner vertex of a held-heading route
twice, `routing.phases.SWITCH_S` apart, once with the leg's heading and once with the next
(`routing.phases._held`); a file gets each position once, with the time the vehicle reaches
it (the first copy) and the course it leaves on (the last copy). Times are ISO 8601 UTC with
milliseconds, depart + t (t in s after departure, the route's own `track.t`), so the last
vertex's time is the route's `arrive`.

- GeoJSON (RFC 7946): feature 0 is the line (a MultiLineString split at +-180, section
  3.1.9) with `coordTimes` aligned to its coordinates (a list per part when split: the
  convention of Mapbox's togeojson; crossing points get the time interpolated linearly in
  longitude); then one Point per vertex with `time`, `t_s` and `heading_deg`.
- KML 2.2: the line Placemark, then a Point Placemark per vertex with its `TimeStamp`.
- GPX 1.1: one track segment, each `trkpt` with its `time`.
- CSV: time_utc,t_s,lat,lon,heading_deg (one row per vertex).

Without a calendar (a field with no time axis: `depart` None) the ISO times are left out and
`route_export_warnings` says so.
"""

from __future__ import annotations

import csv
import json
import pathlib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any
from xml.sax.saxutils import escape

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.formats.antimeridian import split_at_antimeridian, wrap_longitude
from glideplan.formats.tracks import KML_HEAD, geojson_line, kml_line, write_track_gpx
from glideplan.track import iso_times

if TYPE_CHECKING:
    from glideplan.routing.result import RouteResult

__all__ = ["ROUTE_FORMATS", "RouteVertices", "export_route", "iso_times",
           "route_export_warnings", "route_vertices", "write_route_csv",
           "write_route_geojson", "write_route_gpx", "write_route_kml"]

ROUTE_FORMATS = ("geojson", "kml", "gpx", "csv")

#: Consecutive samples closer than this (deg, about 1 cm) are one vertex.
SAME_POSITION_DEG = 1e-7

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class RouteVertices:
    """The route's vertices once each: t_s (s after departure), lat, lon (deg; lon wrapped to
    [-180, 180)), heading_deg (compass course leaving the vertex), depart (UTC or None)."""

    t_s: FloatArray
    lat: FloatArray
    lon: FloatArray
    heading_deg: FloatArray
    depart: np.datetime64 | None

    @property
    def times(self) -> list[str | None]:
        return iso_times(self.depart, self.t_s)


def route_vertices(result: RouteResult) -> RouteVertices:
    """The track's samples with each position once (module docstring): the first copy's time,
    the last copy's heading."""
    tr = result.track
    if not tr.size or not tr.geographic:
        raise InvalidParameterError("route", result.status.value, "has no geographic track")
    lat, lon = tr.lat, tr.lon
    new = np.r_[True, (np.abs(np.diff(lat)) > SAME_POSITION_DEG)
                | (np.abs(np.diff(lon)) > SAME_POSITION_DEG)]
    first = np.flatnonzero(new)
    last = np.r_[first[1:] - 1, lat.size - 1]
    return RouteVertices(t_s=tr.t[first], lat=lat[first], lon=wrap_longitude(lon[first]),
                         heading_deg=np.asarray(result.heading_deg, dtype=float)[last],
                         depart=result.depart)


def route_export_warnings(result: RouteResult) -> tuple[str, ...]:
    """What the files cannot carry: per-vertex UTC times without a calendar."""
    if result.depart is None:
        return ("the field has no calendar: the route's files carry t_s (s after departure) "
                "but no UTC times",)
    return ()


def _properties(result: RouteResult) -> dict[str, Any]:
    arrive = result.arrive
    return {"kind": "route", "status": result.status.value, "duration_s": result.duration_s,
            "distance_m": result.distance_m, "method": result.method,
            "depart": iso_times(result.depart, 0.0)[0],
            "arrive": None if arrive is None else iso_times(arrive, 0.0)[0]}


def _part_times(v: RouteVertices) -> list[list[float]]:
    """Per part of the split line, the t (s) of each written position: a vertex's own, a
    crossing point's interpolated linearly in longitude between its two vertices."""
    lat, lon, t = v.lat, v.lon, v.t_s
    if lat.size == 1:  # a zero-length route: the line repeats its one position
        return [[float(t[0]), float(t[0])]]
    out: list[list[float]] = []
    i = 0  # the next vertex to meet
    for pl, po in split_at_antimeridian(lat, lon):
        times = []
        for a, b in zip(pl, po, strict=True):
            def same(k: int, a: float = a, b: float = b) -> bool:
                return bool(0 <= k < lat.size and a == lat[k]
                            and abs((b - lon[k] + 180.0) % 360.0 - 180.0) < 1e-9)
            if same(i):
                times.append(float(t[i]))
                i += 1
            elif same(i - 1):  # a vertex on the seam, written again to start the next part
                times.append(float(t[i - 1]))
            else:
                d_all = (lon[i] - lon[i - 1] + 180.0) % 360.0 - 180.0
                d_part = (b - lon[i - 1] + 180.0) % 360.0 - 180.0
                f = abs(d_part) / abs(d_all) if d_all else 0.0
                times.append(float(t[i - 1] + f * (t[i] - t[i - 1])))
        out.append(times)
    return out


def write_route_geojson(result: RouteResult, path: pathlib.Path) -> pathlib.Path:
    """FeatureCollection: the line with `coordTimes`, then a Point per vertex (docstring)."""
    v = route_vertices(result)
    line = geojson_line(v.lat, v.lon)
    parts = [iso_times(v.depart, p) for p in _part_times(v)]
    props = _properties(result) | {
        "coordTimes": parts[0] if line["type"] == "LineString" else parts}
    feats: list[dict[str, Any]] = [{"type": "Feature", "geometry": line, "properties": props}]
    for k, when in enumerate(v.times):
        feats.append({"type": "Feature",
                      "geometry": {"type": "Point",
                                   "coordinates": [float(v.lon[k]), float(v.lat[k])]},
                      "properties": {"kind": "vertex", "index": k, "time": when,
                                     "t_s": float(v.t_s[k]),
                                     "heading_deg": float(v.heading_deg[k])}})
    text = json.dumps({"type": "FeatureCollection", "features": feats}, indent=1,
                      allow_nan=False)
    path.write_text(text + "\n", encoding="utf-8")
    return path


def write_route_kml(result: RouteResult, path: pathlib.Path) -> pathlib.Path:
    """KML 2.2: the line Placemark, then a timestamped Point Placemark per vertex."""
    v = route_vertices(result)
    p = _properties(result)
    took = "no duration" if result.duration_s is None else f"{result.duration_s:.0f} s"
    desc = f"{p['status']}, {took}, depart {p['depart']}, arrive {p['arrive']}"
    parts = [KML_HEAD, "<Document>", "<name>glideplan route</name>",
             '<Style id="track"><LineStyle><color>ff0000ff</color><width>2</width>'
             "</LineStyle></Style>",
             f"<Placemark><name>glideplan route</name><description>{escape(desc)}"
             f"</description><styleUrl>#track</styleUrl>{kml_line(v.lat, v.lon)}</Placemark>"]
    for k, when in enumerate(v.times):
        stamp = "" if when is None else f"<TimeStamp><when>{when}</when></TimeStamp>"
        parts.append(
            f"<Placemark><name>{k}</name>{stamp}<description>t = {v.t_s[k]:.1f} s, "
            f"heading {v.heading_deg[k]:.1f} deg</description><Point><coordinates>"
            f"{v.lon[k]:.9f},{v.lat[k]:.9f},0</coordinates></Point></Placemark>")
    parts += ["</Document>", "</kml>", ""]
    path.write_text("\n".join(parts), encoding="utf-8")
    return path


def write_route_gpx(result: RouteResult, path: pathlib.Path) -> pathlib.Path:
    """GPX 1.1: one track segment, each point with its UTC time (none without a calendar)."""
    import datetime as dt

    v = route_vertices(result)
    start = None
    if v.depart is not None:
        start = np.asarray(v.depart).astype("datetime64[ms]").item().replace(tzinfo=dt.UTC)
    return write_track_gpx(path, v.lat, v.lon, name="glideplan route",
                           times_s=None if start is None else v.t_s, start_time=start)


def write_route_csv(result: RouteResult, path: pathlib.Path) -> pathlib.Path:
    """CSV: time_utc,t_s,lat,lon,heading_deg, one row per vertex (time_utc empty without a
    calendar)."""
    v = route_vertices(result)
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["time_utc", "t_s", "lat", "lon", "heading_deg"])
        for k, when in enumerate(v.times):
            w.writerow([when or "", f"{v.t_s[k]:.3f}", f"{v.lat[k]:.9f}", f"{v.lon[k]:.9f}",
                        f"{v.heading_deg[k]:.4f}"])
    return path


_WRITERS = {"geojson": write_route_geojson, "kml": write_route_kml, "gpx": write_route_gpx,
            "csv": write_route_csv}


def export_route(result: RouteResult, exports: Mapping[str, pathlib.Path]
                 ) -> dict[str, str]:
    """Write each format -> path of `exports` (formats from `ROUTE_FORMATS`); format -> path
    written. A route without a track (unreachable) writes nothing."""
    for fmt in exports:
        if fmt not in _WRITERS:
            raise InvalidParameterError("format", fmt, f"must be one of {ROUTE_FORMATS}")
    if not result.track.size:
        return {}
    return {fmt: str(_WRITERS[fmt](result, pathlib.Path(p))) for fmt, p in exports.items()}
