"""Read forecast fields: xarray datasets, NetCDF (CF conventions) and GRIB (cfgrib) files.

Components are found by CF `standard_name` (eastward/northward sea water velocity or wind,
through cf-xarray) and then by the common names: `uo/vo` (Copernicus Marine), `water_u/
water_v` (HYCOM), `u10/v10` (ERA5/GFS), `u_eastward/v_northward` and `u/v` (ROMS),
`vozocrtx/vomecrty` (NEMO). Conventions handled:

- Longitudes: any mix of -180..180 and 0..360 (duplicated columns such as 360 = 0 dropped).
  A regional field is cut at its largest gap in longitude and written -180..180 when it fits,
  else 0..360 (a field across the antimeridian, e.g. 170..190). A global field keeps its
  file's convention and wraps (`GriddedField.periodic_lon`).
- Latitudes made ascending (ERA5 and GRIB scan north to south).
- Time: the coordinate of datetimes along a dimension (`valid_time` of ERA5/cfgrib, `time`,
  `ocean_time` of ROMS). One time step (a length-1 or a scalar coordinate) or none: a steady
  field, with a warning that it is held constant. ERA5's `expver` dimension (ERA5 and ERA5T
  mixed) is merged (first non-missing value); other extra dimensions of size 1 (`number`) are
  dropped, larger ones refused.
- Depth: with `depth_range=(z0, z1)` (m, positive down) the field is averaged over the layer
  by the trapezoidal rule on the file's depth levels (profile interpolated linearly at z0 and
  z1): ubar = (1 / (z1 - z0)) * integral_{z0}^{z1} u(z) dz. Above the first level (Copernicus
  starts at 0.494 m) the top level's value is held constant to the surface, with a warning. A
  layer that reaches below the deepest valid value (NaN) is land. Without a range: the level
  nearest the surface (ROMS s-levels: the top one).
- Curvilinear grids (2-D `lat_rho/lon_rho`, `nav_lat/nav_lon`, staggered `lat_u`, `lat_v`):
  regridded to a regular lat/lon grid (`regrid_curvilinear`), with a warning.

Why this module is long: (about 570 lines, a third of them the name tables and this text): every
convention above is a few lines of detection in one walk over the dataset, kept together so
a reader sees every rule a file passes through; the depth layer (`fields.vertical`), the
grid helpers (`fields.io_grids`), the regridding (`fields.regrid`) and the reading notes
(`fields.read_notes`) live apart.
"""
from __future__ import annotations

import pathlib
import re
from collections.abc import Sequence
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import NODATA_FLOOR, NODATA_OUTSIDE, GriddedField
from glideplan.fields.io_grids import lon_order as _lon_order
from glideplan.fields.io_grids import same_grid as _same_grid
from glideplan.fields.read_notes import SKIPPED_ATTR, quiet_cfgrib, refuse_all_nan
from glideplan.fields.vertical import DEPTH_NAMES, S_LEVELS, depth_average
from glideplan.fields.vertical import reduce_vertical as _vertical

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
_COMMON_NAMES = (("uo", "vo"), ("water_u", "water_v"), ("u10", "v10"),
                 ("u_eastward", "v_northward"), ("vozocrtx", "vomecrty"), ("u", "v"),
                 ("U", "V"), ("uwnd", "vwnd"), ("ugrd10m", "vgrd10m"))
#: Names (and standard-name parts) of a current in water and of a wind in air: which row of
#: `PHYSICAL_RANGES` the field's speeds and a vehicle's speed through it are checked against.
_WATER_NAMES = frozenset({"uo", "water_u", "u_eastward", "vozocrtx"})
_AIR_NAMES = frozenset({"u10", "uwnd", "ugrd10m"})
#: Names whose components are east/north even on a curvilinear grid (others are grid axes).
_EAST_NORTH_NAMES = frozenset({"water_u", "u10", "u_eastward", "uwnd", "ugrd10m"})
_UNITS = {"m s-1": 1.0, "m/s": 1.0, "m s**-1": 1.0, "meter second-1": 1.0, "m.s-1": 1.0,
          "meters/second": 1.0, "metres/second": 1.0, "meter/second": 1.0, "ms-1": 1.0,
          "m sec-1": 1.0, "cm/s": 0.01, "cm s-1": 0.01, "knots": 0.514444, "kt": 0.514444,
          "meter second-1 ": 1.0, "m s^-1": 1.0, "m.s^-1": 1.0}
