"""Regrid a curvilinear ocean-model grid (ROMS, NEMO) to a regular lat/lon grid (NumPy).

Each component is interpolated linearly on its own source points (staggered grids: u on
`lat_u/lon_u`, v on `lat_v/lon_v`) over the source grid's own cells, each split into two
triangles (so a concave or curved grid boundary is never bridged, unlike a Delaunay
triangulation of the points). A target node inside a triangle (P_1, P_2, P_3) gets

    f(P) = sum_k w_k f(P_k),   w = barycentric weights of P (in the lat/lon plane),

NaN outside the source grid, and NaN when a corner is NaN (land stays land, as on regular
grids). The target spacing is the median distance between neighbouring source nodes, d
(degrees of arc): d in latitude and d / cos(lat_c) in longitude.

Grid-relative components (ROMS `u/v`, NEMO `vozocrtx/vomecrty`: along the grid's i and j
axes) are rotated to east/north by the angle alpha of the i axis counter-clockwise from east
(ROMS `angle`, else from the coordinates: alpha = atan2(d lat / di, cos(lat) d lon / di)):

    u_east = u cos(alpha) - v sin(alpha),   v_north = u sin(alpha) + v cos(alpha),

with cos(alpha) and sin(alpha) interpolated (not alpha, which wraps at +-pi).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError

__all__ = ["CurvilinearSource", "RegularGrid", "regrid_curvilinear"]

FloatArray = NDArray[np.float64]

_WHAT_TO_DO = ("regrid it to a regular lat/lon grid first (e.g. `cdo remapbil,r<nx>x<ny> in.nc "
               "out.nc`, or xESMF) and give that file")


@dataclass(frozen=True)
class CurvilinearSource:
    """One component on a curvilinear grid: values (nt, ny, nx); lat, lon (ny, nx) degrees."""

    values: FloatArray
    lat: FloatArray
    lon: FloatArray
    label: str = "lat/lon"


@dataclass(frozen=True)
class RegularGrid:
    """The regridded field: lat (nlat,), lon (nlon,) ascending degrees; u, v (nt, nlat, nlon)."""

    lat: FloatArray
    lon: FloatArray
    u: FloatArray
    v: FloatArray
    warnings: tuple[str, ...]
    outside: NDArray[np.bool_] | None = None  # (nlat, nlon): outside the source grid
    floor: NDArray[np.bool_] | None = None  # (nlat, nlon): a depth range below the sea floor


def _refuse(src: CurvilinearSource, reason: str) -> InvalidParameterError:
    ny, nx = src.lat.shape
    return InvalidParameterError(
        "field grid", f"curvilinear {ny}x{nx} ({src.label})",
        f"cannot be regridded ({reason}): {_WHAT_TO_DO}",
    )


def _unwrap_lon(lon: FloatArray, lon0: float) -> FloatArray:
    """Each longitude's representative within 180 degrees of lon0."""
    return lon0 + np.mod(lon - lon0 + 180.0, 360.0) - 180.0


def _native_spacing(src: CurvilinearSource, lon: FloatArray) -> float:
    """Median distance (degrees of arc) between neighbouring nodes along both grid axes."""
    coslat = np.cos(np.radians(src.lat))
    steps = []
    for axis in (0, 1):
        dlat = np.diff(src.lat, axis=axis)
        dlon = np.diff(lon, axis=axis) * 0.5 * (
            np.take(coslat, range(coslat.shape[axis] - 1), axis=axis)
            + np.take(coslat, range(1, coslat.shape[axis]), axis=axis))
        steps.append(np.hypot(dlat, dlon).ravel())
    d = np.concatenate(steps)
    d = d[np.isfinite(d) & (d > 0.0)]
    return float(np.median(d)) if d.size else math.nan


