"""Lookahead-based guidance on regularly parameterised paths (Breivik & Fossen 2008), vectorised.

Dissertation §3.4; REFERENCE_NOTES §1.2-1.4. A batch of N piecewise-constant-curvature paths
(Dubins paths: arcs and straights) is held as arrays `PathArrays` parameterised by arc length
varpi (so |p_p'(varpi)| = 1: a regular parameterisation). Past the end the path continues
along its final tangent, before the start along its initial tangent, so the path-parameter
law never stalls. For a vehicle at p with ground velocity g and path point p_p(varpi) with
tangent angle chi_p:

- errors in the path-tangential frame: along-track s = (p - p_p) . t, cross-track
  e = (p - p_p) . n (positive to the left of the path);
- course command chi_d = chi_p + atan(-e / Delta) (lookahead distance Delta > 0);
- path-parameter update varpi' = g . t + gamma s (the measured-course variant of
  U cos(chi_d - chi_p) + gamma s, robust while the course is not yet tracked).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.dubins_kernel import (
    DIRECTIONS,
    WORDS,
    mod_2pi_snapped,
    segment_table,
    shortest_word,
)
from glideplan.pose import Pose
from glideplan.segments import Arc, Segment, Straight
from glideplan.validation import check_finite_array, check_positive

__all__ = ["GuidanceCommand", "PathArrays", "lookahead_guidance"]

_DIRS = np.array([DIRECTIONS[w] for w in WORDS], dtype=float)  # (6, 3)


def _advance(x, y, h, kappa, d):
    """Pose after arc length d on a constant-curvature piece (kappa = 0: straight)."""
    half = 0.5 * kappa * d
    chord = d * np.sinc(half / math.pi)  # 2 sin(kappa d / 2) / kappa
    mid = h + half
    return x + chord * np.cos(mid), y + chord * np.sin(mid), h + kappa * d


@dataclass(frozen=True, eq=False)
class PathArrays:
    """N paths of K constant-curvature segments each, as arrays (m, rad, 1/m).

    x0, y0, h0: start pose of each segment (N, K); kappa: signed curvature (N, K), + left;
    s0: arc length at each segment's start (N, K); length: total length (N,);
    end: final pose (N, 3); arm: arc length where the last segment of positive length starts
    (the finish-line detector is armed once the path point passes it, REFERENCE_NOTES §1.5).
    """

    x0: np.ndarray
    y0: np.ndarray
    h0: np.ndarray
    kappa: np.ndarray
    s0: np.ndarray
    length: np.ndarray
    end: np.ndarray
    arm: np.ndarray

    @property
    def count(self) -> int:
        return int(self.length.shape[0])

    @classmethod
    def from_segments(
        cls,
        start: ArrayLike,
        directions: ArrayLike,
        lengths: ArrayLike,
        radius: ArrayLike,
    ) -> PathArrays:
        """Paths from start poses (N, 3), turn directions (N, K) in {+1, 0, -1}, segment
        lengths (N, K) in m and turn radii (N,) or scalar, in m."""
        st = check_finite_array("start", start, last_dim=3)
        dirs = np.asarray(directions, dtype=float)
        lens = check_finite_array("lengths", lengths)
        if st.ndim != 2 or dirs.shape != lens.shape or dirs.shape[0] != st.shape[0]:
            raise InvalidParameterError(
                "lengths", lens.shape, "need start (N, 3), directions and lengths (N, K)"
            )
        if np.any(lens < 0.0):
            raise InvalidParameterError("lengths", "array", "must be >= 0")
        r = np.broadcast_to(np.asarray(radius, dtype=float), (st.shape[0],))
        if not np.all(np.isfinite(r)) or np.any(r <= 0.0):
            raise InvalidParameterError("radius", "array", "must be finite and > 0")
        kappa = dirs / r[:, None]
        n, k = lens.shape
        x0, y0, h0 = (np.empty((n, k)) for _ in range(3))
        x, y, h = st[:, 0].copy(), st[:, 1].copy(), st[:, 2].copy()
        for j in range(k):
            x0[:, j], y0[:, j], h0[:, j] = x, y, h
            x, y, h = _advance(x, y, h, kappa[:, j], lens[:, j])
        s0 = np.concatenate([np.zeros((n, 1)), np.cumsum(lens, axis=1)[:, :-1]], axis=1)
        length = lens.sum(axis=1)
        # the last segment with positive length (its start arms the finish line)
        positive = lens > 0.0
        last = np.where(positive.any(axis=1), k - 1 - np.argmax(positive[:, ::-1], axis=1), 0)
        arm = s0[np.arange(n), last]
        return cls(x0, y0, h0, kappa, s0, length, np.stack([x, y, h], axis=-1), arm)

    @classmethod
    def dubins(cls, goals: ArrayLike, radius: ArrayLike) -> PathArrays:
        """Shortest Dubins paths from the origin (heading 0) to goals (N, 3) with radii (N,)."""
        g = check_finite_array("goals", goals, last_dim=3).reshape(-1, 3)
        r = np.asarray(radius, dtype=float)
        if not np.all(np.isfinite(r)) or np.any(r <= 0.0):
            raise InvalidParameterError("radius", radius, "must be finite and > 0")
        # the Dubins kernel in the start frame (origin, heading 0), scaled by 1 / radius
        r = np.broadcast_to(r, g.shape[:1])
        inv = 1.0 / r
        table = segment_table(g[:, 0] * inv, g[:, 1] * inv, mod_2pi_snapped(g[:, 2]))
        _, word_index, seg = shortest_word(table * r[:, None, None])
        return cls.from_segments(np.zeros_like(g), _DIRS[word_index], seg, radius)

    @classmethod
    def from_paths(cls, paths: Sequence[Path]) -> PathArrays:
        """The same paths as arrays: each `Path` of straights and constant-radius arcs
        (`Straight`, `Arc`) becomes one row; shorter paths are padded with empty straights."""
        if not paths:
            raise InvalidParameterError("paths", paths, "needs at least one Path")
        k = max(len(p.segments) for p in paths)
        dirs, lens, radii = np.zeros((len(paths), k)), np.zeros((len(paths), k)), []
        for i, p in enumerate(paths):
            arcs = {seg.radius for seg in p.segments if isinstance(seg, Arc)}
            if any(not isinstance(seg, (Arc, Straight)) for seg in p.segments) or len(arcs) > 1:
                raise InvalidParameterError(
                    "paths", i, "needs straights and arcs of one radius (constant curvature)"
                )
            radii.append(arcs.pop() if arcs else 1.0)
            for j, seg in enumerate(p.segments):
                dirs[i, j], lens[i, j] = seg.direction, seg.length
        start = np.array([p.start.as_array() for p in paths])
        return cls.from_segments(start, dirs, lens, np.array(radii))

    def path(self, i: int, speed: float = 1.0) -> Path:
        """Row `i` as a `Path` of `Straight` and `Arc` segments flown at `speed` (m/s)."""
        segments: list[Segment] = []
        for j in range(self.kappa.shape[1]):
            start = Pose(float(self.x0[i, j]), float(self.y0[i, j]), float(self.h0[i, j]))
            nxt = self.s0[i, j + 1] if j + 1 < self.s0.shape[1] else self.length[i]
            length = float(nxt - self.s0[i, j])
            kap = float(self.kappa[i, j])
            if kap == 0.0:
                segments.append(Straight(start, length, speed))
            else:
                direction = 1 if kap > 0.0 else -1
                segments.append(Arc(start, length * abs(kap), 1.0 / abs(kap), direction, speed))
        return Path(tuple(segments))

    def take(self, index: np.ndarray) -> PathArrays:
        """The paths selected by an index or boolean mask."""
        return PathArrays(
            self.x0[index],
            self.y0[index],
            self.h0[index],
            self.kappa[index],
            self.s0[index],
            self.length[index],
            self.end[index],
            self.arm[index],
        )

    def point(self, varpi: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Path point (x, y) and tangent angle chi_p at arc lengths varpi (N,)."""
        return self.point_curvature(varpi)[:3]

    def points_along(
        self, i: int, varpi: ArrayLike
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points (x, y) and tangent angles of row `i` at many arc lengths varpi (M,) within
        [0, length] (m): one path sampled densely (`point` takes one varpi per row)."""
        w = np.clip(np.asarray(varpi, dtype=float), 0.0, self.length[i])
        idx = np.searchsorted(self.s0[i], w, side="right") - 1
        idx = np.clip(idx, 0, self.s0.shape[1] - 1)
        return _advance(self.x0[i, idx], self.y0[i, idx], self.h0[i, idx], self.kappa[i, idx],
                        w - self.s0[i, idx])

    def point_curvature(
        self, varpi: ArrayLike
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Path point, tangent angle and signed curvature (1/m, 0 beyond the ends) at varpi."""
        w = np.asarray(varpi, dtype=float)
        n, k = self.s0.shape
        idx = np.zeros(n, dtype=np.intp)
        for j in range(1, k):
            idx += w >= self.s0[:, j]
        rows = np.arange(n)
        x0, y0, h0 = self.x0[rows, idx], self.y0[rows, idx], self.h0[rows, idx]
        kap = self.kappa[rows, idx]
        wc = np.clip(w, 0.0, self.length)
        x, y, h = _advance(x0, y0, h0, kap, wc - self.s0[rows, idx])
        extra = w - wc  # beyond either end: along the end tangent
        kap = np.where(extra == 0.0, kap, 0.0)
        return x + extra * np.cos(h), y + extra * np.sin(h), h, kap


@dataclass(frozen=True, eq=False)
class GuidanceCommand:
    """Course command chi_d (rad), path-parameter rate (m/s), the errors s, e (m) and the
    path's turn rate at the path point, kappa_p varpi' (rad/s; a feedforward for the course)."""

    course: np.ndarray
    varpi_rate: np.ndarray
    along_track: np.ndarray
    cross_track: np.ndarray
    path_turn_rate: np.ndarray


def lookahead_guidance(
    paths: PathArrays,
    varpi: np.ndarray,
    x: np.ndarray,
    y: np.ndarray,
    ground_vx: np.ndarray,
    ground_vy: np.ndarray,
    *,
    lookahead: float,
    gamma: float,
) -> GuidanceCommand:
    """Breivik-Fossen lookahead guidance (module docstring) for N vehicles at once.

    lookahead: Delta (m); gamma: along-track gain (1/s); ground velocity in m/s.
    """
    check_positive("lookahead", lookahead)
    xp, yp, chi_p, kappa = paths.point_curvature(varpi)
    c, s = np.cos(chi_p), np.sin(chi_p)
    dx, dy = x - xp, y - yp
    along = dx * c + dy * s
    cross = dy * c - dx * s
    course = chi_p - np.arctan(cross / lookahead)
    rate = ground_vx * c + ground_vy * s + gamma * along
    return GuidanceCommand(course, rate, along, cross, kappa * rate)
