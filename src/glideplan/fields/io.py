"""Read forecast fields: xarray datasets, NetCDF (CF conventions) and GRIB (cfgrib) files.

Components are found by CF `standard_name` (eastward/northward sea water velocity or wind,
through cf-xarray) and then by the common names: `uo/vo` (Copernicus Marine), `water_u/
water_v` (HYCOM), `u10/v10` (ERA5/GFS GRIB), `u/v`. Longitudes are normalised to -180..180
(kept 0..360 when the field crosses the antimeridian), latitudes made ascending, times made
datetime64. With `depth_range=(z0, z1)` (m, positive down) the field is averaged over the
layer by the trapezoidal rule on the file's depth levels (profile interpolated linearly at
z0 and z1): ubar = (1 / (z1 - z0)) * integral_{z0}^{z1} u(z) dz. A layer that reaches below
the deepest valid value (NaN) is land.
"""

from __future__ import annotations

import pathlib
from collections.abc import Sequence
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import GriddedField

__all__ = ["depth_average", "from_xarray", "open_field", "pyproj_before_eccodes"]


def pyproj_before_eccodes() -> None:
    """Load PROJ (pyproj) before ecCodes: the other order crashes the interpreter at exit.

    Measured here (eccodes 2.x wheels with pyproj 3.x): importing eccodes first and then
    using pyproj ends the process with "double free or corruption" / SIGSEGV at shutdown;
    pyproj first is clean. Called before every cfgrib/eccodes use.
    """
    try:
        import pyproj  # noqa: F401
    except ImportError:  # pragma: no cover - pyproj is a core dependency of routing
        pass

_STANDARD_NAMES = (
    ("eastward_sea_water_velocity", "northward_sea_water_velocity"),
    ("surface_eastward_sea_water_velocity", "surface_northward_sea_water_velocity"),
    ("baroclinic_eastward_sea_water_velocity", "baroclinic_northward_sea_water_velocity"),
    ("eastward_wind", "northward_wind"),
)
_COMMON_NAMES = (("uo", "vo"), ("water_u", "water_v"), ("u10", "v10"), ("u", "v"),
                 ("U", "V"), ("uwnd", "vwnd"), ("ugrd10m", "vgrd10m"))
_UNITS = {"m s-1": 1.0, "m/s": 1.0, "m s**-1": 1.0, "meter second-1": 1.0, "m.s-1": 1.0,
          "meters/second": 1.0, "metres/second": 1.0, "meter/second": 1.0, "ms-1": 1.0,
          "m sec-1": 1.0, "cm/s": 0.01, "cm s-1": 0.01, "knots": 0.514444, "kt": 0.514444}
_LAT = ("latitude", "lat", "nav_lat", "y")
_LON = ("longitude", "lon", "nav_lon", "x")
_TIME = ("valid_time", "time", "t", "MT")
_DEPTH = ("depth", "lev", "z", "deptht", "level")


def _find_components(ds: Any) -> tuple[str, str]:
    import cf_xarray  # noqa: F401  (registers the .cf accessor)

    names = ds.cf.standard_names
    for east, north in _STANDARD_NAMES:
        if east in names and north in names:
            e = [n for n in names[east] if n in ds.data_vars]
            n_ = [n for n in names[north] if n in ds.data_vars]
            if e and n_:
                return e[0], n_[0]
    for east, north in _COMMON_NAMES:
        if east in ds.data_vars and north in ds.data_vars:
            return east, north
    raise InvalidParameterError(
        "field variables",
        sorted(str(k) for k in ds.data_vars),
        "no eastward/northward velocity pair found (standard_name eastward_sea_water_velocity"
        "/eastward_wind, or uo/vo, water_u/water_v, u10/v10)",
    )


def _coord_name(da: Any, candidates: Sequence[str], what: str, required: bool = True) -> Any:
    import cf_xarray  # noqa: F401

    try:
        found = da.cf.coordinates.get(what, [])
    except Exception:  # cf-xarray may not recognise exotic metadata; fall back to names
        found = []
    for name in list(found) + list(candidates):
        if name in da.coords and (da[name].ndim == 1 or da[name].size == 1):
            return name
    if required:
        raise InvalidParameterError(
            f"field {what}", sorted(str(c) for c in da.coords), f"no {what} coordinate found"
        )
    return None


def _unit_scale(da: Any, name: str) -> float:
    units = str(da.attrs.get("units", "m s-1")).strip()
    if units not in _UNITS:
        raise InvalidParameterError(f"{name} units", units, "not a known speed unit (m s-1)")
    return _UNITS[units]


