"""The routing window: a lat/lon grid about the start and goal that grows with the front.

Nodes sit on one lattice for the whole solve: lat_i = lat_s + i dlat, lon_j = lon_s + j dlon
(degrees), (lat_s, lon_s) the start, longitudes in a frame unwrapped about the start (the goal
is taken within 180 deg of it, so a route across 0 or 180 deg is continuous). dlat = h / R
(h the spacing in metres), dlon = dlat / cos(lat_ref) rounded so that 360 / dlon is an
integer (lat_ref the mean |latitude| of start and goal, at most 80 deg): a window that grows
to the whole circle of a global field closes exactly (`periodic`). Because the nodes never
move, a grown window holds the old one as a block (the front's state is embedded in it).

The lattice is bounded by the field's extent (in the frame) and by +-85 deg latitude (the
metric's cos(lat) vanishes at the poles; on grids coarser than ~0.7 deg, 89 deg less the edge
pad); `fixed_sides` are the window's sides on a bound.

`WindowCurrents` samples the field on the window at time levels (the field's own, one for a
steady field, or every `sample_dt` seconds for an analytic one), lazily, and interpolates
linearly in time; `obstacles` (`routing.land`, with the other land helpers) marks the nodes
within the land clearance of land: the land points are the field's own NaN nodes (for a
gridded field; its linear interpolation reads NaN anywhere within one cell of them) and the
window's NaN nodes, at their coasts; the distance is the great-circle distance (a k-d tree
on 3-D positions, chord radius 2 R sin(c / 2R)).
"""

from __future__ import annotations

import bisect
import math
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, GriddedField, UniformField
from glideplan.routing.land import (  # the land helpers, one import away
    _coast as _coast,
)
from glideplan.routing.land import (
    _xyz as _xyz,
)
from glideplan.routing.land import (
    distance_to_land as distance_to_land,
)
from glideplan.routing.land import (
    land_clearance_default as land_clearance_default,
)
from glideplan.routing.land import (
    land_points as land_points,
)
from glideplan.routing.land import (
    obstacles as obstacles,
)
from glideplan.routing.sphere import EARTH_RADIUS_M, unwrap_lon

__all__ = ["MAX_LAT_DEG", "Lattice", "Window", "WindowCurrents", "initial_window",
           "land_clearance_default", "obstacles"]

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]

#: The window never goes beyond this latitude (deg): hx = R cos(lat) dlon -> 0 at the poles.
MAX_LAT_DEG = 85.0
SIDES = ("south", "north", "west", "east")
#: Nodes beyond the field's edge (or +-85 deg) in a window that reaches it: obstacles, so the
#: front's band never comes within the kernel's edge margin of a side that cannot grow.
EDGE_PAD = 5


@dataclass(frozen=True)
class Lattice:
    """Node lattice (module docstring): origin (start), steps (deg), index bounds (inclusive;
    jmin/jmax None when longitude is unbounded: a global or unbounded field)."""

    lat0: float
    lon0: float
    dlat: float
    dlon: float
    imin: int
    imax: int
    jmin: int | None
    jmax: int | None
    spacing_m: float

    @property
    def n_circle(self) -> int:
        return round(360.0 / self.dlon)

    @property
    def wraps(self) -> bool:
        return self.jmin is None