class _Triangles:
    """Barycentric weights of the target nodes in the source grid's own triangles.

    Each cell (j, i)-(j, i+1)-(j+1, i+1)-(j+1, i) is split into two triangles. Work happens in
    target index space (row = (lat - lat_0) / dlat, column = (lon - lon_0) / dlon), an affine
    image of the lat/lon plane, so barycentric weights are those of the plane; each triangle
    tests the target nodes of its bounding box.
    """

    def __init__(self, src: CurvilinearSource, lon: FloatArray, tlat: FloatArray,
                 tlon: FloatArray) -> None:
        ny, nx = src.lat.shape
        nlat, nlon = tlat.size, tlon.size
        row = (src.lat - tlat[0]) / (tlat[1] - tlat[0])
        col = (lon - tlon[0]) / (tlon[1] - tlon[0])
        jj, ii = np.meshgrid(np.arange(ny - 1), np.arange(nx - 1), indexing="ij")
        c00 = (jj * nx + ii).ravel()
        corners = np.concatenate([np.column_stack([c00, c00 + 1, c00 + nx + 1]),
                                  np.column_stack([c00, c00 + nx + 1, c00 + nx])])
        r, c = row.ravel()[corners], col.ravel()[corners]  # (ntri, 3)
        area2 = (r[:, 1] - r[:, 0]) * (c[:, 2] - c[:, 0]) - (r[:, 2] - r[:, 0]) * (
            c[:, 1] - c[:, 0])
        with np.errstate(invalid="ignore"):
            ok = np.isfinite(area2) & (np.abs(area2) > 1e-12)
        if not np.any(ok):
            raise _refuse(src, "no grid cell has an area (collinear or coincident nodes)")
        corners, r, c, area2 = corners[ok], r[ok], c[ok], area2[ok]
        r0 = np.maximum(np.ceil(r.min(axis=1) - 1e-9), 0).astype(np.intp)
        r1 = np.minimum(np.floor(r.max(axis=1) + 1e-9), nlat - 1).astype(np.intp)
        c0 = np.maximum(np.ceil(c.min(axis=1) - 1e-9), 0).astype(np.intp)
        c1 = np.minimum(np.floor(c.max(axis=1) + 1e-9), nlon - 1).astype(np.intp)
        nr, nc = np.maximum(r1 - r0 + 1, 0), np.maximum(c1 - c0 + 1, 0)
        count = nr * nc
        self.weights = np.zeros((nlat * nlon, 3))
        self.flat_index = np.zeros((nlat * nlon, 3), dtype=np.intp)
        self.inside = np.zeros(nlat * nlon, dtype=bool)
        self.shape = (nlat, nlon)
        ends = np.cumsum(count)
        budget = 2_000_000  # candidate (triangle, node) pairs per block
        start = 0
        while start < count.size:
            stop = int(np.searchsorted(ends, (ends[start] - count[start]) + budget, "right"))
            stop = max(stop, start + 1)
            self._block(np.arange(start, stop), corners, r, c, area2, r0, c0, nc, count, nlon)
            start = stop

    def _block(self, t: NDArray[np.intp], corners: NDArray[np.intp], r: FloatArray,
               c: FloatArray, area2: FloatArray, r0: NDArray[np.intp], c0: NDArray[np.intp],
               nc: NDArray[np.intp], count: NDArray[np.intp], nlon: int) -> None:
        """Test the bounding-box nodes of triangles t; keep those inside (weights >= -1e-9)."""
        k = count[t]
        tid = np.repeat(t, k)
        if tid.size == 0:
            return
        local = np.arange(tid.size) - np.repeat(np.cumsum(k) - k, k)
        qr = r0[tid] + local // nc[tid]
        qc = c0[tid] + local % nc[tid]
        rr, cc = r[tid], c[tid]
        # Barycentric weights of (qr, qc) in the triangle (rr_m, cc_m), m = 0, 1, 2.
        w1 = ((qr - rr[:, 0]) * (cc[:, 2] - cc[:, 0]) - (rr[:, 2] - rr[:, 0]) * (
            qc - cc[:, 0])) / area2[tid]
        w2 = ((rr[:, 1] - rr[:, 0]) * (qc - cc[:, 0]) - (qr - rr[:, 0]) * (
            cc[:, 1] - cc[:, 0])) / area2[tid]
        w0 = 1.0 - w1 - w2
        hit = (w0 >= -1e-9) & (w1 >= -1e-9) & (w2 >= -1e-9)
        node = qr[hit] * nlon + qc[hit]
        self.weights[node] = np.column_stack([w0[hit], w1[hit], w2[hit]])
        self.flat_index[node] = corners[tid[hit]]
        self.inside[node] = True

    def __call__(self, values: FloatArray) -> FloatArray:
        """values (nt, ny, nx) -> (nt, nlat, nlon); NaN outside or next to a NaN corner."""
        flat = values.reshape(values.shape[0], -1)
        out = np.empty((values.shape[0], self.inside.size))
        for k in range(values.shape[0]):
            out[k] = np.einsum("ij,ij->i", flat[k][self.flat_index], self.weights)
        out[:, ~self.inside] = np.nan
        return out.reshape((values.shape[0], *self.shape))


