"""Unit conversions used only at the edges (CLI, files, presets); SI is used inside."""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "G0",
    "deg_to_rad",
    "inch3_to_m3",
    "inch_to_m",
    "kmh_to_ms",
    "litre_to_m3",
    "m3_to_litre",
    "ms_to_kmh",
    "pa_to_psi",
    "psi_to_pa",
    "rad_to_deg",
]

G0 = 9.80665  # standard gravity, m/s^2
_PSI = 6894.757293168361  # Pa per psi
_INCH = 0.0254  # m per inch


def kmh_to_ms(v_kmh: ArrayLike) -> np.ndarray | float:
    """Speed in km/h to m/s."""
    return np.asarray(v_kmh, dtype=float) / 3.6 if np.ndim(v_kmh) else float(v_kmh) / 3.6


def ms_to_kmh(v_ms: ArrayLike) -> np.ndarray | float:
    """Speed in m/s to km/h."""
    return np.asarray(v_ms, dtype=float) * 3.6 if np.ndim(v_ms) else float(v_ms) * 3.6


def deg_to_rad(a_deg: ArrayLike) -> np.ndarray | float:
    """Angle in degrees to radians."""
    return np.deg2rad(a_deg) if np.ndim(a_deg) else math.radians(float(a_deg))


def rad_to_deg(a_rad: ArrayLike) -> np.ndarray | float:
    """Angle in radians to degrees."""
    return np.rad2deg(a_rad) if np.ndim(a_rad) else math.degrees(float(a_rad))


def psi_to_pa(p_psi: ArrayLike) -> np.ndarray | float:
    """Pressure in psi to pascal."""
    return np.asarray(p_psi, dtype=float) * _PSI if np.ndim(p_psi) else float(p_psi) * _PSI


def pa_to_psi(p_pa: ArrayLike) -> np.ndarray | float:
    """Pressure in pascal to psi."""
    return np.asarray(p_pa, dtype=float) / _PSI if np.ndim(p_pa) else float(p_pa) / _PSI


def litre_to_m3(v_l: ArrayLike) -> np.ndarray | float:
    """Volume in litres to cubic metres."""
    return np.asarray(v_l, dtype=float) * 1e-3 if np.ndim(v_l) else float(v_l) * 1e-3


def m3_to_litre(v_m3: ArrayLike) -> np.ndarray | float:
    """Volume in cubic metres to litres."""
    return np.asarray(v_m3, dtype=float) * 1e3 if np.ndim(v_m3) else float(v_m3) * 1e3


def inch_to_m(l_in: ArrayLike) -> np.ndarray | float:
    """Length in inches to metres."""
    return np.asarray(l_in, dtype=float) * _INCH if np.ndim(l_in) else float(l_in) * _INCH


def inch3_to_m3(v_in3: ArrayLike) -> np.ndarray | float:
    """Volume in cubic inches to cubic metres."""
    k = _INCH**3
    return np.asarray(v_in3, dtype=float) * k if np.ndim(v_in3) else float(v_in3) * k
