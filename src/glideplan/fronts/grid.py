"""`LatLonGrid`: nodes on a regular latitude/longitude grid, with the sphere's metric.

Node (i, j) sits at (lat[i], lon[j]) degrees. On a sphere of radius R the physical spacings are

    hx_i = R cos(lat_i) dlon,    hy = R dlat          (metres; dlon, dlat in radians),

so the physical gradient of a function phi on the nodes is (d phi/d lon / (R cos lat),
d phi/d lat / R), which is what the front kernel differences: the eikonal/Hamilton-Jacobi
equation written in these coordinates needs no other metric term. `periodic` grids wrap in
longitude (a global field: nx dlon = 360 deg).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = ["EARTH_RADIUS_M", "LatLonGrid"]

FloatArray = NDArray[np.float64]


#: Latitudes beyond this are refused: cos(lat) -> 0 makes hx vanish (and the time step with it).
MAX_ABS_LAT_DEG = 89.0


@dataclass(frozen=True, eq=False)
class LatLonGrid:
    """Regular lat/lon nodes (degrees, ascending, uniform steps); periodic in longitude or not."""

    lat: FloatArray
    lon: FloatArray
    periodic: bool = False
    radius_m: float = EARTH_RADIUS_M

    def __post_init__(self) -> None:
        lat = np.asarray(self.lat, dtype=float)
        lon = np.asarray(self.lon, dtype=float)
        object.__setattr__(self, "lat", lat)
        object.__setattr__(self, "lon", lon)
        for name, a in (("lat", lat), ("lon", lon)):
            if a.ndim != 1 or a.size < 3 or not np.all(np.isfinite(a)):
                raise InvalidParameterError(f"grid {name}", a.shape, "needs >= 3 finite values")
            d = np.diff(a)
            if np.any(d <= 0) or np.ptp(d) > 1e-6 * abs(d[0]) + 1e-12:
                raise InvalidParameterError(f"grid {name}", "steps", "must be uniform, ascending")
        if np.max(np.abs(lat)) > MAX_ABS_LAT_DEG:
            raise InvalidParameterError("grid lat", float(np.max(np.abs(lat))),
                                        f"must lie within +-{MAX_ABS_LAT_DEG} deg")
        if self.periodic and abs(lon.size * self.dlon_deg - 360.0) > 1e-6 * 360.0:
            raise InvalidParameterError("grid lon", (lon.size, self.dlon_deg),
                                        "a periodic grid must span 360 deg (nx dlon = 360)")

    @property
    def shape(self) -> tuple[int, int]:
        return int(self.lat.size), int(self.lon.size)

    @property
    def dlat_deg(self) -> float:
        return float(self.lat[1] - self.lat[0])

    @property
    def dlon_deg(self) -> float:
        return float(self.lon[1] - self.lon[0])

    @cached_property
    def hx(self) -> FloatArray:
        """Metres between neighbouring columns, per row: R cos(lat_i) dlon."""
        return self.radius_m * np.cos(np.radians(self.lat)) * math.radians(self.dlon_deg)

    @property
    def hy(self) -> float:
        """Metres between neighbouring rows: R dlat."""
        return self.radius_m * math.radians(self.dlat_deg)

    @property
    def min_spacing_m(self) -> float:
        return float(min(self.hy, float(np.min(self.hx))))

    def frac_index(self, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """Fractional (row, column) of points; longitudes taken in the grid's frame."""
        la = np.asarray(lat, dtype=float)
        lo = np.asarray(lon, dtype=float)
        fi = (la - self.lat[0]) / self.dlat_deg
        if self.periodic:
            lo = self.lon[0] + np.mod(lo - self.lon[0], 360.0)
        else:  # the representative nearest the grid's centre
            c = 0.5 * (self.lon[0] + self.lon[-1])
            lo = c + np.mod(lo - c + 180.0, 360.0) - 180.0
        fj = (lo - self.lon[0]) / self.dlon_deg
        return fi, fj

    def contains(self, lat: ArrayLike, lon: ArrayLike, margin: float = 0.0) -> NDArray[np.bool_]:
        """True where a point lies inside the grid (by `margin` nodes)."""
        fi, fj = self.frac_index(lat, lon)
        ny, nx = self.shape
        ok_i = (fi >= margin) & (fi <= ny - 1 - margin)
        ok_j = np.ones_like(ok_i) if self.periodic else (fj >= margin) & (fj <= nx - 1 - margin)
        return ok_i & ok_j

    def local_xy(self, lat0: float, lon0: float) -> tuple[FloatArray, FloatArray]:
        """(x, y) m of every node in the equirectangular plane tangent at (lat0, lon0)."""
        c = math.cos(math.radians(lat0))
        dlon = np.mod(self.lon - lon0 + 180.0, 360.0) - 180.0
        x = self.radius_m * c * np.radians(dlon)
        y = self.radius_m * np.radians(self.lat - lat0)
        return np.broadcast_to(x[None, :], self.shape), np.broadcast_to(y[:, None], self.shape)
