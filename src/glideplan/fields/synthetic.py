"""Build forecast-like datasets and files in the layouts of real products (tests, benchmarks).

- `copernicus_dataset`: `uo`/`vo` (standard_name eastward/northward_sea_water_velocity,
  units m s-1) on (time, depth, latitude, longitude), longitudes -180..180, ascending latitude.
- `hycom_dataset`: `water_u`/`water_v` on (time, depth, lat, lon), longitudes 0..360,
  packed as int16 with scale_factor 0.001 and _FillValue -30000 like HYCOM's files.
- `write_grib`: `10u`/`10v` GRIB2 messages (ERA5/GFS-like, read by cfgrib as u10/v10) on a
  regular lat/lon grid scanned north to south, longitudes 0..360, one message per step.

Arrays u, v are (time, depth, lat, lon) with lat ascending and lon in -180..180 (the
builders reorder them into each layout). NaN marks land.
"""

from __future__ import annotations

import pathlib
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

__all__ = ["copernicus_dataset", "hycom_dataset", "write_grib"]


def _pyproj_before_eccodes() -> None:
    from glideplan.fields.io import pyproj_before_eccodes

    pyproj_before_eccodes()


def _arrays(u: ArrayLike, v: ArrayLike, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    ua = np.broadcast_to(np.asarray(u, dtype=float), shape).copy()
    va = np.broadcast_to(np.asarray(v, dtype=float), shape).copy()
    return ua, va


def copernicus_dataset(lat: ArrayLike, lon: ArrayLike, times: ArrayLike, depth: ArrayLike,
                       u: ArrayLike, v: ArrayLike) -> Any:
    """A Copernicus Marine-like dataset (module docstring)."""
    import xarray as xr

    la, lo = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    tt = np.asarray(times, dtype="datetime64[ns]")
    zz = np.asarray(depth, dtype=float)
    ua, va = _arrays(u, v, (tt.size, zz.size, la.size, lo.size))
    dims = ("time", "depth", "latitude", "longitude")
    ds = xr.Dataset(
        {
            "uo": (dims, ua.astype(np.float32), {"standard_name": "eastward_sea_water_velocity",
                                                 "units": "m s-1"}),
            "vo": (dims, va.astype(np.float32), {"standard_name": "northward_sea_water_velocity",
                                                 "units": "m s-1"}),
        },
        coords={"time": tt, "depth": ("depth", zz, {"positive": "down", "units": "m"}),
                "latitude": ("latitude", la, {"units": "degrees_north"}),
                "longitude": ("longitude", lo, {"units": "degrees_east"})},
    )
    return ds


def hycom_dataset(lat: ArrayLike, lon: ArrayLike, times: ArrayLike, depth: ArrayLike,
                  u: ArrayLike, v: ArrayLike, descending_lat: bool = False,
                  packed: bool = True) -> Any:
    """A HYCOM-like dataset (module docstring): lon 0..360 (sorted), packed int16 (or float32
    with `packed=False`)."""
    import xarray as xr

    la, lo = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    tt = np.asarray(times, dtype="datetime64[ns]")
    zz = np.asarray(depth, dtype=float)
    ua, va = _arrays(u, v, (tt.size, zz.size, la.size, lo.size))
    lo360 = np.mod(lo, 360.0)
    order = np.argsort(lo360)
    lo360, ua, va = lo360[order], ua[..., order], va[..., order]
    if descending_lat:
        la, ua, va = la[::-1], ua[:, :, ::-1], va[:, :, ::-1]
    dims = ("time", "depth", "lat", "lon")
    enc: dict[str, Any] = ({"dtype": "int16", "scale_factor": 0.001, "_FillValue": -30000}
                           if packed else {"dtype": "float32"})
    ds = xr.Dataset(
        {"water_u": (dims, ua, {"units": "m/s"}), "water_v": (dims, va, {"units": "m/s"})},
        coords={"time": tt, "depth": ("depth", zz, {"units": "m"}),
                "lat": ("lat", la, {"units": "degrees_north"}),
                "lon": ("lon", lo360, {"units": "degrees_east"})},
    )
    ds["water_u"].encoding.update(enc)
    ds["water_v"].encoding.update(enc)
    return ds


def write_grib(path: str | pathlib.Path, lat: ArrayLike, lon: ArrayLike, times: ArrayLike,
               u: ArrayLike, v: ArrayLike) -> pathlib.Path:
    """GRIB2 10u/10v messages (module docstring); lat ascending in, written north to south.

    lat and lon must be regularly spaced; times are forecast steps from the first (whole
    hours). u, v: (time, lat, lon).
    """
    _pyproj_before_eccodes()
    import eccodes

    la, lo = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    tt = np.asarray(times, dtype="datetime64[s]")
    ua, va = _arrays(u, v, (tt.size, la.size, lo.size))
    base = tt[0].astype("datetime64[D]")
    hour0 = int((tt[0] - base) / np.timedelta64(1, "h"))
    date = int(str(base).replace("-", ""))
    lo360 = np.mod(lo, 360.0)
    out = pathlib.Path(path)
    with out.open("wb") as fh:
        for k in range(tt.size):
            step = int((tt[k] - tt[0]) / np.timedelta64(1, "h"))
            for short, arr in (("10u", ua[k]), ("10v", va[k])):
                h = eccodes.codes_grib_new_from_samples("regular_ll_sfc_grib2")
                eccodes.codes_set_key_vals(h, {
                    "Ni": lo.size, "Nj": la.size,
                    "latitudeOfFirstGridPointInDegrees": float(la[-1]),
                    "latitudeOfLastGridPointInDegrees": float(la[0]),
                    "longitudeOfFirstGridPointInDegrees": float(lo360[0]),
                    "longitudeOfLastGridPointInDegrees": float(lo360[-1]),
                    "iDirectionIncrementInDegrees": float(abs(lo[1] - lo[0])),
                    "jDirectionIncrementInDegrees": float(abs(la[1] - la[0])),
                    "jScansPositively": 0, "dataDate": date, "dataTime": hour0 * 100,
                    "stepUnits": 1, "forecastTime": step,
                })
                eccodes.codes_set_string(h, "shortName", short)
                eccodes.codes_set_values(h, np.ascontiguousarray(arr[::-1]).ravel())
                eccodes.codes_write(h, fh)
                eccodes.codes_release(h)
    return out
