"""Build forecast-like datasets and files in the layouts of real products (tests, benchmarks).

- `copernicus_dataset`: `uo`/`vo` (standard_name eastward/northward_sea_water_velocity,
  units m s-1) on (time, depth, latitude, longitude), longitudes -180..180, ascending latitude.
- `hycom_dataset`: `water_u`/`water_v` on (time, depth, lat, lon), longitudes 0..360,
  packed as int16 with scale_factor 0.001 and _FillValue -30000 like HYCOM's files.
- `write_grib`: `10u`/`10v` GRIB2 messages (ERA5/GFS-like, read by cfgrib as u10/v10) on a
  regular lat/lon grid scanned north to south, longitudes 0..360, one message per step.

Arrays u, v are (time, depth, lat, lon) with lat ascending and lon in -180..180 (the
builders reorder them into each layout). NaN marks land.

Fields given as functions (`fn(t_s, lat, lon) -> (u_east, v_north)` in m/s, t_s seconds since
the first time, lat/lon degrees as stored in the file) are sampled at the nodes:

- `global_dataset`: a global grid in either longitude convention (0..360 or -180..180), wind
  (`u10/v10`) or current (`uo/vo`), uniform or a function, with an optional land mask.
- `era5_dataset`: the new ERA5 NetCDF layout (CDS): `valid_time`, latitude 90..-90, longitude
  0..359.75, `u10/v10` in "m s**-1", scalar `number`, `expver` along time (or the old layout
  with an `expver` dimension, ERA5 and ERA5T mixed).
- `copernicus_headland_dataset`: Copernicus-like, depth levels from 0.494 m (the GLO12
  levels), a rectangular headland of land (NaN at every depth) reaching from the south edge.
- `roms_dataset`: ROMS-like curvilinear grid rotated by `angle`: `lat_rho/lon_rho`, staggered
  `u` on `lat_u/lon_u` and `v` on `lat_v/lon_v` along the grid's axes, `mask_*`, `s_rho`
  levels, `ocean_time` (or `u_eastward/v_northward` on rho points).
- `nemo_datasets`: NEMO-like grid_U and grid_V files (`vozocrtx`, `vomecrty` along the grid's
  axes), each with its own 2-D `nav_lat/nav_lon`, `time_counter`, `depthu`/`depthv`.
- `basin_dataset` / `basin_current`: a basin-scale Copernicus-like 1/12 deg field (260 x 500
  nodes x 13 times): a meandering jet and westward Rossby-like waves, speeds <= 0.48 m/s.

Why this module is long: (about 510 lines) a catalogue, one builder of 20-40 lines per
product layout, kept together so tests and benchmarks find every layout in one place.
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = [
    "COPERNICUS_DEPTHS",
    "EARTH_RADIUS_M",
    "basin_current",
    "basin_dataset",
    "copernicus_dataset",
    "copernicus_headland_dataset",
    "era5_dataset",
    "global_dataset",
    "hycom_dataset",
    "nemo_datasets",
    "roms_dataset",
    "write_grib",
]

#: u, v (m/s east, north) as functions of (t_s, lat, lon) (arrays, broadcast).
VelocityFn = Callable[[np.ndarray, np.ndarray, np.ndarray], tuple[ArrayLike, ArrayLike]]
#: True where (lat, lon) is land.
LandFn = Callable[[np.ndarray, np.ndarray], np.ndarray]

#: The first 32 depth levels (m) of Copernicus Marine's global 1/12 deg analysis (GLO12).
COPERNICUS_DEPTHS = (
    0.494025, 1.541375, 2.645669, 3.819495, 5.078224, 6.440614, 7.92956, 9.572997, 11.405,
    13.46714, 15.81007, 18.49556, 21.59882, 25.21141, 29.44473, 34.43415, 40.34405, 47.37369,
    55.76429, 65.80727, 77.85385, 92.32607, 109.7293, 130.666, 155.8507, 186.1256, 222.4752,
    266.0403, 318.1274, 380.213, 453.9377, 541.0889,
)
_DEFAULT_TIMES = ("2026-01-01T00", "2026-01-11T00")


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


def _sample(fn: VelocityFn | None, u: float, v: float, tt: np.ndarray, lat: np.ndarray,
            lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(nt, ...) arrays of fn at seconds since tt[0] (or the uniform u, v)."""
    ts = ((tt - tt[0]) / np.timedelta64(1, "s")).reshape((-1,) + (1,) * lat.ndim)
    shape = (tt.size, *np.broadcast_shapes(lat.shape, lon.shape))
    if fn is None:
        return np.full(shape, float(u)), np.full(shape, float(v))
    uu, vv = fn(ts, lat[None], lon[None])
    return (np.broadcast_to(np.asarray(uu, dtype=float), shape).copy(),
            np.broadcast_to(np.asarray(vv, dtype=float), shape).copy())


