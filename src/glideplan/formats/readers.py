"""Read a route (ordered waypoints, optional headings) from CSV, GPX, KML or GeoJSON.

The extension chooses the reader. Geographic files give WGS84 latitude/longitude (degrees)
and optional compass headings (degrees clockwise from north); a CSV may instead give local
metres `x, y` with headings in the `plan` convention (degrees CCW from +x). Every problem is
one `InvalidParameterError` whose message names the file, the line or feature and the rule.
"""

from __future__ import annotations

import csv
import json
import math
import pathlib
from dataclasses import dataclass, field
from typing import Any

from glideplan.errors import InvalidParameterError
from glideplan.missions.route import Route

__all__ = ["ROUTE_EXTENSIONS", "read_route"]

ROUTE_EXTENSIONS = (".csv", ".gpx", ".kml", ".geojson", ".json")


@dataclass
class _Points:
    """Waypoints as read: names, first and second coordinate, headings (deg, NaN free)."""

    names: list[str] = field(default_factory=list)
    a: list[float] = field(default_factory=list)  # lat or x
    b: list[float] = field(default_factory=list)  # lon or y
    headings: list[float] = field(default_factory=list)
    where: list[str] = field(default_factory=list)  # "line 3", "rtept 2": for error messages

    def add(self, name: str, a: float, b: float, where: str, heading: float = math.nan) -> None:
        """Append one waypoint (heading in degrees, NaN when free)."""
        self.names.append(name)
        self.a.append(a)
        self.b.append(b)
        self.headings.append(heading)
        self.where.append(where)


def _bad(path: pathlib.Path, where: str, value: Any, rule: str) -> InvalidParameterError:
    return InvalidParameterError(f"{path} {where}".strip(), value, rule)


def read_route(path: str | pathlib.Path) -> Route:
    """The route in `path` (.csv, .gpx, .kml, .geojson/.json) as a `Route`."""
    p = pathlib.Path(path)
    ext = p.suffix.lower()
    if ext not in ROUTE_EXTENSIONS:
        raise _bad(p, "", p.suffix or "(none)",
                   f"unknown route file type: use one of {', '.join(ROUTE_EXTENSIONS)}")
    if not p.is_file():
        raise _bad(p, "", str(p), "no such file")
    try:
        text = p.read_bytes()
    except OSError as exc:
        raise _bad(p, "", str(p), f"cannot read: {exc.strerror}") from None
    local = False
    if ext == ".csv":
        pts, local = _read_csv(p, text)
    elif ext == ".gpx":
        pts = _read_gpx(p, text)
    elif ext == ".kml":
        pts = _read_kml(p, text)
    else:
        pts = _read_geojson(p, text)
    if len(pts.names) < 2:
        raise _bad(p, "", f"{len(pts.names)} waypoint(s)", "a route needs at least two waypoints")
    if not local:
        for lat, lon, where in zip(pts.a, pts.b, pts.where, strict=True):
            if not -90.0 <= lat <= 90.0:
                raise _bad(p, f"{where} latitude", lat, "must be in [-90, 90] degrees")
            if not -180.0 <= lon <= 360.0:
                raise _bad(p, f"{where} longitude", lon, "must be in [-180, 360] degrees")
    for h, where in zip(pts.headings, pts.where, strict=True):
        if math.isinf(h):
            raise _bad(p, f"{where} heading", h, "must be finite degrees or empty (free)")
    labels = tuple(pts.where)
    try:
        if local:
            heads = [math.radians(h) for h in pts.headings]
            return Route.from_local(pts.names, pts.a, pts.b, heads, source=str(p), labels=labels)
        return Route.from_geographic(pts.names, pts.a, pts.b, pts.headings, source=str(p),
                                     labels=labels)
    except InvalidParameterError as exc:
        if str(p) in exc.name:
            raise
        raise _bad(p, exc.name, exc.value, exc.rule) from None


def _number(p: pathlib.Path, where: str, field: str, text: str, *, empty_nan: bool = False
            ) -> float:
    t = text.strip()
    if t == "" and empty_nan:
        return math.nan
    try:
        v = float(t)
    except ValueError:
        raise _bad(p, f"{where} {field}", t, "must be a number") from None
    if not math.isfinite(v):
        raise _bad(p, f"{where} {field}", t, "must be finite")
    return v


def _read_csv(p: pathlib.Path, data: bytes) -> tuple[_Points, bool]:
    """`name,lat,lon[,heading_deg]` or `name,x,y[,heading_deg]` with a header row."""
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise _bad(p, "", "binary", "not a UTF-8 text CSV file") from None
    rows = [
        (n, r) for n, r in enumerate(csv.reader(text.splitlines()), start=1)
        if r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")
    ]
    if not rows:
        raise _bad(p, "", "empty", "no header row (name,lat,lon[,heading_deg] or name,x,y)")
    hline, header = rows[0]
    cols = [c.strip().lower() for c in header]
    if "lat" in cols and "lon" in cols:
        ka, kb, local = cols.index("lat"), cols.index("lon"), False
    elif "x" in cols and "y" in cols:
        ka, kb, local = cols.index("x"), cols.index("y"), True
    else:
        raise _bad(p, f"line {hline}", ",".join(header),
                   "the header must name lat,lon or x,y columns (and optionally name, "
                   "heading_deg)")
    kn = cols.index("name") if "name" in cols else None
    kh = next((cols.index(c) for c in ("heading_deg", "heading") if c in cols), None)
    out = _Points()
    for n, row in rows[1:]:
        where = f"line {n}"
        if len(row) != len(cols):
            raise _bad(p, where, ",".join(row),
                       f"has {len(row)} fields, the header has {len(cols)}")
        a = _number(p, where, cols[ka], row[ka])
        b = _number(p, where, cols[kb], row[kb])
        h = math.nan if kh is None else _number(p, where, cols[kh], row[kh], empty_nan=True)
        name = (row[kn].strip() if kn is not None and row[kn].strip()
                else f"WP{len(out.names) + 1:02d}")
        out.add(name, a, b, where, h)
    return out, local


