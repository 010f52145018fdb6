"""GeoTIFF DEMs (Copernicus DEM, SRTM mosaics) through rasterio, in WGS84 lat/lon.

rasterio reports an area-convention transform (GDAL shifts point-convention rasters by half a
pixel), so sample (row, col) sits at the pixel centre: lon = c + a (col + 1/2),
lat = f + e (row + 1/2). Only north-up rasters in geographic WGS84 (EPSG:4326) are read;
nodata samples are voids (refused, or filled with a warning).
"""

from __future__ import annotations

import pathlib

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.terrain.grid import Terrain
from glideplan.terrain.voids import fill_voids

__all__ = ["read_geotiff", "write_geotiff"]


def read_geotiff(path: str | pathlib.Path, *, voids: str = "refuse") -> Terrain:
    """Band 1 of a GeoTIFF as a `Terrain` (latitudes ascending)."""
    import rasterio
    from rasterio.errors import RasterioIOError

    p = pathlib.Path(path)
    try:
        ds_cm = rasterio.open(p)
    except RasterioIOError as exc:
        raise InvalidParameterError(str(p), str(p), f"not a readable GeoTIFF ({exc})") from None
    with ds_cm as ds:
        crs = ds.crs
        if crs is None or not crs.is_geographic or crs.to_epsg() not in (4326, None):
            raise InvalidParameterError(
                str(p), str(crs), "the DEM must be in geographic WGS84 lat/lon (EPSG:4326)")
        t = ds.transform
        if t.b != 0 or t.d != 0 or t.a <= 0:
            raise InvalidParameterError(str(p), tuple(t)[:6],
                                        "the DEM must be north-up (no rotation)")
        band = ds.read(1, masked=True)
        nodata = np.ma.getmaskarray(band)
        z = np.asarray(band.filled(0), dtype=np.float32)
        nodata |= ~np.isfinite(z)
        lon = t.c + t.a * (np.arange(ds.width) + 0.5)
        lat = t.f + t.e * (np.arange(ds.height) + 0.5)
    if lat[0] > lat[-1]:
        lat, z, nodata = lat[::-1], z[::-1], nodata[::-1]
    filled, warning = fill_voids(z, nodata, voids, str(p))
    return Terrain(lat, lon, filled, (str(p),), (warning,) if warning else ())


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
