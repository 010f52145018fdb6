"""Landables from a SeeYou `.cup` waypoint file (each line decoded by aerofiles).

SeeYou styles 2-5 are landable (2 grass airfield, 3 outlanding, 4 gliding airfield, 5 paved
airfield); other waypoints are skipped. Elevations in feet are converted to metres.

Files as pilots have them: SeeYou writes Windows-1252 (Latin-1 plus curly quotes, euro sign),
newer tools UTF-8, some with a byte-order mark. The text is decoded as UTF-8 (BOM dropped)
when it is valid UTF-8 -- a Windows-1252 file with accented names almost never is (an accented
letter is one byte >= 0x80 followed by an ASCII one, which UTF-8 forbids) -- else as
Windows-1252, else as Latin-1 (the five bytes Windows-1252 leaves undefined); a UTF-16 file
is recognised by its BOM. A landable with an empty elevation takes the terrain's (bilinear)
at its position, with a note; one outside the terrain is skipped with a note. Coordinates are
DDMM.mmm: a minute field >= 60 is refused (aerofiles would carry it into the degrees).
"""

from __future__ import annotations

import codecs
import pathlib
import re
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from glideplan.errors import InvalidParameterError
from glideplan.reach.problem import Landable

if TYPE_CHECKING:
    from glideplan.terrain.grid import Terrain

__all__ = ["LANDABLE_STYLES", "CupLandables", "read_cup", "read_cup_landables",
           "write_cup_landables"]

LANDABLE_STYLES = frozenset({2, 3, 4, 5})
FT = 0.3048
_MINUTES = re.compile(r"^\s*(\d{2,3})(\d{2}(?:\.\d*)?)\s*([NSEW])\s*$", re.I)
_NOT_CUP = ("not a SeeYou .cup file (expected a header 'name,code,country,lat,lon,elev,"
            "style,...' and one waypoint per line)")


@dataclass(frozen=True)
class CupLandables:
    """What a .cup file gave: the landables in its order, the number of non-landable
    waypoints skipped, notes (elevations taken from the terrain, fields skipped) and the
    text encoding it was read in."""

    landables: tuple[Landable, ...]
    skipped: int
    notes: tuple[str, ...]
    encoding: str


def decode_text(raw: bytes, source: str) -> tuple[str, str]:
    """(text, encoding name) of a text file's bytes (module docstring)."""
    for bom, enc in ((codecs.BOM_UTF8, "utf-8"), (codecs.BOM_UTF16_LE, "utf-16-le"),
                     (codecs.BOM_UTF16_BE, "utf-16-be")):
        if raw.startswith(bom):
            try:
                return raw[len(bom):].decode(enc), f"{enc} with BOM"
            except UnicodeDecodeError as exc:
                raise InvalidParameterError(source, source, f"{_NOT_CUP}: invalid {enc} text "
                                            f"after its byte-order mark ({exc.reason})") from None
    if b"\0" in raw:
        raise InvalidParameterError(source, source, f"{_NOT_CUP}: a binary file (NUL bytes)")
    for enc in ("utf-8", "cp1252"):
        try:
            return raw.decode(enc), enc
        except UnicodeDecodeError:
            continue
    return raw.decode("latin-1"), "latin-1"


def _check_minutes(field: str, what: str, where: str) -> None:
    """Refuse DDMM.mmm / DDDMM.mmm with minutes >= 60."""
    m = _MINUTES.match(field)
    if m is not None and float(m.group(2)) >= 60.0:
        raise InvalidParameterError(
            f"{where} {what}", field, f"the minute field {m.group(2)} must be below 60 "
            f"(.cup {what}s are {'DD' if what == 'latitude' else 'DDD'}MM.mmm: degrees, then "
            "minutes 00-59.999)")


