"""Unit conversions used only at the edges (CLI, files, presets); SI is used inside.

Every factor is an exact definition (NIST SP 811): g0 = 9.80665 m/s^2, 1 lb = 0.45359237 kg,
1 lbf = g0 lb, 1 in = 0.0254 m, 1 ft = 0.3048 m, 1 psi = 1 lbf/in^2, 0 degC = 273.15 K. They
are the values of `scipy.constants` (checked in the tests), written here because importing
`scipy.constants` costs a large part of the CLI's start-up time.
"""

from __future__ import annotations

import math
from typing import overload

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "FT_M",
    "G0",
    "INCH_M",
    "LBF_N",
    "LB_KG",
    "PSI_PA",
    "ZERO_CELSIUS_K",
    "celsius_to_kelvin",
    "deg_to_rad",
    "feet_to_m",
    "inch3_to_m3",
    "inch_to_m",
    "kmh_to_ms",
    "lb_to_kg",
    "litre_to_m3",
    "m3_to_litre",
    "ms_to_kmh",
    "n_to_lbf",
    "pa_to_psi",
    "psi_to_pa",
    "rad_to_deg",
    "wind_from_compass",
    "wind_to_compass",
]

#: A steady wind or current inside the library: (east, north) velocity in m/s, the direction
#: it blows TOWARDS. Compass "from" degrees appear only at the edges (CLI, files, explorer,
#: labels), converted by `wind_from_compass` / `wind_to_compass` and nothing else.
WindEN = tuple[float, float]

G0 = 9.80665  # standard gravity, m/s^2
LB_KG = 0.45359237  # kg per pound (mass)
LBF_N = G0 * LB_KG  # N per pound-force
INCH_M = 0.0254  # m per inch
FT_M = 12.0 * INCH_M  # m per foot
PSI_PA = LBF_N / INCH_M**2  # Pa per psi
ZERO_CELSIUS_K = 273.15  # K at 0 degC
_KMH_MS = 1.0 / 3.6  # m/s per km/h


def wind_from_compass(speed_ms: float, from_deg: float, *, param: str = "wind") -> WindEN:
    """(east, north) m/s, blowing TOWARDS, of a wind of `speed_ms` blowing FROM compass `from_deg`.

    A wind from bearing b blows towards b + 180 deg: (u, v) = -speed (sin b, cos b); e.g. from
    270 deg (west) at 10 m/s is (+10, 0). `param` names the input in a refusal (`--wind` on the
    command line); the speed must lie in `PHYSICAL_RANGES["wind_speed"]`, the direction in
    `PHYSICAL_RANGES["heading"]`.
    """
    from glideplan.validation import check_physical

    speed = check_physical(f"{param} speed", speed_ms, "wind_speed")
    b = math.radians(check_physical(f"{param} direction", from_deg, "heading"))
    if speed == 0.0:
        return 0.0, 0.0
    return -speed * math.sin(b), -speed * math.cos(b)


def wind_to_compass(east_ms: float, north_ms: float) -> tuple[float, float]:
    """(speed m/s, compass direction it blows FROM in [0, 360) deg) of an (east, north) wind.

    The inverse of `wind_from_compass`: speed = hypot(u, v), from = atan2(-u, -v) mod 360; a
    calm has direction 0. Both are rounded (speed to 1e-12 m/s, direction to 1e-9 deg) so that
    a compass wind given at an edge reads back as given.
    """
    u, v = float(east_ms), float(north_ms)
    speed = math.hypot(u, v)
    if speed == 0.0:
        return 0.0, 0.0
    b = round(math.degrees(math.atan2(-u, -v)) % 360.0, 9) % 360.0
    return round(speed, 12), b


def _scaled(x: ArrayLike, factor: float, offset: float = 0.0) -> np.ndarray | float:
    """x * factor + offset: a float for a scalar, an array otherwise."""
    if np.ndim(x):
        return np.asarray(x, dtype=float) * factor + offset
    return float(x) * factor + offset  # type: ignore[arg-type]


@overload
def kmh_to_ms(v_kmh: float) -> float: ...
@overload
def kmh_to_ms(v_kmh: ArrayLike) -> np.ndarray | float: ...
def kmh_to_ms(v_kmh: ArrayLike) -> np.ndarray | float:
    """Speed in km/h to m/s."""
    return _scaled(v_kmh, _KMH_MS)


