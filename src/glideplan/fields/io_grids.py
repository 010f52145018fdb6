"""Components of a field file on one grid (`glideplan.fields.io`): a 2-D lat/lon that is a
product of 1-D axes is a regular grid; two components on different grids (staggered, Arakawa
C) are both treated as curvilinear and regridded; longitudes put in one ascending order
(`lon_order`: cut at the largest gap, -180..180 when it fits, else 0..360; a global field
keeps its convention).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["lon_order", "same_grid"]


def same_grid(comps: list[Any]) -> list[Any]:
    """Both components on one regular grid, else both curvilinear (staggered: regridded)."""
    import xarray as xr

    reg = [_as_regular(c) for c in comps]
    if all(c[0] == "regular" for c in reg):
        a, b = reg
        if a[2].shape == b[2].shape and a[3].shape == b[3].shape and np.allclose(
                a[2].values, b[2].values, atol=1e-9, rtol=0) and np.allclose(
                a[3].values, b[3].values, atol=1e-9, rtol=0):
            return reg
    out = []
    for kind, arr, lat_c, lon_c, tdim, tvals in reg:
        if kind == "regular":  # a staggered regular grid (Arakawa C): regrid it too
            la2, lo2 = np.meshgrid(np.asarray(lat_c.values, dtype=float),
                                   np.asarray(lon_c.values, dtype=float), indexing="ij")
            lat_c = xr.DataArray(la2, dims=("y", "x"), name=lat_c.name or "lat")
            lon_c = xr.DataArray(lo2, dims=("y", "x"), name=lon_c.name or "lon")
        out.append(("curvilinear", arr, lat_c, lon_c, tdim, tvals))
    return out


def _as_regular(comp: tuple[Any, ...]) -> tuple[Any, ...]:
    """A 2-D lat/lon that is a product of 1-D axes (lat along one dimension, lon along the
    other, to 1e-9 deg) is a regular grid: no regridding."""
    kind, arr, lat_c, lon_c, tdim, tvals = comp
    if kind != "curvilinear" or lat_c.dims != lon_c.dims:
        return comp
    la, lo = np.asarray(lat_c.values, dtype=float), np.asarray(lon_c.values, dtype=float)
    for ax in (0, 1):
        other = 1 - ax
        lat_axis = np.take(la, 0, axis=other)  # lat varies along `ax` only
        lon_axis = np.take(lo, 0, axis=ax)  # lon varies along `other` only
        if np.allclose(la, np.expand_dims(lat_axis, other), atol=1e-9, rtol=0) and np.allclose(
                lo, np.expand_dims(lon_axis, ax), atol=1e-9, rtol=0):
            if ax == 1:
                arr = np.swapaxes(arr, 1, 2)
            import xarray as xr

            return ("regular", arr, xr.DataArray(lat_axis, dims=("y",)),
                    xr.DataArray(lon_axis, dims=("x",)), tdim, tvals)
    return comp


def lon_order(lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(new longitudes ascending, indices into lon): one column per meridian (360 = 0 dropped).

    Global (the columns close the circle): the file's convention (-180..180 if it has negative
    longitudes, else 0..360). Regional: cut at the largest gap, written -180..180 if it fits,
    else 0..360, else from the cut (a field across both 0 and 180).
    """
    m = np.mod(np.asarray(lon, dtype=float), 360.0)
    m = np.where(m >= 360.0 - 1e-9, 0.0, m)
    _, first = np.unique(np.round(m, 9), return_index=True)
    keep = first[np.argsort(m[first], kind="stable")]
    ms = m[keep]
    n = ms.size
    if n < 2:
        return np.asarray(lon, dtype=float)[keep], keep
    dlon = (ms[-1] - ms[0]) / (n - 1)
    if abs(n * dlon - 360.0) <= 0.5 * dlon:  # global: keep the file's convention
        if np.min(lon) < 0.0:
            a = np.mod(ms + 180.0, 360.0) - 180.0
            o = np.argsort(a, kind="stable")
            return a[o], keep[o]
        return ms, keep
    gaps = np.diff(np.concatenate([ms, [ms[0] + 360.0]]))
    start = (int(np.argmax(gaps)) + 1) % n
    idx = np.roll(np.arange(n), -start)
    rep = ms[idx].copy()
    rep[1:] += 360.0 * (np.cumsum(np.diff(rep) < 0.0))
    a = rep - 360.0 * np.floor((rep[0] + 180.0) / 360.0)
    if a[-1] <= 180.0:
        return a, keep[idx]
    b = rep - 360.0 * np.floor(rep[0] / 360.0)
    return (b if b[-1] < 360.0 else a), keep[idx]
