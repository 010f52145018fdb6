"""Landables from a SeeYou `.cup` waypoint file (read by aerofiles).

SeeYou styles 2-5 are landable (2 grass airfield, 3 outlanding, 4 gliding airfield, 5 paved
airfield); other waypoints are skipped. Elevations in feet are converted to metres.
"""

from __future__ import annotations

import pathlib

from glideplan.errors import InvalidParameterError
from glideplan.reach.problem import Landable

__all__ = ["LANDABLE_STYLES", "read_cup_landables"]

LANDABLE_STYLES = frozenset({2, 3, 4, 5})
FT = 0.3048


def read_cup_landables(path: str | pathlib.Path) -> tuple[tuple[Landable, ...], int]:
    """(landables in the file's order, number of non-landable waypoints skipped)."""
    from aerofiles.errors import ParserError
    from aerofiles.seeyou import Reader

    p = pathlib.Path(path)
    try:
        with open(p, encoding="utf-8-sig", newline="") as fp:
            data = Reader().read(fp)
    except ParserError as exc:
        raise InvalidParameterError(str(p), str(p), f"not a SeeYou .cup file ({exc})") from None
    except UnicodeDecodeError:
        raise InvalidParameterError(str(p), str(p), "not a SeeYou .cup file (not UTF-8 text: "
                                    "a binary file?)") from None
    except (ValueError, IndexError):
        raise InvalidParameterError(str(p), str(p), "not a SeeYou .cup file (expected a header "
                                    "'name,code,country,lat,lon,elev,style,...' and one "
                                    "waypoint per line)") from None
    out: list[Landable] = []
    skipped = 0
    for k, wp in enumerate(data["waypoints"], start=1):
        if wp["style"] not in LANDABLE_STYLES:
            skipped += 1
            continue
        elev = wp["elevation"]
        value = elev.get("value")
        if value is None:
            raise InvalidParameterError(f"{p} waypoint {k} ({wp['name']}) elevation", None,
                                        "a landable needs its elevation")
        unit = (elev.get("unit") or "m").lower()
        out.append(Landable(wp["name"], float(wp["latitude"]), float(wp["longitude"]),
                            float(value) * (FT if unit == "ft" else 1.0), int(wp["style"]),
                            wp.get("code") or ""))
    return tuple(out), skipped


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
