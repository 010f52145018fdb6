"""The quadratic glide polar w(v) = a v^2 + b v + c of chapter 5 as pure functions.

One place for the polar's formulas, shared by `QuadraticPolarGlider` (chapter 5) and
`glideplan.sailplane.SailplanePolar` (real polars). SI: v and w in m/s, w positive down.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["best_glide_speed", "min_sink_rate", "min_sink_speed", "quadratic_sink"]


def quadratic_sink(a: float, b: float, c: float, speed: ArrayLike) -> NDArray[np.float64]:
    """Sink rate w(v) = a v^2 + b v + c (m/s) at airspeed v (m/s), eq. (5.4)."""
    v = np.asarray(speed, dtype=float)
    return (a * v + b) * v + c


def min_sink_speed(a: float, b: float) -> float:
    """Minimum-sink speed v_ms = -b / 2a (m/s), where dw/dv = 0."""
    return -b / (2.0 * a)


def min_sink_rate(a: float, b: float, c: float) -> float:
    """Minimum sink rate w(v_ms) = c - b^2 / 4a (m/s)."""
    return c - b * b / (4.0 * a)


def best_glide_speed(a: float, c: float) -> float:
    """Speed to fly in still air v_stf = sqrt(c / a) (m/s): the tangent through the origin."""
    return math.sqrt(c / a)
