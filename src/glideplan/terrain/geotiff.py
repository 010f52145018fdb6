"""GeoTIFF DEMs (Copernicus DEM, SRTM mosaics) through rasterio, in WGS84 lat/lon.

rasterio reports an area-convention transform (GDAL shifts point-convention rasters by half a
pixel), so sample (row, col) sits at the pixel centre: lon = c + a (col + 1/2),
lat = f + e (row + 1/2). Nodata samples are voids (refused, or filled with a warning).

A raster in any other CRS (a projected UTM tile, a national grid, another datum) is
reprojected to WGS84 lat/lon, its voids filled (or refused) first in its own grid. The
lat/lon grid keeps the source's ground spacing h (m) at the mid latitude phi_m:
dlat = h_y / R, dlon = h_x / (R cos phi_m) (radians), rounded to a whole number of samples
per degree with nodes at whole multiples of the step (adjacent tiles of one source then
share a lattice and merge). Each lat/lon node is carried into the source CRS
(rasterio.warp.transform, i.e. PROJ: exactly on every 8th node, bilinearly between, which is
checked to within 1e-3 source pixel at the coarse cells' centres, else exact everywhere) and
the source samples are interpolated there bilinearly (scipy.ndimage.map_coordinates,
order 1). Bilinear because elevations are a continuous field: it stays within the 4
surrounding samples (no overshoot, unlike cubic; no half-pixel staircase, unlike nearest)
and errs by at most (h_x^2 + h_y^2)/8 max|d2z/ds2|. GDAL's warper (rasterio.warp.reproject,
bilinear) was measured 4x over that bound on a smooth UTM test surface (its 1/8-pixel
approximate transformer, and a kernel widened when the destination is a little coarser
than the source), hence the transform checked to 1e-3 pixel and scipy's interpolation.
Nodes outside the source's pixel centres are NaN (outside the terrain), never extrapolated.
"""

from __future__ import annotations

import pathlib
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain
from glideplan.terrain.voids import fill_voids

__all__ = ["read_geotiff", "write_geotiff"]


def read_geotiff(path: str | pathlib.Path, *, voids: str = "refuse") -> Terrain:
    """Band 1 of a GeoTIFF as a `Terrain` (latitudes ascending); a raster not in WGS84
    lat/lon (EPSG:4326) is reprojected (module docstring) and says so in `warnings`."""
    import warnings

    import rasterio
    from rasterio.errors import NotGeoreferencedWarning, RasterioIOError

    p = pathlib.Path(path)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", NotGeoreferencedWarning)  # refused below, by name
            ds_cm = rasterio.open(p)
    except RasterioIOError as exc:
        raise InvalidParameterError(str(p), str(p), f"not a readable GeoTIFF ({exc})") from None
    with ds_cm as ds:
        crs = ds.crs
        if crs is None:
            raise InvalidParameterError(
                str(p), "no CRS", "the DEM must say its coordinate reference system (a "
                "GeoTIFF with georeferencing; a plain TIFF image is not a DEM)")
        t = ds.transform
        band = ds.read(1, masked=True)
        nodata = np.ma.getmaskarray(band)
        z = np.asarray(band.filled(0), dtype=np.float32)
        nodata |= ~np.isfinite(z)
        wgs84 = crs.is_geographic and crs.to_epsg() in (4326, None)
        if not wgs84 or t.b != 0 or t.d != 0 or t.a <= 0:
            return _reprojected(p, ds, z, nodata, voids)
        lon = t.c + t.a * (np.arange(ds.width) + 0.5)
        lat = t.f + t.e * (np.arange(ds.height) + 0.5)
    if lat[0] > lat[-1]:
        lat, z, nodata = lat[::-1], z[::-1], nodata[::-1]
    filled, warning = fill_voids(z, nodata, voids, str(p))
    return Terrain(lat, lon, filled, (str(p),), (warning,) if warning else ())


