"""Maps over a grid of goals: the Dubins partition (Fig 3.1) and the tradespace ratio (Fig 3.2).

Dissertation section 3.3. For a final heading psi1 the plane of final positions (in units of
the minimum turn radius R0, start at the origin with heading 0) is partitioned by the optimal
Dubins word (Bui et al. 1994; REFERENCE_NOTES 4.3), and the ratio
T(x1, y1, psi1, eps) = d_feasible / d_optimal compares the shortest path planned with the
feasible radius R0' = R0 (1 + eps)^2 (eq. 3.3) to the one planned with R0 (REFERENCE_NOTES 4.4).
Both evaluate the batched closed-form Dubins lengths over the grid, in chunks through
`glideplan.batch.run_batch` for large grids. Plotting lives in `glideplan.studies.map_plots`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.batch import map_chunks
from glideplan.errors import InvalidParameterError
from glideplan.planners.dubins import WORDS, dubins_word_lengths, feasible_radius
from glideplan.validation import check_finite, check_in_range, check_positive

__all__ = [
    "PartitionMap",
    "PartitionRegion",
    "TradespaceMap",
    "grid_axis",
    "partition_map",
    "partition_regions",
    "tradespace_map",
    "tradespace_ratio",
]

_PARALLEL_POINTS = 1_000_000  # grids larger than this go through run_batch in chunks
_CHUNK = 131_072


def grid_axis(extent: float, n: int) -> np.ndarray:
    """`n` evenly spaced coordinates over [-extent, extent] (units of R0)."""
    extent = check_positive("extent", extent)
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 2:
        raise InvalidParameterError("n", n, "must be an integer >= 2")
    if n > 4001:
        raise InvalidParameterError("n", n, "must be <= 4001 (grid of n x n goals)")
    return np.linspace(-extent, extent, int(n))


def _lengths_kernel(goals: np.ndarray, radius: float) -> np.ndarray:
    """Six word lengths `(m, 6)` from the origin to `goals` `(m, 3)` with turn radius `radius`."""
    return dubins_word_lengths(np.zeros(3), goals, radius)


def _grid_word_lengths(
    x: np.ndarray, y: np.ndarray, psi1: float, radius: float, batch_options: dict[str, Any]
) -> np.ndarray:
    """Word lengths `(ny, nx, 6)` on the grid of goals (x, y, psi1), rows indexed by y."""
    gx, gy = np.meshgrid(x, y)
    goals = np.stack([gx.ravel(), gy.ravel(), np.full(gx.size, psi1)], axis=-1)
    kernel = functools.partial(_lengths_kernel, radius=radius)
    forced = any(batch_options.get(k) is not None for k in ("scheduler", "processes"))
    if goals.shape[0] > _PARALLEL_POINTS or forced:
        out = map_chunks(kernel, [goals], chunk_size=_CHUNK, **batch_options)
    else:
        out = kernel(goals)
    return out.reshape(*gx.shape, 6)


def _check_heading(psi1: float) -> float:
    return check_finite("heading", psi1)


@dataclass(frozen=True, eq=False)
class PartitionMap:
    """Optimal Dubins word over a grid of final positions for one final heading (Fig 3.1).

    `x`, `y` are the grid axes (units of R0); `label_index[i, j]` indexes `labels` at
    (x[j], y[i]); a label joins near-tied optimal words with "/" (e.g. "LSL/RSR");
    `lengths[i, j, k]` is the length of `WORDS[k]` (units of R0, NaN when infeasible).
    """

    x: np.ndarray
    y: np.ndarray
    heading: float
    eps: float
    labels: tuple[str, ...]
    label_index: np.ndarray
    lengths: np.ndarray

    @property
    def label_grid(self) -> np.ndarray:
        """The labels as a string array `(ny, nx)`."""
        return np.asarray(self.labels, dtype=object)[self.label_index]

    def fractions(self) -> dict[str, float]:
        """Fraction of grid points carrying each label."""
        counts = np.bincount(self.label_index.ravel(), minlength=len(self.labels))
        return {
            lab: float(c) / self.label_index.size
            for lab, c in zip(self.labels, counts, strict=True)
        }

    def label_at(self, x: float, y: float) -> str:
        """The label of the grid point nearest to (x, y)."""
        j = int(np.argmin(np.abs(self.x - x)))
        i = int(np.argmin(np.abs(self.y - y)))
        return self.labels[int(self.label_index[i, j])]

    def columns(self) -> dict[str, np.ndarray]:
        """Flat columns for a table: x, y, label and the six word lengths."""
        gx, gy = np.meshgrid(self.x, self.y)
        out: dict[str, np.ndarray] = {
            "x": gx.ravel(),
            "y": gy.ravel(),
            "label": self.label_grid.ravel().astype(str),
        }
        for k, w in enumerate(WORDS):
            out[f"length_{w}"] = self.lengths[..., k].ravel()
        return out


def partition_map(
    psi1: float,
    extent: float = 6.0,
    n: int = 121,
    eps: float = 0.0,
    *,
    rel_tol: float = 1e-9,
    **batch_options: Any,
) -> PartitionMap:
    """Partition of the plane by optimal Dubins word for final heading `psi1` (rad) (Fig 3.1).

    Section 3.3 / Bui et al. (1994): goals (x, y, psi1) on an `n` x `n` grid over
    [-extent, extent]^2 in units of R0, planned with radius R0 (1 + eps)^2 (eq. 3.3). Words
    within `rel_tol` (relative to max(1, optimal length)) of the optimum share the label, e.g.
    "LSL/RSR". `batch_options` (scheduler, processes, progress) go to `run_batch` for big grids.
    """
    psi1 = _check_heading(psi1)
    eps = check_in_range("eps", eps, 0.0, 1.0, high_open=True)
    rel_tol = check_in_range("rel_tol", rel_tol, 0.0, 1e-3)
    x = grid_axis(extent, n)
    y = x.copy()
    radius = float(feasible_radius(1.0, eps))
    lengths = _grid_word_lengths(x, y, psi1, radius, batch_options)
    filled = np.where(np.isnan(lengths), np.inf, lengths)
    best = filled.min(axis=-1, keepdims=True)
    tied = filled - best <= rel_tol * np.maximum(best, 1.0)
    codes = tied @ (1 << np.arange(len(WORDS)))
    uniq, inverse = np.unique(codes, return_inverse=True)
    labels = tuple("/".join(w for k, w in enumerate(WORDS) if c >> k & 1) for c in uniq)
    return PartitionMap(
        x=x,
        y=y,
        heading=psi1,
        eps=eps,
        labels=labels,
        label_index=inverse.reshape(codes.shape),
        lengths=lengths,
    )


@dataclass(frozen=True, eq=False)
class TradespaceMap:
    """The ratio T = d_feasible / d_optimal over a grid of final positions (Fig 3.2).

    `ratio[i, j]` at (x[j], y[i]) (units of R0); NaN where d_optimal = 0 (goal = start).
    `word_optimal` / `word_feasible` index `WORDS`.
    """

    x: np.ndarray
    y: np.ndarray
    heading: float
    eps: float
    ratio: np.ndarray
    d_optimal: np.ndarray
    d_feasible: np.ndarray
    word_optimal: np.ndarray
    word_feasible: np.ndarray

    def ratio_at(self, x: float, y: float) -> float:
        """T at the grid point nearest to (x, y)."""
        j = int(np.argmin(np.abs(self.x - x)))
        i = int(np.argmin(np.abs(self.y - y)))
        return float(self.ratio[i, j])

    def columns(self) -> dict[str, np.ndarray]:
        """Flat columns for a table: x, y, ratio, both lengths and both words."""
        gx, gy = np.meshgrid(self.x, self.y)
        words = np.asarray(WORDS)
        return {
            "x": gx.ravel(),
            "y": gy.ravel(),
            "ratio": self.ratio.ravel(),
            "d_optimal": self.d_optimal.ravel(),
            "d_feasible": self.d_feasible.ravel(),
            "word_optimal": words[self.word_optimal].ravel(),
            "word_feasible": words[self.word_feasible].ravel(),
        }


@dataclass(frozen=True)
class PartitionRegion:
    """A connected region of one label: its label, size (grid points) and an interior point."""

    label: str
    points: int
    x: float
    y: float


def partition_regions(pmap: PartitionMap, min_points: int = 12) -> list[PartitionRegion]:
    """The connected 2-D regions of a partition, largest first (thin boundary strips dropped).

    A region needs at least `min_points` grid points and a width of 3 points in x and y; its
    interior point is the one farthest from the region's edge (regions need not be convex).
    """
    from scipy import ndimage

    regions: list[PartitionRegion] = []
    for k, label in enumerate(pmap.labels):
        components, count = ndimage.label(pmap.label_index == k)
        for r in range(1, count + 1):
            mask = components == r
            ii, jj = np.nonzero(mask)
            if ii.size < min_points or np.ptp(ii) < 3 or np.ptp(jj) < 3:
                continue
            depth = ndimage.distance_transform_edt(np.pad(mask, 1))[1:-1, 1:-1]
            i, j = np.unravel_index(int(np.argmax(depth)), depth.shape)
            regions.append(PartitionRegion(label, int(ii.size), float(pmap.x[j]), float(pmap.y[i])))
    return sorted(regions, key=lambda r: -r.points)


def tradespace_ratio(x: Any, y: Any, psi1: Any, eps: Any) -> np.ndarray:
    """T(x1, y1, psi1, eps) = d_feasible / d_optimal at goals in units of R0 (section 3.3).

    Pure function broadcasting over its arguments; NaN where d_optimal = 0.
    """
    from glideplan.planners.dubins import dubins_distance

    e = np.asarray(eps, dtype=float)
    if not np.all(np.isfinite(e)) or np.any((e < 0.0) | (e >= 1.0)):
        raise InvalidParameterError("eps", eps, "must lie in [0, 1)")
    xb, yb, hb, eb = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (x, y, psi1)), e)
    goals = np.stack([xb, yb, hb], axis=-1)
    d_opt = np.asarray(dubins_distance(np.zeros(3), goals, 1.0))
    d_feas = np.asarray(dubins_distance(np.zeros(3), goals, feasible_radius(1.0, eb)))
    return _ratio(d_feas, d_opt)


def _ratio(d_feas: np.ndarray, d_opt: np.ndarray) -> np.ndarray:
    out = np.full(np.shape(d_opt), np.nan)
    np.divide(d_feas, d_opt, out=out, where=d_opt > 0.0)
    return out


def tradespace_map(
    psi1: float,
    eps: float = 0.25,
    extent: float = 6.0,
    n: int = 121,
    **batch_options: Any,
) -> TradespaceMap:
    """T(x1, y1, psi1, eps) = d_feasible / d_optimal on an `n` x `n` grid (Fig 3.2).

    Section 3.3: d_optimal is planned with R0 = 1, d_feasible with R0' = (1 + eps)^2
    (eq. 3.3), goals (x, y, psi1) over [-extent, extent]^2 in units of R0.
    """
    psi1 = _check_heading(psi1)
    eps = check_in_range("eps", eps, 0.0, 1.0, high_open=True)
    x = grid_axis(extent, n)
    y = x.copy()
    words = []
    dists = []
    for radius in (1.0, float(feasible_radius(1.0, eps))):
        lengths = _grid_word_lengths(x, y, psi1, radius, batch_options)
        filled = np.where(np.isnan(lengths), np.inf, lengths)
        idx = np.argmin(filled, axis=-1)
        words.append(idx)
        dists.append(np.take_along_axis(filled, idx[..., None], axis=-1)[..., 0])
    return TradespaceMap(
        x=x,
        y=y,
        heading=psi1,
        eps=eps,
        ratio=_ratio(dists[1], dists[0]),
        d_optimal=dists[0],
        d_feasible=dists[1],
        word_optimal=words[0],
        word_feasible=words[1],
    )
