"""Read a route (ordered waypoints, optional headings) from CSV, GPX, KML/KMZ or GeoJSON.

The extension chooses the reader. Geographic files give WGS84 latitude/longitude (degrees)
and optional compass headings (degrees clockwise from north); a CSV may instead give local
metres `x, y` with headings in the `plan` convention (degrees CCW from +x). Every problem is
one `InvalidParameterError` whose message names the file, the line or feature and the rule;
what is read despite a flaw (a GeoJSON feature without geometry, skipped) is reported in
`Route.warnings` (the CLI prints them as `glideplan: warning: ...`).

What is read, per format:

* CSV: a header row, then one waypoint per row. Delimiter `,`, `;` or tab (the one that makes
  the header name the coordinate columns). Columns, any case: latitude `lat`/`latitude`,
  longitude `lon`/`long`/`lng`/`longitude` (or local `x`, `y`), optional `name` (or
  `waypoint`, `wpt`, `label`, `id`) and `heading_deg` (or `heading`). Coordinates follow
  `formats.coordinates`: decimal degrees; degrees and minutes apart (`40 22.552 N`); packed
  DDMM.MMMM when the column header says DDMM (`lat_ddmm`). When the numbers contain commas
  (a `;`- or tab-delimited file, or quoted fields) and none has a `.`, the comma is the
  decimal mark (`41,5`, with a warning); a file mixing both marks is refused.
* GPX: the route points of the first route with points, else the waypoints, else the track
  points of the first track (names from `<name>`).
* KML (2.2, or the older `http://earth.google.com/kml/2.x` namespaces) and KMZ (a zip holding
  `doc.kml`, else its first `.kml`): the first Placemark holding a line (a LineString, or the
  lines of a MultiGeometry joined in order, see below), else the Point placemarks (and the
  points of MultiGeometries) in order. Per-vertex names of a line: an ExtendedData
  `<Data name="names">` holding a JSON list (as glideplan writes).
* GeoJSON: the first feature holding a line (LineString, or MultiLineString joined in order),
  else the Point/MultiPoint features in order (properties `name`, `heading_deg`). A line's
  per-vertex names: property `names` (a list). A feature whose geometry is `null` is skipped
  with a warning.

Lines in several parts (GeoJSON MultiLineString, KML MultiGeometry) are ONE route: the parts
are concatenated in the order given, because that is how a line split at the antimeridian is
written (RFC 7946 section 3.1.9, `formats.antimeridian`): where a part ends at the point the
next one starts (e.g. longitude 180 and -180 at the same latitude) the point is kept once;
a vertex glideplan interpolated on the seam carries the name `null` in `names` and is dropped.
Parts that do not meet are still joined in order (a straight leg between them), with a warning.

Why this module is long: (about 550 lines, 50 of them this text): the four readers share
the waypoint accumulator (`_Points`), the error that names file and line, and the
line-joining rule above; kept in one module so every format is read by the same rules.
"""

from __future__ import annotations

import csv
import dataclasses
import io
import json
import math
import pathlib
import re
import zipfile
from dataclasses import dataclass, field
from typing import Any

from glideplan.errors import InvalidParameterError
from glideplan.formats.antimeridian import join_at_antimeridian
from glideplan.formats.coordinates import CoordinateError, parse_coordinate
from glideplan.missions.route import Route

__all__ = ["ROUTE_EXTENSIONS", "read_route"]

ROUTE_EXTENSIONS = (".csv", ".gpx", ".kml", ".kmz", ".geojson", ".json")

KML_NAMESPACE = "http://www.opengis.net/kml/2.2"
OLD_KML_NAMESPACES = tuple(f"http://earth.google.com/kml/2.{k}" for k in range(3))
MAX_KMZ_BYTES = 64 * 2**20  # a KML inside a KMZ larger than this is refused (zip bombs)

LAT_NAMES = ("lat", "latitude")
LON_NAMES = ("lon", "long", "lng", "longitude")
NAME_NAMES = ("name", "waypoint", "wpt", "label", "id")
HEADING_NAMES = ("heading_deg", "heading")


@dataclass
class _Points:
    """Waypoints as read: names, first and second coordinate, headings (deg, NaN free)."""

    names: list[str] = field(default_factory=list)
    a: list[float] = field(default_factory=list)  # lat or x
    b: list[float] = field(default_factory=list)  # lon or y
    headings: list[float] = field(default_factory=list)
    where: list[str] = field(default_factory=list)  # "line 3", "rtept 2": for error messages
    warnings: list[str] = field(default_factory=list)

    def add(self, name: str, a: float, b: float, where: str, heading: float = math.nan) -> None:
        """Append one waypoint (heading in degrees, NaN when free)."""
        self.names.append(name)
        self.a.append(a)
        self.b.append(b)
        self.headings.append(heading)
        self.where.append(where)


