"""Argument checks that raise `InvalidParameterError` naming the parameter and the rule."""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError

__all__ = [
    "PHYSICAL_RANGES",
    "PhysicalRange",
    "check_fields",
    "check_finite",
    "check_finite_array",
    "check_in_range",
    "check_integer",
    "check_less",
    "check_nonnegative",
    "check_nonnegative_array",
    "check_physical",
    "check_physical_array",
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
    if type(value) is float and math.isfinite(value):  # the common case, without the checks
        return value
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


@dataclass(frozen=True)
class PhysicalRange:
    """The values a physical input may take: [low, high] in `unit` (an end is open when asked),
    and why (`reason`, shown with every refusal)."""

    low: float
    high: float
    unit: str
    reason: str
    low_open: bool = False

    def rule(self) -> str:
        """`must lie in (0, 343] m/s (reason)`: the refusal's text."""
        lb = "(" if self.low_open else "["
        unit = f" {self.unit}" if self.unit else ""
        return f"must lie in {lb}{self.low:g}, {self.high:g}]{unit} ({self.reason})"

    def contains(self, value: float) -> bool:
        lo_ok = value > self.low if self.low_open else value >= self.low
        return lo_ok and value <= self.high


# The ONE table of physical ranges that every command checks its numeric inputs against
# (`check_physical`): wide enough for every vehicle the package models (underwater gliders at
# 0.3 m/s to sailplanes and soaring UAVs), narrow enough that a typo or an overflow (1e300)
# is refused up front instead of planned. Documented in the README ("Input ranges").
PHYSICAL_RANGES: Mapping[str, PhysicalRange] = {
    # ---- positions, headings, heights (the edges: degrees and metres) -------------------
    "altitude": PhysicalRange(
        -500.0, 20_000.0, "m", "Dead Sea shore to above any glider's or sailplane's ceiling"
    ),
    "elevation": PhysicalRange(-500.0, 9_000.0, "m", "ground elevation: Dead Sea to Everest"),
    "height": PhysicalRange(0.0, 5_000.0, "m", "a safety or arrival height above the ground"),
    "heading": PhysicalRange(
        -3600.0, 3600.0, "deg", "a heading or compass bearing, up to ten turns either way"
    ),
    "depth": PhysicalRange(0.0, 11_000.0, "m", "sea surface to the deepest ocean trench"),
    # ---- speeds and rates ----------------------------------------------------------------
    "speed": PhysicalRange(
        0.0, 343.0, "m/s", "speed through the water or air: below the speed of sound",
        low_open=True,
    ),
    "wind_speed": PhysicalRange(0.0, 150.0, "m/s", "no wind or current on Earth is faster"),
    "water_speed": PhysicalRange(
        0.0, 20.0, "m/s",
        "a vehicle's speed through water: 40 knots; faster (up to 343 m/s) is an air vehicle",
        low_open=True,
    ),
    "current_speed": PhysicalRange(
        0.0, 10.0, "m/s",
        "an ocean current: the fastest tidal races reach about 10 m/s, the Gulf Stream 2.5",
    ),
    "mc": PhysicalRange(
        0.0, 10.0, "m/s", "MacCready setting: the expected climb rate, no thermal climbs faster"
    ),
    "turn_radius": PhysicalRange(
        1e-6, 100_000.0, "m",
        "a turn wider than 100 km is not a turn; below a micrometre it is round-off",
    ),
    "turn_rate": PhysicalRange(
        1e-6, 1e6, "rad/s", "the planners' closed forms hold to 1e-6 of the length scale here"
    ),
    "speed_ratio": PhysicalRange(
        1.0, 1e6, "", "a top speed at most a million times the lowest (else round-off)"
    ),
    "distance": PhysicalRange(
        0.0, 100_000.0, "m", "a distance or tolerance up to 100 km",
        low_open=True,
    ),
    "clearance": PhysicalRange(
        0.0, 100_000.0, "m",
        "a clearance wider than 100 km leaves no coastal water to route through",
    ),
    "duration": PhysicalRange(
        0.0, 366 * 86_400.0, "s", "a route or mission of up to a year", low_open=True
    ),
    "bank": PhysicalRange(0.0, 80.0, "deg", "a bank angle a sailplane can hold", low_open=True),
    # ---- the environment and the vehicle (chapter 7 design parameters, SI) ---------------
    "gravity": PhysicalRange(
        0.1, 100.0, "m/s^2", "surface gravity, from small moons to ten times the Earth's"
    ),
    "water_density": PhysicalRange(
        500.0, 2_000.0, "kg/m^3", "a liquid a glider can swim in (fresh water 1000)"
    ),
    "pressure": PhysicalRange(
        0.0, 1e9, "Pa", "an absolute pressure up to 1 GPa; gas cylinders hold less than 0.1 GPa",
        low_open=True,
    ),
    "pressure_coefficient": PhysicalRange(
        -1e8, 1e8, "Pa", "a bladder elastic coefficient of at most 100 MPa in size"
    ),
    "temperature": PhysicalRange(
        150.0, 500.0, "K", "the temperature of the gas in a working tank or the water"
    ),
    "volume": PhysicalRange(0.0, 100.0, "m^3", "a tank, bladder or hull volume", low_open=True),
    "mass": PhysicalRange(0.0, 100_000.0, "kg", "a vehicle or part up to 100 t", low_open=True),
    "mass_ratio": PhysicalRange(
        0.5, 2.0, "",
        "a polar scales by sqrt(m / m_ref) only near the wing loading it was measured at; "
        "water ballast at most doubles it",
    ),
    "length": PhysicalRange(0.0, 1_000.0, "m", "a vehicle dimension", low_open=True),
    "station": PhysicalRange(-1_000.0, 1_000.0, "m", "a position along the vehicle"),
    "area": PhysicalRange(0.0, 10_000.0, "m^2", "a wing or reference area", low_open=True),
    "coefficient": PhysicalRange(
        0.0, 1_000.0, "", "a dimensionless aerodynamic or hydrodynamic coefficient",
        low_open=True,
    ),
    "position": PhysicalRange(-1e7, 1e7, "m", "a position within 10,000 km of the origin"),
    "sound_speed": PhysicalRange(
        1_000.0, 2_000.0, "m/s", "the speed of sound in water (about 1480)"
    ),
}


def check_physical(name: str, value: Any, kind: str) -> float:
    """Return `value` as a float inside `PHYSICAL_RANGES[kind]`, else refuse it naming `name`.

    `name` is what the caller's user typed or reads (`mc` in the library, `--mc` on the
    command line); the rule gives the range, its unit and its reason.
    """
    out = check_finite(name, value)
    limits = PHYSICAL_RANGES[kind]
    if not limits.contains(out):
        raise InvalidParameterError(name, value, limits.rule())
    return out


def check_physical_array(name: str, value: Any, kind: str) -> np.ndarray:
    """Return `value` as a finite float array with every entry inside `PHYSICAL_RANGES[kind]`."""
    arr = check_finite_array(name, value)
    limits = PHYSICAL_RANGES[kind]
    lo_bad = arr <= limits.low if limits.low_open else arr < limits.low
    bad = lo_bad | (arr > limits.high)
    if np.any(bad):
        raise InvalidParameterError(name, _first_bad(arr, bad), limits.rule())
    return arr
