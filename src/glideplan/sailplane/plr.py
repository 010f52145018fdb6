"""WinPilot / LK8000 / XCSoar polar files (`.plr`): read, validate, report the offending line.

Format (FORMATS.md): lines starting with `*` are comments; the first data line is
`mass_kg, max_ballast_l, v1_kmh, w1, v2_kmh, w2, v3_kmh, w3[, wing_area_m2[, ...]]` with sink
rates negative (m/s). Real files differ in spacing (spaces, tabs), trailing fields, `//`
comments at the end of the data line (some state the best glide ratio, `// BestLD42@97kph`)
and line endings (CR LF, LF, CR). Lines after the first data line (flap tables in some LK8000
files) are not part of the polar and are not read.
"""

from __future__ import annotations

import math
import pathlib
import re
from dataclasses import dataclass

from glideplan.errors import InvalidParameterError

__all__ = ["PolarFile", "PolarFileError", "parse_plr", "read_plr"]

_BEST_LD = re.compile(r"BestLD\s*([0-9]+(?:\.[0-9]+)?)", re.IGNORECASE)
_SPLIT = re.compile(r"[,;\s]+")


class PolarFileError(InvalidParameterError):
    """A malformed polar file: the message names the file, the line number and the rule."""

    def __init__(self, source: str, line_no: int | None, text: str, rule: str) -> None:
        where = f"polar file {source}, line {line_no}" if line_no else f"polar file {source}"
        super().__init__(where, text.strip(), rule)


@dataclass(frozen=True)
class PolarFile:
    """The numbers of a `.plr` file, as written (km/h, m/s with sink negative, kg, litres).

    `points` are three (speed km/h, sink m/s) pairs sorted by speed; `wing_area_m2` is
    None when the file has none or gives 0; `best_ld` is the glide ratio stated in a
    `// BestLD..` comment, if any.
    """

    source: str
    name: str
    mass_kg: float
    max_ballast_l: float
    points: tuple[tuple[float, float], tuple[float, float], tuple[float, float]]
    wing_area_m2: float | None
    best_ld: float | None
    comment: str
    line_no: int


def _number(source: str, line_no: int, text: str, token: str, what: str) -> float:
    try:
        value = float(token)
    except ValueError:
        raise PolarFileError(
            source, line_no, text, f"{what} must be a number, got {token!r}"
        ) from None
    if not math.isfinite(value):
        raise PolarFileError(source, line_no, text, f"{what} must be finite, got {token!r}")
    return value


def parse_plr(text: str, source: str = "<text>") -> PolarFile:
    """Parse the text of a `.plr` file; raise `PolarFileError` naming the line and the rule."""
    name = pathlib.Path(source).stem
    for line_no, raw in enumerate(text.splitlines(), start=1):
        line = raw.strip().lstrip("\ufeff")
        if not line:
            continue
        if line.startswith("*"):
            m = re.search(r"polar for:\s*(.+)$", line, re.IGNORECASE)
            if m:
                name = m.group(1).strip()
            continue
        data, _, comment = line.partition("//")
        tokens = [t for t in _SPLIT.split(data.strip()) if t]
        if len(tokens) < 8:
            raise PolarFileError(
                source,
                line_no,
                raw,
                f"the data line needs at least 8 comma-separated numbers (mass, ballast, "
                f"3 x speed, sink), found {len(tokens)}",
            )
        fields = ("mass", "max ballast", "v1", "w1", "v2", "w2", "v3", "w3")
        vals = [
            _number(source, line_no, raw, tok, what)
            for tok, what in zip(tokens[:8], fields, strict=True)
        ]
        area: float | None = None
        if len(tokens) >= 9:
            area = _number(source, line_no, raw, tokens[8], "wing area")
            if area < 0.0:
                raise PolarFileError(source, line_no, raw, "wing area must be >= 0 (m^2)")
            area = area if area > 0.0 else None
        mass, ballast = vals[0], vals[1]
        if mass <= 0.0:
            raise PolarFileError(source, line_no, raw, f"mass must be > 0 kg, got {mass:g}")
        if ballast < 0.0:
            raise PolarFileError(
                source, line_no, raw, f"max ballast must be >= 0 litres, got {ballast:g}"
            )
        speeds, sinks = vals[2::2], vals[3::2]
        if any(v <= 0.0 for v in speeds):
            raise PolarFileError(source, line_no, raw, "speeds must be > 0 km/h")
        if len(set(speeds)) < 3:
            raise PolarFileError(source, line_no, raw, "the three speeds must differ")
        if any(w >= 0.0 for w in sinks):
            raise PolarFileError(
                source, line_no, raw, "sink rates must be negative (m/s, the .plr convention)"
            )
        ld = _BEST_LD.search(comment)
        # some files list the points out of order (Para_Competition.plr): sort by speed
        pts = tuple(sorted((float(v), float(w)) for v, w in zip(speeds, sinks, strict=True)))
        return PolarFile(
            source=source,
            name=name,
            mass_kg=mass,
            max_ballast_l=ballast,
            points=pts,  # type: ignore[arg-type]
            wing_area_m2=area,
            best_ld=float(ld.group(1)) if ld else None,
            comment=comment.strip(),
            line_no=line_no,
        )
    raise PolarFileError(source, None, "", "has no data line (only comments or blank lines)")


def read_plr(path: str | pathlib.Path) -> PolarFile:
    """Read a `.plr` file (any line ending; UTF-8 or Latin-1)."""
    p = pathlib.Path(path)
    try:
        raw = p.read_bytes()
    except IsADirectoryError:
        raise PolarFileError(str(p), None, "", "is a directory, not a polar file") from None
    except FileNotFoundError:
        raise PolarFileError(str(p), None, "", "does not exist") from None
    if b"\x00" in raw:
        raise PolarFileError(str(p), None, "", "is a binary file, not a text polar file")
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")
    return parse_plr(text, str(p))