def build_lattice(fld: FlowField, start: tuple[float, float], goal_frame: tuple[float, float],
                  spacing: float) -> Lattice:
    """The lattice of spacing `spacing` (m) about `start`, bounded by the field (docstring)."""
    lat_ref = min(0.5 * (abs(start[0]) + abs(goal_frame[0])), 80.0)
    dlat = math.degrees(spacing / EARTH_RADIUS_M)
    n = max(round(360.0 / (dlat / math.cos(math.radians(lat_ref)))), 8)
    dlon = 360.0 / n
    ext = fld.extent
    # +-85 deg, or less on coarse grids: the edge pad must fit before the kernel's 89 deg
    cap = min(MAX_LAT_DEG, 89.0 - (EDGE_PAD + 0.5) * dlat)
    lat_lo, lat_hi = -cap, cap
    jmin: int | None = None
    jmax: int | None = None
    if ext is not None:
        lat_lo, lat_hi = max(lat_lo, ext.lat_min), min(lat_hi, ext.lat_max)
        if not ext.periodic:
            lo_min = start[1] - float(np.mod(start[1] - ext.lon_min, 360.0))
            lo_max = lo_min + (ext.lon_max - ext.lon_min)
            jmin = math.ceil((lo_min - start[1]) / dlon - 1e-9)
            jmax = math.floor((lo_max - start[1]) / dlon + 1e-9)
    imin = math.ceil((lat_lo - start[0]) / dlat - 1e-9)
    imax = math.floor((lat_hi - start[0]) / dlat + 1e-9)
    return Lattice(float(start[0]), float(start[1]), dlat, dlon, imin, imax, jmin, jmax,
                   float(spacing))




