"""Planar poses (x, y, heading), angle wrapping and rigid frame changes.

Headings are radians, counter-clockwise from +x. A frame change maps a pose expressed in a
frame (a `Pose` giving that frame's origin and orientation) to the world and back; an optional
reflection about the frame's x-axis is applied first (mirror symmetry of planning problems).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.validation import check_finite

__all__ = ["Pose", "mod_2pi", "to_local", "to_world", "wrap_to_pi"]

TWO_PI = 2.0 * math.pi


def wrap_to_pi(angle: ArrayLike) -> np.ndarray | float:
    """Wrap angles to [-pi, pi)."""
    a = np.asarray(angle, dtype=float)
    out = (a + math.pi) % TWO_PI - math.pi
    return float(out) if out.ndim == 0 else out


def mod_2pi(angle: ArrayLike) -> np.ndarray | float:
    """Wrap angles to [0, 2 pi)."""
    a = np.asarray(angle, dtype=float)
    out = np.mod(a, TWO_PI)
    out = np.where(out >= TWO_PI, 0.0, out)
    return float(out) if out.ndim == 0 else out


@dataclass(frozen=True, slots=True)
class Pose:
    """An oriented point: position (x, y) in metres (or normalised units) and heading in rad."""

    x: float = 0.0
    y: float = 0.0
    heading: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "x", check_finite("x", self.x))
        object.__setattr__(self, "y", check_finite("y", self.y))
        object.__setattr__(self, "heading", check_finite("heading", self.heading))

    @classmethod
    def from_degrees(cls, x: float, y: float, heading_deg: float) -> Pose:
        """A pose with the heading given in degrees."""
        return cls(x, y, math.radians(check_finite("heading_deg", heading_deg)))

    @classmethod
    def from_array(cls, values: ArrayLike) -> Pose:
        """A pose from a length-3 sequence (x, y, heading)."""
        arr = np.asarray(values, dtype=float).reshape(-1)
        if arr.size != 3:
            from glideplan.errors import InvalidParameterError

            raise InvalidParameterError("pose", values, "needs exactly three values x, y, heading")
        return cls(float(arr[0]), float(arr[1]), float(arr[2]))

    def as_array(self) -> np.ndarray:
        """The pose as a float array [x, y, heading]."""
        return np.array([self.x, self.y, self.heading])

    @property
    def position(self) -> np.ndarray:
        """The position [x, y]."""
        return np.array([self.x, self.y])

    def wrapped(self) -> Pose:
        """The same pose with its heading wrapped to [-pi, pi)."""
        return Pose(self.x, self.y, float(wrap_to_pi(self.heading)))

    def relative_to(self, frame: Pose, reflect: bool = False) -> Pose:
        """This pose expressed in `frame` (inverse of `from_frame`)."""
        return Pose.from_array(to_local(self.as_array(), frame.as_array(), reflect=reflect))

    def from_frame(self, frame: Pose, reflect: bool = False) -> Pose:
        """This pose, given in `frame`, expressed in the world."""
        return Pose.from_array(to_world(self.as_array(), frame.as_array(), reflect=reflect))

    def distance_to(self, other: Pose) -> float:
        """Euclidean distance between the positions."""
        return math.hypot(other.x - self.x, other.y - self.y)

    def heading_error(self, other: Pose) -> float:
        """Absolute heading difference modulo 2 pi, in [0, pi]."""
        return abs(float(wrap_to_pi(other.heading - self.heading)))


def to_local(poses: ArrayLike, frame: ArrayLike, *, reflect: bool = False) -> np.ndarray:
    """Express world poses `(..., 3)` in `frame` `(..., 3)` (broadcast); optional x-axis mirror."""
    p = np.asarray(poses, dtype=float)
    f = np.asarray(frame, dtype=float)
    dx = p[..., 0] - f[..., 0]
    dy = p[..., 1] - f[..., 1]
    c, s = np.cos(f[..., 2]), np.sin(f[..., 2])
    x = c * dx + s * dy
    y = -s * dx + c * dy
    h = p[..., 2] - f[..., 2]
    if reflect:
        y, h = -y, -h
    return np.stack(np.broadcast_arrays(x, y, h), axis=-1)


def to_world(poses: ArrayLike, frame: ArrayLike, *, reflect: bool = False) -> np.ndarray:
    """Map poses `(..., 3)` given in `frame` to the world (inverse of `to_local`)."""
    p = np.asarray(poses, dtype=float)
    f = np.asarray(frame, dtype=float)
    x, y, h = p[..., 0], p[..., 1], p[..., 2]
    if reflect:
        y, h = -y, -h
    c, s = np.cos(f[..., 2]), np.sin(f[..., 2])
    wx = f[..., 0] + c * x - s * y
    wy = f[..., 1] + s * x + c * y
    wh = h + f[..., 2]
    return np.stack(np.broadcast_arrays(wx, wy, wh), axis=-1)
