"""Forecast files for replanning at sea: issue times, the newest forecast, the field planned on.

A forecast is one file, or several files with the same issue time (merged, e.g. u and v
apart). Its issue time is its CF `forecast_reference_time` -- a variable (scalar or 1-D) or a
global attribute -- else its first time step.

The field planned on (`planning_field`) is the forecast, in the truth's clock, with two
changes a pilot makes:

- past the forecast's last time step its last field is held (persistence) until the horizon;
  a forecast's eddies are its best guess of where they are, and blending towards a mean would
  smear them; the next forecast replaces it anyway (a warning says so);
- near the vehicle, the forecast is corrected by the bias the vehicle measured: its
  depth-averaged current since its last fix (ground displacement minus its own through-water
  displacement, over the time between fixes) minus the forecast's current averaged along the
  same path. The correction decays with distance d from the vehicle and with time since the fix:

      u_plan(t, x) = u_fc(t, x) + b exp(-d^2 / (2 L^2)) exp(-(t - t_fix) / tau)

  (L = `bias_length_m`, tau = `bias_time_s`): forecast errors are correlated over about an
  eddy radius and a fraction of an eddy turnover time, so the measurement says little beyond.
"""

from __future__ import annotations

import glob as globmod
import math
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import GriddedField
from glideplan.geodesy import EARTH_RADIUS_M  # the one Earth radius

__all__ = ["Forecast", "forecast_issue_time", "newest", "open_forecasts", "planning_field"]



@dataclass(frozen=True, eq=False)
class Forecast:
    """One forecast: its issue time (datetime64[s]), its field, the files it came from."""

    issued: np.datetime64
    field: GriddedField
    paths: tuple[str, ...]


def forecast_issue_time(path: str | pathlib.Path) -> np.datetime64:
    """The file's issue time: CF forecast_reference_time (variable or global attribute),
    else its first time step (datetime64[s])."""
    import xarray as xr

    from glideplan.fields.io import _engine

    try:  # a PNG or a text file: "not a NetCDF or GRIB file", as --truth and --field say
        _engine(pathlib.Path(path))
    except InvalidParameterError as exc:
        raise InvalidParameterError("--forecasts", str(path), exc.rule) from None
    except OSError as exc:  # a folder the glob matched, an unreadable file
        raise InvalidParameterError("--forecasts", str(path), str(exc.strerror)) from None
    try:
        with xr.open_dataset(path) as ds:
            for name in ds.variables:
                var = ds[name]
                if name == "forecast_reference_time" or \
                        var.attrs.get("standard_name") == "forecast_reference_time":
                    vals = np.asarray(var.values).ravel()
                    if vals.size and np.issubdtype(vals.dtype, np.datetime64):
                        return np.datetime64(vals[0], "s")
            attr = ds.attrs.get("forecast_reference_time")
            if attr is not None:
                return np.datetime64(str(attr).strip().rstrip("Z").replace(" ", "T"), "s")
            for name in ("time", "valid_time", "time_counter"):
                if name in ds.variables and np.issubdtype(ds[name].dtype, np.datetime64):
                    return np.datetime64(np.asarray(ds[name].values).ravel()[0], "s")
    except InvalidParameterError:
        raise
    except Exception as exc:
        msg = " ".join(str(exc).split())[:120]
        raise InvalidParameterError("--forecasts", str(path), f"cannot read ({msg})") from None
    raise InvalidParameterError("--forecasts", str(path),
                                "has no forecast_reference_time and no time axis: add one")