def _waypoints(text: str, source: str) -> list[tuple[int, dict[str, Any]]]:
    """(line number, aerofiles waypoint dict) for each waypoint line, up to the task part."""
    import csv
    import io

    from aerofiles.errors import ParserError
    from aerofiles.seeyou import Reader

    reader = Reader()
    rows = csv.reader(io.StringIO(text, newline=""))
    out: list[tuple[int, dict[str, Any]]] = []
    while True:
        try:
            fields = next(rows)
        except StopIteration:
            break
        except csv.Error as exc:
            raise InvalidParameterError(f"{source} line {rows.line_num}", None,
                                        f"{_NOT_CUP} ({exc})") from None
        line = rows.line_num
        if fields == ["-----Related Tasks-----"]:
            break
        if not out and fields and fields[0].strip().lower() in ("name", "title"):
            continue  # a header in other words (older SeeYou: Title,Code,...,Latitude,...)
        try:
            wp = reader.decode_waypoint(fields)
        except (ParserError, ValueError, IndexError) as exc:
            detail = str(exc) or type(exc).__name__
            raise InvalidParameterError(f"{source} line {line}", ",".join(fields)[:60],
                                        f"{_NOT_CUP}: {detail}") from None
        if wp is None:  # header, comment or empty line
            continue
        stripped = [f.strip() for f in fields]
        for what, key in (("latitude", "lat"), ("longitude", "lon")):
            _check_minutes(stripped[reader.headers.index(key)], what, f"{source} line {line}")
        out.append((line, wp))
    if not out and not text.strip():
        raise InvalidParameterError(source, source, f"{_NOT_CUP}: the file is empty")
    return out


def read_cup(path: str | pathlib.Path, terrain: Terrain | None = None) -> CupLandables:
    """The landables of a SeeYou `.cup` file (module docstring); `terrain` gives the
    elevation of landables whose `elev` field is empty (without it they are refused)."""
    import math

    p = pathlib.Path(path)
    text, encoding = decode_text(p.read_bytes(), str(p))
    out: list[Landable] = []
    notes: list[str] = []
    skipped = 0
    for line, wp in _waypoints(text, str(p)):
        if wp["style"] not in LANDABLE_STYLES:
            skipped += 1
            continue
        name, lat, lon = wp["name"], float(wp["latitude"]), float(wp["longitude"])
        value = wp["elevation"].get("value")
        if value is None:
            where = f"{p} line {line} ({name})"
            if terrain is None:
                raise InvalidParameterError(f"{where} elevation", None, "a landable needs its "
                                            "elevation (or terrain to take it from)")
            ground = float(terrain.elevation(lat, lon))
            if not math.isfinite(ground):
                notes.append(f"{where}: no elevation in the file and outside the terrain; "
                             "skipped")
                continue
            notes.append(f"{where}: no elevation in the file; the terrain's {ground:.0f} m "
                         "is used")
            elevation = ground
        else:
            unit = (wp["elevation"].get("unit") or "m").lower()
            elevation = float(value) * (FT if unit == "ft" else 1.0)
        out.append(Landable(name, lat, lon, elevation, int(wp["style"]), wp.get("code") or ""))
    return CupLandables(tuple(out), skipped, tuple(notes), encoding)


def read_cup_landables(path: str | pathlib.Path, terrain: Terrain | None = None,
                       notes: list[str] | None = None) -> tuple[tuple[Landable, ...], int]:
    """(landables in the file's order, number of non-landable waypoints skipped); `read_cup`'s
    notes are appended to `notes` when given."""
    got = read_cup(path, terrain)
    if notes is not None:
        notes.extend(got.notes)
    return got.landables, got.skipped


def write_cup_landables(path: str | pathlib.Path, landables: list[Landable]) -> pathlib.Path:
    """Write landables as a SeeYou `.cup` file (aerofiles writer; style 0 becomes 3)."""
    from aerofiles.seeyou import Writer

    p = pathlib.Path(path)
    with open(p, "wb") as fp:
        w = Writer(fp)
        for lnd in landables:
            code = lnd.code or "".join(c for c in lnd.name.upper() if c.isalnum())[:6] or "WP"
            w.write_waypoint(lnd.name, code, "", lnd.lat, lnd.lon, float(lnd.elevation_m),
                             style=lnd.style or 3)
    return p
