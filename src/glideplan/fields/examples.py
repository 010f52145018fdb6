"""Built-in example fields that need no file: the classic time-periodic double gyre.

Double gyre (Shadden, Lekien & Marsden 2005), on x in [0, 2L], y in [0, L]:
    psi = A sin(pi f(x, t)) sin(pi y),  f = eps sin(w t) x^2 + (1 - 2 eps sin(w t)) x,
    u = -pi A sin(pi f) cos(pi y),  v = pi A cos(pi f) sin(pi y) df/dx
in nondimensional units (A = 0.1, eps = 0.25, w = 2 pi / 10). Dimensional: x = X / L,
t = T / Ts with Ts = pi A L / U0 so the largest speed is U0 (m/s). The box is placed with
its south-west corner at (lat0, lon0), x east and y north, metres mapped to degrees by a
local equirectangular scale (R = `geodesy.EARTH_RADIUS_M`) — the field is defined on that
lat/lon box.
"""

from __future__ import annotations

import math

import numpy as np

from glideplan.fields.field import AnalyticField, Extent
from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = ["EARTH_RADIUS_M", "double_gyre"]

EXAMPLE_EPOCH = np.datetime64("2026-01-01T00:00:00", "ns")


def double_gyre(
    length_m: float = 100_000.0,
    max_speed: float = 0.3,
    lat0: float = 30.0,
    lon0: float = -40.0,
    amplitude: float = 0.1,
    eps: float = 0.25,
    omega: float = 2.0 * math.pi / 10.0,
) -> AnalyticField:
    """The time-periodic double gyre on a 2L x L box (module docstring); speeds <= max_speed."""
    ts = math.pi * amplitude * length_m / max_speed  # s per nondimensional time unit
    lat_c = lat0 + math.degrees(0.5 * length_m / EARTH_RADIUS_M)
    m_per_deg_lat = math.radians(1.0) * EARTH_RADIUS_M
    m_per_deg_lon = m_per_deg_lat * math.cos(math.radians(lat_c))
    scale = length_m / ts  # m/s per nondimensional speed

    def fn(t: np.ndarray, lat: np.ndarray, lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = (lon - lon0) * m_per_deg_lon / length_m
        y = (lat - lat0) * m_per_deg_lat / length_m
        s = eps * np.sin(omega * t / ts)
        f = s * x * x + (1.0 - 2.0 * s) * x
        dfdx = 2.0 * s * x + (1.0 - 2.0 * s)
        u = -math.pi * amplitude * np.sin(math.pi * f) * np.cos(math.pi * y)
        v = math.pi * amplitude * np.cos(math.pi * f) * np.sin(math.pi * y) * dfdx
        return u * scale, v * scale

    extent = Extent(lat0, lat0 + length_m / m_per_deg_lat, lon0,
                    lon0 + 2 * length_m / m_per_deg_lon)
    return AnalyticField(
        fn=fn, extent=extent, epoch=EXAMPLE_EPOCH, name="double-gyre",
        extra={"length_m": length_m, "max_speed": max_speed, "period_s": 2 * math.pi / omega * ts},
    )
