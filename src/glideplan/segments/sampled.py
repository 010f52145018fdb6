"""A segment given by the nodes of a direct method's solution."""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.pose import Pose, to_world
from glideplan.segments.base import Segment
from glideplan.words import run_word, turn_letters

__all__ = ["Sampled"]


def _as_nodes(name: str, values: ArrayLike) -> np.ndarray:
    arr = np.asarray(values, dtype=float).reshape(-1)
    if not np.all(np.isfinite(arr)):
        raise InvalidParameterError(name, "array", "must be finite")
    return arr


@dataclass(frozen=True, eq=False)
class Sampled(Segment):
    """A segment given by nodes from a direct method: times (s), states and controls.

    Controls are interpolated linearly between nodes; states by cubic Hermite interpolation
    (`scipy.interpolate.CubicHermiteSpline`) using the kinematics as derivatives. `t` starts
    at 0 and increases strictly.
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
    piecewise_linear_controls: ClassVar[bool] = True

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

    @functools.cached_property
    def _spline(self) -> Any:
        """The cubic Hermite interpolant of (x, y, heading) with the kinematics as slopes."""
        from scipy.interpolate import CubicHermiteSpline  # imported where used (start-up)

        values = np.stack([self.x, self.y, self.heading])
        slopes = np.stack(
            [self.speed * np.cos(self.heading), self.speed * np.sin(self.heading), self.turn_rate]
        )
        return CubicHermiteSpline(self.t, values, slopes, axis=1)

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.clip(np.asarray(t, dtype=float), 0.0, self.duration)
        x, y, h = self._spline(tt)
        return x, y, h

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
