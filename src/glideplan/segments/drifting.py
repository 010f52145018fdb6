"""Segments flown in a steady uniform wind or current: an air-frame arc or straight plus the
drift w t ("convected" Dubins segments; dissertation section 3.2, eq. A.4).

They report `drift = (wx, wy)`, so `glideplan.verify` integrates the inertial dynamics along
their controls. Their `length` is the air-relative distance flown (v times the duration);
`ground_length` is the length of the ground track.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, ClassVar, Self

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.pose import Pose
from glideplan.segments.base import Segment
from glideplan.segments.constant import Arc, Straight
from glideplan.validation import check_finite

__all__ = ["DriftingStraight", "TrochoidArc"]

_GL_X, _GL_W = np.polynomial.legendre.leggauss(24)


def _map_drift(drift: tuple[float, float], frame: Pose, reflect: bool) -> tuple[float, float]:
    wx, wy = drift
    if reflect:
        wy = -wy
    c, s = math.cos(frame.heading), math.sin(frame.heading)
    return (c * wx - s * wy, s * wx + c * wy)


def _check_drift(drift: Any) -> tuple[float, float]:
    try:
        wx, wy = drift
    except (TypeError, ValueError):
        raise InvalidParameterError("drift", drift, "must be a pair (wx, wy) in m/s") from None
    return (check_finite("drift x", wx), check_finite("drift y", wy))


class _Drifting(Segment):
    """Shared parts of the segments flown in a steady uniform wind: the air-frame segment
    (`_air_segment`, which also validates the fields) plus the drift w t."""

    constant_controls: ClassVar[bool] = True
    # the fields shared with the air-frame segment (validated and normalised by it)
    _air_fields: ClassVar[tuple[str, ...]] = ()
    drift: tuple[float, float]
    speed: float

    def _air(self) -> Arc | Straight:
        """The same manoeuvre in the air-relative frame F_A (no drift)."""
        raise NotImplementedError

    def __post_init__(self) -> None:
        air = self._air()  # validates the air-frame fields
        for name in self._air_fields:
            object.__setattr__(self, name, getattr(air, name))
        self.__dict__["_air_segment"] = air  # the cached property's value, built once
        object.__setattr__(self, "drift", _check_drift(self.drift))

    @functools.cached_property
    def _air_segment(self) -> Arc | Straight:
        """The air-frame segment, built once."""
        return self._air()

    @property
    def duration(self) -> float:
        return self._air_segment.duration

    @property
    def length(self) -> float:
        return self.speed * self.duration

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        return np.asarray(s, dtype=float) / self.speed

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Ground position (air-frame position plus drift w t) and heading at local times t."""
        tt = np.asarray(t, dtype=float)
        x, y, h = self._air_segment.states(tt)
        return x + self.drift[0] * tt, y + self.drift[1] * tt, h

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        return self._air_segment.controls(t)

    def transformed(self, frame: Pose, reflect: bool = False) -> Self:
        """The air-frame segment mapped by the rigid motion, with the drift rotated alike.

        Built from the (validated) mapped air segment without validating again.
        """
        air = self._air_segment.transformed(frame, reflect)
        new = object.__new__(type(self))
        new.__dict__.update(self.__dict__)
        for name in self._air_fields:
            new.__dict__[name] = getattr(air, name)
        new.__dict__.update(
            start=air.start, drift=_map_drift(self.drift, frame, reflect), _air_segment=air
        )
        return new

    @property
    def end(self) -> Pose:
        """The air-frame segment's end (closed form) moved by the drift w T."""
        air, T = self._air_segment.end, self.duration
        return Pose(air.x + self.drift[0] * T, air.y + self.drift[1] * T, air.heading)

    @property
    def ground_length(self) -> float:
        """Length of the ground track (m), by Gauss-Legendre quadrature of the ground speed."""
        if self.duration <= 0.0:
            return 0.0
        half = 0.5 * self.duration
        t = half * (_GL_X + 1.0)
        v, _u = self.controls(t)
        h = self.states(t)[2]
        gx = v * np.cos(h) + self.drift[0]
        gy = v * np.sin(h) + self.drift[1]
        return float(half * np.hypot(gx, gy) @ _GL_W)

    def to_dict(self) -> dict[str, Any]:
        return {
            **self._air_segment.to_dict(),
            **super().to_dict(),
            "drift": list(self.drift),
            "ground_length": self.ground_length,
        }


@dataclass(frozen=True)
class TrochoidArc(_Drifting):
    """A maximum-rate turn flown in a steady wind: an air-frame circle of `radius` (m) through
    heading change `angle` (rad) at airspeed `speed` (m/s), drifting with `drift` (m/s) — a
    trochoid over ground (Techy & Woolsey 2009; dissertation §3.2)."""

    start: Pose
    angle: float
    radius: float
    direction: int
    speed: float = 1.0
    drift: tuple[float, float] = (0.0, 0.0)
    label: str = "B"

    kind: ClassVar[str] = "trochoid_arc"
    _air_fields: ClassVar[tuple[str, ...]] = ("angle", "radius", "direction", "speed")

    def _air(self) -> Arc:
        return Arc(self.start, self.angle, self.radius, self.direction, self.speed, self.label)

    @property
    def turn_rate(self) -> float:
        """Signed turn rate (rad/s)."""
        return self.direction * self.speed / self.radius


@dataclass(frozen=True)
class DriftingStraight(_Drifting):
    """A straight flown at constant heading and airspeed `speed` (m/s) for an air-relative
    distance `length_m` (m), drifting with `drift` (m/s): a straight over ground along
    v (cos psi, sin psi) + w."""

    start: Pose
    length_m: float
    speed: float = 1.0
    drift: tuple[float, float] = (0.0, 0.0)
    label: str = "S"

    kind: ClassVar[str] = "drifting_straight"
    _air_fields: ClassVar[tuple[str, ...]] = ("length_m", "speed")

    @property
    def direction(self) -> int:  # type: ignore[override]
        return 0

    def _air(self) -> Straight:
        return Straight(self.start, self.length_m, self.speed, self.label)
