"""Flow fields (currents or winds): vectorised velocity(t, lat, lon) -> (u_east, v_north) in m/s.

Three kinds share one interface (`FlowField`):

- `UniformField(u, v)`: the same velocity everywhere, always.
- `AnalyticField(fn, ...)`: a callable fn(t, lat, lon) -> (u, v), with an optional extent and
  time span.
- `GriddedField(...)`: values on a (time, latitude, longitude) grid, linearly interpolated in
  space and time (SciPy's RegularGridInterpolator). NaN means land or missing data: any query
  whose interpolation stencil touches a NaN returns NaN, which the router treats as an
  obstacle, never as zero.

Time `t` is seconds since the field's `epoch` (a `numpy.datetime64`, or None for a field with
no calendar); `datetime64` values are accepted too. A query outside the field's extent or
time span raises `InvalidParameterError` naming the bound; nothing is extrapolated.

Global fields wrap in longitude. A `GriddedField` whose nx columns at step dlon close the circle
(|nx dlon - 360| <= dlon / 2, e.g. 0..359.75 or -180..179.75 at 0.25 deg) is periodic
(`periodic_lon`, `Extent.periodic`): every longitude is inside it, and a query in the seam
between the last and the first column (359.75..360) interpolates linearly between them, as
anywhere else. Longitudes are taken modulo 360 (-3 and 357 are the same meridian).

Fields carry `warnings` (e.g. a depth layer extended to the surface, a regridded curvilinear
grid, a single time step held constant); `describe()` lists them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.point import grid_values, interpolate, position_in_frame

__all__ = [
    "AnalyticField",
    "Extent",
    "FlowField",
    "GriddedField",
    "UniformField",
    "to_seconds",
]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class Extent:
    """Latitude/longitude box (degrees). Longitudes may run past 180 (a 0..360 field).

    `periodic`: the field closes the circle of longitude (a global file); then
    lon_max = lon_min + 360 and every longitude is inside (taken modulo 360).
    """

    lat_min: float
    lat_max: float
    lon_min: float
    lon_max: float
    periodic: bool = False

    def contains_lon(self, lon: ArrayLike) -> NDArray[np.bool_]:
        """Whether each longitude (any representation, degrees) lies inside the extent."""
        lo = self.lon_min + np.mod(np.asarray(lon, dtype=float) - self.lon_min, 360.0)
        if self.periodic:
            return np.ones(lo.shape, dtype=bool)
        return lo <= self.lon_max + 1e-9

    def to_dict(self) -> dict[str, Any]:
        return {
            "lat_min": self.lat_min,
            "lat_max": self.lat_max,
            "lon_min": self.lon_min,
            "lon_max": self.lon_max,
            "periodic": self.periodic,
        }


def parse_utc(text: str | None, name: str = "depart") -> np.datetime64 | None:
    """An ISO 8601 time (UTC when it has no offset; 'Z' accepted) as numpy.datetime64[ms] in
    UTC, or None for None; a bad text (also "") is refused naming `name`."""
    if text is None:
        return None
    import datetime as dt

    try:
        when = dt.datetime.fromisoformat(text.strip())
    except ValueError:
        raise InvalidParameterError(name, text, "must be ISO 8601 (2026-01-01T06:00Z)") from None
    if when.tzinfo is not None:
        when = when.astimezone(dt.UTC).replace(tzinfo=None)
    return np.datetime64(when, "ms")


def to_seconds(t: Any, epoch: np.datetime64 | None) -> FloatArray:
    """Seconds since `epoch` of `t` (seconds already, or datetime64 values)."""
    a = np.asarray(t)
    if np.issubdtype(a.dtype, np.datetime64):
        if epoch is None:
            raise InvalidParameterError("time", t, "this field has no calendar: give seconds")
        return (a - epoch) / np.timedelta64(1, "s")
    try:
        out = np.asarray(a, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError("time", t, "must be seconds or datetime64") from None
    if not np.all(np.isfinite(out)):
        raise InvalidParameterError("time", t, "must be finite")
    return out


class FlowField:
    """Base of every field: `velocity(t, lat, lon)` plus extent, time span and a description."""

    epoch: np.datetime64 | None = None
    extent: Extent | None = None
    #: (t_first, t_last) seconds since epoch, or None for a steady field.
    time_span: tuple[float, float] | None = None
    info: Mapping[str, Any] = {}
    #: What the reader changed or assumed (printed by the CLI as "glideplan: warning: ...").
    warnings: tuple[str, ...] = ()

    def velocity(self, t: Any, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
        """(u_east, v_north) in m/s at times t (s since epoch) and WGS84 lat/lon (deg)."""
        raise NotImplementedError

    def velocity_at(self, t: float, lat: float, lon: float) -> tuple[float, float]:
        """`velocity` at one time and point, as floats (the integrators' hot path).

        Same values and the same errors as `velocity`; fields override it with a scalar
        path that skips the array machinery (a flown route asks ~10^5 single points).
        """
        u, v = self.velocity(t, lat, lon)
        return float(u), float(v)

    def _scalar_position(self, t: float, lat: float, lon: float) -> float | None:
        """The longitude in the field's frame when (t, lat, lon) passes `check_time` and
        `check_position` (same tolerances and wrapping), else None (then `velocity` raises)."""
        return position_in_frame(self.extent, self.time_span, t, lat, lon)

    @property
    def time_levels(self) -> FloatArray | None:
        """The field's own time levels (s since epoch), None when it has none (steady/analytic)."""
        return None

    def check_time(self, t: Any) -> FloatArray:
        """Times as seconds; raise naming the bound when outside the time span."""
        ts = to_seconds(t, self.epoch)
        if self.time_span is not None and ts.size:
            lo, hi = self.time_span
            tol = 1e-6 * max(1.0, hi - lo)
            if np.min(ts) < lo - tol:
                raise InvalidParameterError(
                    "time", self.format_time(float(np.min(ts))),
                    f"before the field's first time {self.format_time(lo)}",
                )
            if np.max(ts) > hi + tol:
                raise InvalidParameterError(
                    "time", self.format_time(float(np.max(ts))),
                    f"after the field's last time {self.format_time(hi)}",
                )
        return ts

    def check_position(self, lat: ArrayLike, lon: ArrayLike, name: str = "position") -> tuple[
        FloatArray, FloatArray
    ]:
        """(lat, lon) arrays with lon shifted into the field's longitude frame; raise outside."""
        la = np.asarray(lat, dtype=float)
        lo = np.asarray(lon, dtype=float)
        if not (np.all(np.isfinite(la)) and np.all(np.isfinite(lo))):
            raise InvalidParameterError(name, (lat, lon), "latitude/longitude must be finite")
        ext = self.extent
        if ext is None:
            return la, lo
        if ext.periodic:  # every longitude is inside: its representative in [lon_min, +360)
            lo = ext.lon_min + np.mod(lo - ext.lon_min, 360.0)
            lo = np.where(lo >= ext.lon_max, lo - 360.0, lo)  # rounding of mod
            self._check_lat(la, ext, name)
            return la, lo
        # The representative of each longitude nearest the field's centre (0..360 or -180..180).
        centre = 0.5 * (ext.lon_min + ext.lon_max)
        lo = centre + np.mod(lo - centre + 180.0, 360.0) - 180.0
        tol = 1e-9
        for arr, low, high, axis, unit in (
            (la, ext.lat_min, ext.lat_max, "latitude", "south"),
            (lo, ext.lon_min, ext.lon_max, "longitude", "west"),
        ):
            if arr.size and np.min(arr) < low - tol:
                raise InvalidParameterError(
                    f"{name} {axis}", float(np.min(arr)),
                    f"outside the field: {unit} bound {low:g}",
                )
            if arr.size and np.max(arr) > high + tol:
                other = "north" if axis == "latitude" else "east"
                raise InvalidParameterError(
                    f"{name} {axis}", float(np.max(arr)),
                    f"outside the field: {other} bound {high:g}",
                )
        return la, lo

    @staticmethod
    def _check_lat(la: FloatArray, ext: Extent, name: str, tol: float = 1e-9) -> None:
        if la.size and np.min(la) < ext.lat_min - tol:
            raise InvalidParameterError(f"{name} latitude", float(np.min(la)),
                                        f"outside the field: south bound {ext.lat_min:g}")
        if la.size and np.max(la) > ext.lat_max + tol:
            raise InvalidParameterError(f"{name} latitude", float(np.max(la)),
                                        f"outside the field: north bound {ext.lat_max:g}")

    def nan_cause(self, t: float, lat: float, lon: float) -> str:
        """Why the current at (t, lat, lon) is NaN, as the rule of an error: "is on land ..."
        here; a gridded field tells its other causes apart (`GriddedField.nan_cause`)."""
        return LAND_RULE

    def format_time(self, t: float) -> str:
        """ISO 8601 of t seconds since epoch (or 't=...s' without a calendar)."""
        if self.epoch is None:
            return f"t={t:g}s"
        return str(self.epoch + np.timedelta64(round(t * 1e3), "ms"))[:19] + "Z"

    def describe(self) -> dict[str, Any]:
        """JSON-ready description: kind, variables, extent, time span, warnings."""
        out: dict[str, Any] = dict(self.info)
        out["extent"] = None if self.extent is None else self.extent.to_dict()
        if self.time_span is not None:
            out["time_span"] = [self.format_time(self.time_span[0]),
                                self.format_time(self.time_span[1])]
        out["warnings"] = list(self.warnings)
        return out


#: The rule of the error for a point whose current is NaN because it is on land.
LAND_RULE = "is on land (no current data: NaN)"
#: `GriddedField.nodata` codes: why a node has no data besides land.
NODATA_OUTSIDE = 1  # outside the source grid of a regridded (curvilinear, e.g. ROMS) file
NODATA_FLOOR = 2  # the depth range reaches below the sea floor there (the layer mean is NaN)


@dataclass(frozen=True)
class UniformField(FlowField):
    """The same velocity (u east, v north; m/s) everywhere and always."""

    u: float = 0.0
    v: float = 0.0
    epoch: np.datetime64 | None = None

    def __post_init__(self) -> None:
        for name in ("u", "v"):
            val = getattr(self, name)
            if not np.isfinite(val):
                raise InvalidParameterError(name, val, "must be finite (m/s)")

    @property
    def info(self) -> Mapping[str, Any]:  # type: ignore[override]
        return {"kind": "uniform", "u": self.u, "v": self.v}

    def velocity(self, t: Any, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
        la, lo = self.check_position(lat, lon)
        shape = np.broadcast_shapes(np.shape(to_seconds(t, self.epoch)), la.shape, lo.shape)
        return np.full(shape, float(self.u)), np.full(shape, float(self.v))


@dataclass(frozen=True)
class AnalyticField(FlowField):
    """A field given by fn(t, lat, lon) -> (u, v), t in seconds since `epoch`."""

    fn: Callable[[FloatArray, FloatArray, FloatArray], tuple[ArrayLike, ArrayLike]]
    extent: Extent | None = None
    time_span: tuple[float, float] | None = None
    epoch: np.datetime64 | None = None
    name: str = "analytic"
    extra: Mapping[str, Any] = field(default_factory=dict)

    @property
    def info(self) -> Mapping[str, Any]:  # type: ignore[override]
        return {"kind": "analytic", "name": self.name, **self.extra}

    def velocity(self, t: Any, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
        ts = self.check_time(t)
        la, lo = self.check_position(lat, lon)
        ts, la, lo = np.broadcast_arrays(ts, la, lo)
        u, v = self.fn(ts, la, lo)
        return np.asarray(u, dtype=float), np.asarray(v, dtype=float)

    def velocity_at(self, t: float, lat: float, lon: float) -> tuple[float, float]:
        """`velocity` at one point: `fn` on 0-d arrays after the scalar checks."""
        lo = self._scalar_position(t, lat, lon)
        if lo is None:
            return super().velocity_at(t, lat, lon)
        u, v = self.fn(np.asarray(float(t)), np.asarray(float(lat)), np.asarray(lo))
        return float(np.asarray(u)), float(np.asarray(v))


@dataclass(frozen=True, eq=False)
class GriddedField(FlowField):
    """Velocity on a (time, lat, lon) grid; linear interpolation (SciPy); NaN = land.

    times: (nt,) seconds since `epoch` (ascending; nt = 1 is a steady field); lat: (ny,)
    ascending degrees; lon: (nx,) ascending degrees (may exceed 180; span < 360); u, v:
    (nt, ny, nx) m/s. When the columns close the circle (`periodic_lon`) the field wraps in
    longitude: the seam between the last column and the first (+360) is interpolated like any
    other cell. `warnings`: what the reader changed or assumed (listed by `describe()`).
    """

    times: FloatArray
    lat: FloatArray
    lon: FloatArray
    u: FloatArray
    v: FloatArray
    epoch: np.datetime64 | None = None
    info: Mapping[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()
    #: (ny, nx) int8 or None: why a NaN node has no data besides land (NODATA_* codes; 0 land)
    nodata: NDArray[np.int8] | None = None

    def __post_init__(self) -> None:
        shape = (self.times.size, self.lat.size, self.lon.size)
        if self.u.shape != shape or self.v.shape != shape:
            raise InvalidParameterError(
                "field", (self.u.shape, self.v.shape), f"u and v must have shape {shape}"
            )
        for name, axis in (("time", self.times), ("latitude", self.lat), ("longitude", self.lon)):
            if not np.all(np.isfinite(axis)):
                raise InvalidParameterError(f"field {name}", "non-finite", "must be finite")
            if axis.size > 1 and np.any(np.diff(axis) <= 0):
                raise InvalidParameterError(f"field {name}", "unsorted", "must be increasing")
        if self.lat.size < 2 or self.lon.size < 2:
            raise InvalidParameterError(
                "field", (self.lat.size, self.lon.size), "needs at least 2 latitudes and longitudes"
            )
        if self.lat[0] < -90.0 - 1e-9 or self.lat[-1] > 90.0 + 1e-9:
            raise InvalidParameterError(
                "field latitude", (float(self.lat[0]), float(self.lat[-1])),
                "must lie within -90..90 degrees",
            )
        if self.lon[-1] - self.lon[0] >= 360.0 - 1e-9:
            raise InvalidParameterError(
                "field longitude", (float(self.lon[0]), float(self.lon[-1])),
                "spans 360 degrees or more: drop the repeated column (e.g. 360 = 0)",
            )
        if not isinstance(self.warnings, tuple):
            object.__setattr__(self, "warnings", tuple(self.warnings))

    @cached_property
    def periodic_lon(self) -> bool:
        """Whether the columns close the circle: |nx dlon - 360| <= dlon / 2 (dlon the mean step).

        Equivalently the seam lon[0] + 360 - lon[-1] lies between dlon / 2 and 3 dlon / 2.
        """
        n = self.lon.size
        dlon = float(self.lon[-1] - self.lon[0]) / (n - 1)
        return abs(n * dlon - 360.0) <= 0.5 * dlon

    @property
    def extent(self) -> Extent:  # type: ignore[override]
        lon_max = float(self.lon[0]) + 360.0 if self.periodic_lon else float(self.lon[-1])
        return Extent(float(self.lat[0]), float(self.lat[-1]), float(self.lon[0]), lon_max,
                      periodic=self.periodic_lon)

    @property
    def time_span(self) -> tuple[float, float] | None:  # type: ignore[override]
        if self.times.size < 2:
            return None
        return float(self.times[0]), float(self.times[-1])

    @property
    def time_levels(self) -> FloatArray | None:
        return self.times if self.times.size > 1 else None

    @cached_property
    def _padded(self) -> tuple[FloatArray, NDArray[np.float64]]:
        """The longitudes and (nt, ny, nx', 2) values the interpolation runs on
        (`glideplan.fields.point.grid_values`: one wrapped column each side when periodic)."""
        return grid_values(self.lon, self.u, self.v, self.periodic_lon)

    @cached_property
    def _scalar_axes(self) -> tuple[list[float], list[float], list[float]]:
        """times, lat and padded lon as lists (bisection without NumPy's per-call cost)."""
        return self.times.tolist(), self.lat.tolist(), self._padded[0].tolist()

    def velocity_at(self, t: float, lat: float, lon: float) -> tuple[float, float]:
        """`velocity` at one point by the same (bi/tri)linear rule as SciPy's interpolator
        (`glideplan.fields.point.interpolate`): NaN on land, the same errors outside."""
        lo = self._scalar_position(t, lat, lon)
        if lo is None:
            return super().velocity_at(t, lat, lon)
        times, lats, lons = self._scalar_axes
        return interpolate(times, lats, lons, self._padded[1], float(t), float(lat), lo)

    @cached_property
    def _interpolator(self) -> Any:
        """SciPy's linear `RegularGridInterpolator` over (time,) lat, lon of (u, v).

        Linear interpolation multiplies every corner of the cell by its weight, so a cell
        that touches a NaN node (land) gives NaN, even at a weight of zero: land is land.
        A periodic field is padded with one wrapped column on each side (lon[-1] - 360 and
        lon[0] + 360), so the seam cell interpolates between the last and the first column.
        """
        from scipy.interpolate import RegularGridInterpolator

        lon, values = self._padded
        if self.times.size == 1:
            return RegularGridInterpolator(
                (self.lat, lon), values[0], method="linear", bounds_error=False,
                fill_value=np.nan,
            )
        return RegularGridInterpolator(
            (self.times, self.lat, lon), values, method="linear", bounds_error=False,
            fill_value=np.nan,
        )

    def velocity(self, t: Any, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray, FloatArray]:
        ts = self.check_time(t)
        la, lo = self.check_position(lat, lon)
        ts, la, lo = np.broadcast_arrays(ts, la, lo)
        axes = (la, lo) if self.times.size == 1 else (ts, la, lo)
        points = np.stack([np.asarray(a, dtype=float).ravel() for a in axes], axis=-1)
        uv = self._interpolator(points).reshape(*la.shape, 2)
        return uv[..., 0], uv[..., 1]

    def nan_cause(self, t: float, lat: float, lon: float) -> str:
        """Why the current at (t, lat, lon) is NaN: a time step with no data at all (every
        value NaN that time), a point outside the source grid of a regridded file, a depth
        range reaching below the sea floor, or land. The nodes are the (up to 2 x 2 x 2)
        corners of the interpolation cell; the first cause found in that order names it."""
        la, lo = self.check_position(lat, lon)
        ks = [0] if self.times.size == 1 else sorted({
            int(np.clip(np.searchsorted(self.times, t, side="right") - 1, 0, self.times.size - 1)),
            int(np.clip(np.searchsorted(self.times, t, side="left"), 0, self.times.size - 1))})
        for k in ks:
            if not (np.isfinite(self.u[k]).any() and np.isfinite(self.v[k]).any()):
                return (f"has no current: the field's time step {self.format_time(self.times[k])}"
                        " is all NaN (no data at that time)")
        if self.nodata is None:
            return LAND_RULE
        i = int(np.clip(np.searchsorted(self.lat, float(la), side="right") - 1, 0,
                        self.lat.size - 2))
        j = int(np.searchsorted(self.lon, float(lo), side="right") - 1)
        cols = [j % self.lon.size, (j + 1) % self.lon.size] if self.periodic_lon else [
            int(np.clip(j, 0, self.lon.size - 2)), int(np.clip(j, 0, self.lon.size - 2)) + 1]
        codes = self.nodata[np.ix_([i, i + 1], cols)]
        if np.any(codes == NODATA_OUTSIDE):
            return ("is outside the file's curvilinear grid (no data there: the regridded "
                    "lat/lon box reaches past the rotated grid's edges), not on land")
        if np.any(codes == NODATA_FLOOR):
            z0, z1 = self.info.get("depth_average_m", ("Z0", "Z1"))
            return (f"has no current over the depth range {z0:g}..{z1:g} m: the sea floor "
                    f"there is shallower than {z1:g} m (not land); give a shallower depth "
                    "range")
        return LAND_RULE

    def lattice_level(self, k: int, lat: ArrayLike, lon: ArrayLike) -> tuple[FloatArray,
                                                                              FloatArray]:
        """(u, v) of time level k on the lattice lat (ny,) x lon (nx,) degrees: (ny, nx) each.

        The same bilinear values as `velocity(times[k], ...)` (a cell touching NaN is NaN),
        computed separably: the row and column weights are found once for the whole lattice
        (fast: routing samples every level on its window). Points outside are NaN; longitudes
        are taken in the field's frame (periodic fields wrap).
        """
        la = np.asarray(lat, dtype=float)
        lo = np.asarray(lon, dtype=float)
        ext = self.extent
        if ext.periodic:
            lo = ext.lon_min + np.mod(lo - ext.lon_min, 360.0)
        else:
            centre = 0.5 * (ext.lon_min + ext.lon_max)
            lo = centre + np.mod(lo - centre + 180.0, 360.0) - 180.0
        lat_ax, lon_ax = self.lat, self.lon
        u, v = self.u[k], self.v[k]
        if ext.periodic:  # the seam column: lon[0] + 360 holds the first column again
            lon_ax = np.concatenate([lon_ax, [lon_ax[0] + 360.0]])
            u = np.concatenate([u, u[:, :1]], axis=1)
            v = np.concatenate([v, v[:, :1]], axis=1)

        def weights(q: FloatArray, ax: FloatArray) -> tuple[Any, Any, Any]:
            i = np.clip(np.searchsorted(ax, q, side="right") - 1, 0, ax.size - 2)
            w = (q - ax[i]) / (ax[i + 1] - ax[i])
            ok = (q >= ax[0] - 1e-9) & (q <= ax[-1] + 1e-9)
            return i, np.clip(w, 0.0, 1.0), ok

        i, wy, oki = weights(la, lat_ax)
        j, wx, okj = weights(lo, lon_ax)
        out = []
        for comp in (u, v):
            a = comp[i][:, j]
            b = comp[i][:, j + 1]
            c = comp[i + 1][:, j]
            d = comp[i + 1][:, j + 1]
            wxx = wx[None, :]
            val = (1 - wy)[:, None] * ((1 - wxx) * a + wxx * b) + wy[:, None] * (
                (1 - wxx) * c + wxx * d)
            val[~oki, :] = np.nan
            val[:, ~okj] = np.nan
            out.append(val)
        return out[0], out[1]