def _grid_angle(lat: FloatArray, lon: FloatArray) -> FloatArray:
    """Angle (rad, CCW from east) of the grid's i axis: atan2(dlat/di, cos(lat) dlon/di)."""
    dlat = np.gradient(lat, axis=1)
    dlon = np.gradient(lon, axis=1) * np.cos(np.radians(lat))
    return np.arctan2(dlat, dlon)


def _lon_frame(lon: FloatArray) -> FloatArray:
    """Shift an ascending longitude axis by 360 k into -180..180 if it fits, else 0..360."""
    a = lon - 360.0 * math.floor((lon[0] + 180.0) / 360.0)
    if a[-1] <= 180.0:
        return a
    b = lon - 360.0 * math.floor(lon[0] / 360.0)
    return b if b[-1] < 360.0 else a


def _check_sources(*sources: CurvilinearSource) -> None:
    """2-D coordinates of one shape, values (nt, ny, nx) on them, at least 2 x 2 nodes."""
    for src in sources:
        if src.lat.ndim != 2 or src.lat.shape != src.lon.shape:
            raise _refuse(src, f"coordinates of shapes {src.lat.shape} and {src.lon.shape}")
        if src.values.shape[1:] != src.lat.shape:
            raise _refuse(src, f"values {src.values.shape[1:]} on coordinates {src.lat.shape}")
        if min(src.lat.shape) < 2:
            raise _refuse(src, "a single row or column of nodes")


def _target_axes(east: CurvilinearSource, north_lat: FloatArray, lons: list[FloatArray],
                 max_nodes: int, notes: list[str]) -> tuple[FloatArray, FloatArray, float, float]:
    """The regular target axes (lat, lon unwrapped about the grid's mean longitude) and their
    steps: the native spacing d in latitude and d / cos(lat_c) in longitude, coarsened to
    max_nodes."""
    all_lat = np.concatenate([s[np.isfinite(s)] for s in (east.lat, north_lat)])
    all_lon = np.concatenate([x[np.isfinite(x)] for x in lons])
    lat_min, lat_max = float(np.min(all_lat)), float(np.max(all_lat))
    lon_min, lon_max = float(np.min(all_lon)), float(np.max(all_lon))
    if lon_max - lon_min > 300.0:
        raise _refuse(east, f"it spans {lon_max - lon_min:.0f} degrees of longitude: a global "
                      "(tripolar) grid; cut a regional subset or")
    d = _native_spacing(east, lons[0])
    if not (math.isfinite(d) and d > 0.0):
        raise _refuse(east, "no two distinct neighbouring nodes")
    lat_c = 0.5 * (lat_min + lat_max)
    coslat = max(math.cos(math.radians(lat_c)), 0.05)
    dlat, dlon = d, d / coslat
    nlat = math.floor((lat_max - lat_min) / dlat + 1e-9) + 1
    nlon = math.floor((lon_max - lon_min) / dlon + 1e-9) + 1
    if nlat * nlon > max_nodes:
        f = math.sqrt(nlat * nlon / max_nodes)
        dlat, dlon = dlat * f, dlon * f
        nlat = math.floor((lat_max - lat_min) / dlat + 1e-9) + 1
        nlon = math.floor((lon_max - lon_min) / dlon + 1e-9) + 1
        notes.append(f"coarsened {f:.2f}x to stay within {max_nodes} nodes")
    if nlat < 2 or nlon < 2:
        raise _refuse(east, f"it spans {lat_max - lat_min:.3g} x {lon_max - lon_min:.3g} "
                      f"degrees, less than two nodes at its spacing {d:.3g} degrees")
    tlat: FloatArray = lat_min + dlat * np.arange(nlat, dtype=float)
    tlon: FloatArray = lon_min + dlon * np.arange(nlon, dtype=float)
    return tlat, tlon, dlat, dlon


