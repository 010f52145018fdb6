"""The chapter 5 B arc: a maximum-rate turn whose speed depends on the heading."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.pose import Pose
from glideplan.segments.base import Segment, _check_direction, _map_pose
from glideplan.validation import check_finite, check_nonnegative, check_positive

__all__ = ["HeadingSpeedArc"]


@dataclass(frozen=True)
class HeadingSpeedArc(Segment):
    """A maximum-rate turn whose speed depends on heading: v = v0 - lam cos(psi - theta).

    Heading psi(t) = psi0 + direction * turn_rate * t for t in [0, angle / turn_rate]. This is
    the chapter 5 B arc (Table 5.1; closed forms re-derived, cf. C.5-C.8 whose lambda term
    has a sign error in the extracted text). Positions integrate in closed form:
    X(psi) = v0 sin psi - lam/2 [psi cos theta + sin(2 psi - theta)/2],
    Y(psi) = -v0 cos psi - lam/2 [psi sin theta - cos(2 psi - theta)/2],
    x = x0 + direction (X(psi) - X(psi0)) / turn_rate (likewise y).
    """

    start: Pose
    angle: float
    direction: int
    turn_rate: float
    v0: float
    lam: float
    theta: float
    label: str = "B"

    kind: ClassVar[str] = "heading_speed_arc"

    def __post_init__(self) -> None:
        object.__setattr__(self, "angle", check_nonnegative("angle", self.angle))
        object.__setattr__(self, "direction", _check_direction(self.direction))
        object.__setattr__(self, "turn_rate", check_positive("turn_rate", self.turn_rate))
        object.__setattr__(self, "v0", check_positive("v0", self.v0))
        object.__setattr__(self, "lam", check_finite("lam", self.lam))
        object.__setattr__(self, "theta", check_finite("theta", self.theta))
        # the speed must stay positive over the headings actually flown
        vmin = float(np.min(self.speed_at_heading(self._headings_dense())))
        if vmin <= 0.0:
            raise InvalidParameterError(
                "lam", self.lam, "speed v0 - lam cos(psi - theta) must stay > 0"
            )

    def _headings_dense(self) -> np.ndarray:
        return self.start.heading + self.direction * np.linspace(0.0, self.angle, 65)

    def speed_at_heading(self, psi: ArrayLike) -> np.ndarray:
        """Speed (m/s) at heading psi (rad)."""
        return self.v0 - self.lam * np.cos(np.asarray(psi, dtype=float) - self.theta)

    def _X(self, psi: np.ndarray) -> np.ndarray:
        th, lam = self.theta, self.lam
        return self.v0 * np.sin(psi) - 0.5 * lam * (psi * math.cos(th) + 0.5 * np.sin(2 * psi - th))

    def _Y(self, psi: np.ndarray) -> np.ndarray:
        th, lam = self.theta, self.lam
        return -self.v0 * np.cos(psi) - 0.5 * lam * (
            psi * math.sin(th) - 0.5 * np.cos(2 * psi - th)
        )

    def _S(self, psi: np.ndarray) -> np.ndarray:
        return self.v0 * psi - self.lam * np.sin(psi - self.theta)

    @property
    def duration(self) -> float:
        return self.angle / self.turn_rate

    @property
    def length(self) -> float:
        h0 = np.array(self.start.heading)
        h1 = h0 + self.direction * self.angle
        return float(self.direction * (self._S(h1) - self._S(h0)) / self.turn_rate)

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        s, d, u = self.start, self.direction, self.turn_rate
        h0 = np.array(s.heading)
        h = s.heading + d * u * tt
        x = s.x + d * (self._X(h) - self._X(h0)) / u
        y = s.y + d * (self._Y(h) - self._Y(h0)) / u
        return x, y, h

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        h = self.start.heading + self.direction * self.turn_rate * tt
        return self.speed_at_heading(h), np.full_like(tt, self.direction * self.turn_rate)

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        """Local time at arc length s: the root of S(t) = s, with S increasing (dS/dt = v > 0).

        Bracketed in [0, duration] and solved elementwise by SciPy (Chandrupatla's method);
        lengths outside [0, length] map to the ends.
        """
        from scipy.optimize import elementwise  # imported where used (start-up time)

        target = np.asarray(s, dtype=float)
        d, u = self.direction, self.turn_rate
        h0 = np.array(self.start.heading)
        s0 = self._S(h0)
        out = np.where(target <= 0.0, 0.0, self.duration)
        inside = (target > 0.0) & (target < self.length)
        if not np.any(inside):
            return out

        def excess(t: np.ndarray, want: np.ndarray) -> np.ndarray:
            return d * (self._S(self.start.heading + d * u * t) - s0) / u - want

        res = elementwise.find_root(excess, (0.0, self.duration), args=(target[inside],))
        if not np.all(res.success):  # pragma: no cover - a valid bracket always converges
            raise RuntimeError("arc length to time: the root search did not converge")
        out[inside] = res.x
        return out

    def transformed(self, frame: Pose, reflect: bool = False) -> HeadingSpeedArc:
        theta = -self.theta if reflect else self.theta
        d = -self.direction if reflect else self.direction
        return HeadingSpeedArc(
            _map_pose(self.start, frame, reflect),
            self.angle,
            d,
            self.turn_rate,
            self.v0,
            self.lam,
            theta + frame.heading,
            self.label,
        )

    def to_dict(self) -> dict[str, Any]:
        return {
            **super().to_dict(),
            "angle": self.angle,
            "turn_rate": self.direction * self.turn_rate,
            "v0": self.v0,
            "lam": self.lam,
            "theta": self.theta,
        }