def global_dataset(step_deg: float = 1.0, lon_convention: str = "0..360", u: float = 0.0,
                   v: float = 0.0, fn: VelocityFn | None = None, land: LandFn | None = None,
                   times: Sequence[Any] = _DEFAULT_TIMES, kind: str = "wind") -> Any:
    """A global field: lat -90..90 ascending, lon 0..360-step or -180..180-step (ascending).

    Uniform (u, v) m/s, or fn(t_s, lat, lon) with lon as stored; land(lat, lon) True -> NaN.
    kind "wind": `u10/v10` (eastward_wind, m s-1) on (time, latitude, longitude); "current":
    Copernicus `uo/vo` with one depth level 0.494 m.
    """
    import xarray as xr

    if lon_convention not in ("0..360", "-180..180"):
        raise ValueError("lon_convention must be '0..360' or '-180..180'")
    n_lon = round(360.0 / step_deg)
    lat = np.linspace(-90.0, 90.0, round(180.0 / step_deg) + 1)
    lon = np.arange(n_lon) * step_deg + (0.0 if lon_convention == "0..360" else -180.0)
    tt = np.asarray(times, dtype="datetime64[ns]")
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ua, va = _sample(fn, u, v, tt, LA, LO)
    if land is not None:
        wet = ~np.asarray(land(LA, LO), dtype=bool)
        ua, va = np.where(wet, ua, np.nan), np.where(wet, va, np.nan)
    if kind == "current":
        return copernicus_dataset(lat, lon, tt, [COPERNICUS_DEPTHS[0]], ua[:, None],
                                  va[:, None])
    if kind != "wind":
        raise ValueError("kind must be 'wind' or 'current'")
    dims = ("time", "latitude", "longitude")
    return xr.Dataset(
        {"u10": (dims, ua.astype(np.float32), {"standard_name": "eastward_wind",
                                               "units": "m s-1"}),
         "v10": (dims, va.astype(np.float32), {"standard_name": "northward_wind",
                                               "units": "m s-1"})},
        coords={"time": tt, "latitude": ("latitude", lat, {"units": "degrees_north"}),
                "longitude": ("longitude", lon, {"units": "degrees_east"})},
    )


