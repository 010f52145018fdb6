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
"""
from __future__ import annotations

import pathlib
import re
from collections.abc import Sequence
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import NODATA_FLOOR, NODATA_OUTSIDE, GriddedField
from glideplan.fields.read_notes import SKIPPED_ATTR, quiet_cfgrib, refuse_all_nan

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
_DEPTH = ("depth", "lev", "z", "deptht", "depthu", "depthv", "level")
_S_LEVELS = ("s_rho", "s_w")


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


def _horizontal(ds: Any, da: Any, name: str) -> tuple[str, Any, Any]:
    """("regular", lat 1-D DataArray, lon 1-D) or ("curvilinear", lat 2-D, lon 2-D) of `da`."""
    found = {}
    for what, names, units, axis in (("latitude", _LAT, _LAT_UNITS, "Y"),
                                     ("longitude", _LON, _LON_UNITS, "X")):
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


def depth_average(profile: np.ndarray, depths: np.ndarray, z0: float, z1: float) -> np.ndarray:
    """Trapezoidal layer mean over [z0, z1] (m, positive down) along axis 0 of `profile`.

    ubar = (1/(z1-z0)) sum_k (z_{k+1} - z_k) (u_k + u_{k+1}) / 2 over the levels inside the
    layer, with the profile linearly interpolated at z0 and z1. Above the first level z_1 the
    profile is held at u_1 (to the surface, z0 >= 0): the layer [0, z_1] adds z_1 u_1. NaN
    anywhere in the layer (below the sea floor, land) gives NaN.
    """
    z = np.asarray(depths, dtype=float).reshape(-1)
    order = np.argsort(z)
    z = z[order]
    prof = np.asarray(profile, dtype=float)[order]
    if not (np.isfinite(z0) and np.isfinite(z1) and z0 < z1):
        raise InvalidParameterError("depth_range", (z0, z1), "needs Z0 < Z1 (m, positive down)")
    if z0 < 0.0:
        raise InvalidParameterError(
            "depth_range", (z0, z1), "depths are metres below the surface (Z0 >= 0)"
        )
    if z1 > z[-1] + 1e-9:
        raise InvalidParameterError(
            "depth_range", (z0, z1),
            f"below the file's deepest level {z[-1]:g} m (depth levels {z[0]:g}..{z[-1]:g} m)",
        )
    if z0 < z[0]:  # constant extrapolation to the surface only
        z = np.concatenate([[z0], z])
        prof = np.concatenate([prof[:1], prof], axis=0)

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


def _lon_order(lon: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
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


def _vertical(ds: Any, d: Any, depth_range: tuple[float, float] | None, info: dict[str, Any],
              warnings: list[str]) -> Any:
    """Reduce the depth (or ROMS s-level) dimension: layer mean or the level nearest 0 m."""
    for sname in _S_LEVELS:
        if sname in d.dims:
            if depth_range is not None:
                raise InvalidParameterError(
                    "depth_range", depth_range,
                    f"the file has terrain-following levels ({sname}) without fixed depths: "
                    "interpolate it to depth levels first, or omit the depth range to use the "
                    "top level",
                )
            s = np.asarray(d[sname].values if sname in d.coords else np.arange(d.sizes[sname]),
                           dtype=float)
            k = int(np.argmax(s))
            info["depth_m"] = 0.0
            info["level"] = f"top {sname} level ({s[k]:g})"
            return d.isel({sname: k}, drop=True)
    depth_n = None
    for n in list(_DEPTH) + [str(c) for c in d.coords]:
        if n in d.coords and d[n].ndim == 1 and d[n].dims[0] in d.dims and (
                n in _DEPTH or d[n].attrs.get("positive") in ("down", "up")
                or d[n].attrs.get("axis") == "Z"):
            depth_n = n
            break
    if depth_n is None:
        if depth_range is not None:
            raise InvalidParameterError("depth_range", depth_range,
                                        "the field has no depth levels")
        return d
    depths = np.abs(np.asarray(d[depth_n].values, dtype=float))
    zdim = d[depth_n].dims[0]
    d = d.transpose(zdim, ...)
    if depth_range is None:
        k = int(np.argmin(depths))
        info["depth_m"] = float(depths[k])
        return d.isel({zdim: k}, drop=True)
    z0, z1 = float(depth_range[0]), float(depth_range[1])
    vals = depth_average(np.asarray(d.values, dtype=float), depths, z0, z1)
    info["depth_average_m"] = [z0, z1]
    # nodes with water at the top level but no layer mean: the range reaches the sea floor
    top_ok = np.isfinite(np.asarray(d.isel({zdim: int(np.argmin(depths))}).values, dtype=float))
    info["_floor"] = d.isel({zdim: 0}, drop=True).copy(data=top_ok & ~np.isfinite(vals))
    top = float(np.min(depths))
    if np.isfinite(z0) and z0 < top:
        text = (f"depth range {z0:g}..{z1:g} m starts above the file's first level {top:g} m: "
                f"the top level's value is used from {z0:g} to {top:g} m (held constant to "
                "the surface)")
        if text not in warnings:
            warnings.append(text)
    return d.isel({zdim: 0}, drop=True).copy(data=vals)


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
    tdim, tvals = None, None
    for name in (east, north):
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
            floors.append(np.asarray(fl.reshape((-1, *arr.shape[-2:])).any(axis=0)))
        if tdim is None:
            arr = arr[None]
        comps.append((kind, arr, lat_c, lon_c, tdim, tvals))
    t_e, t_n = comps[0][5], comps[1][5]
    if comps[0][4] != comps[1][4] or (t_e is None) != (t_n is None) or (
            t_e is not None and t_n is not None and not np.array_equal(t_e, t_n)):
        raise InvalidParameterError("field", (east, north),
                                    "the two components have different times")
    if tvals is not None and tdim is not None:
        order = np.argsort(tvals, kind="stable")
        tvals = tvals[order]
        if np.any(np.diff(tvals) <= np.timedelta64(0, "ns")):
            raise InvalidParameterError("field time", "repeated", "two records at the same time")
        comps = [(k, a[order], la, lo, td, tv) for k, a, la, lo, td, tv in comps]
    same = comps[0][2].shape == comps[1][2].shape
    comps = _same_grid(comps)
    nodata = None
    if comps[0][0] == "curvilinear":
        lat, lon, u, v, outside, below = _regrid(ds, east, comps, warnings,
                                                 floors if len(floors) == 2 else [])
        nodata = np.where(outside, NODATA_OUTSIDE,
                          np.where(below, NODATA_FLOOR, 0)).astype(np.int8)
    else:
        lat = np.asarray(comps[0][2].values, dtype=float)
        lon_raw = np.asarray(comps[0][3].values, dtype=float)
        lon, xo = _lon_order(lon_raw)
        yo = np.argsort(lat)
        lat = lat[yo]
        u, v = (c[1][:, yo][:, :, xo] for c in comps)
        if floors and same and all(f.shape == u.shape[1:] for f in floors):
            floor = np.logical_or.reduce([f[yo][:, xo] for f in floors])
            nodata = np.where(floor, NODATA_FLOOR, 0).astype(np.int8)
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


def _same_grid(comps: list[Any]) -> list[Any]:
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
