"""The segment protocol: what every piece of path provides (see docs/ARCHITECTURE.md).

A segment is flown under one control law; times `t` are local to the segment, in
[0, duration]. Subclasses integrate the planar kinematics x' = v cos psi + wx,
y' = v sin psi + wy, psi' = u (dissertation eqs. 2.1, 4.1, 5.1-5.3, A.4) for their control law.
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.pose import Pose

__all__ = ["RateFunction", "Segment", "direction_letter"]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)

RateFunction = Callable[[np.ndarray, np.ndarray], np.ndarray]


def direction_letter(direction: int) -> str:
    """'L' for +1 (counter-clockwise), 'R' for -1, 'S' for 0."""
    return {1: "L", -1: "R", 0: "S"}[int(direction)]


def _check_direction(direction: Any) -> int:
    if direction not in (1, -1):
        raise InvalidParameterError("direction", direction, "must be +1 (left) or -1 (right)")
    return int(direction)


def _map_pose(start: Pose, frame: Pose, reflect: bool) -> Pose:
    """`start` given in `frame` mapped to the world: `pose.to_world` for one pose, in floats."""
    y, h = (-start.y, -start.heading) if reflect else (start.y, start.heading)
    c, s = math.cos(frame.heading), math.sin(frame.heading)
    return Pose(frame.x + c * start.x - s * y, frame.y + s * start.x + c * y, h + frame.heading)


class Segment(ABC):
    """A piece of path flown under one control law (see module docstring)."""

    kind: ClassVar[str] = "segment"
    # True when speed and turn rate do not change along the segment (verification uses it to
    # evaluate them once; it checks the claim at the start, middle and end)
    constant_controls: ClassVar[bool] = False
    # True when speed and turn rate are linear between consecutive `breakpoints()` (node
    # arrays of a direct method): verification integrates each interval by quadrature
    piecewise_linear_controls: ClassVar[bool] = False

    start: Pose
    label: str
    # steady uniform wind or current (wx, wy) in m/s carried along with the segment: the
    # ground velocity is the air-relative one plus drift (eq. A.4); none for most segments
    drift: tuple[float, float] = (0.0, 0.0)

    @property
    @abstractmethod
    def length(self) -> float:
        """Arc length flown (m)."""

    @property
    @abstractmethod
    def duration(self) -> float:
        """Time taken (s)."""

    direction: int  # +1 left, -1 right, 0 straight or mixed (a field or property of subclasses)

    @abstractmethod
    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Positions x, y (m) and heading (rad) at local times t (s)."""

    @abstractmethod
    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Speed (m/s) and turn rate (rad/s) at local times t (s)."""

    @abstractmethod
    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        """Local time (s) at which local arc length s (m) is reached."""

    @abstractmethod
    def transformed(self, frame: Pose, reflect: bool = False) -> Segment:
        """The segment mapped by reflection about the x-axis (optional), rotation, translation."""

    def breakpoints(self) -> np.ndarray:
        """Local times bounding the pieces on which the controls are smooth."""
        return np.array([0.0, self.duration])

    @property
    def end(self) -> Pose:
        """The pose at the end of the segment."""
        x, y, h = self.states(np.array([self.duration]))
        return Pose(float(x[0]), float(y[0]), float(h[0]))

    @property
    def letter(self) -> str:
        """Turn-direction letter: L, R or S."""
        return direction_letter(self.direction)

    def turn_word(self) -> str:
        """Turn-direction letters flown along the segment (one letter unless sampled)."""
        return self.letter

    def integrate_rate(self, rate: RateFunction, t: ArrayLike | None = None) -> np.ndarray:
        """Integral over [0, t] of rate(speed, turn_rate) (composite Gauss-Legendre, 24 nodes).

        With `t=None`, the integral over the whole segment (shape ()).
        """
        bp = np.unique(np.clip(self.breakpoints(), 0.0, self.duration))
        if bp.size < 2:
            bp = np.array([0.0, self.duration])
        a, b = bp[:-1], bp[1:]
        half, mid = 0.5 * (b - a), 0.5 * (b + a)
        nodes = mid[:, None] + half[:, None] * _GL_X[None, :]
        v, u = self.controls(nodes.ravel())
        vals = np.asarray(rate(v, u), dtype=float).reshape(nodes.shape)
        pieces = half * (vals @ _GL_W)
        if t is None:
            return np.asarray(pieces.sum())
        tq = np.clip(np.asarray(t, dtype=float), 0.0, self.duration)
        flat = tq.ravel()
        k = np.clip(np.searchsorted(bp, flat, side="right") - 1, 0, a.size - 1)
        before = np.concatenate([[0.0], np.cumsum(pieces)])[k]
        h2 = 0.5 * (flat - a[k])
        nodes2 = (a[k] + h2)[:, None] + h2[:, None] * _GL_X[None, :]
        v2, u2 = self.controls(nodes2.ravel())
        vals2 = np.asarray(rate(v2, u2), dtype=float).reshape(nodes2.shape)
        return (before + h2 * (vals2 @ _GL_W)).reshape(tq.shape)

    def to_dict(self) -> dict[str, Any]:
        """A JSON-ready description."""
        s = self.start
        return {
            "kind": self.kind,
            "label": self.label,
            "direction": self.letter,
            "length": self.length,
            "duration": self.duration,
            "start": {"x": s.x, "y": s.y, "heading": s.heading},
        }