def _read_gpx(p: pathlib.Path, data: bytes) -> _Points:
    """Route points of the first route with points, else waypoints, else track points."""
    import gpxpy
    import gpxpy.gpx

    try:
        gpx = gpxpy.parse(data.decode("utf-8-sig", errors="replace"))
    except (gpxpy.gpx.GPXException, ValueError) as exc:
        raise _bad(p, "", "GPX", f"not a readable GPX file: {' '.join(str(exc).split())}"
                   ) from None
    route = next((r for r in gpx.routes if r.points), None)
    pts: list[Any]
    if route is not None:
        pts, kind = list(route.points), "rtept"
    elif gpx.waypoints:
        pts, kind = list(gpx.waypoints), "wpt"
    else:
        pts = [q for t in gpx.tracks[:1] for s in t.segments for q in s.points]
        kind = "trkpt"
    out = _Points()
    for i, q in enumerate(pts, start=1):
        out.add((q.name or "").strip() or f"WP{i:02d}", float(q.latitude), float(q.longitude),
                f"{kind} {i}")
    if not out.names:
        raise _bad(p, "", "GPX", "has no route points, waypoints or track points")
    return out


def _read_kml(p: pathlib.Path, data: bytes) -> _Points:
    """The first LineString placemark, else the Point placemarks in order."""
    from fastkml import kml

    try:
        doc = kml.KML.from_string(data)  # type: ignore[arg-type]  # lxml takes bytes
    except Exception as exc:  # lxml / fastkml raise many types for a foreign file
        raise _bad(p, "", "KML", f"not a readable KML file: {' '.join(str(exc).split())}"
                   ) from None
    placemarks: list[Any] = []

    def walk(node: Any) -> None:
        for f in getattr(node, "features", None) or []:
            if getattr(f, "geometry", None) is not None:
                placemarks.append(f)
            walk(f)

    walk(doc)
    out = _Points()
    for k, pm in enumerate(placemarks, start=1):
        g = pm.geometry
        if type(g).__name__ == "LineString":
            name = (pm.name or "").strip() or "WP"
            for i, c in enumerate(g.coords, start=1):
                out.add(f"{name}{i:02d}" if name == "WP" else f"{name}-{i}", float(c[1]),
                        float(c[0]), f"placemark {k} ({pm.name or 'LineString'}) point {i}")
            return out
    for k, pm in enumerate(placemarks, start=1):
        g = pm.geometry
        if type(g).__name__ == "Point":
            out.add((pm.name or "").strip() or f"WP{len(out.names) + 1:02d}", float(g.y),
                    float(g.x), f"placemark {k} ({pm.name or 'Point'})")
    if not out.names:
        raise _bad(p, "", "KML", "has no LineString or Point placemarks")
    return out


def _read_geojson(p: pathlib.Path, data: bytes) -> _Points:
    """A LineString (the first) or Point features in order; properties name, heading_deg."""
    try:
        obj = json.loads(data.decode("utf-8-sig"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise _bad(p, "", "JSON", f"not a readable GeoJSON file: {exc}") from None
    if not isinstance(obj, dict) or "type" not in obj:
        raise _bad(p, "", type(obj).__name__, "not a GeoJSON object (no 'type')")
    if obj["type"] == "FeatureCollection":
        feats = obj.get("features")
        if not isinstance(feats, list):
            raise _bad(p, "", "features", "a FeatureCollection needs a 'features' list")
    elif obj["type"] == "Feature":
        feats = [obj]
    else:
        feats = [{"type": "Feature", "geometry": obj, "properties": {}}]
    out = _Points()
    geoms = []
    for k, f in enumerate(feats, start=1):
        g = f.get("geometry") if isinstance(f, dict) else None
        if not isinstance(g, dict):
            raise _bad(p, f"feature {k}", f, "has no geometry object")
        geoms.append((k, g, f.get("properties") or {}))
    for k, g, _ in geoms:
        if g.get("type") == "LineString":
            coords = g.get("coordinates")
            if not isinstance(coords, list):
                raise _bad(p, f"feature {k}", g.get("coordinates"), "needs a coordinate list")
            for i, c in enumerate(coords, start=1):
                where = f"feature {k} point {i}"
                lon, lat = _position(p, where, c)
                out.add(f"WP{i:02d}", lat, lon, where)
            return out
    for k, g, props in geoms:
        if g.get("type") == "Point":
            where = f"feature {k}"
            lon, lat = _position(p, where, g.get("coordinates"))
            name = str(props.get("name") or f"WP{len(out.names) + 1:02d}")
            h = props.get("heading_deg")
            heading = math.nan if h is None else _number(p, where, "heading_deg", str(h))
            out.add(name, lat, lon, where, heading)
    if not out.names:
        raise _bad(p, "", "GeoJSON", "has no LineString or Point features")
    return out


def _position(p: pathlib.Path, where: str, c: Any) -> tuple[float, float]:
    if not isinstance(c, list) or len(c) < 2:
        raise _bad(p, where, c, "a position is [longitude, latitude(, altitude)]")
    lon = _number(p, where, "longitude", str(c[0]))
    lat = _number(p, where, "latitude", str(c[1]))
    return lon, lat
