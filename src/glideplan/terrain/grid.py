"""`Terrain`: elevations on one regular WGS84 lat/lon grid, sampled bilinearly.

Samples sit at the grid's nodes (SRTM's convention: a 1201-sample tile spans its degree
square corner to corner). Between nodes the elevation is bilinear,

    z(lat, lon) = sum over the cell's 4 corners of z_ij (1 - |fy - i|)(1 - |fx - j|),

so it never exceeds the largest of the 4 corner samples -- which `pooled_max` relies on to
give a coarse grid whose nodes never understate the terrain of their cell. NaN marks no data
(outside the merged tiles); it is outside the terrain.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = ["EARTH_RADIUS_M", "Terrain"]

FloatArray = NDArray[np.float64]



@dataclass(frozen=True, eq=False)
class Terrain:
    """Elevation z (ny, nx) in metres at nodes lat (ny,), lon (nx,) (degrees, ascending,
    uniform steps). `sources` names the files; `warnings` what reading them changed."""

    lat: FloatArray
    lon: FloatArray
    z: NDArray[np.floating]
    sources: tuple[str, ...] = ()
    warnings: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        lat = np.asarray(self.lat, dtype=float)
        lon = np.asarray(self.lon, dtype=float)
        z = np.asarray(self.z)
        if lat.ndim != 1 or lon.ndim != 1 or lat.size < 2 or lon.size < 2:
            raise InvalidParameterError("terrain", (lat.shape, lon.shape),
                                        "needs 1-D lat and lon with at least 2 nodes each")
        if z.shape != (lat.size, lon.size):
            raise InvalidParameterError("terrain", z.shape,
                                        f"elevations must have shape {(lat.size, lon.size)}")
        for name, a in (("lat", lat), ("lon", lon)):
            d = np.diff(a)
            if not (np.all(d > 0) and np.allclose(d, d[0], rtol=1e-6, atol=1e-12)):
                raise InvalidParameterError(f"terrain {name}", a[:3].tolist(),
                                            "must be ascending with a uniform step")
        if lat[0] < -90 or lat[-1] > 90:
            raise InvalidParameterError("terrain lat", (lat[0], lat[-1]), "must be in [-90, 90]")
        object.__setattr__(self, "lat", lat)
        object.__setattr__(self, "lon", lon)
        object.__setattr__(self, "z", z if np.issubdtype(z.dtype, np.floating) else
                           z.astype(np.float32))

    # ----- geometry ------------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.lat.size), int(self.lon.size))

    @property
    def dlat(self) -> float:
        """Latitude step (degrees)."""
        return float((self.lat[-1] - self.lat[0]) / (self.lat.size - 1))

    @property
    def dlon(self) -> float:
        """Longitude step (degrees)."""
        return float((self.lon[-1] - self.lon[0]) / (self.lon.size - 1))

    @property
    def spacing_m(self) -> tuple[float, float]:
        """(east, north) sample spacing (m) at the mid latitude: R cos(lat) dlon, R dlat."""
        mid = math.radians(0.5 * (self.lat[0] + self.lat[-1]))
        return (EARTH_RADIUS_M * math.cos(mid) * math.radians(self.dlon),
                EARTH_RADIUS_M * math.radians(self.dlat))

    @property
    def extent(self) -> tuple[float, float, float, float]:
        """(south, north, west, east) in degrees."""
        return (float(self.lat[0]), float(self.lat[-1]), float(self.lon[0]), float(self.lon[-1]))

    def contains(self, lat: ArrayLike, lon: ArrayLike) -> NDArray[np.bool_]:
        """Inside the extent and on data (the bilinear elevation is not NaN)."""
        return np.isfinite(self.elevation(lat, lon))

    # ----- sampling ------------------------------------------------------------------------
    def elevation(self, lat: ArrayLike, lon: ArrayLike) -> FloatArray:
        """Bilinear elevation (m) at (lat, lon) degrees; NaN outside the extent or on no data."""
        la = np.asarray(lat, dtype=float)
        lo = np.asarray(lon, dtype=float)
        fy = (la - self.lat[0]) / self.dlat
        fx = (lo - self.lon[0]) / self.dlon
        ny, nx = self.shape
        eps = 1e-9
        inside = (fy >= -eps) & (fy <= ny - 1 + eps) & (fx >= -eps) & (fx <= nx - 1 + eps)
        fy = np.clip(np.where(inside, fy, 0.0), 0.0, ny - 1)
        fx = np.clip(np.where(inside, fx, 0.0), 0.0, nx - 1)
        i = np.minimum(np.floor(fy).astype(np.intp), ny - 2)
        j = np.minimum(np.floor(fx).astype(np.intp), nx - 2)
        wy, wx = fy - i, fx - j
        z = self.z
        v = ((1 - wy) * ((1 - wx) * z[i, j] + wx * z[i, j + 1])
             + wy * ((1 - wx) * z[i + 1, j] + wx * z[i + 1, j + 1]))
        return np.where(inside, v, np.nan).astype(float)

    def crop(self, south: float, north: float, west: float, east: float) -> Terrain:
        """The nodes covering [south, north] x [west, east] (one node beyond each side)."""
        i0 = max(math.floor((south - self.lat[0]) / self.dlat) - 1, 0)
        i1 = min(math.ceil((north - self.lat[0]) / self.dlat) + 1, self.lat.size - 1)
        j0 = max(math.floor((west - self.lon[0]) / self.dlon) - 1, 0)
        j1 = min(math.ceil((east - self.lon[0]) / self.dlon) + 1, self.lon.size - 1)
        if i1 - i0 < 1 or j1 - j0 < 1:
            raise InvalidParameterError("terrain", (south, north, west, east),
                                        "the crop does not overlap the terrain")
        return Terrain(self.lat[i0:i1 + 1], self.lon[j0:j1 + 1], self.z[i0:i1 + 1, j0:j1 + 1],
                       self.sources, self.warnings)

    def pooled_max(self, factor: int, reach: int | None = None
                   ) -> tuple[FloatArray, FloatArray, FloatArray]:
        """A grid `factor` times coarser: (lat, lon, z) with z the largest sample within
        `reach` fine samples of each coarse node (default ceil(f/2): the node's own cell).

        The cell of node (I, J) spans fine indices fI +- f/2; the bilinear surface there is
        bounded by the samples with indices in [floor(fI - f/2), ceil(fI + f/2)], i.e.
        within ceil(f/2) of fI. NaN (no data) anywhere in the window makes the node NaN.
        """
        f = int(factor)
        if f < 1:
            raise InvalidParameterError("factor", factor, "must be an integer >= 1")
        z = np.asarray(self.z, dtype=np.float32)
        r = (f + 1) // 2 if reach is None else int(reach)
        if r == 0:
            return self.lat[::f].copy(), self.lon[::f].copy(), z[::f, ::f].astype(float)
        from scipy.ndimage import maximum_filter

        nan = np.isnan(z)
        filled = np.where(nan, np.float32(np.inf), z)  # no data dominates the max
        pooled = maximum_filter(filled, size=2 * r + 1, mode="nearest")
        pooled = pooled[::f, ::f].astype(float)
        pooled[np.isinf(pooled)] = np.nan
        return self.lat[::f].copy(), self.lon[::f].copy(), pooled
