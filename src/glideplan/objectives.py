"""Named objectives as integrands of the controls: J = integral of rate(speed, turn_rate) dt.

"length" (eq. 2.3 with unit speed), "time" (eq. 4.6), "altitude" (altitude loss, eq. 5.4 /
6.12: the vehicle's sink rate). Adding an objective adds an entry here.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.vehicles.base import Vehicle

__all__ = ["OBJECTIVES", "Objective", "get_objective"]


@dataclass(frozen=True)
class Objective:
    """A cost functional: its name, unit and integrand rate(vehicle)(speed, turn_rate)."""

    name: str
    unit: str
    description: str
    rate_for: Callable[[Vehicle | None], Callable[[np.ndarray, np.ndarray], np.ndarray]]


def _length_rate(vehicle: Vehicle | None) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    return lambda v, u: v


def _time_rate(vehicle: Vehicle | None) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    return lambda v, u: np.ones_like(v)


def _altitude_rate(vehicle: Vehicle | None) -> Callable[[np.ndarray, np.ndarray], np.ndarray]:
    if vehicle is None:
        raise InvalidParameterError(
            "objective", "altitude", "needs a path that carries its vehicle (sink-rate model)"
        )
    return vehicle.sink_rate


OBJECTIVES: dict[str, Objective] = {
    "length": Objective("length", "m", "path length", _length_rate),
    "time": Objective("time", "s", "flight time", _time_rate),
    "altitude": Objective("altitude", "m", "altitude loss", _altitude_rate),
}


def get_objective(name: str) -> Objective:
    """The objective called `name`; an unknown name is an error listing the known ones."""
    try:
        return OBJECTIVES[name]
    except KeyError:
        known = ", ".join(sorted(OBJECTIVES))
        raise InvalidParameterError("objective", name, f"must be one of {known}") from None