def _rotation(east: CurvilinearSource, angle: CurvilinearSource | None, lon0: float,
              lon_e: FloatArray, tri_e: _Triangles, tlat: FloatArray, tlon: FloatArray,
              notes: list[str]) -> tuple[FloatArray, FloatArray]:
    """cos(alpha), sin(alpha) on the target grid (interpolated, then normalised), alpha from
    `angle` or from east's coordinates; a note when |alpha| reaches 0.05 deg."""
    if angle is None:
        alpha = _grid_angle(east.lat, lon_e)[None]
        tri_a, src_label = tri_e, f"its coordinates {east.label}"
    else:
        alpha = angle.values[:1]
        tri_a = _Triangles(angle, _unwrap_lon(angle.lon, lon0), tlat, tlon)
        src_label = "the file's `angle`"
    c = tri_a(np.cos(alpha))[0]
    s = tri_a(np.sin(alpha))[0]
    norm = np.hypot(c, s)
    biggest = float(np.nanmax(np.abs(np.degrees(alpha)))) if np.any(
        np.isfinite(alpha)) else 0.0
    if biggest >= 0.05:
        notes.append(f"velocities rotated from the grid's axes to east/north by the grid "
                     f"angle from {src_label} (|angle| up to {biggest:.1f} deg)")
    return c / norm, s / norm


def regrid_curvilinear(
    east: CurvilinearSource,
    north: CurvilinearSource,
    angle: CurvilinearSource | None = None,
    grid_relative: bool = False,
    max_nodes: int = 4_000_000,
    floor: tuple[NDArray[np.bool_] | None, NDArray[np.bool_] | None] = (None, None),
) -> RegularGrid:
    """Regrid two components to a regular lat/lon grid (module docstring for the method).

    east, north: the components (grid-relative x, y when `grid_relative`); angle: the grid's
    i-axis angle (rad, CCW from east; ROMS `angle`), computed from east's coordinates when
    None. max_nodes bounds nlat x nlon (the spacing is coarsened to fit, with a warning).
    floor: per component, (ny, nx) True where a depth range reaches below the sea floor; a
    target node with no value whose triangle has such a corner is `RegularGrid.floor`.
    """
    _check_sources(east, north, *(() if angle is None else (angle,)))
    ok = np.isfinite(east.lat) & np.isfinite(east.lon)
    if not np.any(ok):
        raise _refuse(east, "no finite coordinates")
    rad = np.radians(east.lon[ok])
    lon0 = math.degrees(math.atan2(float(np.mean(np.sin(rad))), float(np.mean(np.cos(rad)))))
    lons = [_unwrap_lon(s.lon, lon0) for s in (east, north)]
    notes: list[str] = []
    tlat, tlon, dlat, dlon = _target_axes(east, north.lat, lons, max_nodes, notes)
    tri_e = _Triangles(east, lons[0], tlat, tlon)
    u = tri_e(east.values)
    tri_n = tri_e if (north.lat.shape == east.lat.shape and np.array_equal(
        north.lat, east.lat, equal_nan=True) and np.array_equal(
        lons[1], lons[0], equal_nan=True)) else _Triangles(north, lons[1], tlat, tlon)
    v = tri_n(north.values)
    if grid_relative:
        c, s = _rotation(east, angle, lon0, lons[0], tri_e, tlat, tlon, notes)
        u, v = u * c - v * s, u * s + v * c
    land = np.isnan(u) | np.isnan(v)
    u[land] = np.nan
    v[land] = np.nan
    ny, nx = east.lat.shape
    text = (f"regridded the curvilinear {ny}x{nx} grid ({east.label}) to a regular "
            f"{tlat.size}x{tlon.size} lat/lon grid, {dlat:.4g} deg latitude x {dlon:.4g} deg "
            "longitude (linear in the grid's own cells); NaN outside the source grid and next "
            "to land")
    if notes:
        text += "; " + "; ".join(notes)
    outside = np.isnan(tri_e(np.ones((1, *east.lat.shape)))[0])  # no cell of the source
    return RegularGrid(lat=tlat, lon=_lon_frame(tlon), u=u, v=v, warnings=(text,),
                       outside=outside, floor=_floor(floor, (tri_e, tri_n), (east, north),
                                                     np.all(land, axis=0) & ~outside))


def _floor(floor: tuple[NDArray[np.bool_] | None, NDArray[np.bool_] | None],
           tris: tuple[_Triangles, _Triangles], sources: tuple[CurvilinearSource, ...],
           nodata: NDArray[np.bool_]) -> NDArray[np.bool_] | None:
    """Target nodes without data (`nodata`) that a floor node of either component touches."""
    out = None
    for mask, tri, src in zip(floor, tris, sources, strict=True):
        if mask is None or mask.shape != src.lat.shape:
            continue
        touched = tri(np.asarray(mask, dtype=float)[None])[0] > 0.0
        out = touched if out is None else out | touched
    return None if out is None else out & nodata
