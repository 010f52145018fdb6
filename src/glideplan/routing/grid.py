"""A local azimuthal-equidistant plane about a point, and the field on it (glider scale).

Routes are solved on the sphere (`routing.window`, `routing.phases`); this plane grid serves
the glider-scale tools that work in one local plane (`routing.glider`'s flyable paths, the
mission legs' end courses, the grid A* baseline of `benchmarks/route.py`).

Nodes (x_j, y_i) in metres (x east, y north at the start); `water` marks nodes inside the
field's extent where the current is finite (NaN = land = obstacle). Currents are rotated from
(east, north) into the local axes at each node (meridian convergence of the projection):
c_local = u e_hat + v n_hat, with n_hat, e_hat the local images of true north and east.
`CurrentSampler` gives the current on the grid at any time by linear interpolation between
time levels (the field's own levels, or regular samples of an analytic field), evaluated
lazily and cached, so only the levels the front needs are ever computed.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.geodesy import LocalProjection

__all__ = ["CurrentSampler", "RouteGrid", "build_grid", "interp_grid", "local_rotation"]

FloatArray = NDArray[np.float64]
_NORTH_STEP_DEG = 1e-4


def local_rotation(proj: LocalProjection, lat: FloatArray, lon: FloatArray) -> tuple[
    FloatArray, FloatArray
]:
    """(cos g, sin g): the local direction of true north is (-sin g, cos g) in (x, y)."""
    lat_c = np.clip(lat, -89.9, 89.9 - _NORTH_STEP_DEG)
    x0, y0 = proj.to_local(lat_c, lon)
    x1, y1 = proj.to_local(lat_c + _NORTH_STEP_DEG, lon)
    dx, dy = x1 - x0, y1 - y0
    norm = np.hypot(dx, dy)
    return dy / norm, -dx / norm


def rotate_to_local(u: FloatArray, v: FloatArray, cos_g: FloatArray, sin_g: FloatArray) -> tuple[
    FloatArray, FloatArray
]:
    """Local (x, y) components of an (east, north) vector: north -> (-sin g, cos g)."""
    return u * cos_g - v * sin_g, u * sin_g + v * cos_g


@dataclass(frozen=True, eq=False)
class RouteGrid:
    """Nodes of the local plane and what lies on them (module docstring)."""

    proj: LocalProjection
    x: FloatArray
    y: FloatArray
    lat: FloatArray
    lon: FloatArray
    cos_g: FloatArray
    sin_g: FloatArray
    inside: NDArray[np.bool_]
    spacing: float

    @property
    def shape(self) -> tuple[int, int]:
        return self.y.size, self.x.size


def build_grid(
    field_: FlowField,
    proj: LocalProjection,
    goal_xy: tuple[float, float],
    resolution: float | None,
    margin: float = 0.5,
    cells: int = 200,
) -> RouteGrid:
    """Grid over the start-goal box grown by `margin` x distance, clipped to the field."""
    gx, gy = goal_xy
    dist = math.hypot(gx, gy)
    pad = max(margin * dist, 1.0)
    x0, x1 = min(0.0, gx) - pad, max(0.0, gx) + pad
    y0, y1 = min(0.0, gy) - pad, max(0.0, gy) + pad
    h = float(resolution) if resolution is not None else max(x1 - x0, y1 - y0) / cells
    if not (math.isfinite(h) and h > 0):
        raise InvalidParameterError("resolution", resolution, "must be finite and > 0 (m)")
    if dist < 4 * h:
        raise InvalidParameterError(
            "resolution", h, f"too coarse: start and goal are {dist:.0f} m apart (need >= 4 cells)"
        )
    xs = np.arange(math.floor(x0 / h), math.ceil(x1 / h) + 1) * h
    ys = np.arange(math.floor(y0 / h), math.ceil(y1 / h) + 1) * h
    if xs.size * ys.size > 4_000_000:
        raise InvalidParameterError(
            "resolution", h, f"gives {xs.size} x {ys.size} nodes (limit 4e6): choose a coarser one"
        )
    xx, yy = np.meshgrid(xs, ys)
    lat, lon = proj.to_geographic(xx, yy)
    ext = field_.extent
    if ext is not None:
        lon_f = ext.lon_min + np.mod(lon - ext.lon_min, 360.0)
        inside = (lat >= ext.lat_min) & (lat <= ext.lat_max) & (lon_f >= ext.lon_min) & (
            lon_f <= ext.lon_max)
        rows, cols = np.nonzero(inside)
        if rows.size == 0:
            raise InvalidParameterError("field", "extent", "does not cover the route's area")
        r0, r1 = max(rows.min() - 1, 0), min(rows.max() + 2, ys.size)
        c0, c1 = max(cols.min() - 1, 0), min(cols.max() + 2, xs.size)
        xs, ys = xs[c0:c1], ys[r0:r1]
        lat, lon, inside = lat[r0:r1, c0:c1], lon[r0:r1, c0:c1], inside[r0:r1, c0:c1]
    else:
        inside = np.ones(lat.shape, dtype=bool)
    cos_g, sin_g = local_rotation(proj, lat, lon)
    return RouteGrid(proj, np.asarray(xs, dtype=float), np.asarray(ys, dtype=float), lat, lon,
                     cos_g, sin_g, inside, h)


@dataclass(eq=False)
class CurrentSampler:
    """Local current (cx, cy) on the grid at any time, linear between cached time levels."""

    grid: RouteGrid
    field_: FlowField
    levels: FloatArray
    _cache: dict[int, tuple[FloatArray, FloatArray]] = field(default_factory=dict)
    _grad: dict[int, FloatArray] = field(default_factory=dict)
    _stacked: dict[int, FloatArray] = field(default_factory=dict)
    evaluations: int = 0
    max_cached: int = 128

    @classmethod
    def for_span(cls, grid: RouteGrid, field_: FlowField, t0: float, t1: float,
                 sample_dt: float) -> CurrentSampler:
        """Levels: the field's own (bracketing [t0, t1]) or every `sample_dt` seconds."""
        own = field_.time_levels
        if own is not None:
            i0 = max(int(np.searchsorted(own, t0, side="right")) - 1, 0)
            i1 = min(int(np.searchsorted(own, t1, side="left")), own.size - 1)
            levels = np.asarray(own[i0:i1 + 1], dtype=float)
        elif _is_steady(field_):
            levels = np.array([t0])
        else:
            n = max(math.ceil((t1 - t0) / sample_dt), 1)
            levels = t0 + np.arange(n + 1) * ((t1 - t0) / n)
        return cls(grid, field_, levels)

    def level(self, k: int) -> tuple[FloatArray, FloatArray]:
        """(cx, cy) on the grid at level k; NaN at land and outside the field."""
        if k not in self._cache:
            g = self.grid
            u = np.full(g.shape, np.nan)
            v = np.full(g.shape, np.nan)
            m = g.inside
            uu, vv = self.field_.velocity(self.levels[k], g.lat[m], g.lon[m])
            u[m], v[m] = uu, vv
            self._cache[k] = rotate_to_local(u, v, g.cos_g, g.sin_g)
            self.evaluations += 1
            if len(self._cache) > self.max_cached:
                self._cache.pop(next(iter(self._cache)))
        else:  # least recently used goes first
            self._cache[k] = self._cache.pop(k)
        return self._cache[k]

    def level_with_gradient(self, k: int) -> FloatArray:
        """(6, ny, nx): cx, cy, dcx/dx, dcx/dy, dcy/dx, dcy/dy at level k (NaN near land)."""
        if k not in self._grad:
            cx, cy = self.level(k)
            h = self.grid.spacing
            dcx_dy, dcx_dx = np.gradient(cx, h)
            dcy_dy, dcy_dx = np.gradient(cy, h)
            self._grad[k] = np.stack([cx, cy, dcx_dx, dcx_dy, dcy_dx, dcy_dy])
            if len(self._grad) > self.max_cached:
                self._grad.pop(next(iter(self._grad)))
        return self._grad[k]

    def level_stacked(self, k: int) -> FloatArray:
        """(2, ny, nx): cx, cy at level k."""
        if k not in self._stacked:
            self._stacked[k] = np.stack(self.level(k))
            if len(self._stacked) > self.max_cached:
                self._stacked.pop(next(iter(self._stacked)))
        return self._stacked[k]

    def points_multi(self, t: FloatArray, x: FloatArray, y: FloatArray) -> FloatArray:
        """(cx, cy) at points with their own times t (grouped by time bracket: few groups)."""
        lv = self.levels
        if lv.size == 1:
            return interp_grid(self.level_stacked(0), self.grid, x, y)
        ks = np.clip(np.searchsorted(lv, t, side="right") - 1, 0, lv.size - 2)
        w = np.clip((t - lv[ks]) / (lv[ks + 1] - lv[ks]), 0.0, 1.0)
        out = np.empty((2, np.size(x)))
        for k in np.unique(ks):
            sel = ks == k
            a = interp_grid(self.level_stacked(int(k)), self.grid, x[sel], y[sel])
            b = interp_grid(self.level_stacked(int(k) + 1), self.grid, x[sel], y[sel])
            out[:, sel] = (1 - w[sel]) * a + w[sel] * b
        return out

    def points(self, t: float, x: FloatArray, y: FloatArray, gradient: bool = False) -> FloatArray:
        """Values at points (x, y) at time t: rows cx, cy (and the 4 derivatives), bilinear."""
        k, w = self.bracket(t)
        get = self.level_with_gradient if gradient else self.level_stacked
        vals = interp_grid(get(k), self.grid, x, y)
        if w > 0.0 and self.levels.size > 1:
            vals = (1 - w) * vals + w * interp_grid(get(k + 1), self.grid, x, y)
        return vals

    def bracket(self, t: float) -> tuple[int, float]:
        """Level index k and weight w with t between levels k and k+1."""
        lv = self.levels
        if lv.size == 1:
            return 0, 0.0
        k = int(np.clip(np.searchsorted(lv, t, side="right") - 1, 0, lv.size - 2))
        w = float(np.clip((t - lv[k]) / (lv[k + 1] - lv[k]), 0.0, 1.0))
        return k, w

    def at(self, t: float) -> tuple[FloatArray, FloatArray]:
        """(cx, cy) on the grid at time t (s since epoch)."""
        k, w = self.bracket(t)
        a = self.level(k)
        if w == 0.0 or self.levels.size == 1:
            return a
        b = self.level(k + 1)
        return (1 - w) * a[0] + w * b[0], (1 - w) * a[1] + w * b[1]

    def box_at(self, t: float, i0: int, i1: int, j0: int, j1: int) -> tuple[
        FloatArray, FloatArray
    ]:
        """(cx, cy) on the sub-grid [i0:i1, j0:j1] at time t (linear between levels)."""
        k, w = self.bracket(t)
        a = self.level(k)
        if w == 0.0 or self.levels.size == 1:
            return a[0][i0:i1, j0:j1], a[1][i0:i1, j0:j1]
        b = self.level(k + 1)
        return ((1 - w) * a[0][i0:i1, j0:j1] + w * b[0][i0:i1, j0:j1],
                (1 - w) * a[1][i0:i1, j0:j1] + w * b[1][i0:i1, j0:j1])

    def land(self) -> NDArray[np.bool_]:
        """Nodes where the current is NaN at the first level, or outside the field."""
        cx, _ = self.level(0)
        return ~np.isfinite(cx)