_LAT = ("latitude", "lat", "nav_lat", "y", "lat_rho", "lat_u", "lat_v", "gphit", "gphiu",
        "gphiv", "TLAT", "XLAT")
_LON = ("longitude", "lon", "nav_lon", "x", "lon_rho", "lon_u", "lon_v", "glamt", "glamu",
        "glamv", "TLONG", "XLONG")
_LAT_UNITS = ("degrees_north", "degree_north", "degree_n", "degrees_n", "degreen", "degreesn")
_LON_UNITS = ("degrees_east", "degree_east", "degree_e", "degrees_e", "degreee", "degreese")
#: Units of projected coordinates (x/y in metres), never latitude/longitude.
_LENGTH_UNITS = frozenset({"m", "km", "meter", "meters", "metre", "metres", "kilometer",
                           "kilometers", "kilometre", "kilometres"})
_TIME = ("valid_time", "time", "ocean_time", "time_counter", "t", "MT")
_DEPTH = DEPTH_NAMES
_S_LEVELS = S_LEVELS


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
        "/eastward_wind, or uo/vo, water_u/water_v, u10/v10, u_eastward/v_northward, u/v)",
    )


def _grid_relative(ds: Any, east: str) -> bool:
    """Whether the components follow a curvilinear grid's axes (not east/north)."""
    attrs = ds[east].attrs
    if "GRIB_uvRelativeToGrid" in attrs:  # GRIB says it (e.g. HRRR on Lambert: 1)
        return bool(int(attrs["GRIB_uvRelativeToGrid"]))
    std = str(attrs.get("standard_name", ""))
    return "eastward" not in std and east not in _EAST_NORTH_NAMES


def _unit_scale(da: Any, name: str) -> float:
    units = str(da.attrs.get("units", "m s-1")).strip()
    if units not in _UNITS:
        raise InvalidParameterError(f"{name} units", units, "not a known speed unit (m s-1)")
    return _UNITS[units]


def _candidates(ds: Any, da: Any, names: Sequence[str], units: Sequence[str],
                standard: str, axis: str) -> list[str]:
    """Names that may hold the latitude or longitude of `da`: CF first, then common names."""
    import cf_xarray  # noqa: F401

    out: list[str] = []
    own = ds[da.name] if da.name in ds.variables else da  # the file's variable, its encoding
    listed = str(own.encoding.get("coordinates", own.attrs.get("coordinates", ""))).split()
    out += [n for n in listed if n in names or re.sub(r"_\d+$", "", n) in names or (
        n in ds.variables and (str(ds[n].attrs.get("units", "")).lower() in units
                               or ds[n].attrs.get("standard_name") == standard))]
    try:
        out += [str(n) for n in da.cf.coordinates.get(standard, [])]
    except Exception:  # cf-xarray may not recognise exotic metadata; fall back to names
        pass
    out += list(names)
    out += [str(c) for c in da.coords if re.sub(r"_\d+$", "", str(c)) in names]
    for name, var in list(da.coords.items()) + list(ds.variables.items()):
        attrs = var.attrs
        if (str(attrs.get("units", "")).lower() in units
                or attrs.get("standard_name") == standard or attrs.get("axis") == axis):
            out.append(str(name))
    return list(dict.fromkeys(out))


#: Per horizontal axis: names, units, the axis's name and its CF axis letter (`_candidates`).
_AXES = {"latitude": (_LAT, _LAT_UNITS, "latitude", "Y"),
         "longitude": (_LON, _LON_UNITS, "longitude", "X")}


