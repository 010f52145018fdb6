"""The variable-speed car of chapter 4: speed in [v_min, v_max], turn rate in [-u_max, u_max]."""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

from glideplan.validation import check_less
from glideplan.vehicles.base import (
    Vehicle,
    check_length,
    check_speed,
    check_speed_ratio,
    check_turn_rate,
)

__all__ = ["VariableSpeedCar"]


@dataclass(frozen=True)
class VariableSpeedCar(Vehicle):
    """Kinematic car whose speed is a control (section 4.2, eqs. 4.1-4.5).

    Speeds `v_min` <= v <= `v_max` (m/s, 0 < v_min) and turn rate |u| <= `u_max` (rad/s).
    Bang turns (B) fly at v_max on radius R = v_max/u_max, cornering turns (C) at v_min on
    radius r = v_min/u_max (Table 4.1). With v_min == v_max the car is a Dubins car.

    Supported range (`glideplan.vehicles.base`): speeds in [1e-6, 1e6] m/s with
    v_max / v_min <= 1e6, u_max in [1e-6, 1e6] rad/s, both radii R and r in [1e-6, 1e7] m;
    anything else is refused (at v_max = 1e200 the synthesis is round-off, not a path).
    """

    v_min: float = 0.3
    v_max: float = 1.0
    u_max: float = 1.0

    model: ClassVar[str] = "variable_speed_car"
    default_objective: ClassVar[str] = "time"

    def __post_init__(self) -> None:
        object.__setattr__(self, "v_min", check_speed("v_min", self.v_min))
        object.__setattr__(self, "v_max", check_speed("v_max", self.v_max))
        object.__setattr__(self, "u_max", check_turn_rate("u_max", self.u_max))
        check_less("v_min", self.v_min, "v_max", self.v_max, strict=False)
        check_speed_ratio("v_max", self.v_max, "v_min", self.v_min)
        check_length("v_max/u_max", self.bang_radius)
        check_length("v_min/u_max", self.corner_radius)

    @property
    def bang_radius(self) -> float:
        """R = v_max / u_max (m): radius of B arcs."""
        return self.v_max / self.u_max

    @property
    def corner_radius(self) -> float:
        """r = v_min / u_max (m): radius of C arcs."""
        return self.v_min / self.u_max

    @property
    def speed_ratio(self) -> float:
        """r / R = v_min / v_max (in (0, 1])."""
        return self.v_min / self.v_max

    @property
    def length_scale(self) -> float:
        return self.bang_radius
