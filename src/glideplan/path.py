"""A path: a continuous sequence of typed segments, with its cost, samples and transforms."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.objectives import get_objective
from glideplan.pose import Pose, wrap_to_pi
from glideplan.segments import Segment
from glideplan.vehicles.base import Vehicle
from glideplan.words import run_word

__all__ = ["MAX_SAMPLES", "Path", "PathSamples"]

_JOIN_TOL = 1e-7
# At most this many samples per `Path.sample` call: ten float arrays of this length take
# 800 MB; more is a mistake (or needs chunks), not a MemoryError halfway through.
MAX_SAMPLES = 10_000_000


@dataclass(frozen=True, eq=False)
class PathSamples:
    """Samples along a path: time (s), arc length (m), pose, controls and cumulative cost."""

    t: np.ndarray
    s: np.ndarray
    x: np.ndarray
    y: np.ndarray
    heading: np.ndarray
    speed: np.ndarray
    turn_rate: np.ndarray
    cost: np.ndarray | None = None
    segment_index: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))


@dataclass(frozen=True, eq=False)
class Path:
    """A C0 sequence of segments (position and heading continuous); see docs/ARCHITECTURE.md."""

    segments: tuple[Segment, ...]
    vehicle: Vehicle | None = None

    def __post_init__(self) -> None:
        segs = tuple(self.segments)
        if not segs:
            raise InvalidParameterError("segments", segs, "a path needs at least one segment")
        object.__setattr__(self, "segments", segs)
        scale = max(1.0, self.length)
        for i in range(1, len(segs)):
            a, b = segs[i - 1].end, segs[i].start
            gap = a.distance_to(b)
            dh = a.heading_error(b)
            if gap > _JOIN_TOL * scale or dh > _JOIN_TOL:
                raise InvalidParameterError(
                    "segments",
                    i,
                    f"segment {i} does not start where segment {i - 1} ends "
                    f"(gap {gap:.3g} m, heading {dh:.3g} rad)",
                )

    # ----- geometry and cost -------------------------------------------------------------
    @property
    def start(self) -> Pose:
        return self.segments[0].start

    @property
    def end(self) -> Pose:
        return self.segments[-1].end

    @property
    def length(self) -> float:
        return float(sum(s.length for s in self.segments))

    @property
    def duration(self) -> float:
        return float(sum(s.duration for s in self.segments))

    @property
    def word(self) -> str:
        """Turn-direction word: consecutive equal turns merged, zero-length segments dropped."""
        letters: list[str] = []
        weights: list[float] = []
        for seg in self.segments:
            w = seg.turn_word()
            letters += list(w)
            weights += [seg.length] * len(w)
        return run_word(letters, weights, min_weight=0.0, strict=True)

    @property
    def family(self) -> str:
        """Segment family labels joined, e.g. 'CBSB' (zero-length segments kept)."""
        return "".join(s.label for s in self.segments)

    def cost(self, objective: str = "length") -> float:
        """Total cost under a named objective (see `glideplan.objectives`)."""
        if objective == "length":
            return self.length
        if objective == "time":
            return self.duration
        rate = get_objective(objective).rate_for(self.vehicle)
        return float(sum(float(s.integrate_rate(rate)) for s in self.segments))

    # ----- sampling ----------------------------------------------------------------------
    def _segment_starts(self) -> tuple[np.ndarray, np.ndarray]:
        t0 = np.concatenate([[0.0], np.cumsum([s.duration for s in self.segments])])
        s0 = np.concatenate([[0.0], np.cumsum([s.length for s in self.segments])])
        return t0, s0

    def sample(
        self,
        n: int | None = None,
        *,
        times: ArrayLike | None = None,
        lengths: ArrayLike | None = None,
        objective: str | None = None,
    ) -> PathSamples:
        """Sample at `n` evenly spaced times, or at given `times` (s) or arc `lengths` (m).

        With `objective`, also the cumulative cost along the path.
        """
        given = sum(a is not None for a in (n, times, lengths))
        if given > 1:
            raise InvalidParameterError("sample", given, "give only one of n, times, lengths")
        t0, s0 = self._segment_starts()
        nseg = len(self.segments)
        if lengths is not None:
            sq = np.clip(np.asarray(lengths, dtype=float).ravel(), 0.0, s0[-1])
            k = np.clip(np.searchsorted(s0, sq, side="right") - 1, 0, nseg - 1)
            tl = np.empty_like(sq)
            for i in np.unique(k):
                m = k == i
                tl[m] = self.segments[i].time_at_length(sq[m] - s0[i])
            tq = t0[k] + tl
        else:
            if times is None:
                if n is not None and (isinstance(n, bool) or not float(n).is_integer()):
                    raise InvalidParameterError("n", n, "must be an integer")
                count = 200 if n is None else int(n)
                if count < 2 or count > MAX_SAMPLES:
                    raise InvalidParameterError(
                        "n", n, f"must lie in [2, {MAX_SAMPLES}] (samples per call)"
                    )
                tq = np.linspace(0.0, t0[-1], count)
            else:
                tq = np.clip(np.asarray(times, dtype=float).ravel(), 0.0, t0[-1])
            k = np.clip(np.searchsorted(t0, tq, side="right") - 1, 0, nseg - 1)
        out = {name: np.empty_like(tq) for name in ("x", "y", "h", "v", "u", "s", "c")}
        rate = get_objective(objective).rate_for(self.vehicle) if objective else None
        cum_cost = 0.0
        for i, seg in enumerate(self.segments):
            m = k == i
            tl = tq[m] - t0[i]
            x, y, h = seg.states(tl)
            v, u = seg.controls(tl)
            out["x"][m], out["y"][m], out["h"][m], out["v"][m], out["u"][m] = x, y, h, v, u
            if lengths is None:
                out["s"][m] = s0[i] + seg.integrate_rate(lambda v_, u_: v_, tl)
            else:
                out["s"][m] = sq[m]
            if rate is not None:
                out["c"][m] = cum_cost + seg.integrate_rate(rate, tl)
                cum_cost += float(seg.integrate_rate(rate))
        return PathSamples(
            t=tq,
            s=out["s"],
            x=out["x"],
            y=out["y"],
            heading=out["h"],
            speed=out["v"],
            turn_rate=out["u"],
            cost=out["c"] if rate is not None else None,
            segment_index=k,
        )

    # ----- transforms --------------------------------------------------------------------
    def transformed(self, frame: Pose, reflect: bool = False) -> Path:
        """Map the path by reflection about the x-axis (optional), rotation and translation."""
        return Path(tuple(s.transformed(frame, reflect) for s in self.segments), self.vehicle)

    def translated(self, dx: float, dy: float) -> Path:
        return self.transformed(Pose(dx, dy, 0.0))

    def rotated(self, angle: float) -> Path:
        """Rotate about the origin by `angle` (rad, counter-clockwise)."""
        return self.transformed(Pose(0.0, 0.0, angle))

    def reflected(self) -> Path:
        """Mirror about the x-axis (left and right turns swap)."""
        return self.transformed(Pose(0.0, 0.0, 0.0), reflect=True)

    def concatenate(self, other: Path) -> Path:
        """This path followed by `other` (which must start where this one ends)."""
        return Path(self.segments + other.segments, self.vehicle or other.vehicle)

    __add__ = concatenate

    def with_vehicle(self, vehicle: Vehicle | None) -> Path:
        return Path(self.segments, vehicle)

    def endpoint_gap(self, goal: Pose) -> tuple[float, float]:
        """Position (m) and heading (rad) differences between the path's end and `goal`."""
        e = self.end
        return e.distance_to(goal), abs(float(wrap_to_pi(goal.heading - e.heading)))

    # ----- output ------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        return {
            "word": self.word,
            "family": self.family,
            "length": self.length,
            "duration": self.duration,
            "segments": [s.to_dict() for s in self.segments],
        }

    def plot(self, ax: Any = None, **kwargs: Any) -> Any:
        """Draw the path (see `glideplan.plotting.plot_path`)."""
        from glideplan.plotting import plot_path

        return plot_path(self, ax=ax, **kwargs)
