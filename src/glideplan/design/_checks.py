"""Array argument checks for the design toolkit; errors name the argument."""

from __future__ import annotations

from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError

__all__ = [
    "finite_array",
    "nonnegative_array",
    "positive_array",
    "probability",
    "scalar_or_array",
]


def finite_array(name: str, value: Any) -> np.ndarray:
    """Return `value` as a float array whose entries are all finite."""
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a real number or array of them") from None
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(name, value, "must be finite (no NaN or infinity)")
    return arr


def nonnegative_array(name: str, value: Any) -> np.ndarray:
    """Return `value` as a finite float array with every entry >= 0."""
    arr = finite_array(name, value)
    if np.any(arr < 0.0):
        raise InvalidParameterError(name, _first_bad(arr, arr < 0.0), "must be >= 0")
    return arr


def positive_array(name: str, value: Any) -> np.ndarray:
    """Return `value` as a finite float array with every entry > 0."""
    arr = finite_array(name, value)
    if np.any(arr <= 0.0):
        raise InvalidParameterError(name, _first_bad(arr, arr <= 0.0), "must be > 0")
    return arr


def probability(name: str, value: Any) -> float:
    """Return `value` as a float in [0, 1]."""
    arr = finite_array(name, value)
    if arr.ndim != 0 or not 0.0 <= float(arr) <= 1.0:
        raise InvalidParameterError(name, value, "must be a probability in [0, 1]")
    return float(arr)


def _first_bad(arr: np.ndarray, mask: np.ndarray) -> float:
    return float(arr[mask].flat[0]) if arr.ndim else float(arr)


def scalar_or_array(x: np.ndarray) -> np.ndarray | float:
    """Return a Python float for 0-d results, the array otherwise."""
    return float(x) if np.ndim(x) == 0 else x