def depth_average(profile: np.ndarray, depths: np.ndarray, z0: float, z1: float) -> np.ndarray:
    """Trapezoidal layer mean over [z0, z1] (m, positive down) along axis 0 of `profile`.

    ubar = (1/(z1-z0)) sum_k (z_{k+1} - z_k) (u_k + u_{k+1}) / 2 over the levels inside the
    layer, with the profile linearly interpolated at z0 and z1. NaN anywhere in the layer
    (below the sea floor, land) gives NaN.
    """
    z = np.asarray(depths, dtype=float)
    order = np.argsort(z)
    z = z[order]
    prof = np.asarray(profile, dtype=float)[order]
    if not (z0 < z1):
        raise InvalidParameterError("depth_range", (z0, z1), "needs Z0 < Z1 (m, positive down)")
    if z0 < z[0] - 1e-9 or z1 > z[-1] + 1e-9:
        raise InvalidParameterError(
            "depth_range", (z0, z1),
            f"outside the file's depth levels [{z[0]:g}, {z[-1]:g}] m",
        )

    def at(zq: float) -> np.ndarray:
        k = int(np.clip(np.searchsorted(z, zq, side="right") - 1, 0, z.size - 2))
        w = (zq - z[k]) / (z[k + 1] - z[k])
        if w <= 0.0:
            return prof[k]
        if w >= 1.0:
            return prof[k + 1]
        return (1.0 - w) * prof[k] + w * prof[k + 1]

    inner = (z > z0) & (z < z1)
    zs = np.concatenate([[z0], z[inner], [z1]])
    vals = np.concatenate([at(z0)[None], prof[inner], at(z1)[None]], axis=0)
    dz = np.diff(zs).reshape((-1,) + (1,) * (vals.ndim - 1))
    return (0.5 * dz * (vals[1:] + vals[:-1])).sum(axis=0) / (z1 - z0)


def _normalise_lon(lon: np.ndarray) -> np.ndarray:
    """-180..180 unless that breaks monotonicity (a field across the antimeridian): 0..360."""
    a = (lon + 180.0) % 360.0 - 180.0
    if np.all(np.diff(a) > 0):
        return a
    b = lon % 360.0
    if np.all(np.diff(b) > 0):
        return b
    return a  # sorted below


def from_xarray(
    ds: Any,
    depth_range: tuple[float, float] | None = None,
    source: str = "dataset",
) -> GriddedField:
    """A `GriddedField` from an xarray Dataset (module docstring for the conventions)."""
    east, north = _find_components(ds)
    das = []
    info: dict[str, Any] = {"kind": "gridded", "source": source, "variables": [east, north]}
    for name in (east, north):
        da = ds[name]
        da = da * _unit_scale(da, name)
        das.append(da)
    da = das[0]
    lat_n = _coord_name(da, _LAT, "latitude")
    lon_n = _coord_name(da, _LON, "longitude")
    time_n = _coord_name(da, _TIME, "time", required=False)
    if time_n is not None and da[time_n].ndim == 1 and da[time_n].dims[0] not in da.dims:
        time_n = None
    if time_n is None and "time" in da.coords and da["time"].size == 1:
        time_n = None
    depth_n = _coord_name(da, _DEPTH, "vertical", required=False)
    if depth_n is not None and (da[depth_n].ndim != 1 or da[depth_n].dims[0] not in da.dims):
        depth_n = None
    dims_needed = {da[lat_n].dims[0], da[lon_n].dims[0]}
    if time_n is not None:
        dims_needed.add(da[time_n].dims[0])
    if depth_n is not None:
        dims_needed.add(da[depth_n].dims[0])
    out = []
    for d in das:
        extra = [dim for dim in d.dims if dim not in dims_needed]
        for dim in extra:
            if d.sizes[dim] != 1:
                raise InvalidParameterError(
                    "field", f"dimension {dim!r} of size {d.sizes[dim]}",
                    "unexpected extra dimension: select one member first",
                )
        d = d.squeeze(extra, drop=True) if extra else d
        if depth_n is not None:
            depths = np.asarray(d[depth_n].values, dtype=float)
            zdim = d[depth_n].dims[0]
            d = d.transpose(zdim, ...)
            if depth_range is not None:
                vals = depth_average(np.asarray(d.values, dtype=float), np.abs(depths),
                                     float(depth_range[0]), float(depth_range[1]))
                d = d.isel({zdim: 0}, drop=True).copy(data=vals)
                info["depth_average_m"] = [float(depth_range[0]), float(depth_range[1])]
            else:
                k = int(np.argmin(np.abs(depths)))
                d = d.isel({zdim: k}, drop=True)
                info["depth_m"] = float(abs(depths[k]))
        out.append(d)
    if depth_range is not None and depth_n is None:
        raise InvalidParameterError("depth_range", depth_range, "the field has no depth levels")
    lat = np.asarray(out[0][lat_n].values, dtype=float)
    lon = _normalise_lon(np.asarray(out[0][lon_n].values, dtype=float))
    ydim, xdim = out[0][lat_n].dims[0], out[0][lon_n].dims[0]
    yo, xo = np.argsort(lat), np.argsort(lon)
    if time_n is not None:
        tdim = out[0][time_n].dims[0]
        tvals = np.asarray(out[0][time_n].values)
        if not np.issubdtype(tvals.dtype, np.datetime64):
            raise InvalidParameterError("field time", str(tvals.dtype), "must decode to dates")
        tvals = tvals.astype("datetime64[ns]")
        to = np.argsort(tvals)
        epoch = tvals[to][0]
        times = (tvals[to] - epoch) / np.timedelta64(1, "s")
        arrs = [np.asarray(d.transpose(tdim, ydim, xdim).values, dtype=float)[to][:, yo][:, :, xo]
                for d in out]
    else:
        epoch = None
        times = np.zeros(1)
        arrs = [np.asarray(d.transpose(ydim, xdim).values, dtype=float)[yo][:, xo][None]
                for d in out]
        if "time" in ds.coords and ds["time"].size == 1:
            tv = np.asarray(ds["time"].values).reshape(-1)[0]
            if np.issubdtype(np.asarray(tv).dtype, np.datetime64):
                epoch = np.datetime64(tv, "ns")
    return GriddedField(times=np.asarray(times, dtype=float), lat=lat[yo], lon=lon[xo],
                        u=arrs[0], v=arrs[1], epoch=epoch, info=info)