def interp_grid(a: FloatArray, grid: RouteGrid, x: FloatArray, y: FloatArray) -> FloatArray:
    """Bilinear values of stacked grid arrays a (m, ny, nx) at points (x, y) -> (m, npts).

    Points outside the grid get NaN."""
    xa = np.atleast_1d(np.asarray(x, dtype=float))
    ya = np.atleast_1d(np.asarray(y, dtype=float))
    h = grid.spacing
    fx = (xa - grid.x[0]) / h
    fy = (ya - grid.y[0]) / h
    nx, ny = grid.x.size, grid.y.size
    out_of = ~((fx >= -1e-9) & (fx <= nx - 1 + 1e-9) & (fy >= -1e-9) & (fy <= ny - 1 + 1e-9))
    if out_of.any():  # NaN or outside: evaluate at node 0, then blank
        fx = np.where(out_of, 0.0, fx)
        fy = np.where(out_of, 0.0, fy)
    j = np.minimum(np.maximum(np.floor(fx), 0), nx - 2).astype(np.intp)
    i = np.minimum(np.maximum(np.floor(fy), 0), ny - 2).astype(np.intp)
    wx = np.minimum(np.maximum(fx - j, 0.0), 1.0)
    wy = np.minimum(np.maximum(fy - i, 0.0), 1.0)
    flat = a.reshape(a.shape[0], -1)
    k = i * nx + j
    v = ((1 - wy) * ((1 - wx) * flat[:, k] + wx * flat[:, k + 1])
         + wy * ((1 - wx) * flat[:, k + nx] + wx * flat[:, k + nx + 1]))
    if out_of.any():
        v[:, out_of] = np.nan
    return v


def _is_steady(field_: Any) -> bool:
    from glideplan.fields.field import GriddedField, UniformField

    return isinstance(field_, UniformField) or (
        isinstance(field_, GriddedField) and field_.times.size == 1
    )
