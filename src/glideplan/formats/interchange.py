"""Interchange files of a planned mission: GeoJSON, KML, GPX (track + waypoints) and CSV.

GeoJSON (RFC 7946) and KML put longitude first. Each file carries the mission waypoints
(points with name and compass heading), the straight-leg waypoint list (a route, with its
waypoint names: GeoJSON property `names`, KML ExtendedData `names`, GPX `<name>`, a CSV
column) and the dense planned track. `read_route` reads the straight-leg list back, names
included. Lines crossing the antimeridian are split there in GeoJSON and KML
(`formats.tracks`, RFC 7946 section 3.1.9); GPX and CSV give longitudes in [-180, 180).
"""

from __future__ import annotations

import csv
import json
import pathlib
from dataclasses import dataclass
from typing import Any
from xml.sax.saxutils import escape

import numpy as np

from glideplan.formats.antimeridian import wrap_longitude
from glideplan.formats.tracks import geojson_line, kml_line, vertex_names
from glideplan.missions.field_mission import FieldMission
from glideplan.missions.plan import MissionPlan, Track
from glideplan.missions.straight_legs import StraightLegList
from glideplan.track import iso_times

__all__ = ["write_csv", "write_geojson", "write_gpx", "write_kml"]


@dataclass(frozen=True)
class _LatLon:
    """A mission's waypoints, straight legs and planned track in WGS84 degrees."""

    lat: np.ndarray
    lon: np.ndarray
    legs_lat: np.ndarray
    legs_lon: np.ndarray
    track_lat: np.ndarray
    track_lon: np.ndarray


def _latlon(plan: MissionPlan | FieldMission, legs: StraightLegList, track: Track) -> _LatLon:
    """The geographic coordinates every interchange writer needs (the track projected back)."""
    r = plan.route
    assert r.lat is not None and r.lon is not None and legs.lat is not None
    assert legs.lon is not None and r.projection is not None
    lat, lon = r.projection.to_geographic(track.x, track.y)
    return _LatLon(r.lat, wrap_longitude(r.lon), legs.lat, wrap_longitude(legs.lon), lat,
                   wrap_longitude(lon))


def write_geojson(
    plan: MissionPlan | FieldMission, legs: StraightLegList, track: Track, path: pathlib.Path
) -> pathlib.Path:
    """A FeatureCollection: mission waypoints (Points, with their ETAs), straight legs and
    track (LineStrings)."""
    r, g = plan.route, _latlon(plan, legs, track)
    hd = plan.headings_deg
    eta, when = plan.waypoint_eta_s, iso_times(plan.depart_time, plan.waypoint_eta_s)
    feats: list[dict[str, Any]] = [
        {
            "type": "Feature",
            "geometry": {"type": "Point", "coordinates": [float(g.lon[i]), float(g.lat[i])]},
            "properties": {"name": r.names[i], "kind": "waypoint", "heading_deg": hd[i],
                           "heading_given": not bool(r.free[i]), "eta_s": eta[i],
                           "eta": when[i]},
        }
        for i in range(r.n)
    ]
    feats.append({
        "type": "Feature",
        "geometry": geojson_line(g.legs_lat, g.legs_lon),
        "properties": {"name": "straight legs", "kind": "straight_legs",
                       "max_deviation_m": legs.max_deviation_m,
                       "names": vertex_names(g.legs_lat, g.legs_lon, legs.names),
                       "eta_s": legs.eta_s.tolist(),
                       "eta": iso_times(plan.depart_time, legs.eta_s)},
    })
    feats.append({
        "type": "Feature",
        "geometry": geojson_line(g.track_lat, g.track_lon),
        "properties": {"name": "track", "kind": "track",
                       "length_m": plan.total_length_m, "duration_s": plan.total_duration_s},
    })
    path.write_text(json.dumps({"type": "FeatureCollection", "features": feats}, indent=1))
    return path


def write_kml(
    plan: MissionPlan | FieldMission, legs: StraightLegList, track: Track, path: pathlib.Path
) -> pathlib.Path:
    """KML 2.2: a Document with waypoint Placemarks (each with its ETA: a TimeStamp when the
    departure's UTC time is known), the straight legs and the track."""
    r, g = plan.route, _latlon(plan, legs, track)
    hd = plan.headings_deg
    eta, when = plan.waypoint_eta_s, iso_times(plan.depart_time, plan.waypoint_eta_s)
    parts = [
        '<?xml version="1.0" encoding="UTF-8"?>',
        '<kml xmlns="http://www.opengis.net/kml/2.2">',
        "<Document>",
        "<name>glideplan mission</name>",
        '<Style id="track"><LineStyle><color>ff0000ff</color><width>2</width></LineStyle>'
        "</Style>",
        '<Style id="legs"><LineStyle><color>ffff0000</color><width>1</width></LineStyle>'
        "</Style>",
    ]
    for i in range(r.n):
        stamp = "" if when[i] is None else f"<TimeStamp><when>{when[i]}</when></TimeStamp>"
        parts.append(
            f"<Placemark><name>{escape(r.names[i])}</name>{stamp}"
            f"<description>heading {hd[i]:.1f} deg, ETA {_eta_text(eta[i], when[i])}"
            "</description>"
            f"<Point><coordinates>{g.lon[i]:.9f},{g.lat[i]:.9f},0</coordinates></Point>"
            "</Placemark>"
        )
    names = json.dumps(vertex_names(g.legs_lat, g.legs_lon, legs.names), ensure_ascii=False)
    parts.append(
        "<Placemark><name>straight legs</name><styleUrl>#legs</styleUrl>"
        f'<ExtendedData><Data name="names"><value>{escape(names)}</value></Data>'
        f"</ExtendedData>{kml_line(g.legs_lat, g.legs_lon)}</Placemark>"
    )
    parts.append(
        "<Placemark><name>track</name><styleUrl>#track</styleUrl>"
        f"{kml_line(g.track_lat, g.track_lon)}</Placemark>"
    )
    parts += ["</Document>", "</kml>", ""]
    path.write_text("\n".join(parts), encoding="utf-8")
    return path


