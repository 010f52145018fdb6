"""The common base of all vehicle models: frozen, validated dataclasses."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["Vehicle"]


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