def _horizontal(ds: Any, da: Any, name: str) -> tuple[str, Any, Any]:
    """("regular", lat 1-D DataArray, lon 1-D) or ("curvilinear", lat 2-D, lon 2-D) of `da`."""
    found = {}
    for what, (names, units, _, axis) in _AXES.items():
        cands = _candidates(ds, da, names, units, what, axis)
        one = [c for c in cands if c in da.coords and da[c].ndim == 1
               and da[c].dims[0] in da.dims and da[c].size > 1
               and str(da[c].attrs.get("units", "")).strip().lower() not in _LENGTH_UNITS]
        two = []
        for c in cands:
            var = da.coords[c] if c in da.coords else ds.variables.get(c)
            if var is not None and var.ndim == 2 and set(var.dims) <= set(da.dims):
                two.append(var)
        found[what] = (one, two)
    (lat1, lat2), (lon1, lon2) = found["latitude"], found["longitude"]
    if lat1 and lon1 and da[lat1[0]].dims[0] != da[lon1[0]].dims[0]:
        return "regular", da[lat1[0]], da[lon1[0]]
    if lat2 and lon2:
        for la in lat2:
            for lo in lon2:
                if la.dims == lo.dims:
                    return "curvilinear", la, lo
    for what, (one, two) in found.items():
        single = [c for c in _candidates(ds, da, *_AXES[what]) if c in da.coords
                  and da[c].ndim <= 1 and da[c].size == 1]
        if not one and not two and single:  # a subset one row or column wide
            raise InvalidParameterError(
                f"field {what}", float(np.asarray(da[single[0]].values).ravel()[0]),
                f"coordinate {single[0]!r} of {name!r} has one value: a field needs at least "
                "two rows and two columns to interpolate (download a wider box)")
        if not one and not two:
            raise InvalidParameterError(
                f"field {what}", sorted(str(c) for c in da.coords),
                f"no {what} coordinate found for {name!r}",
            )
    raise InvalidParameterError(
        "field coordinates", sorted(str(c) for c in da.coords),
        f"no latitude/longitude pair spans the dimensions of {name!r} {tuple(da.dims)}",
    )


def _is_time(var: Any) -> bool:
    return bool(np.issubdtype(np.asarray(var.values).dtype, np.datetime64))


def _time_axis(ds: Any, da: Any) -> tuple[str | None, np.ndarray | None]:
    """(time dimension or None, datetime64[ns] values (nt,) or None when the file has none).

    A 1-D coordinate of dates along a dimension of `da` (valid_time before time: cfgrib's
    `time` is the forecast's start); else a scalar (0-d) or length-1 date: one time step.
    """
    names = list(_TIME) + [str(c) for c in da.coords if c not in _TIME]
    for n in names:
        if n in da.coords and da[n].ndim == 1 and da[n].dims[0] in da.dims:
            if _is_time(da[n]):
                return str(da[n].dims[0]), np.asarray(da[n].values, dtype="datetime64[ns]")
            if n in _TIME and da[n].size > 1:
                raise InvalidParameterError(
                    "field time", f"{n} ({da[n].dtype})",
                    "must decode to dates (CF units such as 'hours since 2026-01-01')",
                )
    for n in names:
        if n in da.coords and da[n].ndim >= 2 and _is_time(da[n]) and da[n].size > 1:
            raise InvalidParameterError(
                "field time", f"{n} of dimensions {tuple(da[n].dims)}",
                "several forecasts (time x step): select one forecast run first",
            )
    for n in names:
        if n in da.coords and da[n].size == 1 and _is_time(da[n]):
            return None, np.asarray(da[n].values, dtype="datetime64[ns]").reshape(1)
    return None, None


def _merge_expver(d: Any) -> Any:
    """ERA5 with an `expver` dimension (ERA5 and ERA5T): first non-missing value along it."""
    if "expver" not in d.dims:
        return d
    out = d.isel(expver=0, drop=True)
    for k in range(1, d.sizes["expver"]):
        out = out.fillna(d.isel(expver=k, drop=True))
    return out


def _component(ds: Any, name: str, depth_range: tuple[float, float] | None,
               info: dict[str, Any], warnings: list[str]) -> tuple[tuple[Any, ...], Any]:
    """One component: (kind, values (nt, ny, nx) in m/s, lat, lon coordinates, time dimension
    and values) and its (ny, nx) floor mask (the depth range reaches below the sea floor;
    None without a depth range). Extra dimensions of size 1 are dropped, larger refused."""
    d = _merge_expver(ds[name])
    d = d * _unit_scale(d, name)
    kind, lat_c, lon_c = _horizontal(ds, d, name)
    tdim, tvals = _time_axis(ds, d)
    needed = set(lat_c.dims) | set(lon_c.dims) | ({tdim} if tdim is not None else set())
    needed |= {dim for dim in d.dims if dim in _S_LEVELS}
    needed |= {d[n].dims[0] for n in d.coords if d[n].ndim == 1 and (
        n in _DEPTH or d[n].attrs.get("positive") in ("down", "up")
        or d[n].attrs.get("axis") == "Z")}
    extra = [dim for dim in d.dims if dim not in needed]
    for dim in extra:
        if d.sizes[dim] != 1:
            raise InvalidParameterError(
                "field", f"dimension {dim!r} of size {d.sizes[dim]} in {name!r}",
                "unexpected extra dimension: select one member first",
            )
    d = d.isel({dim: 0 for dim in extra}, drop=True) if extra else d
    d = _vertical(ds, d, depth_range, info, warnings)
    lead = [tdim] if tdim is not None else []
    dims = (*lead, *lat_c.dims) if kind == "curvilinear" else (
        *lead, lat_c.dims[0], lon_c.dims[0])
    arr = np.asarray(d.transpose(*dims).values, dtype=float)
    floor = info.pop("_floor", None)
    if floor is not None:
        fl = np.asarray(floor.transpose(*dims).values, dtype=bool)
        floor = np.asarray(fl.reshape((-1, *arr.shape[-2:])).any(axis=0))
    if tdim is None:
        arr = arr[None]
    return (kind, arr, lat_c, lon_c, tdim, tvals), floor