def _bad(path: pathlib.Path, where: str, value: Any, rule: str) -> InvalidParameterError:
    return InvalidParameterError(f"{path} {where}".strip(), value, rule)


def read_route(path: str | pathlib.Path, *, check_extent: bool = True) -> Route:
    """The route in `path` (.csv, .gpx, .kml, .kmz, .geojson/.json) as a `Route`; what was
    read despite a flaw is listed in its `warnings`. check_extent=False: no limit on the
    route's size (`Route.from_geographic`; missions routed through a field)."""
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
    elif ext == ".kmz":
        pts = _read_kml(p, _kmz_document(p, text))
    else:
        pts = _read_geojson(p, text)
    if len(pts.names) < 2:
        raise _bad(p, "", f"{len(pts.names)} waypoint(s)", "a route needs at least two waypoints")
    if not local:
        for lat, lon, where in zip(pts.a, pts.b, pts.where, strict=True):
            if not -90.0 <= lat <= 90.0:
                raise _bad(p, f"{where} latitude", lat, "must be in [-90, 90] degrees"
                           + _ddmm_hint(ext, lat))
            if not -180.0 <= lon <= 360.0:
                raise _bad(p, f"{where} longitude", lon, "must be in [-180, 360] degrees"
                           + _ddmm_hint(ext, lon))
    for h, where in zip(pts.headings, pts.where, strict=True):
        if math.isinf(h):
            raise _bad(p, f"{where} heading", h, "must be finite degrees or empty (free)")
    labels = tuple(pts.where)
    try:
        if local:
            heads = [math.radians(h) for h in pts.headings]
            route = Route.from_local(pts.names, pts.a, pts.b, heads, source=str(p),
                                     labels=labels)
        else:
            route = Route.from_geographic(pts.names, pts.a, pts.b, pts.headings, source=str(p),
                                          labels=labels, check_extent=check_extent)
    except InvalidParameterError as exc:
        if str(p) in exc.name:
            raise
        raise _bad(p, exc.name, exc.value, exc.rule) from None
    if pts.warnings:
        route = dataclasses.replace(route, warnings=tuple(f"{p}: {w}" for w in pts.warnings))
    return route


def _ddmm_hint(ext: str, value: float) -> str:
    """A hint for a CSV value that looks like packed DDMM.MMMM read as degrees."""
    if ext != ".csv" or not 100.0 <= abs(value) < 18100.0:
        return ""
    return (" (if the column is degrees and minutes packed as DDMM.MMMM, say so in its header, "
            "e.g. lat_ddmm, lon_ddmm)")


def _number(p: pathlib.Path, where: str, field: str, text: str, *, empty_nan: bool = False,
            decimal_comma: bool = False) -> float:
    t = text.strip()
    if t == "" and empty_nan:
        return math.nan
    if decimal_comma:
        t = t.replace(",", ".")
    try:
        v = float(t)
    except ValueError:
        raise _bad(p, f"{where} {field}", text.strip(), "must be a number") from None
    if not math.isfinite(v):
        raise _bad(p, f"{where} {field}", text.strip(), "must be finite")
    return v


# ----- CSV ----------------------------------------------------------------------------------
def _header_key(cell: str) -> tuple[str, bool]:
    """(the first word of a header cell, lower case; whether it says DDMM)."""
    low = cell.strip().lower()
    words = re.findall(r"[a-z]+", low)
    return (words[0] if words else low), "ddmm" in low


@dataclass(frozen=True)
class _Columns:
    ka: int
    kb: int
    local: bool
    ddmm_a: bool
    ddmm_b: bool
    kn: int | None
    kh: int | None


