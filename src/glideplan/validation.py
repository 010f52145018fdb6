"""Argument checks that raise `InvalidParameterError` naming the parameter and the rule."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError

__all__ = [
    "check_fields",
    "check_finite",
    "check_finite_array",
    "check_in_range",
    "check_integer",
    "check_less",
    "check_nonnegative",
    "check_nonnegative_array",
    "check_positive",
    "check_positive_array",
    "check_probability",
    "scalar_or_array",
]


def _as_float(name: str, value: Any) -> float:
    # A bool or a string is not a number, although float() accepts both (True -> 1.0).
    if isinstance(value, (bool, np.bool_, str, bytes)):
        raise InvalidParameterError(name, value, "must be a real number (not a bool or text)")
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a real number") from None
    return out


def check_finite(name: str, value: Any) -> float:
    """Return `value` as a float; it must be finite (no NaN or infinity)."""
    out = _as_float(name, value)
    if not math.isfinite(out):
        raise InvalidParameterError(name, value, "must be finite (no NaN or infinity)")
    return out


def check_positive(name: str, value: Any) -> float:
    """Return `value` as a float; it must be finite and > 0."""
    out = check_finite(name, value)
    if out <= 0.0:
        raise InvalidParameterError(name, value, "must be > 0")
    return out


def check_nonnegative(name: str, value: Any) -> float:
    """Return `value` as a float; it must be finite and >= 0."""
    out = check_finite(name, value)
    if out < 0.0:
        raise InvalidParameterError(name, value, "must be >= 0")
    return out


def check_in_range(
    name: str,
    value: Any,
    low: float,
    high: float,
    *,
    low_open: bool = False,
    high_open: bool = False,
) -> float:
    """Return `value` as a float inside [low, high] (ends open when asked)."""
    out = check_finite(name, value)
    lo_ok = out > low if low_open else out >= low
    hi_ok = out < high if high_open else out <= high
    if not (lo_ok and hi_ok):
        lb = "(" if low_open else "["
        hb = ")" if high_open else "]"
        raise InvalidParameterError(name, value, f"must lie in {lb}{low:g}, {high:g}{hb}")
    return out


def check_less(name_a: str, a: float, name_b: str, b: float, *, strict: bool = True) -> None:
    """Require a < b (or a <= b when not strict)."""
    ok = a < b if strict else a <= b
    if not ok:
        op = "<" if strict else "<="
        raise InvalidParameterError(name_a, a, f"must be {op} {name_b}={b:g}")


def check_fields(obj: Any, check: Callable[[str, Any], Any], names: Iterable[str]) -> None:
    """Replace each named field of a (frozen) dataclass by `check(name, value)`, in order."""
    for name in names:
        object.__setattr__(obj, name, check(name, getattr(obj, name)))


def check_integer(name: str, value: Any, low: int) -> Any:
    """`value` unchanged when it is a whole number >= `low` (4 and 4.0 pass; 4.5 does not)."""
    if int(value) != value or value < low:
        raise InvalidParameterError(name, value, f"must be an integer >= {low}")
    return value


def check_finite_array(name: str, value: Any, *, last_dim: int | None = None) -> np.ndarray:
    """Return `value` as a float array with only finite entries (and the given last axis size).

    A scalar is a 0-d array; a bool or text (or an array of them) is refused.
    """
    if isinstance(value, (bool, np.bool_, str, bytes)) or (
        isinstance(value, np.ndarray) and value.dtype.kind in "bSUO"
    ):
        raise InvalidParameterError(name, value, "must be a real number or array of them")
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a real number or array of them") from None
    if last_dim is not None and (arr.ndim == 0 or arr.shape[-1] != last_dim):
        raise InvalidParameterError(name, arr.shape, f"last axis must have size {last_dim}")
    if not np.all(np.isfinite(arr)):
        shown = value if arr.ndim == 0 else "array"
        raise InvalidParameterError(name, shown, "must be finite (no NaN or infinity)")
    return arr


def _first_bad(arr: np.ndarray, mask: np.ndarray) -> float:
    return float(arr[mask].flat[0]) if arr.ndim else float(arr)


def check_nonnegative_array(name: str, value: Any) -> np.ndarray:
    """Return `value` as a finite float array with every entry >= 0."""
    arr = check_finite_array(name, value)
    if np.any(arr < 0.0):
        raise InvalidParameterError(name, _first_bad(arr, arr < 0.0), "must be >= 0")
    return arr


def check_positive_array(name: str, value: Any) -> np.ndarray:
    """Return `value` as a finite float array with every entry > 0."""
    arr = check_finite_array(name, value)
    if np.any(arr <= 0.0):
        raise InvalidParameterError(name, _first_bad(arr, arr <= 0.0), "must be > 0")
    return arr


def check_probability(name: str, value: Any) -> float:
    """Return `value` as a float in [0, 1]."""
    arr = check_finite_array(name, value)
    if arr.ndim != 0 or not 0.0 <= float(arr) <= 1.0:
        raise InvalidParameterError(name, value, "must be a probability in [0, 1]")
    return float(arr)


def scalar_or_array(x: np.ndarray) -> np.ndarray | float:
    """Return a Python float for 0-d results, the array otherwise."""
    return float(x) if np.ndim(x) == 0 else x