@overload
def ms_to_kmh(v_ms: float) -> float: ...
@overload
def ms_to_kmh(v_ms: ArrayLike) -> np.ndarray | float: ...
def ms_to_kmh(v_ms: ArrayLike) -> np.ndarray | float:
    """Speed in m/s to km/h."""
    return _scaled(v_ms, 3.6)


@overload
def deg_to_rad(a_deg: float) -> float: ...
@overload
def deg_to_rad(a_deg: ArrayLike) -> np.ndarray | float: ...
def deg_to_rad(a_deg: ArrayLike) -> np.ndarray | float:
    """Angle in degrees to radians."""
    return np.deg2rad(a_deg) if np.ndim(a_deg) else math.radians(float(a_deg))  # type: ignore[arg-type]


@overload
def rad_to_deg(a_rad: float) -> float: ...
@overload
def rad_to_deg(a_rad: ArrayLike) -> np.ndarray | float: ...
def rad_to_deg(a_rad: ArrayLike) -> np.ndarray | float:
    """Angle in radians to degrees."""
    return np.rad2deg(a_rad) if np.ndim(a_rad) else math.degrees(float(a_rad))  # type: ignore[arg-type]


@overload
def psi_to_pa(p_psi: float) -> float: ...
@overload
def psi_to_pa(p_psi: ArrayLike) -> np.ndarray | float: ...
def psi_to_pa(p_psi: ArrayLike) -> np.ndarray | float:
    """Pressure in psi to pascal."""
    return _scaled(p_psi, PSI_PA)


@overload
def pa_to_psi(p_pa: float) -> float: ...
@overload
def pa_to_psi(p_pa: ArrayLike) -> np.ndarray | float: ...
def pa_to_psi(p_pa: ArrayLike) -> np.ndarray | float:
    """Pressure in pascal to psi."""
    return _scaled(p_pa, 1.0 / PSI_PA)


@overload
def litre_to_m3(v_l: float) -> float: ...
@overload
def litre_to_m3(v_l: ArrayLike) -> np.ndarray | float: ...
def litre_to_m3(v_l: ArrayLike) -> np.ndarray | float:
    """Volume in litres to cubic metres."""
    return _scaled(v_l, 1e-3)


@overload
def m3_to_litre(v_m3: float) -> float: ...
@overload
def m3_to_litre(v_m3: ArrayLike) -> np.ndarray | float: ...
def m3_to_litre(v_m3: ArrayLike) -> np.ndarray | float:
    """Volume in cubic metres to litres."""
    return _scaled(v_m3, 1e3)


@overload
def inch_to_m(l_in: float) -> float: ...
@overload
def inch_to_m(l_in: ArrayLike) -> np.ndarray | float: ...
def inch_to_m(l_in: ArrayLike) -> np.ndarray | float:
    """Length in inches to metres."""
    return _scaled(l_in, INCH_M)


@overload
def inch3_to_m3(v_in3: float) -> float: ...
@overload
def inch3_to_m3(v_in3: ArrayLike) -> np.ndarray | float: ...
def inch3_to_m3(v_in3: ArrayLike) -> np.ndarray | float:
    """Volume in cubic inches to cubic metres."""
    return _scaled(v_in3, INCH_M**3)


@overload
def feet_to_m(l_ft: float) -> float: ...
@overload
def feet_to_m(l_ft: ArrayLike) -> np.ndarray | float: ...
def feet_to_m(l_ft: ArrayLike) -> np.ndarray | float:
    """Length in feet to metres."""
    return _scaled(l_ft, FT_M)


@overload
def lb_to_kg(m_lb: float) -> float: ...
@overload
def lb_to_kg(m_lb: ArrayLike) -> np.ndarray | float: ...
def lb_to_kg(m_lb: ArrayLike) -> np.ndarray | float:
    """Mass in pounds to kilograms."""
    return _scaled(m_lb, LB_KG)


@overload
def n_to_lbf(f_n: float) -> float: ...
@overload
def n_to_lbf(f_n: ArrayLike) -> np.ndarray | float: ...
def n_to_lbf(f_n: ArrayLike) -> np.ndarray | float:
    """Force in newtons to pound-force."""
    return _scaled(f_n, 1.0 / LBF_N)


@overload
def celsius_to_kelvin(t_c: float) -> float: ...
@overload
def celsius_to_kelvin(t_c: ArrayLike) -> np.ndarray | float: ...
def celsius_to_kelvin(t_c: ArrayLike) -> np.ndarray | float:
    """Temperature in degC to K."""
    return _scaled(t_c, 1.0, ZERO_CELSIUS_K)