def _in_time_order(comps: list[Any], names: tuple[str, str]) -> tuple[list[Any], Any]:
    """Both components on the same times (else refused), sorted ascending (a repeated time
    refused); the sorted times (or None)."""
    t_e, t_n = comps[0][5], comps[1][5]
    if comps[0][4] != comps[1][4] or (t_e is None) != (t_n is None) or (
            t_e is not None and t_n is not None and not np.array_equal(t_e, t_n)):
        raise InvalidParameterError("field", names, "the two components have different times")
    tdim, tvals = comps[1][4], comps[1][5]
    if tvals is not None and tdim is not None:
        order = np.argsort(tvals, kind="stable")
        tvals = tvals[order]
        if np.any(np.diff(tvals) <= np.timedelta64(0, "ns")):
            raise InvalidParameterError("field time", "repeated", "two records at the same time")
        comps = [(k, a[order], la, lo, td, tv) for k, a, la, lo, td, tv in comps]
    return comps, tvals


def _on_regular_grid(ds: Any, east: str, comps: list[Any], floors: list[np.ndarray],
                     same: bool, warnings: list[str]) -> tuple[Any, ...]:
    """lat, lon (ascending; longitudes per `_lon_order`), u, v (nt, nlat, nlon) and the
    nodata codes (or None): curvilinear components regridded, regular ones reordered."""
    if comps[0][0] == "curvilinear":
        lat, lon, u, v, outside, below = _regrid(ds, east, comps, warnings,
                                                 floors if len(floors) == 2 else [])
        codes = np.where(outside, NODATA_OUTSIDE,
                         np.where(below, NODATA_FLOOR, 0)).astype(np.int8)
        return lat, lon, u, v, codes
    lat = np.asarray(comps[0][2].values, dtype=float)
    lon_raw = np.asarray(comps[0][3].values, dtype=float)
    lon, xo = _lon_order(lon_raw)
    yo = np.argsort(lat)
    lat = lat[yo]
    u, v = (c[1][:, yo][:, :, xo] for c in comps)
    nodata: np.ndarray | None = None
    if floors and same and all(f.shape == u.shape[1:] for f in floors):
        floor = np.logical_or.reduce([f[yo][:, xo] for f in floors])
        nodata = np.where(floor, NODATA_FLOOR, 0).astype(np.int8)
    return lat, lon, u, v, nodata


def from_xarray(
    ds: Any,
    depth_range: tuple[float, float] | None = None,
    source: str = "dataset",
) -> GriddedField:
    """A `GriddedField` from an xarray Dataset (module docstring for the conventions)."""
    east, north = _find_components(ds)
    info: dict[str, Any] = {"kind": "gridded", "source": source, "variables": [east, north]}
    warnings: list[str] = []
    comps = []
    floors: list[np.ndarray] = []  # per component: (ny, nx) the depth range reaches the floor
    for name in (east, north):
        comp, floor = _component(ds, name, depth_range, info, warnings)
        comps.append(comp)
        if floor is not None:
            floors.append(floor)
    comps, tvals = _in_time_order(comps, (east, north))
    same = comps[0][2].shape == comps[1][2].shape
    comps = _same_grid(comps)
    lat, lon, u, v, nodata = _on_regular_grid(ds, east, comps, floors, same, warnings)
    refuse_all_nan(u, v, source, nodata)
    if tvals is None:
        epoch = None
        times = np.zeros(1)
        warnings.append("the file has no time coordinate: the field is held constant in time")
    else:
        epoch = tvals[0]
        times = (tvals - epoch) / np.timedelta64(1, "s")
        if tvals.size == 1:
            warnings.append(f"the file has one time step ({str(epoch)[:19]}Z): the field is "
                            "held constant in time")
    info["medium"] = _medium(ds, east)
    warnings += _too_fast(u, v, (east, north), info["medium"], ds[east].attrs.get("units"))
    return GriddedField(times=np.asarray(times, dtype=float), lat=lat, lon=lon, u=u, v=v,
                        epoch=epoch, info=info, warnings=tuple(warnings), nodata=nodata)