def _engine(path: pathlib.Path) -> str:
    with path.open("rb") as fh:
        head = fh.read(8)
    if head[:4] == b"GRIB":
        return "cfgrib"
    if head[:3] == b"CDF" or head[:8] == b"\x89HDF\r\n\x1a\n":
        try:
            import netCDF4  # noqa: F401
        except ImportError:  # pragma: no cover - the fields extra installs netCDF4
            return "h5netcdf" if head[:3] != b"CDF" else "scipy"
        return "netcdf4"
    raise InvalidParameterError("field", str(path), "not a NetCDF or GRIB file")


def _open_one(path: pathlib.Path) -> Any:
    import xarray as xr

    if not path.exists():
        raise InvalidParameterError("field", str(path), "no such file")
    if not path.is_file():
        raise InvalidParameterError("field", str(path), "not a file")
    engine = _engine(path)
    kwargs: dict[str, Any] = {}
    if engine == "cfgrib":
        pyproj_before_eccodes()
        kwargs["backend_kwargs"] = {"indexpath": ""}
    try:
        # Load and close at once: files left open until interpreter exit can crash HDF5.
        with xr.open_dataset(path, engine=engine, **kwargs) as ds:
            return ds.load()
    except InvalidParameterError:
        raise
    except Exception as exc:  # any reader failure is a bad file for the user
        msg = " ".join(str(exc).split())[:160]
        raise InvalidParameterError("field", str(path), f"cannot read ({msg})") from None


def open_field(
    paths: str | pathlib.Path | Sequence[str | pathlib.Path],
    depth_range: tuple[float, float] | None = None,
) -> GriddedField:
    """Read one or more NetCDF/GRIB files (merged: e.g. u and v apart, or time chunks)."""
    import xarray as xr

    items = [paths] if isinstance(paths, (str, pathlib.Path)) else list(paths)
    if not items:
        raise InvalidParameterError("field", items, "give at least one file")
    dsets = [_open_one(pathlib.Path(p)) for p in items]
    if len(dsets) == 1:
        ds = dsets[0]
    else:
        try:
            ds = xr.merge(dsets, compat="no_conflicts", join="outer", combine_attrs="override")
        except Exception as exc:
            msg = " ".join(str(exc).split())[:160]
            raise InvalidParameterError("field", [str(p) for p in items],
                                        f"files do not combine ({msg})") from None
    return from_xarray(ds, depth_range=depth_range, source=", ".join(str(p) for p in items))