@dataclass(frozen=True)
class Window:
    """Rows i0..i1-1 and columns j0..j1-1 of the lattice (periodic: the whole circle).

    Where the window reaches a bound of the lattice it holds EDGE_PAD more nodes beyond it,
    outside the field (`inside` False): obstacles, the field's edge as a wall."""

    lattice: Lattice
    i0: int
    i1: int
    j0: int
    j1: int
    periodic: bool = False

    @property
    def shape(self) -> tuple[int, int]:
        return self.i1 - self.i0, self.j1 - self.j0

    @property
    def lat(self) -> FloatArray:
        return np.asarray(self.lattice.lat0 + np.arange(self.i0, self.i1) * self.lattice.dlat,
                          dtype=float)

    @property
    def lon(self) -> FloatArray:
        return np.asarray(self.lattice.lon0 + np.arange(self.j0, self.j1) * self.lattice.dlon,
                          dtype=float)

    @property
    def nodes(self) -> int:
        return self.shape[0] * self.shape[1]

    @property
    def inside(self) -> BoolArray:
        """Nodes inside the field's extent (and within +-85 deg)."""
        L = self.lattice
        i = np.arange(self.i0, self.i1)
        rows = (i >= L.imin) & (i <= L.imax)
        if self.periodic or L.jmin is None or L.jmax is None:
            cols = np.ones(self.shape[1], dtype=bool)
        else:
            j = np.arange(self.j0, self.j1)
            cols = (j >= L.jmin) & (j <= L.jmax)
        return rows[:, None] & cols[None, :]

    def grid(self) -> Any:
        """The front kernel's `LatLonGrid` of this window."""
        from glideplan.fronts.grid import LatLonGrid

        return LatLonGrid(lat=self.lat, lon=self.lon, periodic=self.periodic,
                          radius_m=EARTH_RADIUS_M)

    def fixed_sides(self) -> set[str]:
        """Sides on a bound of the lattice (the field's edge, or +-85 deg): they cannot grow."""
        L = self.lattice
        out = set()
        if self.i0 <= L.imin:
            out.add("south")
        if self.i1 - 1 >= L.imax:
            out.add("north")
        if not self.periodic and L.jmin is not None and self.j0 <= L.jmin:
            out.add("west")
        if not self.periodic and L.jmax is not None and self.j1 - 1 >= L.jmax:
            out.add("east")
        return out

    def _clip(self, i0: int, i1: int, j0: int, j1: int) -> tuple[int, int, int, int]:
        L = self.lattice
        lat_lim = 89.0 - 1e-6
        if i0 <= L.imin:
            i0 = max(L.imin - EDGE_PAD, math.ceil((-lat_lim - L.lat0) / L.dlat))
        if i1 - 1 >= L.imax:
            i1 = min(L.imax + EDGE_PAD, math.floor((lat_lim - L.lat0) / L.dlat)) + 1
        if L.jmin is not None and j0 <= L.jmin:
            j0 = L.jmin - EDGE_PAD
        if L.jmax is not None and j1 - 1 >= L.jmax:
            j1 = L.jmax + EDGE_PAD + 1
        return i0, i1, j0, j1

    def grown(self, sides: set[str], by: int | None = None) -> Window:
        """The window grown on `sides` by `by` nodes (default half its size, >= 16), clipped
        to the lattice (with the edge pad); a window of a wrapping lattice that reaches 360 deg
        becomes periodic."""
        L = self.lattice
        ny, nx = self.shape
        i0, i1, j0, j1 = self.i0, self.i1, self.j0, self.j1
        if "south" in sides:
            i0 -= by or max(ny // 2, 16)
        if "north" in sides:
            i1 += by or max(ny // 2, 16)
        if not self.periodic:
            if "west" in sides:
                j0 -= by or max(nx // 2, 16)
            if "east" in sides:
                j1 += by or max(nx // 2, 16)
        i0, i1, j0, j1 = self._clip(i0, i1, j0, j1)
        periodic = self.periodic
        if not periodic and L.wraps and j1 - j0 >= L.n_circle - 1:
            periodic = True
            mid = (self.j0 + self.j1) // 2
            j0 = mid - L.n_circle // 2
            j1 = j0 + L.n_circle
        return replace(self, i0=i0, i1=i1, j0=j0, j1=j1, periodic=periodic)

    def frac_index(self, lat: Any, lon: Any) -> tuple[FloatArray, FloatArray]:
        """Fractional (row, column) in the window of points (deg; lon any representation)."""
        L = self.lattice
        fi = (np.asarray(lat, dtype=float) - L.lat0) / L.dlat - self.i0
        centre = L.lon0 + 0.5 * (self.j0 + self.j1 - 1) * L.dlon
        lo = unwrap_lon(lon, centre)
        fj = (lo - L.lon0) / L.dlon - self.j0
        if self.periodic:
            fj = np.mod(fj, L.n_circle)
        return fi, fj

    def offset_in(self, big: Window) -> tuple[int, int]:
        """(row, column) of this window's first node in the larger window `big`."""
        return self.i0 - big.i0, self.j0 - big.j0


def initial_window(lattice: Lattice, goal_frame: tuple[float, float], distance: float,
                   margin: float, min_cells: int = 10) -> Window:
    """The start-goal box grown by margin x distance + `min_cells` nodes each side, clipped
    to the lattice (with the edge pad where it reaches a bound)."""
    L = lattice
    gi = (goal_frame[0] - L.lat0) / L.dlat
    gj = (goal_frame[1] - L.lon0) / L.dlon
    pad_m = margin * distance
    pad_i = pad_m / L.spacing_m + min_cells
    lat_ref = min(max(abs(L.lat0), abs(goal_frame[0])), MAX_LAT_DEG)
    hx_ref = EARTH_RADIUS_M * math.cos(math.radians(lat_ref)) * math.radians(L.dlon)
    pad_j = pad_m / hx_ref + min_cells
    i0 = math.floor(min(0.0, gi) - pad_i)
    i1 = math.ceil(max(0.0, gi) + pad_i) + 1
    j0 = math.floor(min(0.0, gj) - pad_j)
    j1 = math.ceil(max(0.0, gj) + pad_j) + 1
    w = Window(L, i0, i1, j0, j1)
    i0, i1, j0, j1 = w._clip(i0, i1, j0, j1)
    w = Window(L, i0, i1, j0, j1)
    if L.wraps and j1 - j0 >= L.n_circle - 1:
        w = w.grown(set())
    if min(w.shape) < 3:
        raise InvalidParameterError("field", "extent", "too small for a routing grid here")
    return w


def _is_steady(fld: FlowField) -> bool:
    return isinstance(fld, UniformField) or (isinstance(fld, GriddedField)
                                             and fld.times.size == 1)


@dataclass(eq=False)
class WindowCurrents:
    """The field on the window's nodes at time levels, linear in time (module docstring).

    levels: the field's own time levels, [t0] for a steady field, or None for an analytic
    unsteady one (then level k is at t0 + k sample_dt)."""

    window: Window
    field_: FlowField
    t0: float
    sample_dt: float
    levels: FloatArray | None
    _cache: dict[int, tuple[FloatArray, FloatArray]] = field(default_factory=dict)
    evaluations: int = 0
    _flat_cache: dict[int, tuple[FloatArray, FloatArray]] = field(default_factory=dict)

    @classmethod
    def build(cls, window: Window, fld: FlowField, t0: float, sample_dt: float) -> WindowCurrents:
        own = fld.time_levels
        if _is_steady(fld):
            levels: FloatArray | None = np.array([t0])
        elif own is not None:
            levels = np.asarray(own, dtype=float)
        else:
            levels = None
        return cls(window, fld, t0, sample_dt, levels)

    def regrown(self, window: Window) -> WindowCurrents:
        """The same levels on a grown window: cached levels keep their values on the old
        block; only the new nodes are sampled."""
        new = WindowCurrents(window, self.field_, self.t0, self.sample_dt, self.levels)
        new.evaluations = self.evaluations
        old = self.window
        r0, c0 = old.offset_in(window)
        ny, nx = old.shape
        known = np.zeros(window.shape, dtype=bool)
        known[r0:r0 + ny, c0:c0 + nx] = old.inside
        todo = window.inside & ~known
        LA, LO = np.meshgrid(window.lat, window.lon, indexing="ij")
        for k, (u_old, v_old) in self._cache.items():
            fast = new._own_level(k)
            if fast is not None:
                new._cache[k] = fast
                continue
            u = np.full(window.shape, np.nan)
            v = np.full(window.shape, np.nan)
            u[r0:r0 + ny, c0:c0 + nx] = u_old
            v[r0:r0 + ny, c0:c0 + nx] = v_old
            if todo.any():
                uu, vv = self.field_.velocity(self.level_time(k), LA[todo], LO[todo])
                u[todo], v[todo] = uu, vv
            u[~window.inside] = np.nan
            v[~window.inside] = np.nan
            new._cache[k] = (u, v)
        return new

    @property
    def steady(self) -> bool:
        return self.levels is not None and self.levels.size == 1

    def level_time(self, k: int) -> float:
        if self.levels is not None:
            return float(self.levels[k])
        return self.t0 + k * self.sample_dt

    def bracket(self, t: float) -> tuple[int, float]:
        """Level k and weight w in [0, 1] with t between levels k and k + 1."""
        if self.levels is not None:
            lv = self.levels
            if lv.size == 1:
                return 0, 0.0
            k = min(max(bisect.bisect_right(lv, t) - 1, 0), lv.size - 2)
            a, b = float(lv[k]), float(lv[k + 1])
            return k, min(max((t - a) / (b - a), 0.0), 1.0)
        f = max((t - self.t0) / self.sample_dt, 0.0)
        k = math.floor(f)
        return k, f - k

    def _own_level(self, k: int) -> tuple[FloatArray, FloatArray] | None:
        """Level k of a gridded field sampled on the whole window lattice at once
        (`GriddedField.lattice_level`: the same bilinear values, ~10x faster), or None."""
        from glideplan.fields.field import GriddedField

        fld = self.field_
        if not isinstance(fld, GriddedField) or self.levels is None:
            return None
        if fld.times.size != self.levels.size:
            return None
        u, v = fld.lattice_level(k, self.window.lat, self.window.lon)
        out = ~self.window.inside
        u[out] = np.nan
        v[out] = np.nan
        return u, v

    def level(self, k: int) -> tuple[FloatArray, FloatArray]:
        """(u, v) east/north m/s on the window at level k; NaN on land."""
        if k not in self._cache:
            fast = self._own_level(k)
            if fast is not None:
                u, v = fast
            else:
                LA, LO = np.meshgrid(self.window.lat, self.window.lon, indexing="ij")
                m = self.window.inside
                u = np.full(m.shape, np.nan)
                v = np.full(m.shape, np.nan)
                uu, vv = self.field_.velocity(self.level_time(k), LA[m], LO[m])
                u[m], v[m] = uu, vv
            self._cache[k] = (u, v)
            self.evaluations += 1
            if len(self._cache) > 64:  # least recently used first
                self._cache.pop(next(iter(self._cache)))
        else:
            self._cache[k] = self._cache.pop(k)
        return self._cache[k]

    def peak_speed(self) -> float:
        """The largest current speed (m/s) on the window's nodes over the levels held (0
        where none is finite)."""
        best = 0.0
        for u, v in self._cache.values():
            s = np.hypot(u, v)
            if np.isfinite(s).any():
                best = max(best, float(np.nanmax(s)))
        return best

    def at(self, t: float) -> tuple[FloatArray, FloatArray]:
        """(u, v) on the window at time t, linear between levels."""
        k, w = self.bracket(t)
        a = self.level(k)
        if w == 0.0 or self.steady:
            return a
        b = self.level(k + 1)
        return (1 - w) * a[0] + w * b[0], (1 - w) * a[1] + w * b[1]

    def land(self) -> BoolArray:
        """Nodes inside the field where it is NaN at the first level."""
        u, v = self.level(0)
        return ~(np.isfinite(u) & np.isfinite(v)) & self.window.inside

    def points(self, t: float, lat: Any, lon: Any, gradient: bool = False) -> FloatArray:
        """Bilinear (u, v) at points at time t -> (2, n); with `gradient` also du/dlat,
        du/dlon, dv/dlat, dv/dlon (per radian, the cell's differences) -> rows u, du/dlat,
        du/dlon, v, dv/dlat, dv/dlon (6, n). NaN off the window or near land."""
        k, w = self.bracket(t)
        win = self.window
        L = win.lattice
        lat_a = np.atleast_1d(np.asarray(lat, dtype=float))
        fi = (lat_a - L.lat0) / L.dlat - win.i0
        centre = L.lon0 + 0.5 * (win.j0 + win.j1 - 1) * L.dlon
        lo = np.atleast_1d(np.asarray(lon, dtype=float))
        lo = centre - np.mod(centre - lo + 180.0, 360.0) + 180.0
        fj = (lo - L.lon0) / L.dlon - win.j0
        ny, nx = win.shape
        periodic = win.periodic
        if periodic:
            fj = np.mod(fj, nx)
        inside = (fi >= 0) & (fi <= ny - 1) & (fj >= 0) & (fj <= nx - 1 + (1 if periodic else 0))
        fi = np.where(inside, fi, 0.0)
        fj = np.where(inside, fj, 0.0)
        i = np.minimum(fi.astype(np.intp), ny - 2)
        j = fj.astype(np.intp)
        if not periodic:
            j = np.minimum(j, nx - 2)
        wy, wx = fi - i, fj - j
        j1 = np.mod(j + 1, nx) if periodic else j + 1
        idx = np.stack([i * nx + j, i * nx + j1, (i + 1) * nx + j, (i + 1) * nx + j1])
        c = self._flat(k)[:, idx]  # (2, 4, n)
        if w > 0.0 and not self.steady:
            c = (1 - w) * c + w * self._flat(k + 1)[:, idx]
        c00, c01, c10, c11 = c[:, 0], c[:, 1], c[:, 2], c[:, 3]
        val = (1 - wy) * ((1 - wx) * c00 + wx * c01) + wy * ((1 - wx) * c10 + wx * c11)
        if gradient:
            d_lat = ((1 - wx) * (c10 - c00) + wx * (c11 - c01)) / math.radians(L.dlat)
            d_lon = ((1 - wy) * (c01 - c00) + wy * (c11 - c10)) / math.radians(L.dlon)
            res = np.stack([val[0], d_lat[0], d_lon[0], val[1], d_lat[1], d_lon[1]])
        else:
            res = val
        if not inside.all():
            res[:, ~inside] = np.nan
        return res

    def _flat(self, k: int) -> FloatArray:
        """(2, ny * nx): u and v at level k, flattened."""
        u, v = self.level(k)
        key = -k - 1
        got = self._flat_cache.get(key)
        if got is None or got[0] is not u:
            got = (u, np.stack([u.ravel(), v.ravel()]))
            self._flat_cache[key] = got
            if len(self._flat_cache) > 8:
                self._flat_cache.pop(next(iter(self._flat_cache)))
        return got[1]
