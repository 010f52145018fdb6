"""The fixed-speed Dubins car (dissertation 2.7, eq. 3.1)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from glideplan.validation import check_positive
from glideplan.vehicles.base import Vehicle

__all__ = ["DubinsCar"]


@dataclass(frozen=True)
class DubinsCar(Vehicle):
    """Constant speed `speed` (m/s) and minimum turn radius `turn_radius` (m); u_max = v / R."""

    speed: float = 1.0
    turn_radius: float = 1.0

    model: ClassVar[str] = "dubins_car"
    default_objective: ClassVar[str] = "length"

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", check_positive("speed", self.speed))
        object.__setattr__(self, "turn_radius", check_positive("turn_radius", self.turn_radius))

    @property
    def max_turn_rate(self) -> float:
        """u_max = v / R0 (rad/s)."""
        return self.speed / self.turn_radius

    @property
    def length_scale(self) -> float:
        return self.turn_radius