def _medium(ds: Any, east: str) -> str | None:
    """"water" (a sea-water velocity), "air" (a wind) or None (plain u/v: not known)."""
    std = str(ds[east].attrs.get("standard_name", ""))
    if "sea_water" in std or east in _WATER_NAMES:
        return "water"
    if "wind" in std or east in _AIR_NAMES:
        return "air"
    return None


def _too_fast(u: Any, v: Any, names: tuple[str, str], medium: str | None,
              units: Any) -> list[str]:
    """A warning naming the variables when the field's fastest speed lies beyond its row of
    `PHYSICAL_RANGES` ("current_speed" in water, else "wind_speed"): a field in cm/s labelled
    m/s reads 100 times too fast."""
    from glideplan.validation import PHYSICAL_RANGES

    row = PHYSICAL_RANGES["current_speed" if medium == "water" else "wind_speed"]
    with np.errstate(invalid="ignore"):
        speed = np.hypot(u, v)
    top = float(np.nanmax(speed)) if np.any(np.isfinite(speed)) else 0.0
    if top <= row.high:
        return []
    what = "current" if medium == "water" else "flow"
    return [f"{names[0]}/{names[1]}: the {what} reaches {top:.3g} m/s (units "
            f"{str(units or 'm s-1')!r}), beyond {row.high:g} m/s ({row.reason}): are the "
            "values cm/s labelled m/s?"]


