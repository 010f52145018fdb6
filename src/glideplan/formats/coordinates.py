"""One latitude or longitude of a text file, in the notations route files use, to degrees.

The rule (stated once; `read_route` follows it for CSV files):

* A plain number is decimal degrees (`40.3759`, `-73.896`), unless its column header says
  DDMM (contains `ddmm`, e.g. `lat_ddmm`, `Longitude (DDMM.MMMM)`): then it is degrees and
  decimal minutes packed as one number, `[-]DDMM.MMMM` (`4022.5520` = 40 deg 22.552').
* Degrees and minutes written apart are read as such: `40 22.552 N`, `N40 22.552`,
  `40°22.552'N`, `-73 53.7601`; a third number is seconds (`40 22 33.1 N`). Minutes and
  seconds must be below 60.
* A hemisphere letter (N/S for latitude, E/W for longitude; before or after) gives the sign:
  S and W are negative; it may not be combined with a minus sign.
* With `decimal_comma`, a comma is the decimal mark (`40,3759`): used for files delimited by
  `;` or tabs whose numbers have no `.` (see `read_route`).

Anything else (letters, the wrong hemisphere, minutes >= 60, a bare `4022.552` in a column not
marked DDMM) is refused by `CoordinateError` with the rule; a bare number outside the
latitude/longitude range is reported by the reader with a hint to mark a DDMM column.
"""

from __future__ import annotations

import math
import re

__all__ = ["CoordinateError", "parse_coordinate"]

_DM = re.compile(
    r"""^\s*(?P<h1>[NSEW])?\s*(?P<sign>[-+])?\s*
    (?P<d>\d+(?:\.\d+)?)\s*(?:°|º|\s|d(?:eg)?\b|:)\s*
    (?:(?P<m>\d+(?:\.\d+)?)\s*(?:'|′|m\b|:)?\s*
    (?:(?P<s>\d+(?:\.\d+)?)\s*(?:"|″|''|s\b)?)?)?\s*
    (?P<h2>[NSEW])?\s*$""",
    re.IGNORECASE | re.VERBOSE,
)
_PLAIN = re.compile(
    r"^\s*(?P<h1>[NSEW])?\s*(?P<num>[-+]?(?:\d+\.?\d*|\.\d+))\s*(?P<h2>[NSEW])?\s*$",
    re.IGNORECASE,
)


class CoordinateError(ValueError):
    """A coordinate text that follows none of the notations; the message is the rule."""


def _hemisphere(text: str, h1: str | None, h2: str | None, axis: str, sign: str | None) -> float:
    if h1 and h2:
        raise CoordinateError("give the hemisphere letter once")
    h = (h1 or h2 or "").upper()
    if not h:
        return -1.0 if sign == "-" else 1.0
    if sign == "-":
        raise CoordinateError("give either a minus sign or a hemisphere letter, not both")
    allowed = "NS" if axis == "lat" else "EW"
    if h not in allowed:
        what = "latitude" if axis == "lat" else "longitude"
        raise CoordinateError(f"a {what} takes the hemisphere {allowed[0]} or {allowed[1]}, "
                              f"not {h}")
    return -1.0 if h in "SW" else 1.0


def parse_coordinate(text: str, axis: str, *, ddmm: bool = False,
                     decimal_comma: bool = False) -> float:
    """Degrees of one latitude (`axis="lat"`) or longitude (`"lon"`) written as in the module
    rule; `ddmm` marks a column of packed DDMM.MMMM numbers."""
    t = text.strip()
    if decimal_comma:
        if "." in t:
            raise CoordinateError("mixes '.' and ',' decimal marks")
        t = t.replace(",", ".")
    if not t:
        raise CoordinateError("is empty")
    m = _PLAIN.match(t)
    if m:
        num = m.group("num")
        sign = "-" if num.startswith("-") else None
        s = _hemisphere(t, m.group("h1"), m.group("h2"), axis, sign)
        v = abs(float(num))
        if not math.isfinite(v):
            raise CoordinateError("must be finite")
        if ddmm:
            d = float(math.floor(v / 100.0))
            minutes = v - 100.0 * d
            if minutes >= 60.0:
                raise CoordinateError(f"DDMM.MMMM minutes {minutes:.6g} must be below 60")
            v = d + minutes / 60.0
        return s * v
    m = _DM.match(t)
    if m is None or m.group("m") is None:
        raise CoordinateError(
            "must be decimal degrees (40.3759), degrees and minutes (40 22.552 N, 40°22.552'N) "
            "or DDMM.MMMM in a column whose header says DDMM")
    s = _hemisphere(t, m.group("h1"), m.group("h2"), axis, m.group("sign"))
    d, minutes = float(m.group("d")), float(m.group("m"))
    seconds = float(m.group("s")) if m.group("s") else 0.0
    if m.group("s") and (d != math.floor(d) or minutes != math.floor(minutes)):
        raise CoordinateError("with seconds, degrees and minutes must be whole numbers")
    if d != math.floor(d):
        raise CoordinateError("with minutes, the degrees must be a whole number")
    if minutes >= 60.0 or seconds >= 60.0:
        raise CoordinateError("minutes and seconds must be below 60")
    return s * (d + minutes / 60.0 + seconds / 3600.0)
