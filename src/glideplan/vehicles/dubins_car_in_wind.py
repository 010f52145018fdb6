"""A Dubins car in a known steady uniform wind or current (eq. A.4; Techy & Woolsey 2009)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from glideplan.errors import InvalidParameterError
from glideplan.validation import check_finite, check_nonnegative
from glideplan.vehicles.dubins_car import ConstantSpeedCar

__all__ = ["DubinsCarInWind", "SteadyWind"]


class SteadyWind:
    """Mixin of the vehicles flown in a steady uniform wind of `wind_speed` (m/s) blowing
    TOWARDS `wind_direction` (rad, counter-clockwise from +x); the dataclass declares both."""

    wind_speed: float
    wind_direction: float

    def _check_wind(self, speed_limit: float, rule: str) -> None:
        """Validate the wind fields in place; the wind speed must stay below `speed_limit`."""
        object.__setattr__(self, "wind_speed", check_nonnegative("wind_speed", self.wind_speed))
        object.__setattr__(
            self, "wind_direction", check_finite("wind_direction", self.wind_direction)
        )
        if self.wind_speed >= speed_limit:
            raise InvalidParameterError("wind_speed", self.wind_speed, rule)

    @property
    def wind(self) -> tuple[float, float]:
        """The wind velocity (wx, wy) in m/s (world frame)."""
        return (
            self.wind_speed * math.cos(self.wind_direction),
            self.wind_speed * math.sin(self.wind_direction),
        )


@dataclass(frozen=True)
class DubinsCarInWind(SteadyWind, ConstantSpeedCar):
    """Air- (or water-) relative speed `speed` (m/s), minimum turn radius `turn_radius` (m) in the
    air frame, and a steady uniform wind of `wind_speed` (m/s) blowing towards `wind_direction`
    (rad, counter-clockwise from +x). Kinematics (A.4) with no unknown part:
    x' = v cos psi + w cos psi_w, y' = v sin psi + w sin psi_w, psi' = u, |u| <= v / R0.
    The wind must be slower than the vehicle (w < v).

    Supported range (`glideplan.vehicles.base`): speed in [1e-6, 1e6] m/s, turn radius in
    [1e-6, 1e7] m, u_max = v / R in [1e-6, 1e6] rad/s; anything else is refused.
    """

    wind_speed: float = 0.0
    wind_direction: float = 0.0

    model: ClassVar[str] = "dubins_car_in_wind"
    default_objective: ClassVar[str] = "time"

    def __post_init__(self) -> None:
        super().__post_init__()
        self._check_wind(
            self.speed,
            f"must be < the vehicle's speed {self.speed:g} (else some goals are unreachable)",
        )