def _regrid(ds: Any, east: str, comps: list[Any], warnings: list[str],
            floors: list[np.ndarray]) -> tuple[
        np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Regrid curvilinear components (their own 2-D coordinates) to a regular lat/lon grid;
    floors: per component, where the depth range reaches below the sea floor (or [])."""
    from glideplan.fields.regrid import CurvilinearSource, regrid_curvilinear

    sources = []
    for _, arr, lat_c, lon_c, _, _ in comps:
        la = np.asarray(lat_c.values, dtype=float)
        lo = np.asarray(lon_c.values, dtype=float)
        mask_name = "mask_" + str(lat_c.name).split("_", 1)[-1]
        if str(lat_c.name).startswith("lat_") and mask_name in ds.variables and (
                ds[mask_name].shape == la.shape):
            arr = np.where(np.asarray(ds[mask_name].values) == 0, np.nan, arr)
        sources.append(CurvilinearSource(arr, la, lo, f"{lat_c.name}/{lon_c.name}"))
    angle = None
    rotate = _grid_relative(ds, east)
    if rotate and "angle" in ds.variables and ds["angle"].ndim == 2:
        ang = ds["angle"]
        try:
            kind, la_a, lo_a = _horizontal(ds, ang, "angle")
        except InvalidParameterError:
            kind = "none"
        if kind == "curvilinear":
            units = str(ang.attrs.get("units", "radians")).lower()
            vals = np.asarray(ang.values, dtype=float)
            if units.startswith("deg"):
                vals = np.radians(vals)
            angle = CurvilinearSource(vals[None], np.asarray(la_a.values, dtype=float),
                                      np.asarray(lo_a.values, dtype=float), "angle")
    out = regrid_curvilinear(sources[0], sources[1], angle=angle, grid_relative=rotate,
                             floor=(floors[0], floors[1]) if floors else (None, None))
    warnings.extend(out.warnings)
    outside = np.zeros(out.u.shape[1:], bool) if out.outside is None else out.outside
    below = np.zeros(out.u.shape[1:], bool) if out.floor is None else out.floor
    return out.lat, out.lon, out.u, out.v, outside, below


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
        with quiet_cfgrib() as skipped, xr.open_dataset(path, engine=engine, **kwargs) as ds:
            out = ds.load()
        if skipped:  # said once, as a warning of the field (`open_field`), not a traceback
            out.attrs[SKIPPED_ATTR] = [
                f"{path}: cfgrib skipped the GRIB variable(s) {', '.join(skipped)} (messages "
                "that do not form one hypercube with the rest of the file, e.g. other steps "
                "or levels); the currents were read from the other messages"]
        return out
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
    skipped = [note for d in dsets for note in d.attrs.pop(SKIPPED_ATTR, [])]
    if len(dsets) == 1:
        ds = dsets[0]
    else:
        _check_one_lattice(dsets, items)
        try:
            ds = xr.merge(dsets, compat="no_conflicts", join="outer", combine_attrs="override")
        except Exception as exc:
            ds = _merge_staggered(dsets)
            if ds is None:
                msg = " ".join(str(exc).split())[:160]
                raise InvalidParameterError("field", [str(p) for p in items],
                                            f"files do not combine ({msg})") from None
    out = from_xarray(ds, depth_range=depth_range, source=", ".join(str(p) for p in items))
    if skipped:
        from dataclasses import replace

        out = replace(out, warnings=out.warnings + tuple(skipped))
    return out


def _check_one_lattice(dsets: list[Any], items: list[Any]) -> None:
    """Refuse files whose 1-D latitude/longitude axes leave nodes of their union in no file:
    the outer join would fill them with NaN, which a route reads as land. (u and v apart,
    time chunks and adjacent boxes of one lattice cover every node.)"""
    axes = []
    for names in (_LAT, _LON):
        name = next((n for n in names if all(n in d.dims and n in d.coords for d in dsets)),
                    None)
        if name is None:
            return  # curvilinear or unnamed axes: merged (or refused) as before
        axes.append([np.asarray(d[name].values, dtype=float) for d in dsets])
    lat_all, lon_all = (np.unique(np.concatenate(vals)) for vals in axes)
    for what, vals, union in (("latitude", axes[0], lat_all), ("longitude", axes[1], lon_all)):
        own = max((float(np.max(np.abs(np.diff(v)))) for v in vals if v.size > 1), default=0.0)
        steps = np.diff(union)
        if own > 0 and steps.size and float(steps.max()) > 1.5 * own:
            k = int(np.argmax(steps))
            raise InvalidParameterError(
                "field", [str(p) for p in items],
                f"a gap between the files' {what}s {union[k]:g} and {union[k + 1]:g} (their "
                f"own spacing at most {own:g}) would be interpolated across: merge only files "
                "on one grid (u and v apart, time chunks, adjacent boxes)")
    covered = np.zeros((lat_all.size, lon_all.size), bool)
    for la, lo in zip(*axes, strict=True):
        covered |= np.isin(lat_all, la)[:, None] & np.isin(lon_all, lo)[None, :]
    if not covered.all():
        i, j = np.argwhere(~covered)[0]
        raise InvalidParameterError(
            "field", [str(p) for p in items],
            f"their grids leave {int((~covered).sum())} of {covered.size} nodes of the merged "
            f"grid in no file (e.g. {lat_all[i]:g}, {lon_all[j]:g}: a gap between the files' "
            "areas or different spacings), which would read as land: merge only files on one "
            "grid (u and v apart, time chunks, adjacent boxes)")


def _merge_staggered(dsets: list[Any]) -> Any:
    """Merge files whose non-index coordinates share a name but differ (NEMO grid_U and
    grid_V files both call their points nav_lat/nav_lon): each file's copy, and the
    dimensions it spans, are renamed name_<k> (found again by `_candidates`), so each variable
    keeps its own points. None when that does not combine either."""
    import xarray as xr

    clash = set()
    for i, a in enumerate(dsets):
        for b in dsets[i + 1:]:
            for name in set(a.coords) & set(b.coords):
                if name in a.dims or name in b.dims:
                    continue
                if a[name].shape != b[name].shape or not np.array_equal(
                        np.asarray(a[name].values), np.asarray(b[name].values)):
                    clash.add(name)
    if not clash:
        return None
    renamed = []
    for k, d in enumerate(dsets):
        names = {n: f"{n}_{k}" for n in clash if n in d.variables}
        dims = {dim for n in names for dim in d[n].dims}  # each file keeps its own points
        names.update({dim: f"{dim}_{k}" for dim in dims if dim not in names})
        renamed.append(d.rename(names))
    try:
        return xr.merge(renamed, compat="no_conflicts", join="outer", combine_attrs="override")
    except Exception:
        return None
