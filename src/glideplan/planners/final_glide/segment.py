"""A direct-method control history flown in a steady wind: `Sampled` plus drift."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.pose import Pose, to_world
from glideplan.segments import Sampled, Segment

__all__ = ["DriftingSampled", "DriftingSegment"]


@dataclass(frozen=True)
class DriftingSampled(Sampled):
    """Nodes of a direct method over ground: (x, y) are ground positions, `heading` the air
    heading, `speed` the airspeed; the ground velocity is speed (cos, sin)(heading) + drift.

    `glideplan.verify` integrates x' = v cos psi + wx, y' = v sin psi + wy from the controls
    (it reads `drift`); `states` interpolates the nodes by cubic Hermite with that velocity.
    """

    drift: tuple[float, float] = (0.0, 0.0)

    kind: ClassVar[str] = "drifting_sampled"

    def __post_init__(self) -> None:
        super().__post_init__()
        wx, wy = (float(d) for d in self.drift)
        object.__setattr__(self, "drift", (wx, wy))

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.clip(np.asarray(t, dtype=float), 0.0, self.duration)
        k = np.clip(np.searchsorted(self.t, tt, side="right") - 1, 0, self.t.size - 2)
        h = self.t[k + 1] - self.t[k]
        tau = (tt - self.t[k]) / h
        h00 = 2 * tau**3 - 3 * tau**2 + 1
        h10 = tau**3 - 2 * tau**2 + tau
        h01 = -2 * tau**3 + 3 * tau**2
        h11 = tau**3 - tau**2
        vx = self.speed * np.cos(self.heading) + self.drift[0]
        vy = self.speed * np.sin(self.heading) + self.drift[1]

        def herm(p: np.ndarray, dp: np.ndarray) -> np.ndarray:
            return h00 * p[k] + h10 * h * dp[k] + h01 * p[k + 1] + h11 * h * dp[k + 1]

        return herm(self.x, vx), herm(self.y, vy), herm(self.heading, self.turn_rate)

    @property
    def ground_length(self) -> float:
        """Length of the ground track (m), trapezoidal over the nodes' ground speeds."""
        gx = self.speed * np.cos(self.heading) + self.drift[0]
        gy = self.speed * np.sin(self.heading) + self.drift[1]
        g = np.hypot(gx, gy)
        return float(np.sum(0.5 * (g[1:] + g[:-1]) * np.diff(self.t)))

    def transformed(self, frame: Pose, reflect: bool = False) -> DriftingSampled:
        poses = to_world(
            np.stack([self.x, self.y, self.heading], axis=-1), frame.as_array(), reflect=reflect
        )
        u = -self.turn_rate if reflect else self.turn_rate
        wx, wy = self.drift
        if reflect:
            wy = -wy
        c, s = math.cos(frame.heading), math.sin(frame.heading)
        return DriftingSampled(
            self.t,
            poses[:, 0],
            poses[:, 1],
            poses[:, 2],
            self.speed,
            u,
            self.label,
            self.info,
            (c * wx - s * wy, s * wx + c * wy),
        )

    def to_dict(self) -> dict[str, Any]:
        return {**super().to_dict(), "drift": list(self.drift), "ground_length": self.ground_length}


@dataclass(frozen=True)
class DriftingSegment(Segment):
    """Any air-frame segment flown in a steady wind: ground states = air states + drift t.

    `air` starts at this segment's ground start pose; its controls are the controls flown.
    `glideplan.verify` integrates them with the `drift` added to the velocity (eq. A.4).
    """

    air: Segment
    drift: tuple[float, float] = (0.0, 0.0)

    kind: ClassVar[str] = "drifting"

    @property
    def start(self) -> Pose:  # type: ignore[override]
        return self.air.start

    @property
    def label(self) -> str:  # type: ignore[override]
        return self.air.label

    @property
    def direction(self) -> int:  # type: ignore[override]
        return self.air.direction

    @property
    def constant_controls(self) -> bool:  # type: ignore[override]
        return bool(getattr(self.air, "constant_controls", False))

    @property
    def length(self) -> float:
        return self.air.length

    @property
    def duration(self) -> float:
        return self.air.duration

    def breakpoints(self) -> np.ndarray:
        return self.air.breakpoints()

    def controls(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        return self.air.controls(t)

    def states(self, t: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        tt = np.asarray(t, dtype=float)
        x, y, h = self.air.states(tt)
        return x + self.drift[0] * tt, y + self.drift[1] * tt, h

    def time_at_length(self, s: ArrayLike) -> np.ndarray:
        return self.air.time_at_length(s)

    def transformed(self, frame: Pose, reflect: bool = False) -> DriftingSegment:
        wx, wy = self.drift
        if reflect:
            wy = -wy
        c, s = math.cos(frame.heading), math.sin(frame.heading)
        return DriftingSegment(
            self.air.transformed(frame, reflect), (c * wx - s * wy, s * wx + c * wy)
        )

    def to_dict(self) -> dict[str, Any]:
        return {**self.air.to_dict(), "kind": self.kind, "drift": list(self.drift)}
