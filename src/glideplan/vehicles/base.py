"""The common base of all vehicle models: frozen, validated dataclasses."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "Vehicle",
    "check_length",
    "check_speed",
    "check_speed_ratio",
    "check_turn_rate",
]

# The supported ranges of vehicle parameters are rows of the one range table,
# `glideplan.validation.PHYSICAL_RANGES` ("speed", "turn_radius", "turn_rate", "speed_ratio"):
# inside them every planner's closed forms and the verification by integration agree to better
# than 1e-6 of the length scale; outside them a "solution" can be pure round-off (v_max = 1e200
# gave an endpoint 1.57 m from a goal 2 m away), so they are refused. The functions below only
# name the row each vehicle field is checked against.


def check_speed(name: str, value: Any) -> float:
    """A speed (m/s) inside `PHYSICAL_RANGES["speed"]`."""
    from glideplan.validation import check_physical

    return check_physical(name, value, "speed")


def check_turn_rate(name: str, value: Any) -> float:
    """A turn rate (rad/s) inside `PHYSICAL_RANGES["turn_rate"]`."""
    from glideplan.validation import check_physical

    return check_physical(name, value, "turn_rate")


def check_length(name: str, value: Any) -> float:
    """A turn radius (m) inside `PHYSICAL_RANGES["turn_radius"]`."""
    from glideplan.validation import check_physical

    return check_physical(name, value, "turn_radius")


def check_speed_ratio(name_hi: str, hi: float, name_lo: str, lo: float) -> None:
    """Require hi / lo inside `PHYSICAL_RANGES["speed_ratio"]` (e.g. v_max / v_min)."""
    from glideplan.validation import check_physical

    check_physical(f"{name_hi}/{name_lo}", hi / lo, "speed_ratio")


@dataclass(frozen=True)
class Vehicle:
    """A vehicle model: its kinematics are x' = v cos psi, y' = v sin psi, psi' = u.

    Subclasses set `model` (a short name used in JSON and the planner registry) and
    `default_objective`, validate their fields in `__post_init__`, and implement
    `sink_rate` when altitude loss is a meaningful cost.
    """

    model: ClassVar[str] = "vehicle"
    default_objective: ClassVar[str] = "length"

    def sink_rate(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """Altitude-loss rate (m/s, positive down) at speed (m/s) and turn rate (rad/s)."""
        from glideplan.errors import InvalidParameterError

        raise InvalidParameterError(
            "objective", "altitude", f"vehicle model {self.model!r} has no sink-rate model"
        )

    @property
    def length_scale(self) -> float:
        """A characteristic length (m) used for relative tolerances (e.g. a turn radius)."""
        return 1.0

    def to_dict(self) -> dict[str, Any]:
        """Fields and model name, for JSON output."""
        return {"model": self.model, **asdict(self)}
