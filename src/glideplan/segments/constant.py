"""Constant-control segments: a straight line and a circular arc at constant speed."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.pose import Pose
from glideplan.segments.base import Segment, _check_direction, _map_pose
from glideplan.validation import check_nonnegative, check_positive

__all__ = ["Arc", "Straight"]


@dataclass(frozen=True)
class Straight(Segment):
    """A straight line flown at constant speed (m/s) for `length` (m)."""

    start: Pose
    length_m: float
    speed: float = 1.0
    label: str = "S"

    kind: ClassVar[str] = "straight"
    constant_controls: ClassVar[bool] = True

    @property
    def direction(self) -> int:  # type: ignore[override]
        return 0

    def __post_init__(self) -> None:
        object.__setattr__(self, "length_m", check_nonnegative("length", self.length_m))
        object.__setattr__(self, "speed", check_positive("speed", self.speed))

    @property
    def length(self) -> float:
        return self.length_m

    @property
    def duration(self) -> float:
        return self.length_m / self.speed

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        d = self.speed * np.asarray(t, dtype=float)
        s = self.start
        return (
            s.x + d * math.cos(s.heading),
            s.y + d * math.sin(s.heading),
            np.full_like(d, s.heading),
        )

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        return np.full_like(tt, self.speed), np.zeros_like(tt)

    @property
    def end(self) -> Pose:
        """Closed form: start + length (cos psi0, sin psi0)."""
        s = self.start
        return Pose(
            s.x + self.length_m * math.cos(s.heading),
            s.y + self.length_m * math.sin(s.heading),
            s.heading,
        )

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        return np.asarray(s, dtype=float) / self.speed

    def transformed(self, frame: Pose, reflect: bool = False) -> Straight:
        return Straight(
            _map_pose(self.start, frame, reflect), self.length_m, self.speed, self.label
        )

    def to_dict(self) -> dict[str, Any]:
        return {**super().to_dict(), "speed": self.speed}


@dataclass(frozen=True)
class Arc(Segment):
    """A circular arc of `radius` (m) flown at constant speed through heading change `angle` (rad).

    Turn rate u = direction * speed / radius (eqs. 2.1 with u = +-u_max, 4.1).
    """

    start: Pose
    angle: float
    radius: float
    direction: int
    speed: float = 1.0
    label: str = "B"

    kind: ClassVar[str] = "arc"
    constant_controls: ClassVar[bool] = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "angle", check_nonnegative("angle", self.angle))
        object.__setattr__(self, "radius", check_positive("radius", self.radius))
        object.__setattr__(self, "direction", _check_direction(self.direction))
        object.__setattr__(self, "speed", check_positive("speed", self.speed))

    @property
    def length(self) -> float:
        return self.radius * self.angle

    @property
    def duration(self) -> float:
        return self.radius * self.angle / self.speed

    @property
    def turn_rate(self) -> float:
        """Signed turn rate (rad/s)."""
        return self.direction * self.speed / self.radius

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        s, r, d = self.start, self.radius, self.direction
        h = s.heading + self.turn_rate * tt
        x = s.x + d * r * (np.sin(h) - math.sin(s.heading))
        y = s.y - d * r * (np.cos(h) - math.cos(s.heading))
        return x, y, h

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        return np.full_like(tt, self.speed), np.full_like(tt, self.turn_rate)

    @property
    def end(self) -> Pose:
        """Closed form: heading psi1 = psi0 + d angle, position on the turning circle."""
        s, r, d = self.start, self.radius, self.direction
        h = s.heading + d * self.angle
        return Pose(
            s.x + d * r * (math.sin(h) - math.sin(s.heading)),
            s.y - d * r * (math.cos(h) - math.cos(s.heading)),
            h,
        )

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        return np.asarray(s, dtype=float) / self.speed

    @property
    def center(self) -> np.ndarray:
        """Centre of the turning circle [x, y]."""
        s = self.start
        return np.array(
            [
                s.x - self.direction * self.radius * math.sin(s.heading),
                s.y + self.direction * self.radius * math.cos(s.heading),
            ]
        )

    def transformed(self, frame: Pose, reflect: bool = False) -> Arc:
        d = -self.direction if reflect else self.direction
        return Arc(
            _map_pose(self.start, frame, reflect),
            self.angle,
            self.radius,
            d,
            self.speed,
            self.label,
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            **super().to_dict(),
            "angle": self.angle,
            "radius": self.radius,
            "speed": self.speed,
            "turn_rate": self.turn_rate,
        }
