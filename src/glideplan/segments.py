"""Path segment kinds: straight, constant-speed arc, heading-dependent-speed arc, sampled.

Every segment integrates the planar kinematics x' = v cos psi, y' = v sin psi, psi' = u
(dissertation eqs. 2.1, 4.1, 5.1-5.3) for its own control law, in closed form where one exists.
Times `t` are local to the segment, in [0, duration].
"""

from __future__ import annotations

import math
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.pose import Pose, to_world
from glideplan.validation import check_finite, check_nonnegative, check_positive
from glideplan.words import run_word, turn_letters

__all__ = [
    "Arc",
    "HeadingSpeedArc",
    "Sampled",
    "Segment",
    "Straight",
    "direction_letter",
]

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
    return Pose.from_array(to_world(start.as_array(), frame.as_array(), reflect=reflect))


class Segment(ABC):
    """A piece of path flown under one control law (see module docstring)."""

    kind: ClassVar[str] = "segment"
    # True when speed and turn rate do not change along the segment (verification uses it to
    # evaluate them once; it checks the claim at the start, middle and end)
    constant_controls: ClassVar[bool] = False

    start: Pose
    label: str

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
        target = np.asarray(s, dtype=float)
        d, u = self.direction, self.turn_rate
        h0 = np.array(self.start.heading)
        s0 = self._S(h0)
        t = target / self.v0
        for _ in range(30):  # Newton on s(t) - target; ds/dt = v > 0 and s is smooth
            h = self.start.heading + d * u * t
            f = d * (self._S(h) - s0) / u - target
            t = np.clip(t - f / self.speed_at_heading(h), 0.0, self.duration)
        return t

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


def _as_nodes(name: str, values: ArrayLike) -> np.ndarray:
    arr = np.asarray(values, dtype=float).reshape(-1)
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(name, "array", "must be finite")
    return arr


@dataclass(frozen=True, eq=False)
class Sampled(Segment):
    """A segment given by nodes from a direct method: times (s), states and controls.

    Controls are interpolated linearly between nodes; states by cubic Hermite interpolation
    using the kinematics as derivatives. `t` starts at 0 and increases strictly.
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heading: np.ndarray
    speed: np.ndarray
    turn_rate: np.ndarray
    label: str = "D"
    info: dict[str, Any] = field(default_factory=dict)

    kind: ClassVar[str] = "sampled"

    @property
    def direction(self) -> int:  # type: ignore[override]
        return 0

    def __post_init__(self) -> None:
        names = ("t", "x", "y", "heading", "speed", "turn_rate")
        arrays = [_as_nodes(n, getattr(self, n)) for n in names]
        n = arrays[0].size
        if n < 2 or any(a.size != n for a in arrays):
            raise InvalidParameterError("t", n, "all node arrays need the same length >= 2")
        t = arrays[0]
        if abs(t[0]) > 0.0 or np.any(np.diff(t) <= 0):
            raise InvalidParameterError("t", "array", "must start at 0 and increase strictly")
        if np.any(arrays[4] <= 0):
            raise InvalidParameterError("speed", "array", "must be > 0 at every node")
        for name, arr in zip(names, arrays, strict=True):
            arr.setflags(write=False)
            object.__setattr__(self, name, arr)

    @property
    def start(self) -> Pose:  # type: ignore[override]
        return Pose(float(self.x[0]), float(self.y[0]), float(self.heading[0]))

    @property
    def duration(self) -> float:
        return float(self.t[-1])

    @property
    def length(self) -> float:
        return float(np.sum(0.5 * (self.speed[1:] + self.speed[:-1]) * np.diff(self.t)))

    def breakpoints(self) -> np.ndarray:
        return self.t

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        return np.interp(tt, self.t, self.speed), np.interp(tt, self.t, self.turn_rate)

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.clip(np.asarray(t, dtype=float), 0.0, self.duration)
        k = np.clip(np.searchsorted(self.t, tt, side="right") - 1, 0, self.t.size - 2)
        h = self.t[k + 1] - self.t[k]
        tau = (tt - self.t[k]) / h
        h00 = 2 * tau**3 - 3 * tau**2 + 1
        h10 = tau**3 - 2 * tau**2 + tau
        h01 = -2 * tau**3 + 3 * tau**2
        h11 = tau**3 - tau**2
        vx = self.speed * np.cos(self.heading)
        vy = self.speed * np.sin(self.heading)

        def herm(p: np.ndarray, dp: np.ndarray) -> np.ndarray:
            return h00 * p[k] + h10 * h * dp[k] + h01 * p[k + 1] + h11 * h * dp[k + 1]

        return herm(self.x, vx), herm(self.y, vy), herm(self.heading, self.turn_rate)

    @property
    def end(self) -> Pose:
        return Pose(float(self.x[-1]), float(self.y[-1]), float(self.heading[-1]))

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        cum = np.concatenate(
            [[0.0], np.cumsum(0.5 * (self.speed[1:] + self.speed[:-1]) * np.diff(self.t))]
        )
        return np.interp(np.asarray(s, dtype=float), cum, self.t)

    def turn_word(self, turn_rate_tol: float = 1e-3) -> str:
        """Turn-direction letters of the runs of the turn rate (S where |u| <= tol)."""
        return run_word(turn_letters(self.turn_rate, turn_rate_tol))

    def transformed(self, frame: Pose, reflect: bool = False) -> Sampled:
        poses = to_world(
            np.stack([self.x, self.y, self.heading], axis=-1), frame.as_array(), reflect=reflect
        )
        u = -self.turn_rate if reflect else self.turn_rate
        return Sampled(
            self.t, poses[:, 0], poses[:, 1], poses[:, 2], self.speed, u, self.label, self.info
        )

    def to_dict(self) -> dict[str, Any]:
        return {**super().to_dict(), "nodes": int(self.t.size), "word": self.turn_word()}
