"""Degrees and decimal minutes packed as one number (DDMM.MMMM), as Slocum and Seaglider use.

40 deg 22.552' N -> 4022.5520; 73 deg 53.7601' W -> -7353.7601. Rounding the minutes to
`decimals` places can reach 60: that carries into the degrees (59.99995' at 4 decimals is
the next degree, 00.0000').
"""

from __future__ import annotations

import math

from glideplan.errors import InvalidParameterError

__all__ = ["ddmm_to_degrees", "degrees_to_ddmm"]


def degrees_to_ddmm(degrees: float, decimals: int = 4) -> str:
    """`[-]DDDMM.MMMM` text of decimal `degrees` (minutes rounded to `decimals` places)."""
    if not math.isfinite(degrees):
        raise InvalidParameterError("coordinate", degrees, "must be finite degrees")
    sign = "-" if degrees < 0 else ""
    a = abs(degrees)
    d = math.floor(a)
    minutes = f"{(a - d) * 60.0:.{decimals}f}"
    if float(minutes) >= 60.0:  # the carry: 59.99995' -> 60.0000' -> next degree
        d += 1
        minutes = f"{0.0:.{decimals}f}"
    value = d * 100.0 + float(minutes)  # exact to ~1e-12, far below the last decimal
    if value == 0.0:
        sign = ""  # no "-0.0000"
    return f"{sign}{value:.{decimals}f}"


def ddmm_to_degrees(text: str | float) -> float:
    """Decimal degrees of a DDMM.MMMM number; the minutes must be in [0, 60)."""
    try:
        v = float(text)
    except (TypeError, ValueError):
        raise InvalidParameterError("DDMM.MMMM", text, "must be a number") from None
    if not math.isfinite(v):
        raise InvalidParameterError("DDMM.MMMM", text, "must be finite")
    a = abs(v)
    d = math.floor(a / 100.0)
    m = a - 100.0 * d
    if m >= 60.0:
        raise InvalidParameterError("DDMM.MMMM", text, "minutes must be below 60")
    return math.copysign(d + m / 60.0, v)
