"""Normalised arc geometry for the chapter 4 extremals (R = 1, u_max = 1, v_max = 1).

Lengths are in units of the bang radius R = v_max/u_max and time in units of 1/u_max, so a B
arc has radius 1, a C arc radius rho = v_min/v_max, an S segment moves at unit speed, and the
cost of a path is its total heading change plus its straight length (eq. 4.6 with 4.18-4.19).
Everything here is vectorised over a leading array shape (one entry per value of a family
parameter) and free of Python loops over samples.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

__all__ = [
    "circle_center",
    "compose",
    "compose_one",
    "normal",
    "rotate",
    "tangent",
]


def tangent(h: np.ndarray) -> np.ndarray:
    """Unit vectors (cos h, sin h), shape h.shape + (2,)."""
    h = np.asarray(h, dtype=float)
    out = np.empty((*h.shape, 2))  # filled in place: np.stack costs more than the sines here
    out[..., 0] = np.cos(h)
    out[..., 1] = np.sin(h)
    return out


def normal(h: np.ndarray) -> np.ndarray:
    """Left unit normals (-sin h, cos h), shape h.shape + (2,)."""
    h = np.asarray(h, dtype=float)
    if h.ndim == 0:  # one heading (most calls): math's sin and cos are NumPy's, bit for bit
        v = float(h)
        return np.array([-math.sin(v), math.cos(v)])
    out = np.empty((*h.shape, 2))
    out[..., 0] = -np.sin(h)
    out[..., 1] = np.cos(h)
    return out


def rotate(h: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Rotate vectors v (..., 2) counter-clockwise by angles h (broadcast)."""
    h = np.asarray(h, dtype=float)
    v = np.asarray(v, dtype=float)
    c, s = np.cos(h), np.sin(h)
    return np.stack([c * v[..., 0] - s * v[..., 1], s * v[..., 0] + c * v[..., 1]], axis=-1)


def circle_center(p: np.ndarray, h: np.ndarray, direction: int, radius: float) -> np.ndarray:
    """Centre of the turning circle of `radius` through position p with heading h."""
    return np.asarray(p, dtype=float) + direction * radius * normal(h)


def compose(
    moves: Sequence[tuple[str, int, np.ndarray | float]],
    rho: float,
    shape: tuple[int, ...],
    start: tuple[np.ndarray, np.ndarray] | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """End position (shape + (2,)) and heading of a chain of moves from `start` (default origin).

    A move is (label, direction, amount): label "B" (radius 1) or "C" (radius rho) with the
    heading change `amount` >= 0 turned in `direction` (+1 left, -1 right), or "S" with the
    length `amount` (4.18-4.19 applied arc by arc).
    """
    if start is None:
        p = np.zeros((*shape, 2))
        h = np.zeros(shape)
    else:
        p, h = np.broadcast_to(start[0], (*shape, 2)).copy(), np.broadcast_to(start[1], shape)
    for label, d, amount in moves:
        amount = np.asarray(amount, dtype=float)
        if label == "S":
            p = p + amount[..., None] * tangent(h)
            continue
        radius = 1.0 if label == "B" else rho
        c = p + d * radius * normal(h)
        h = h + d * amount
        p = c - d * radius * normal(h)
    return p, h


def compose_one(moves: Sequence[tuple[str, int, float]], rho: float) -> tuple[float, float, float]:
    """`compose(moves, rho, ())` for one chain of float amounts, in Python floats: (x, y, h).

    The same operations in the same order (arc: centre c = p + d r n(h), h += d x,
    p = c - d r n(h); straight: p += x t(h)).
    """
    px = py = h = 0.0
    for label, d, amount in moves:
        if label == "S":
            px, py = px + amount * math.cos(h), py + amount * math.sin(h)
            continue
        dr = d * (1.0 if label == "B" else rho)
        cx, cy = px + dr * -math.sin(h), py + dr * math.cos(h)
        h = h + d * amount
        px, py = cx - dr * -math.sin(h), cy - dr * math.cos(h)
    return px, py, h
