"""A Dubins car in a known steady uniform wind or current (eq. A.4; Techy & Woolsey 2009)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

from glideplan.errors import InvalidParameterError
from glideplan.units import WindEN
from glideplan.validation import check_finite, check_physical
from glideplan.vehicles.dubins_car import ConstantSpeedCar

__all__ = ["DubinsCarInWind", "SteadyWind"]


class SteadyWind:
    """Mixin of the vehicles flown in a steady uniform wind `wind` = (east, north) = (wx, wy)
    m/s, the direction it blows TOWARDS (`glideplan.units.WindEN`, the library's one wind
    value); the dataclass declares the field."""

    wind: WindEN

    def _check_wind(self, speed_limit: float, rule: str) -> None:
        """Validate the wind in place; its speed must stay below `speed_limit`."""
        try:
            wx, wy = self.wind
        except (TypeError, ValueError):
            raise InvalidParameterError(
                "wind", self.wind, "must be an (east, north) pair in m/s"
            ) from None
        w = (check_finite("wind east", wx), check_finite("wind north", wy))
        object.__setattr__(self, "wind", w)
        check_physical("wind", math.hypot(*w), "wind_speed")
        if self.wind_speed >= speed_limit:
            raise InvalidParameterError("wind", self.wind, f"speed {self.wind_speed:g} m/s {rule}")

    @property
    def wind_speed(self) -> float:
        """|wind| (m/s)."""
        return math.hypot(*self.wind)

    def wind_in_frame(self, heading: float) -> WindEN:
        """The wind in a frame rotated by `heading` (rad, CCW): (wx cos h + wy sin h,
        -wx sin h + wy cos h)."""
        c, s = math.cos(heading), math.sin(heading)
        wx, wy = self.wind
        return wx * c + wy * s, -wx * s + wy * c


@dataclass(frozen=True)
class DubinsCarInWind(SteadyWind, ConstantSpeedCar):
    """Air- (or water-) relative speed `speed` (m/s), minimum turn radius `turn_radius` (m) in the
    air frame, and a steady uniform wind `wind` = (wx, wy) (m/s, east and north, blowing
    TOWARDS). Kinematics (A.4) with no unknown part:
    x' = v cos psi + wx, y' = v sin psi + wy, psi' = u, |u| <= v / R0.
    The wind must be slower than the vehicle (|w| < v).

    Supported range (`glideplan.validation.PHYSICAL_RANGES`): "speed", "turn_radius",
    "turn_rate" (u_max = v / R) and "wind_speed"; anything else is refused.
    """

    wind: WindEN = (0.0, 0.0)

    model: ClassVar[str] = "dubins_car_in_wind"
    default_objective: ClassVar[str] = "time"

    def __post_init__(self) -> None:
        super().__post_init__()
        self._check_wind(
            self.speed,
            f"must be < the vehicle's speed {self.speed:g} (else some goals are unreachable)",
        )