def era5_dataset(step_deg: float = 0.25, u: float = 0.0, v: float = 0.0,
                 fn: VelocityFn | None = None, times: Sequence[Any] = _DEFAULT_TIMES,
                 lat_range: tuple[float, float] = (-90.0, 90.0),
                 lon_range: tuple[float, float] | None = None,
                 expver_dimension: bool = False) -> Any:
    """ERA5 single levels as the CDS writes NetCDF (module docstring); 10 m wind u10/v10.

    Latitude descending from lat_range[1] to lat_range[0]; longitude 0..360-step (or the
    range lon_range, 0..360 values). fn(t_s, lat, lon) with lon in 0..360. With
    `expver_dimension` the old layout: dimensions (time, expver, ...), expver "0001" holding
    the first half of the times and "0005" (ERA5T) the rest, NaN in the other.
    """
    import xarray as xr

    lat = np.arange(round((lat_range[1] - lat_range[0]) / step_deg) + 1) * -step_deg + lat_range[1]
    if lon_range is None:
        lon = np.arange(round(360.0 / step_deg)) * step_deg
    else:
        lon = lon_range[0] + np.arange(round((lon_range[1] - lon_range[0]) / step_deg) + 1) * (
            step_deg)
    tt = np.asarray(times, dtype="datetime64[ns]")
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ua, va = _sample(fn, u, v, tt, LA, LO)
    attrs_u = {"units": "m s**-1", "long_name": "10 metre U wind component",
               "standard_name": "unknown", "GRIB_paramId": 165, "GRIB_shortName": "10u"}
    attrs_v = {"units": "m s**-1", "long_name": "10 metre V wind component",
               "standard_name": "unknown", "GRIB_paramId": 166, "GRIB_shortName": "10v"}
    coords: dict[str, Any] = {
        "number": ((), np.int64(0), {"long_name": "ensemble member numerical id"}),
        "latitude": ("latitude", lat, {"units": "degrees_north", "standard_name": "latitude"}),
        "longitude": ("longitude", lon, {"units": "degrees_east", "standard_name": "longitude"}),
    }
    if expver_dimension:
        half = tt.size // 2
        uu = np.stack([ua, ua]).swapaxes(0, 1).copy()
        vv = np.stack([va, va]).swapaxes(0, 1).copy()
        uu[half:, 0] = vv[half:, 0] = np.nan
        uu[:half, 1] = vv[:half, 1] = np.nan
        dims: tuple[str, ...] = ("time", "expver", "latitude", "longitude")
        coords["time"] = ("time", tt)
        coords["expver"] = ("expver", np.array(["0001", "0005"]))
    else:
        uu, vv = ua, va
        dims = ("valid_time", "latitude", "longitude")
        coords["valid_time"] = ("valid_time", tt, {"standard_name": "time"})
        coords["expver"] = ("valid_time", np.array(["0001"] * tt.size))
    return xr.Dataset({"u10": (dims, uu.astype(np.float32), attrs_u),
                       "v10": (dims, vv.astype(np.float32), attrs_v)}, coords=coords,
                      attrs={"GRIB_centre": "ecmf", "Conventions": "CF-1.7"})


def copernicus_headland_dataset(
    lat_range: tuple[float, float] = (30.0, 31.0),
    lon_range: tuple[float, float] = (-41.0, -39.5),
    step_deg: float = 1.0 / 12.0,
    headland: tuple[float, float, float, float] = (30.0, 30.6, -40.35, -40.15),
    u: float = 0.0, v: float = 0.0, fn: VelocityFn | None = None,
    times: Sequence[Any] = _DEFAULT_TIMES, depths: Sequence[float] = COPERNICUS_DEPTHS[:8],
    shear_per_m: float = 0.0,
) -> Any:
    """Copernicus-like `uo/vo` with depth levels from 0.494 m and a rectangular headland.

    headland (lat0, lat1, lon0, lon1): nodes inside are NaN at every depth (by default a cape
    from the south edge up to 30.6 N). Velocity fn(t_s, lat, lon) (or uniform u, v) at the
    surface, scaled by (1 - shear_per_m z) with depth z (m).
    """
    lat = lat_range[0] + step_deg * np.arange(round((lat_range[1] - lat_range[0]) / step_deg) + 1)
    lon = lon_range[0] + step_deg * np.arange(round((lon_range[1] - lon_range[0]) / step_deg) + 1)
    tt = np.asarray(times, dtype="datetime64[ns]")
    z = np.asarray(depths, dtype=float)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ua, va = _sample(fn, u, v, tt, LA, LO)
    scale = (1.0 - shear_per_m * z)[None, :, None, None]
    ua, va = ua[:, None] * scale, va[:, None] * scale
    la0, la1, lo0, lo1 = headland
    cape = (LA >= la0 - 1e-9) & (LA <= la1 + 1e-9) & (LO >= lo0 - 1e-9) & (LO <= lo1 + 1e-9)
    ua[:, :, cape] = np.nan
    va[:, :, cape] = np.nan
    ds = copernicus_dataset(lat, lon, tt, z, ua, va)
    ds.attrs["glideplan_headland"] = [float(x) for x in headland]
    return ds


