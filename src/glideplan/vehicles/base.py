"""The common base of all vehicle models: frozen, validated dataclasses."""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

__all__ = [
    "LENGTH_LIMITS_M",
    "MAX_SPEED_RATIO",
    "SPEED_LIMITS_M_S",
    "TURN_RATE_LIMITS_RAD_S",
    "Vehicle",
    "check_length",
    "check_speed",
    "check_speed_ratio",
    "check_turn_rate",
]

# The supported range of vehicle parameters. Inside it every planner's closed forms and the
# verification by integration agree to better than 1e-6 of the length scale (double precision
# leaves ~1e-16 * (scale ratio) of round-off; at v_max / v_min = 1e6 or R = 1e7 m with a goal
# a few metres away the endpoint errors measured are <= 1e-8 m). Outside it a "solution" can be
# pure round-off (v_max = 1e200 gave an endpoint 1.57 m from a goal 2 m away), so it is refused.
# The ends are physical too: a turn radius from a micrometre to 10,000 km (beyond that the
# plane is not flat), speeds and turn rates from 1e-6 to 1e6 (m/s, rad/s).
SPEED_LIMITS_M_S = (1e-6, 1e6)
TURN_RATE_LIMITS_RAD_S = (1e-6, 1e6)
LENGTH_LIMITS_M = (1e-6, 1e7)
MAX_SPEED_RATIO = 1e6


def _check_range(name: str, value: Any, limits: tuple[float, float], unit: str) -> float:
    from glideplan.errors import InvalidParameterError
    from glideplan.validation import check_positive

    out = check_positive(name, value)
    low, high = limits
    if not low <= out <= high:
        raise InvalidParameterError(
            name, value, f"must lie in [{low:g}, {high:g}] {unit} (the supported range)"
        )
    return out


def check_speed(name: str, value: Any) -> float:
    """A speed (m/s, or nondimensional) inside `SPEED_LIMITS_M_S`."""
    return _check_range(name, value, SPEED_LIMITS_M_S, "m/s")


def check_turn_rate(name: str, value: Any) -> float:
    """A turn rate (rad/s) inside `TURN_RATE_LIMITS_RAD_S`."""
    return _check_range(name, value, TURN_RATE_LIMITS_RAD_S, "rad/s")


def check_length(name: str, value: Any) -> float:
    """A length such as a turn radius (m) inside `LENGTH_LIMITS_M`."""
    return _check_range(name, value, LENGTH_LIMITS_M, "m")


def check_speed_ratio(name_hi: str, hi: float, name_lo: str, lo: float) -> None:
    """Require hi / lo <= `MAX_SPEED_RATIO` (e.g. v_max / v_min)."""
    from glideplan.errors import InvalidParameterError

    if hi > MAX_SPEED_RATIO * lo:
        raise InvalidParameterError(
            name_hi,
            hi,
            f"{name_hi}/{name_lo} = {hi / lo:.3g} must be <= {MAX_SPEED_RATIO:g} "
            "(the supported range)",
        )


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