def write_gpx(
    plan: MissionPlan | FieldMission, legs: StraightLegList, track: Track, path: pathlib.Path
) -> pathlib.Path:
    """GPX 1.1: waypoints (wpt), the straight-leg route (rte) and the track (trk)."""
    import gpxpy.gpx

    r, g = plan.route, _latlon(plan, legs, track)
    gpx = gpxpy.gpx.GPX()
    gpx.creator = "glideplan"
    hd = plan.headings_deg
    eta, when = plan.waypoint_eta_s, _datetimes(plan.depart_time, plan.waypoint_eta_s)
    for i in range(r.n):
        gpx.waypoints.append(gpxpy.gpx.GPXWaypoint(
            float(g.lat[i]), float(g.lon[i]), name=r.names[i], time=when[i],
            comment=f"heading {hd[i]:.1f} deg, ETA {_eta_text(eta[i], None)}"))
    rte = gpxpy.gpx.GPXRoute(name="straight legs")
    legs_when = _datetimes(plan.depart_time, legs.eta_s)
    for name, a, b, t in zip(legs.names, g.legs_lat, g.legs_lon, legs_when, strict=True):
        rte.points.append(gpxpy.gpx.GPXRoutePoint(float(a), float(b), name=name, time=t))
    gpx.routes.append(rte)
    trk = gpxpy.gpx.GPXTrack(name="track")
    seg = gpxpy.gpx.GPXTrackSegment()
    for a, b in zip(g.track_lat, g.track_lon, strict=True):
        seg.points.append(gpxpy.gpx.GPXTrackPoint(float(a), float(b)))
    trk.segments.append(seg)
    gpx.tracks.append(trk)
    path.write_text(gpx.to_xml(version="1.1"), encoding="utf-8")
    return path


def write_csv(
    plan: MissionPlan | FieldMission, legs: StraightLegList, path: pathlib.Path
) -> pathlib.Path:
    """The straight-leg list as CSV: name,lat,lon,heading_deg,mission,eta_s,eta_utc (or
    name,x,y,... local); eta_utc empty when the departure's UTC time is not known.

    Geographic headings are compass bearings; local ones degrees CCW from +x (as read).
    """
    when = iso_times(plan.depart_time, legs.eta_s)
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        if legs.lat is not None and legs.lon is not None:
            lon = wrap_longitude(legs.lon)
            w.writerow(["name", "lat", "lon", "heading_deg", "mission", "eta_s", "eta_utc"])
            for i, name in enumerate(legs.names):
                w.writerow([name, f"{legs.lat[i]:.9f}", f"{lon[i]:.9f}",
                            f"{legs.bearing_deg[i]:.4f}", int(legs.mission[i]),
                            f"{legs.eta_s[i]:.3f}", when[i] or ""])
        else:
            w.writerow(["name", "x", "y", "heading_deg", "mission", "eta_s", "eta_utc"])
            ccw = np.mod(90.0 - legs.bearing_deg, 360.0)
            for i, name in enumerate(legs.names):
                w.writerow([name, f"{legs.x[i]:.4f}", f"{legs.y[i]:.4f}", f"{ccw[i]:.4f}",
                            int(legs.mission[i]), f"{legs.eta_s[i]:.3f}", when[i] or ""])
    return path


def _eta_text(eta_s: float, when: str | None) -> str:
    """'+HH:MM:SS after departure' and the UTC time when known."""
    m, s = divmod(round(eta_s), 60)
    h, m = divmod(m, 60)
    return f"+{h:02d}:{m:02d}:{s:02d}" + ("" if when is None else f" ({when})")


def _datetimes(depart: np.datetime64 | None, eta_s: Any) -> list[Any]:
    """Timezone-aware datetimes (UTC) of depart + each eta (s), as gpxpy writes them."""
    import datetime as dt

    t = np.atleast_1d(np.asarray(eta_s, dtype=float))
    if depart is None:
        return [None] * t.size
    start = np.asarray(depart).astype("datetime64[ms]").item().replace(tzinfo=dt.UTC)
    return [start + dt.timedelta(seconds=float(v)) for v in t]