def _columns(cells: list[str]) -> _Columns | None:
    """The coordinate, name and heading columns a header names, None if it names none."""
    keys = [_header_key(c) for c in cells]
    exact = [c.strip().lower() for c in cells]

    def find(names: tuple[str, ...], *, whole: bool = False) -> list[int]:
        if whole:
            return [i for i, c in enumerate(exact) if c in names]
        return [i for i, (k, _) in enumerate(keys) if k in names]

    lat, lon = find(LAT_NAMES), find(LON_NAMES)
    if len(lat) == 1 and len(lon) == 1:
        ka, kb, local = lat[0], lon[0], False
    elif len(lat) > 1 or len(lon) > 1:
        return _Columns(-1, -1, False, False, False, None, None)  # ambiguous: reported
    else:
        xs, ys = find(("x",), whole=True), find(("y",), whole=True)
        if len(xs) != 1 or len(ys) != 1:
            return None
        ka, kb, local = xs[0], ys[0], True
    kn = next((i for n in NAME_NAMES for i in find((n,), whole=True)), None)
    kh = next((i for h in HEADING_NAMES for i in find((h,), whole=True)), None)
    return _Columns(ka, kb, local, keys[ka][1], keys[kb][1], kn, kh)


def _read_csv(p: pathlib.Path, data: bytes) -> tuple[_Points, bool]:
    """A header row naming the columns, then one waypoint per row (module docstring)."""
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError:
        raise _bad(p, "", "binary", "not a UTF-8 text CSV file") from None
    lines = text.splitlines()
    first = next(((n, t) for n, t in enumerate(lines, start=1)
                  if t.strip() and not t.lstrip().startswith("#")), None)
    if first is None:
        raise _bad(p, "", "empty", "no header row (name,lat,lon[,heading_deg] or name,x,y)")
    hline, htext = first
    found: list[tuple[str, list[str], _Columns]] = []
    for delim in (",", ";", "\t"):
        cells = next(csv.reader([htext], delimiter=delim))
        cols = _columns(cells)
        if cols is not None:
            found.append((delim, cells, cols))
    if not found:
        raise _bad(p, f"line {hline}", htext.strip(),
                   "the header must name the latitude and longitude columns (lat/latitude, "
                   "lon/long/lng/longitude) or x,y; optionally name and heading_deg; "
                   "delimited by ',', ';' or tabs")
    # the delimiter that splits the header into the most columns (a ';' header has no ',')
    delim, header, cols = max(found, key=lambda f: len(f[1]))
    if cols.ka < 0:
        raise _bad(p, f"line {hline}", htext.strip(),
                   "names more than one latitude or longitude column: keep one of each")
    rows = [
        (n, r) for n, r in enumerate(csv.reader(lines, delimiter=delim), start=1)
        if n > hline and r and any(c.strip() for c in r) and not r[0].lstrip().startswith("#")
    ]
    numeric = [k for k in (cols.ka, cols.kb, cols.kh) if k is not None]
    # a ',' inside a number (delimited by ';' or tabs, or quoted) is a decimal comma when no
    # number of the file has a '.'
    cells = [r[k] for _, r in rows for k in numeric if k < len(r)]
    decimal_comma = any("," in c for c in cells)
    if decimal_comma and any("." in c for c in cells):
        raise _bad(p, "", "decimal marks",
                   "the numbers mix '.' and ',' as decimal marks: use one of them")
    names = [c.strip().lower() for c in header]
    out = _Points()
    if decimal_comma:
        out.warnings.append("',' read as the decimal mark (the coordinates have ',' inside "
                            "numbers and no '.')")
    for n, row in rows:
        where = f"line {n}"
        if len(row) != len(header):
            raise _bad(p, where, delim.join(row),
                       f"has {len(row)} fields, the header has {len(header)}")
        if cols.local:
            a = _number(p, where, names[cols.ka], row[cols.ka], decimal_comma=decimal_comma)
            b = _number(p, where, names[cols.kb], row[cols.kb], decimal_comma=decimal_comma)
        else:
            a = _coordinate(p, where, names[cols.ka], row[cols.ka], "lat", cols.ddmm_a,
                            decimal_comma)
            b = _coordinate(p, where, names[cols.kb], row[cols.kb], "lon", cols.ddmm_b,
                            decimal_comma)
        h = (math.nan if cols.kh is None else
             _number(p, where, names[cols.kh], row[cols.kh], empty_nan=True,
                     decimal_comma=decimal_comma))
        name = (row[cols.kn].strip() if cols.kn is not None and row[cols.kn].strip()
                else f"WP{len(out.names) + 1:02d}")
        out.add(name, a, b, where, h)
    return out, cols.local


def _coordinate(p: pathlib.Path, where: str, column: str, text: str, axis: str, ddmm: bool,
                decimal_comma: bool) -> float:
    try:
        return parse_coordinate(text, axis, ddmm=ddmm, decimal_comma=decimal_comma)
    except CoordinateError as exc:
        raise _bad(p, f"{where} {column}", text.strip(), str(exc)) from None


