"""What a vehicle model supplies to the direct-method engine: controls, bounds, rates."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError

__all__ = ["ControlSystem"]


def _no_path_constraints(c: Any) -> list:
    return []


@dataclass(frozen=True)
class ControlSystem:
    """A planar vehicle x' = v cos psi, y' = v sin psi, psi' = u seen through its controls.

    Time is the independent variable. The functions take a CasADi column of the controls
    (named `control_names`, boxed by `lower`/`upper`) and return CasADi expressions:

    - `kinematics(c) -> (speed, turn_rate)` (m/s, rad/s; speed must stay > 0),
    - `cost_rate(c)` the cost per unit time (e.g. 1 for minimum time, the sink rate for
      minimum altitude loss),
    - `path_constraints(c) -> [(expr, lo, hi), ...]` nonlinear control constraints
      (lo/hi numbers, +-inf allowed), imposed at every collocation point,
    - `controls_from(speed, turn_rate) -> (n, m) ndarray` (NumPy) the controls that fly a
      given speed and turn-rate history; used to turn analytic paths into initial guesses
      (None: the controls are (speed, turn_rate) themselves).

    A steady uniform wind or current is not part of the system: pass it to `solve_direct`
    as `drift` (an NLP parameter, so one built transcription serves every wind).
    """

    name: str
    control_names: tuple[str, ...]
    lower: tuple[float, ...]
    upper: tuple[float, ...]
    kinematics: Callable
    cost_rate: Callable
    path_constraints: Callable = _no_path_constraints
    controls_from: Callable | None = None

    def __post_init__(self) -> None:
        m = len(self.control_names)
        object.__setattr__(self, "control_names", tuple(self.control_names))
        lower = tuple(float(v) for v in self.lower)
        upper = tuple(float(v) for v in self.upper)
        if m == 0 or len(lower) != m or len(upper) != m:
            raise InvalidParameterError(
                "lower", self.lower, f"needs one bound per control ({m} controls)"
            )
        for name, lo, hi in zip(self.control_names, lower, upper, strict=True):
            if np.isnan(lo) or np.isnan(hi) or lo > hi:
                raise InvalidParameterError(f"bounds of {name}", (lo, hi), "need lower <= upper")
        object.__setattr__(self, "lower", lower)
        object.__setattr__(self, "upper", upper)

    @property
    def n_controls(self) -> int:
        return len(self.control_names)

    def guess_controls(self, speed: np.ndarray, turn_rate: np.ndarray) -> np.ndarray:
        """Controls (n, m) that fly the given speed and turn-rate samples, clipped to the box."""
        v = np.asarray(speed, dtype=float).reshape(-1)
        u = np.asarray(turn_rate, dtype=float).reshape(-1)
        if self.controls_from is None:
            if self.n_controls != 2:
                raise InvalidParameterError(
                    "controls_from",
                    None,
                    "is needed when the controls are not (speed, turn_rate)",
                )
            c = np.stack([v, u], axis=-1)
        else:
            c = np.asarray(self.controls_from(v, u), dtype=float).reshape(v.size, self.n_controls)
        return np.clip(c, np.array(self.lower), np.array(self.upper))
