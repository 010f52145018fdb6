"""Edge-unit conversions the design toolkit needs beyond `glideplan.units` (pounds, feet, degC).

Candidates for `glideplan.units`; kept here so the shared module is not edited in parallel.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["LBF_N", "LB_KG", "celsius_to_kelvin", "feet_to_m", "lb_to_kg", "n_to_lbf"]

LB_KG = 0.45359237  # kg per pound (mass)
LBF_N = 4.4482216152605  # N per pound-force
_FT_M = 0.3048


def lb_to_kg(m_lb: ArrayLike) -> np.ndarray | float:
    """Mass in pounds to kilograms."""
    return np.asarray(m_lb, dtype=float) * LB_KG if np.ndim(m_lb) else float(m_lb) * LB_KG


def n_to_lbf(f_n: ArrayLike) -> np.ndarray | float:
    """Force in newtons to pound-force."""
    return np.asarray(f_n, dtype=float) / LBF_N if np.ndim(f_n) else float(f_n) / LBF_N


def feet_to_m(l_ft: ArrayLike) -> np.ndarray | float:
    """Length in feet to metres."""
    return np.asarray(l_ft, dtype=float) * _FT_M if np.ndim(l_ft) else float(l_ft) * _FT_M


def celsius_to_kelvin(t_c: ArrayLike) -> np.ndarray | float:
    """Temperature in degC to K."""
    return np.asarray(t_c, dtype=float) + 273.15 if np.ndim(t_c) else float(t_c) + 273.15