def _pixel_metres(ds: Any) -> tuple[float, float, float, float, float, float]:
    """(h_x, h_y) the source's pixel size (m) and its WGS84 bounds (west, south, east,
    north) in degrees."""
    import math

    from rasterio.warp import transform_bounds

    t, crs = ds.transform, ds.crs
    west, south, east, north = transform_bounds(crs, "EPSG:4326", *ds.bounds, densify_pts=51)
    hx, hy = math.hypot(t.a, t.d), math.hypot(t.b, t.e)
    if crs.is_projected:
        unit = float(crs.linear_units_factor[1])  # metres per CRS unit
        hx, hy = hx * unit, hy * unit
    else:  # degrees of another datum
        mid = math.radians(0.5 * (south + north))
        hx = math.radians(hx) * EARTH_RADIUS_M * math.cos(mid)
        hy = math.radians(hy) * EARTH_RADIUS_M
    return hx, hy, west, south, east, north


def _reprojected(p: pathlib.Path, ds: Any, z: np.ndarray, nodata: np.ndarray,
                 voids: str) -> Terrain:
    """Band 1 of `ds` (z, voids `nodata`) on a WGS84 lat/lon grid (module docstring)."""
    import math

    filled, warning = fill_voids(z, nodata, voids, str(p))
    hx, hy, west, south, east, north = _pixel_metres(ds)
    if not (-90 <= south < north <= 90) or east <= west:
        raise InvalidParameterError(str(p), (west, south, east, north),
                                    "the DEM's bounds are not on the Earth in lat/lon "
                                    "(or it crosses the antimeridian)")
    mid = math.radians(0.5 * (south + north))
    per_lat = max(1, round(1.0 / math.degrees(hy / EARTH_RADIUS_M)))
    per_lon = max(1, round(1.0 / math.degrees(hx / (EARTH_RADIUS_M * math.cos(mid)))))
    dlat, dlon = 1.0 / per_lat, 1.0 / per_lon
    i0, i1 = math.ceil(south / dlat), math.floor(north / dlat)
    j0, j1 = math.ceil(west / dlon), math.floor(east / dlon)
    if i1 - i0 < 1 or j1 - j0 < 1:
        raise InvalidParameterError(str(p), (ds.width, ds.height),
                                    "the DEM is smaller than two samples")
    lat = dlat * np.arange(i0, i1 + 1, dtype=np.float64)
    lon = dlon * np.arange(j0, j1 + 1, dtype=np.float64)
    out = _bilinear_at(filled, ds, lat, lon)
    if not np.isfinite(out).any():
        raise InvalidParameterError(str(p), (ds.width, ds.height),
                                    "the DEM is too small to reproject (no lat/lon node "
                                    "inside its samples)")
    name = ds.crs.to_string() if ds.crs.to_epsg() is None else f"EPSG:{ds.crs.to_epsg()}"
    note = (f"{p}: reprojected from {name} ({hx:.4g} x {hy:.4g} m pixels) to WGS84 lat/lon at "
            f"{dlat * 3600:.4g}\" x {dlon * 3600:.4g}\" (bilinear)")
    return Terrain(lat, lon, out, (str(p),), tuple(w for w in (warning, note) if w))


