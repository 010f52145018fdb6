"""The problem statement shared by the minimum-altitude family solvers (`synthesis.py`,
`chains.py`): the glider's constants, one task (family and orientation, posed with an L first
turn), a solution in the solver's frame, and the tolerances."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.planners.min_altitude.extremals import Kernel
from glideplan.planners.min_altitude.families import Family
from glideplan.pose import Pose, mod_2pi
from glideplan.segments import Segment
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

_MIRROR = str.maketrans("LR", "RL")
_S_MIN = 0.5 * math.pi + 1e-4  # s -> pi/2 is lambda -> infinity (bang-bang speed)
_ROOT_TOL = 1e-11  # position residual accepted from the root finders, in units of R_stf
_ANGLE_TOL = 1e-9


@dataclass(frozen=True)
class _Setup:
    glider: QuadraticPolarGlider
    kern: Kernel
    lam_s: float  # v_stf - v_ms, the BSB multiplier and the lower end of chain multipliers
    scale: float  # R_stf (m)

    @classmethod
    def of(cls, glider: QuadraticPolarGlider) -> _Setup:
        return cls(glider, Kernel.of(glider), glider.v_stf - glider.v_ms, glider.radius_stf)


@dataclass(frozen=True)
class _Found:
    """A solution in the solver's frame: its segments, closed-form cost and parameters."""

    segments: list[Segment]
    cost: float
    info: dict[str, Any]


@dataclass(frozen=True)
class _Task:
    """One orientation of one family, posed with an L first turn (mirrored if needed)."""

    family: Family
    word: str  # the orientation asked for
    reflect: bool  # solved as the mirror image
    goal: Pose  # the goal in the solver's (possibly mirrored) frame
    local_word: str  # the orientation in that frame (first turn L)

    @classmethod
    def of(cls, family: Family, word: str, goal: Pose) -> _Task:
        if word[0] == "R":
            mirrored = Pose(goal.x, -goal.y, -goal.heading)
            return cls(family, word, True, mirrored, word.translate(_MIRROR))
        return cls(family, word, False, goal, word)


def _wrap(angle: np.ndarray | float, low: np.ndarray | float) -> np.ndarray:
    """angle modulo 2 pi, into [low, low + 2 pi)."""
    return np.asarray(mod_2pi(np.asarray(angle) - low)) + low
