"""WinPilot / LK8000 / XCSoar polar files (`.plr`): read, validate, report the offending line.

Format (FORMATS.md): lines starting with `*` are comments; the first data line is
`mass_kg, max_ballast_l, v1_kmh, w1, v2_kmh, w2, v3_kmh, w3[, wing_area_m2[, ...]]` with sink
rates negative (m/s). Real files differ in spacing (spaces, tabs), trailing fields, `//`
comments at the end of the data line (some state the best glide ratio, `// BestLD42@97kph`)
and line endings (CR LF, LF, CR). Lines after the first data line (flap tables in some LK8000
files) are not part of the polar and are not read.

Decimal commas (a file saved in a locale that writes `80,0`): a data line without any `.`
whose fields are separated by spaces, tabs, `;` or `, ` (comma and space) and whose numbers
contain a comma between digits (`325  0  80,0  -0,58 ...`) is read with `,` as the decimal
mark (`PolarFile.decimal_comma`). A line that cannot be split that way (`325,0,80,0,...`,
where a comma may separate fields or decimals) is read with commas as separators, and if that
reading breaks a rule the message says that decimal commas may be the cause and how to fix it.

Physical ranges (absurd numbers are refused with the line and the rule, not planned with):
speeds in (0, 400] km/h (no sailplane is certified beyond ~300 km/h), sink rates of at least
0.2 m/s (the best sailplanes sink ~0.4 m/s at minimum sink), glide ratio v/|w| at each point
and of the fitted polar between 1 and 100 (the best built, eta and Concordia, reach ~70; the
156 real files give 7 to 61), mass up to 5,000 kg (the heaviest two-seaters ~1,100 kg).
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
_DECIMAL_COMMA_SPLIT = re.compile(r"[;\s]+|,(?=\s)")
_DECIMAL_COMMA_NUMBER = re.compile(r"[+-]?\d+(?:,\d+)?")

MAX_SPEED_KMH = 400.0
MIN_SINK_M_S = 0.2
MIN_GLIDE_RATIO = 1.0
MAX_GLIDE_RATIO = 100.0
MAX_MASS_KG = 5000.0
DECIMAL_COMMA_HINT = (
    "decimal commas? The line has commas between digits and no '.', so its commas were read "
    "as separators, and then {rule}. If it uses decimal commas, write '.' decimals, or "
    "separate the fields by spaces or ';' (e.g. '325 0 80,0 -0,58 ...')"
)


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
    decimal_comma: bool = False


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


def _tokens(data: str) -> tuple[list[str], bool, bool]:
    """(the numbers of a data line as text with '.' decimals, whether commas were decimal
    marks, whether the line might use decimal commas but could not be read so)."""
    plain = [t for t in _SPLIT.split(data) if t]
    if "." in data or not re.search(r"\d,\d", data):
        return plain, False, False
    cand = [t for t in _DECIMAL_COMMA_SPLIT.split(data) if t]
    if (len(cand) >= 8 and all(_DECIMAL_COMMA_NUMBER.fullmatch(t) for t in cand)
            and any("," in t for t in cand)):
        return [t.replace(",", ".") for t in cand], True, False
    return plain, False, True


def _glide_ratios(points: list[tuple[float, float]]) -> tuple[float, float]:
    """(lowest, highest) v/|w| of the points and of the parabola through them (km/h, m/s in;
    the parabola w = a v^2 + b v + c, sink positive, checked at its best-glide speed
    sqrt(c/a) when that lies inside the points' speed range and w > 0 there)."""
    v = [p[0] / 3.6 for p in points]
    w = [-p[1] for p in points]
    ratios = [vi / wi for vi, wi in zip(v, w, strict=True)]
    lo, hi = min(ratios), max(ratios)
    (v1, v2, v3), (w1, w2, w3) = v, w
    d12, d23 = (w2 - w1) / (v2 - v1), (w3 - w2) / (v3 - v2)
    a = (d23 - d12) / (v3 - v1)  # divided differences: the parabola through the points
    b = d12 - a * (v1 + v2)
    c = w1 - a * v1 * v1 - b * v1
    if a > 0.0 and c > 0.0:
        vb = math.sqrt(c / a)
        wb = a * vb * vb + b * vb + c
        if v1 <= vb <= v3 and wb > 0.0:
            hi = max(hi, vb / wb)
    return lo, hi


def _check_ranges(source: str, line_no: int, raw: str, mass: float,
                  pts: list[tuple[float, float]], hint: str) -> None:
    """Refuse numbers outside the physical ranges of the module docstring."""
    def bad(rule: str) -> PolarFileError:
        return PolarFileError(source, line_no, raw, hint.format(rule=rule))

    if mass > MAX_MASS_KG:
        raise bad(f"mass must be <= {MAX_MASS_KG:g} kg (the heaviest sailplanes are about "
                  f"1,100 kg), got {mass:g}")
    for v, w in pts:
        if v > MAX_SPEED_KMH:
            raise bad(f"speed {v:g} km/h must be <= {MAX_SPEED_KMH:g} km/h (no sailplane flies "
                      "faster than ~300 km/h)")
        if -w < MIN_SINK_M_S:
            raise bad(f"sink rate {w:g} m/s is too small: it must be <= -{MIN_SINK_M_S:g} m/s "
                      "(the best sailplanes sink ~0.4 m/s at minimum sink)")
    lo, hi = _glide_ratios(pts)
    if hi > MAX_GLIDE_RATIO:
        raise bad(f"the glide ratio reaches {hi:,.0f}: it must be <= {MAX_GLIDE_RATIO:g} (the "
                  "best sailplanes built reach about 70)")
    if lo < MIN_GLIDE_RATIO:
        raise bad(f"the glide ratio falls to {lo:.3g}: it must be >= {MIN_GLIDE_RATIO:g} "
                  "(a wing that sinks faster than it flies)")


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
        tokens, decimal_comma, maybe = _tokens(data.strip())
        hint = DECIMAL_COMMA_HINT if maybe else "{rule}"

        def bad(rule: str, raw: str = raw, hint: str = hint, line_no: int = line_no
                ) -> PolarFileError:
            return PolarFileError(source, line_no, raw, hint.format(rule=rule))

        if len(tokens) < 8:
            raise bad(
                f"the data line needs at least 8 comma-separated numbers (mass, ballast, "
                f"3 x speed, sink), found {len(tokens)}"
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
                raise bad("wing area must be >= 0 (m^2)")
            area = area if area > 0.0 else None
        mass, ballast = vals[0], vals[1]
        if mass <= 0.0:
            raise bad(f"mass must be > 0 kg, got {mass:g}")
        if ballast < 0.0:
            raise bad(f"max ballast must be >= 0 litres, got {ballast:g}")
        speeds, sinks = vals[2::2], vals[3::2]
        if any(v <= 0.0 for v in speeds):
            raise bad("speeds must be > 0 km/h")
        if len(set(speeds)) < 3:
            raise bad("the three speeds must differ")
        if any(w >= 0.0 for w in sinks):
            raise bad("sink rates must be negative (m/s, the .plr convention)")
        # some files list the points out of order (Para_Competition.plr): sort by speed
        pts = sorted((float(v), float(w)) for v, w in zip(speeds, sinks, strict=True))
        _check_ranges(source, line_no, raw, mass, pts, hint)
        ld = _BEST_LD.search(comment)
        return PolarFile(
            source=source,
            name=name,
            mass_kg=mass,
            max_ballast_l=ballast,
            points=tuple(pts),  # type: ignore[arg-type]
            wing_area_m2=area,
            best_ld=float(ld.group(1)) if ld else None,
            comment=comment.strip(),
            line_no=line_no,
            decimal_comma=decimal_comma,
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
