"""The fixed-speed Dubins car (dissertation 2.7, eq. 3.1)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from glideplan.vehicles.base import Vehicle, check_length, check_speed, check_turn_rate

__all__ = ["ConstantSpeedCar", "DubinsCar"]


@dataclass(frozen=True)
class ConstantSpeedCar(Vehicle):
    """Shared part of the Dubins cars: speed `speed` (m/s), minimum turn radius `turn_radius` (m).

    Supported range (`glideplan.vehicles.base`): speed in [1e-6, 1e6] m/s, turn radius in
    [1e-6, 1e7] m, u_max = v / R in [1e-6, 1e6] rad/s; anything else is refused.
    """

    speed: float = 1.0
    turn_radius: float = 1.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", check_speed("speed", self.speed))
        object.__setattr__(self, "turn_radius", check_length("turn_radius", self.turn_radius))
        check_turn_rate("speed/turn_radius", self.speed / self.turn_radius)

    @property
    def max_turn_rate(self) -> float:
        """u_max = v / R0 (rad/s)."""
        return self.speed / self.turn_radius

    @property
    def length_scale(self) -> float:
        return self.turn_radius


@dataclass(frozen=True)
class DubinsCar(ConstantSpeedCar):
    """Constant speed `speed` (m/s) and minimum turn radius `turn_radius` (m); u_max = v / R.

    Supported range (`glideplan.vehicles.base`): speed in [1e-6, 1e6] m/s, turn radius in
    [1e-6, 1e7] m, u_max = v / R in [1e-6, 1e6] rad/s; anything else is refused.
    """

    model: ClassVar[str] = "dubins_car"
    default_objective: ClassVar[str] = "length"
