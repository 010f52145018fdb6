"""A sailplane with a real (quadratic) polar, a bank-angle limit and a steady wind.

Kinematics over ground (eq. A.4 with a known wind): x' = V cos psi + wx, y' = V sin psi + wy,
psi' = u with airspeed V and air heading psi. The controls are airspeed V and bank phi:
u = g tan(phi) / V, |phi| <= bank_max, and V in [v_min sqrt(n), v_max] (the stall speed
rises with the load factor n = 1 / cos phi). The altitude lost per second is the turning
polar w_phi(V) = n^{3/2} w(V / sqrt n) (`SailplanePolar.sink_turning`).

`turning_polar=False` gives chapter 5's small-bank model instead: the sink rate w(V) does not
depend on the turn and the stall speed does not rise, and `turn_rate_max` (rad/s) bounds the
turn rate as u_max does there — with both, the vehicle is the chapter 5 glider (used to check
the planner against `plan min-altitude`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.units import WindEN
from glideplan.validation import check_positive
from glideplan.vehicles.base import Vehicle
from glideplan.vehicles.dubins_car_in_wind import SteadyWind
from glideplan.vehicles.sailplane_polar import GRAVITY, SailplanePolar

__all__ = ["Sailplane", "dg1001m_sailplane"]


@dataclass(frozen=True)
class Sailplane(SteadyWind, Vehicle):
    """A sailplane: `polar` (SI), `bank_max` (rad, in (0, 80 deg]), a steady wind `wind` =
    (east, north) m/s blowing TOWARDS (`glideplan.units.WindEN`, as `DubinsCarInWind`),
    optional `turn_rate_max` (rad/s) and `turning_polar`.
    """

    polar: SailplanePolar
    bank_max: float = math.radians(45.0)
    wind: WindEN = (0.0, 0.0)
    turn_rate_max: float | None = None
    turning_polar: bool = True

    model: ClassVar[str] = "sailplane"
    default_objective: ClassVar[str] = "altitude"

    def __post_init__(self) -> None:
        if not isinstance(self.polar, SailplanePolar):
            raise InvalidParameterError("polar", self.polar, "must be a SailplanePolar")
        bank = check_positive("bank_max", self.bank_max)
        if bank > math.radians(80.0):
            raise InvalidParameterError(
                "bank_max", math.degrees(bank), "must be <= 80 degrees (load factor <= 5.8)"
            )
        object.__setattr__(self, "bank_max", bank)
        if self.turn_rate_max is not None:
            object.__setattr__(
                self, "turn_rate_max", check_positive("turn_rate_max", self.turn_rate_max)
            )
        self._check_wind(
            self.polar.v_max, f"must be < the polar's top speed {self.polar.v_max:.4g} m/s"
        )

    @property
    def v_min(self) -> float:
        """Lowest airspeed in level flight (m/s)."""
        return self.polar.v_min

    @property
    def v_max(self) -> float:
        return self.polar.v_max

    def bank_for(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """Bank angle (rad) that turns at `turn_rate` at airspeed `speed`: atan(u V / g)."""
        return np.arctan(
            np.asarray(turn_rate, dtype=float) * np.asarray(speed, dtype=float) / GRAVITY
        )

    def sink_rate(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """Altitude-loss rate (m/s): the turning polar at bank atan(u V / g), or w(V)."""
        if not self.turning_polar:
            return self.polar.sink(speed) + 0.0 * np.asarray(turn_rate, dtype=float)
        return self.polar.sink_at_turn_rate(speed, turn_rate)

    def max_turn_rate(self, speed: ArrayLike) -> np.ndarray:
        """Largest turn rate (rad/s) at airspeed V: g tan(bank_max) / V (and turn_rate_max)."""
        u = GRAVITY * math.tan(self.bank_max) / np.asarray(speed, dtype=float)
        return np.minimum(u, self.turn_rate_max) if self.turn_rate_max is not None else u

    @property
    def length_scale(self) -> float:
        """Turn radius at the best-glide speed and the bank limit (m)."""
        v = self.polar.v_best_glide
        return float(v / self.max_turn_rate(v))

    def to_dict(self) -> dict[str, Any]:
        return {
            "model": self.model,
            "polar": self.polar.to_dict(),
            "bank_max": self.bank_max,
            "wind": list(self.wind),
            "turn_rate_max": self.turn_rate_max,
            "turning_polar": self.turning_polar,
        }


def dg1001m_sailplane(wind: WindEN = (0.0, 0.0)) -> Sailplane:
    """The DG-1001M of section 5.9 (eq. 5.26 in SI, 750 kg, 75.6–160 km/h) as a `Sailplane`.

    w = a V^2 + b V + c with a = 2.093e-4 / (km/h)^2, b = -0.0381 / (km/h), c = 2.3146 m/s;
    the wind `wind` = (east, north) m/s blows TOWARDS.
    """
    kmh = 1.0 / 3.6
    polar = SailplanePolar(
        a=0.0002093 / kmh**2,
        b=-0.0381 / kmh,
        c=2.3146,
        v_min=75.6 * kmh,
        v_max=160.0 * kmh,
        mass_kg=750.0,
        reference_mass_kg=750.0,
        name="DG-1001M (section 5.9)",
    )
    return Sailplane(polar, wind=wind)