# ----- GPX ----------------------------------------------------------------------------------
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


# ----- lines in parts, per-vertex names ----------------------------------------------------
def _add_line(p: pathlib.Path, out: _Points, parts: list[list[tuple[float, float]]],
              names: Any, base: str, where: str) -> None:
    """Append a line given as parts of (lat, lon) points (joined in order, module docstring);
    `names`, when a list as long as the joined line, names its vertices (None: a seam point
    that glideplan interpolated, dropped)."""
    parts = [q for q in parts if q]
    lat, lon, seam = join_at_antimeridian(
        [([a for a, _ in q], [b for _, b in q]) for q in parts])
    gaps = len(parts) - 1 - sum(seam)  # joints where the parts do not meet
    if gaps:
        out.warnings.append(f"{where}: {gaps} of its {len(parts) - 1} part boundaries are not "
                            "continuous: the parts are joined in order by straight legs")
    given: list[str | None] | None = None
    if names is not None:
        ok = (isinstance(names, list) and len(names) == len(lat)
              and all(n is None or isinstance(n, str | int | float) for n in names))
        if ok:
            given = [None if n is None else str(n) for n in names]
        else:
            out.warnings.append(f"{where}: its vertex names do not match its {len(lat)} "
                                "points: ignored")
    for i, (a, b) in enumerate(zip(lat, lon, strict=True), start=1):
        if given is not None and given[i - 1] is None:
            continue  # a point glideplan interpolated on the antimeridian
        name = (given[i - 1] if given is not None else "") or ""
        if not name.strip():
            name = f"{base}{i:02d}" if base == "WP" else f"{base}-{i}"
        out.add(name.strip(), a, b, f"{where} point {i}")


# ----- KML / KMZ ----------------------------------------------------------------------------
def _kmz_document(p: pathlib.Path, data: bytes) -> bytes:
    """The KML document of a KMZ archive: `doc.kml` at the top, else its first `.kml`."""
    try:
        with zipfile.ZipFile(io.BytesIO(data)) as z:
            infos = [i for i in z.infolist() if i.filename.lower().endswith(".kml")]
            if not infos:
                raise _bad(p, "", "KMZ", "the archive holds no .kml file")
            info = next((i for i in infos if i.filename.lower() == "doc.kml"), infos[0])
            if info.file_size > MAX_KMZ_BYTES:
                raise _bad(p, info.filename, info.file_size,
                           f"is larger than {MAX_KMZ_BYTES // 2**20} MiB uncompressed")
            return z.read(info)
    except (zipfile.BadZipFile, EOFError, OSError) as exc:
        raise _bad(p, "", "KMZ", f"not a readable KMZ (zip) file: {exc}") from None


def _normalise_kml(data: bytes) -> bytes:
    """The KML with the older Google Earth namespace (or none) moved to KML 2.2's."""
    from lxml import etree

    try:
        parser = etree.XMLParser(resolve_entities=False, no_network=True, recover=False)
        root = etree.fromstring(data, parser)
    except etree.XMLSyntaxError:
        return data  # fastkml reports it
    qn = etree.QName(root)
    if qn.namespace == KML_NAMESPACE or qn.localname.lower() != "kml":
        return data
    if qn.namespace not in (*OLD_KML_NAMESPACES, None):
        return data
    old = qn.namespace
    for el in root.iter():
        if isinstance(el.tag, str) and etree.QName(el).namespace == old:
            el.tag = f"{{{KML_NAMESPACE}}}{etree.QName(el).localname}"
    etree.cleanup_namespaces(root)
    out: bytes = etree.tostring(root, encoding="UTF-8", xml_declaration=True)
    return out


def _kml_parts(g: Any) -> tuple[list[list[tuple[float, float]]], list[tuple[float, float]]]:
    """(line parts, points) of a pygeoif geometry, as (lat, lon) pairs."""
    kind = type(g).__name__
    if kind == "LineString":
        return [[(float(c[1]), float(c[0])) for c in g.coords]], []
    if kind == "Point":
        return [], [(float(g.y), float(g.x))]
    lines: list[list[tuple[float, float]]] = []
    points: list[tuple[float, float]] = []
    if kind in ("MultiLineString", "MultiPoint", "GeometryCollection"):
        for sub in g.geoms:
            a, b = _kml_parts(sub)
            lines += a
            points += b
    return lines, points