def _rotated_grid(lat0: float, lon0: float, nx: int, ny: int, spacing_m: float,
                  angle_deg: float) -> Callable[[np.ndarray, np.ndarray], tuple[np.ndarray,
                                                                              np.ndarray]]:
    """(i, j) -> (lat, lon) of a grid of spacing h whose i axis is angle_deg CCW from east:
    x = (i - (nx-1)/2) h, y = (j - (ny-1)/2) h rotated, by a local equirectangular map."""
    a = math.radians(angle_deg)
    coslat0 = math.cos(math.radians(lat0))

    def place(i: np.ndarray, j: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = (i - 0.5 * (nx - 1)) * spacing_m
        y = (j - 0.5 * (ny - 1)) * spacing_m
        east = x * math.cos(a) - y * math.sin(a)
        north = x * math.sin(a) + y * math.cos(a)
        return (lat0 + np.degrees(north / EARTH_RADIUS_M),
                lon0 + np.degrees(east / (EARTH_RADIUS_M * coslat0)))

    return place


def nemo_datasets(
    lat0: float = 30.0, lon0: float = -40.0, nx: int = 41, ny: int = 31,
    spacing_m: float = 2000.0, angle_deg: float = 20.0, u: float = 0.0, v: float = 0.0,
    fn: VelocityFn | None = None, times: Sequence[Any] = _DEFAULT_TIMES,
    land: LandFn | None = None,
) -> tuple[Any, Any]:
    """NEMO-like (grid_U, grid_V) datasets on a rotated curvilinear grid (as `roms_dataset`).

    U points at i + 1/2, V points at j + 1/2 of the T grid, both (y, x) of the same size, each
    file with its own 2-D `nav_lat/nav_lon`; `vozocrtx`/`vomecrty` along the grid axes
    (u_grid = u_e cos(a) + v_n sin(a), v_grid = -u_e sin(a) + v_n cos(a)); `time_counter`;
    `depthu`/`depthv` levels 0.494 and 1.54 m (the second at half speed); land NaN.
    """
    import xarray as xr

    a = math.radians(angle_deg)
    place = _rotated_grid(lat0, lon0, nx, ny, spacing_m, angle_deg)
    tt = np.asarray(times, dtype="datetime64[ns]")
    jj, ii = np.meshgrid(np.arange(ny, dtype=float), np.arange(nx, dtype=float), indexing="ij")
    out = []
    for var, depth, di, dj in (("vozocrtx", "depthu", 0.5, 0.0), ("vomecrty", "depthv", 0.0,
                                                                    0.5)):
        lat, lon = place(ii + di, jj + dj)
        ue, vn = _sample(fn, u, v, tt, lat, lon)
        val = ue * math.cos(a) + vn * math.sin(a) if di else -ue * math.sin(a) + vn * math.cos(a)
        if land is not None:
            val = np.where(np.asarray(land(lat, lon), dtype=bool), np.nan, val)
        vals = val[:, None] * np.array([1.0, 0.5])[None, :, None, None]
        out.append(xr.Dataset(
            {var: (("time_counter", depth, "y", "x"), vals.astype(np.float32),
                   {"units": "m/s", "standard_name": "sea_water_x_velocity" if di else
                    "sea_water_y_velocity"})},
            coords={"time_counter": ("time_counter", tt, {"standard_name": "time"}),
                    depth: (depth, np.array(COPERNICUS_DEPTHS[:2]), {"units": "m",
                                                                   "positive": "down"}),
                    "nav_lat": (("y", "x"), lat, {"units": "degrees_north"}),
                    "nav_lon": (("y", "x"), lon, {"units": "degrees_east"})},
        ))
    return out[0], out[1]


def roms_dataset(
    lat0: float = 30.0, lon0: float = -40.0, nx: int = 41, ny: int = 31,
    spacing_m: float = 2000.0, angle_deg: float = 30.0, u: float = 0.0, v: float = 0.0,
    fn: VelocityFn | None = None, times: Sequence[Any] = _DEFAULT_TIMES,
    land: LandFn | None = None, staggered: bool = True, n_s: int = 3,
) -> Any:
    """A ROMS-like curvilinear grid centred on (lat0, lon0), its xi axis `angle_deg` CCW from east.

    Rho points at x = (i - (nx-1)/2) h, y = (j - (ny-1)/2) h along the grid axes, placed by a
    local equirectangular map (R = `geodesy.EARTH_RADIUS_M`). Staggered (ROMS native): `u` at
    the xi-midpoints
    (eta_u, xi_u), `v` at the eta-midpoints, both along the grid axes,
    u_grid = u_e cos(a) + v_n sin(a), v_grid = -u_e sin(a) + v_n cos(a); land (land(lat,
    lon) True at rho points, and u/v points next to them) is 0 with mask 0, like ROMS. Else
    `u_eastward/v_northward` on rho points, land NaN. Velocities are fn (east, north) at the
    top s-level (s_rho = -1/(2 n_s)) and half of it below.
    """
    import xarray as xr

    a = math.radians(angle_deg)
    place = _rotated_grid(lat0, lon0, nx, ny, spacing_m, angle_deg)
    tt = np.asarray(times, dtype="datetime64[ns]")
    jj, ii = np.meshgrid(np.arange(ny, dtype=float), np.arange(nx, dtype=float), indexing="ij")
    lat_r, lon_r = place(ii, jj)
    lat_u, lon_u = place(ii[:, :-1] + 0.5, jj[:, :-1])
    lat_v, lon_v = place(ii[:-1], jj[:-1] + 0.5)
    s_rho = -(np.arange(n_s)[::-1] + 0.5) / n_s  # ascending, top = -1/(2 n_s)
    level = np.where(np.arange(n_s) == n_s - 1, 1.0, 0.5)[None, :, None, None]
    wet_r = np.ones(lat_r.shape, dtype=bool) if land is None else ~np.asarray(
        land(lat_r, lon_r), dtype=bool)
    rho = (("eta_rho", "xi_rho"), {"units": "degrees_north"})
    coords: dict[str, Any] = {
        "ocean_time": ("ocean_time", tt, {"long_name": "time since initialization"}),
        "s_rho": ("s_rho", s_rho, {"long_name": "S-coordinate at RHO-points",
                                   "positive": "up"}),
        "lat_rho": (rho[0], lat_r, rho[1]), "lon_rho": (rho[0], lon_r, {"units": "degrees_east"}),
    }
    dims_r = ("ocean_time", "s_rho", "eta_rho", "xi_rho")
    data: dict[str, Any] = {
        "angle": (rho[0], np.full(lat_r.shape, a), {"units": "radians",
                                                    "long_name": "angle between XI-axis and EAST"}),
        "mask_rho": (rho[0], wet_r.astype(float), {"long_name": "mask on RHO-points"}),
    }
    if not staggered:
        ue, vn = _sample(fn, u, v, tt, lat_r, lon_r)
        ue = np.where(wet_r, ue, np.nan)[:, None] * level
        vn = np.where(wet_r, vn, np.nan)[:, None] * level
        data["u_eastward"] = (dims_r, ue.astype(np.float32), {
            "standard_name": "eastward_sea_water_velocity", "units": "meter second-1"})
        data["v_northward"] = (dims_r, vn.astype(np.float32), {
            "standard_name": "northward_sea_water_velocity", "units": "meter second-1"})
        return xr.Dataset(data, coords=coords)
    wet_u = wet_r[:, :-1] & wet_r[:, 1:]
    wet_v = wet_r[:-1] & wet_r[1:]
    ue, vn = _sample(fn, u, v, tt, lat_u, lon_u)
    ug = (ue * math.cos(a) + vn * math.sin(a)) * wet_u
    ue, vn = _sample(fn, u, v, tt, lat_v, lon_v)
    vg = (-ue * math.sin(a) + vn * math.cos(a)) * wet_v
    coords.update({
        "lat_u": (("eta_u", "xi_u"), lat_u, {"units": "degrees_north"}),
        "lon_u": (("eta_u", "xi_u"), lon_u, {"units": "degrees_east"}),
        "lat_v": (("eta_v", "xi_v"), lat_v, {"units": "degrees_north"}),
        "lon_v": (("eta_v", "xi_v"), lon_v, {"units": "degrees_east"}),
    })
    data["mask_u"] = (("eta_u", "xi_u"), wet_u.astype(float), {})
    data["mask_v"] = (("eta_v", "xi_v"), wet_v.astype(float), {})
    data["u"] = (("ocean_time", "s_rho", "eta_u", "xi_u"), (ug[:, None] * level).astype(
        np.float32), {"long_name": "u-momentum component", "units": "meter second-1"})
    data["v"] = (("ocean_time", "s_rho", "eta_v", "xi_v"), (vg[:, None] * level).astype(
        np.float32), {"long_name": "v-momentum component", "units": "meter second-1"})
    return xr.Dataset(data, coords=coords)


#: Basin field: jet (speed m/s, half-width m, meander amplitude m, wavelength m, westward phase
#: speed m/s); waves (speed amplitude m/s, wavelength east m, wavelength north m, westward
#: phase speed m/s, phase rad).
_JET = (0.25, 60e3, 72e3, 900e3, 0.04)
_WAVES = ((0.06, 420e3, 610e3, 0.05, 0.3), (0.05, 560e3, -380e3, 0.04, 1.9),
          (0.05, 330e3, 900e3, 0.06, 4.1), (0.04, 700e3, 450e3, 0.03, 2.7))
_BASIN_CENTRE = (30.8, -49.2)


def basin_current(t_s: ArrayLike, lat: ArrayLike, lon: ArrayLike) -> tuple[np.ndarray,
                                                                           np.ndarray]:
    """The basin-scale current (m/s east, north): a meandering jet plus westward Rossby-like waves.

    Local metres about the basin centre (lat_c, lon_c) = (30.8 N, 49.2 W): x = R cos(lat_c)
    (lon - lon_c), y = R (lat - lat_c) (radians). Streamfunction psi; u = -dpsi/dy,
    v = dpsi/dx (divergence free). Jet: psi = -U L tanh(eta), eta = (y - A sin(k (x + c t)))
    / L, so u = U sech^2(eta), v = U sech^2(eta) A k cos(k (x + c t)). Waves: psi = (s / K)
    sin(k x + l y + k c t + phi), K = |(k, l)|, speed s each, moving west at c. Largest speed
    <= U sqrt(1 + (A k)^2) + sum s = 0.28 + 0.20 = 0.48 m/s.
    """
    t = np.asarray(t_s, dtype=float)
    la = np.asarray(lat, dtype=float)
    lo = np.asarray(lon, dtype=float)
    lat_c, lon_c = _BASIN_CENTRE
    x = EARTH_RADIUS_M * math.cos(math.radians(lat_c)) * np.radians(
        ((lo - lon_c) + 180.0) % 360.0 - 180.0)
    y = EARTH_RADIUS_M * np.radians(la - lat_c)
    speed, width, amp, wavelength, c = _JET
    k = 2.0 * math.pi / wavelength
    phase = k * (x + c * t)
    sech2 = 1.0 / np.cosh((y - amp * np.sin(phase)) / width) ** 2
    u = speed * sech2
    v = speed * sech2 * amp * k * np.cos(phase)
    for s, lx, ly, cw, phi in _WAVES:
        kx, ky = 2.0 * math.pi / lx, 2.0 * math.pi / ly
        kk = math.hypot(kx, ky)
        arg = np.cos(kx * x + ky * y + kx * cw * t + phi) * (s / kk)
        u = u - ky * arg  # -dpsi/dy
        v = v + kx * arg  # dpsi/dx
    return u, v


def basin_dataset(n_lat: int = 260, n_lon: int = 500, n_times: int = 13,
                  step_days: float = 10.0, start: str = "2026-01-01T00") -> Any:
    """The basin-scale Copernicus-like field: 1/12 deg, `basin_current`, one depth 0.494 m.

    Nodes 1/12 deg apart from (20 N, 70 W) (defaults: to 41.6 N, 28.4 W: ~4,000 km wide), n_times
    time levels step_days apart (default 13 over 120 days: a 0.25 m/s glider crosses 2,500 km
    in ~116 days of still water). Float32 like the product (~13 MB in memory).
    """
    lat = 20.0 + np.arange(n_lat) / 12.0
    lon = -70.0 + np.arange(n_lon) / 12.0
    tt = np.datetime64(start, "ns") + (np.arange(n_times) * step_days * 86400e9).astype(
        "timedelta64[ns]")
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ua, va = _sample(basin_current, 0.0, 0.0, tt, LA, LO)
    return copernicus_dataset(lat, lon, tt, [COPERNICUS_DEPTHS[0]], ua[:, None], va[:, None])
