"""The problem statement shared by the minimum-altitude family solvers (`synthesis.py`,
`chains.py`): the glider's constants, one task (family and orientation, posed with an L first
turn), a solution in the solver's frame, and the tolerances."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.planners.min_altitude.extremals import (
    Kernel,
    b_arc_pieces,
    b_arc_segments,
    constant_speed_segment,
    straight_segment,
)
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
    """A solution in the solver's frame: its moves, closed-form cost and parameters.

    `moves` are ("B", direction, angle), ("S", 0, length) or ("C", direction, angle) pieces
    from the origin (heading 0); B arcs share `info["lambda"]` and `theta`, C arcs fly at
    `info["speed"]` with label `label`. The segments are built only for the candidates kept
    (`segments`), in the solver's frame or its mirror image."""

    moves: tuple[tuple[str, int, float], ...]
    cost: float
    info: dict[str, Any]
    theta: float = 0.0
    label: str = ""
    keep_empty: bool = False  # a zero-length straight is the path (goal on the start)

    @property
    def letters(self) -> str:
        """The turn word of the moves of positive length (equal neighbours merged)."""
        out = ""
        for kind, direction, amount in self.moves:
            letter = "S" if kind == "S" else ("L" if direction > 0 else "R")
            if amount > 0.0 and not out.endswith(letter):
                out += letter
        return out

    def segments(self, glider: QuadraticPolarGlider, mirror: bool = False) -> list[Segment]:
        """The path's segments from the origin; `mirror`: reflected about the x axis."""
        sign = -1 if mirror else 1
        segs: list[Segment] = []
        pose = Pose()
        for kind, direction, amount in self.moves:
            if kind == "B":
                lam, theta = self.info["lambda"], sign * self.theta
                new = b_arc_segments(pose, sign * direction, amount, lam, theta, glider)
            elif kind == "S":
                new = straight_segment(pose, amount, glider, keep_empty=self.keep_empty)
            else:
                v = self.info["speed"]
                new = constant_speed_segment(pose, sign * direction, amount, v, glider,
                                             self.label)  # fmt: skip
            segs += new
            pose = segs[-1].end if segs else pose
        return segs


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


def _saturated_time(
    phi0: float, direction: int, angle: float, lam: float, glider: QuadraticPolarGlider
) -> float:
    """Time (s) a B arc (`extremals.b_arc_pieces`) spends at a clipped speed."""
    pieces = b_arc_pieces(phi0, direction, angle, lam, glider) if angle > 0.0 else []
    return sum(a1 - a0 for a0, a1, v in pieces if v > 0.0) / glider.u_max


def _wrap(angle: np.ndarray | float, low: np.ndarray | float) -> np.ndarray:
    """angle modulo 2 pi, into [low, low + 2 pi)."""
    return np.asarray(mod_2pi(np.asarray(angle) - low)) + low