def open_forecasts(pattern: str | list[str]) -> list[Forecast]:
    """Every forecast of a glob (or a list of files), grouped by issue time, oldest first."""
    from glideplan.fields.io import open_field

    if isinstance(pattern, str):
        paths = sorted(globmod.glob(pattern))
        if not paths and pathlib.Path(pattern).is_dir():
            paths = sorted(globmod.glob(str(pathlib.Path(pattern) / "*.nc")))
    else:
        paths = sorted(str(p) for p in pattern)
    if not paths:
        raise InvalidParameterError("--forecasts", pattern,
                                    "matches no file: give a quoted glob such as 'FC_DIR/*.nc'")
    groups: dict[np.datetime64, list[str]] = {}
    for p in paths:
        groups.setdefault(forecast_issue_time(p), []).append(p)
    out = []
    for issued in sorted(groups):
        files = groups[issued]
        try:
            fld = open_field(files if len(files) > 1 else files[0])
        except InvalidParameterError as exc:
            raise InvalidParameterError("--forecasts", ", ".join(files), exc.rule) from None
        if fld.epoch is None:
            raise InvalidParameterError("--forecasts", files[0], "has no time axis")
        out.append(Forecast(issued, fld, tuple(files)))
    return out


def newest(forecasts: list[Forecast], when: np.datetime64) -> Forecast | None:
    """The newest forecast issued at or before `when` (None if none is)."""
    best = None
    for fc in forecasts:
        if fc.issued <= when:
            best = fc
    return best


def planning_field(fc: Forecast, epoch: np.datetime64, t_now: float, horizon: float,
                   bias: tuple[float, float] = (0.0, 0.0), at: tuple[float, float] | None = None,
                   t_fix: float = 0.0, length_m: float = 20e3,
                   time_s: float = 12 * 3600.0) -> tuple[GriddedField, list[str]]:
    """The forecast in the clock of `epoch` (s), covering [t_now, horizon], bias-corrected near
    `at` (module docstring); and the warnings (the last field held past the forecast's end)."""
    fld = fc.field
    assert fld.epoch is not None
    shift = float((fld.epoch - epoch) / np.timedelta64(1, "s"))
    times = fld.times + shift
    u, v = fld.u, fld.v
    warnings: list[str] = []
    if times[0] > t_now:  # issued before its first step: hold the first field back to now
        times = np.r_[t_now, times]
        u, v = np.concatenate([u[:1], u]), np.concatenate([v[:1], v])
    if times[-1] < horizon:
        last = fld.format_time(fld.times[-1])
        warnings.append(f"the forecast issued {fc.issued!s}Z ends at {last}: planned past it "
                        "with its last field held (persistence keeps its eddies where it put "
                        "them; the next forecast replaces it)")
        times = np.r_[times, horizon + 3600.0]
        u, v = np.concatenate([u, u[-1:]]), np.concatenate([v, v[-1:]])
    if at is not None and (bias[0] or bias[1]) and length_m > 0:
        lat = np.radians(fld.lat)[:, None]
        dlat = lat - math.radians(at[0])
        dlon = np.radians(fld.lon)[None, :] - math.radians(at[1])
        d2 = (dlat ** 2 + (math.cos(math.radians(at[0])) * dlon) ** 2) * EARTH_RADIUS_M ** 2
        w_xy = np.exp(-0.5 * d2 / length_m ** 2)
        w_t = np.exp(-np.clip(times - t_fix, 0.0, None) / max(time_s, 1e-9))
        w = w_t[:, None, None] * w_xy[None]
        u, v = u + bias[0] * w, v + bias[1] * w
    from glideplan.fields.scalar import ScalarGridded

    out = ScalarGridded(times=np.asarray(times, dtype=float), lat=fld.lat, lon=fld.lon,
                       u=np.asarray(u, dtype=float), v=np.asarray(v, dtype=float), epoch=epoch,
                       info=dict(fld.info), warnings=())
    return out, warnings


def mean_current(fld: Any, t: np.ndarray, lat: np.ndarray, lon: np.ndarray) -> tuple[float, float]:
    """The field's current averaged over track points (times clipped into its span)."""
    tt = np.asarray(t, dtype=float)
    if fld.time_span is not None:
        tt = np.clip(tt, *fld.time_span)
    u, v = fld.velocity(tt, lat, lon)
    ok = np.isfinite(u) & np.isfinite(v)
    if not ok.any():
        return 0.0, 0.0
    return float(np.mean(u[ok])), float(np.mean(v[ok]))