def _kml_names(pm: Any) -> Any:
    """A Placemark's per-vertex names: ExtendedData `names` holding a JSON list, or None."""
    ext = getattr(pm, "extended_data", None)
    for el in getattr(ext, "elements", None) or []:
        if getattr(el, "name", None) == "names" and getattr(el, "value", None):
            try:
                return json.loads(el.value)
            except json.JSONDecodeError:
                return el.value
    return None


def _read_kml(p: pathlib.Path, data: bytes) -> _Points:
    """The first placemark with a line, else the point placemarks in order."""
    from fastkml import kml

    try:
        doc = kml.KML.from_string(_normalise_kml(data))  # type: ignore[arg-type]  # bytes ok
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
        lines, _ = _kml_parts(pm.geometry)
        if lines:
            name = (pm.name or "").strip() or "WP"
            _add_line(p, out, lines, _kml_names(pm), name,
                      f"placemark {k} ({pm.name or 'line'})")
            return out
    for k, pm in enumerate(placemarks, start=1):
        _, points = _kml_parts(pm.geometry)
        name = (pm.name or "").strip()
        for i, (lat, lon) in enumerate(points, start=1):
            label = f"placemark {k} ({pm.name or 'Point'})"
            if len(points) > 1:
                label += f" point {i}"
                wp = f"{name}-{i}" if name else f"WP{len(out.names) + 1:02d}"
            else:
                wp = name or f"WP{len(out.names) + 1:02d}"
            out.add(wp, lat, lon, label)
    if not out.names:
        raise _bad(p, "", "KML", "has no LineString or Point placemarks")
    return out


# ----- GeoJSON ------------------------------------------------------------------------------
def _read_geojson(p: pathlib.Path, data: bytes) -> _Points:
    """The first line feature, else the point features in order (module docstring)."""
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
        if not isinstance(f, dict) or "geometry" not in f:
            raise _bad(p, f"feature {k}", f, "has no geometry member (RFC 7946: a geometry "
                       "object or null)")
        g = f["geometry"]
        if g is None:
            out.warnings.append(f"feature {k} has no geometry (null): skipped")
            continue
        if not isinstance(g, dict):
            raise _bad(p, f"feature {k}", g, "geometry must be an object or null")
        props = f.get("properties")
        geoms.append((k, g, props if isinstance(props, dict) else {}))
    for k, g, props in geoms:
        kind = g.get("type")
        if kind in ("LineString", "MultiLineString"):
            coords = g.get("coordinates")
            parts = [coords] if kind == "LineString" else coords
            if not isinstance(parts, list) or not all(isinstance(q, list) for q in parts):
                raise _bad(p, f"feature {k}", coords, f"a {kind} needs coordinate lists")
            latlon = []
            for j, part in enumerate(parts, start=1):
                sub = f"feature {k} part {j}" if kind == "MultiLineString" else f"feature {k}"
                latlon.append([_position(p, f"{sub} point {i}", c)[::-1]
                               for i, c in enumerate(part, start=1)])
            _add_line(p, out, latlon, props.get("names"), "WP", f"feature {k}")
            return out
    for k, g, props in geoms:
        kind = g.get("type")
        if kind not in ("Point", "MultiPoint"):
            continue
        where = f"feature {k}"
        h = props.get("heading_deg")
        heading = math.nan if h is None else _number(p, where, "heading_deg", str(h))
        base = str(props.get("name") or "").strip()
        if kind == "Point":
            lon, lat = _position(p, where, g.get("coordinates"))
            out.add(base or f"WP{len(out.names) + 1:02d}", lat, lon, where, heading)
            continue
        coords = g.get("coordinates")
        if not isinstance(coords, list):
            raise _bad(p, where, coords, "a MultiPoint needs a coordinate list")
        for i, c in enumerate(coords, start=1):
            lon, lat = _position(p, f"{where} point {i}", c)
            out.add(f"{base}-{i}" if base else f"WP{len(out.names) + 1:02d}", lat, lon,
                    f"{where} point {i}")
    if not out.names:
        raise _bad(p, "", "GeoJSON", "has no LineString, MultiLineString, Point or MultiPoint "
                   "features" + (" (features without geometry were skipped)"
                                 if out.warnings else ""))
    return out


def _position(p: pathlib.Path, where: str, c: Any) -> tuple[float, float]:
    if not isinstance(c, list) or len(c) < 2:
        raise _bad(p, where, c, "a position is [longitude, latitude(, altitude)]")
    lon = _number(p, where, "longitude", str(c[0]))
    lat = _number(p, where, "latitude", str(c[1]))
    return lon, lat