def _source_pixels(ds: Any, lat: np.ndarray, lon: np.ndarray, stride: int = 8
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Where the lat/lon nodes fall in the source: PROJ's exact transformation
    (rasterio.warp.transform) of every `stride`-th node, the coarse grids' (row, col)
    pixel-centre indices, and the coarse positions (ci, cj) of every fine row and column.
    Between coarse nodes the indices are bilinear in (ci, cj); that is checked at the coarse
    cells' centres and the stride is dropped to 1 (all exact) if it errs by 1e-3 pixel."""
    from rasterio.warp import transform

    inv = ~ds.transform

    def exact(la: np.ndarray, lo: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        xs, ys = transform("EPSG:4326", ds.crs, lo.ravel(), la.ravel())
        col, row = inv @ (np.asarray(xs), np.asarray(ys))
        return (np.asarray(row).reshape(la.shape) - 0.5, np.asarray(col).reshape(la.shape) - 0.5)

    ii = np.unique(np.r_[np.arange(0, lat.size, stride), lat.size - 1])
    jj = np.unique(np.r_[np.arange(0, lon.size, stride), lon.size - 1])
    fy, fx = exact(*np.meshgrid(lat[ii], lon[jj], indexing="ij"))
    if stride > 1 and ii.size > 1 and jj.size > 1:  # check half-way between coarse nodes
        mla = 0.5 * (lat[ii[:-1]] + lat[ii[1:]])
        mlo = 0.5 * (lon[jj[:-1]] + lon[jj[1:]])
        ey, ex = exact(*np.meshgrid(mla, mlo, indexing="ij"))
        iy = 0.25 * (fy[:-1, :-1] + fy[1:, :-1] + fy[:-1, 1:] + fy[1:, 1:])
        ix = 0.25 * (fx[:-1, :-1] + fx[1:, :-1] + fx[:-1, 1:] + fx[1:, 1:])
        if max(np.max(np.abs(iy - ey)), np.max(np.abs(ix - ex))) > 1e-3:
            return _source_pixels(ds, lat, lon, 1)
    ci = np.interp(np.arange(lat.size), ii, np.arange(ii.size))
    cj = np.interp(np.arange(lon.size), jj, np.arange(jj.size))
    return fy, fx, ci, cj


def _bilinear_at(z: np.ndarray, ds: Any, lat: np.ndarray, lon: np.ndarray,
                 block: int = 500_000) -> np.ndarray:
    """z (the source grid of `ds`) at the lat/lon nodes (ny, nx), bilinear; NaN outside the
    source's pixel centres. Rows are done in blocks of about `block` nodes (memory)."""
    from scipy.ndimage import map_coordinates

    fy_c, fx_c, ci, cj = _source_pixels(ds, lat, lon)
    out = np.full((lat.size, lon.size), np.nan, dtype=np.float32)
    rows = max(1, block // lon.size)
    zf = np.asarray(z, dtype=np.float64)
    for r0 in range(0, lat.size, rows):
        gi, gj = np.meshgrid(ci[r0:r0 + rows], cj, indexing="ij")
        fy = map_coordinates(fy_c, [gi, gj], order=1, mode="nearest")
        fx = map_coordinates(fx_c, [gi, gj], order=1, mode="nearest")
        inside = (fx >= 0) & (fx <= z.shape[1] - 1) & (fy >= 0) & (fy <= z.shape[0] - 1)
        v = map_coordinates(zf, [np.where(inside, fy, 0), np.where(inside, fx, 0)], order=1,
                            mode="nearest")
        out[r0:r0 + rows] = np.where(inside, v, np.nan)
    return out


def write_geotiff(path: str | pathlib.Path, lat: np.ndarray, lon: np.ndarray,
                  z: np.ndarray, *, nodata: float | None = None) -> pathlib.Path:
    """Write z (ny, nx) at nodes lat (ascending), lon as a float32 EPSG:4326 GeoTIFF whose
    pixel centres are the nodes (for tests and benchmarks); NaN -> `nodata` when given."""
    import rasterio
    from affine import Affine

    la, lo = np.asarray(lat, float), np.asarray(lon, float)
    dlat, dlon = (la[-1] - la[0]) / (la.size - 1), (lo[-1] - lo[0]) / (lo.size - 1)
    data = np.asarray(z, dtype=np.float32)[::-1]  # rows north to south
    if nodata is not None:
        data = np.where(np.isfinite(data), data, np.float32(nodata))
    # (rasterio.transform.from_origin composes Affines with `*`, deprecated in affine 3)
    transform = Affine(dlon, 0.0, lo[0] - dlon / 2, 0.0, -dlat, la[-1] + dlat / 2)
    with rasterio.open(pathlib.Path(path), "w", driver="GTiff", height=data.shape[0],
                       width=data.shape[1], count=1, dtype="float32", crs="EPSG:4326",
                       transform=transform, nodata=nodata) as ds:
        ds.write(data, 1)
    return pathlib.Path(path)
