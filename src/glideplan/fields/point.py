"""One-point queries of a field without NumPy's per-call cost: the integrators' hot path.

A flown route asks its field for ~10^5 single points; `FlowField.velocity` builds arrays,
broadcasts and calls SciPy for each. These pure functions apply the same rules to floats:
`position_in_frame` the checks of `FlowField.check_time` / `check_position` (tolerances,
longitude wrapping), `interpolate` the (bi/tri)linear rule of SciPy's
`RegularGridInterpolator` that `GriddedField` uses.
"""

from __future__ import annotations

import bisect
import math
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from glideplan.fields.field import Extent

__all__ = ["grid_values", "interpolate", "position_in_frame"]


def grid_values(lon: Any, u: Any, v: Any, periodic: bool) -> tuple[Any, Any]:
    """(lon', values): the longitudes and the (nt, ny, nx', 2) stack of u, v to interpolate.

    A periodic field gets one wrapped column on each side, lon[-1] - 360 and lon[0] + 360
    (nx' = nx + 2), so the seam cell interpolates between the last and the first column.
    """
    import numpy as np

    if not periodic:
        return lon, np.stack([u, v], axis=-1)
    lon2 = np.concatenate([[lon[-1] - 360.0], lon, [lon[0] + 360.0]])
    nt, ny, nx = u.shape
    values = np.empty((nt, ny, nx + 2, 2))
    for k, comp in enumerate((u, v)):
        values[:, :, 1:-1, k] = comp
        values[:, :, 0, k] = comp[:, :, -1]
        values[:, :, -1, k] = comp[:, :, 0]
    return lon2, values


def position_in_frame(extent: Extent | None, time_span: tuple[float, float] | None,
                      t: float, lat: float, lon: float) -> float | None:
    """The longitude (deg) in the field's frame when (t, lat, lon) is inside, else None.

    Inside means what `check_time` and `check_position` accept: finite values, t within the
    span +- 1e-6 of its length (1 s at least), lat and the shifted lon within the extent
    +- 1e-9 deg; lon is shifted to lon_min + (lon - lon_min) mod 360 on a periodic field,
    else to the representative nearest the extent's centre.
    """
    if not (math.isfinite(t) and math.isfinite(lat) and math.isfinite(lon)):
        return None
    if time_span is not None:
        tol_t = 1e-6 * max(1.0, time_span[1] - time_span[0])
        if t < time_span[0] - tol_t or t > time_span[1] + tol_t:
            return None
    if extent is None:
        return lon
    tol = 1e-9
    if lat < extent.lat_min - tol or lat > extent.lat_max + tol:
        return None
    if extent.periodic:
        lo = extent.lon_min + (lon - extent.lon_min) % 360.0
        return lo - 360.0 if lo >= extent.lon_max else lo
    centre = 0.5 * (extent.lon_min + extent.lon_max)
    lo = centre + (lon - centre + 180.0) % 360.0 - 180.0
    if lo < extent.lon_min - tol or lo > extent.lon_max + tol:
        return None
    return lo


def _cell(axis: list[float], x: float) -> tuple[int, float] | None:
    """(i, w): i = searchsorted(axis, x) - 1 clipped to [0, n - 2], w the weight of i + 1."""
    if not axis[0] <= x <= axis[-1]:
        return None
    i = min(max(bisect.bisect_left(axis, x) - 1, 0), len(axis) - 2)
    return i, (x - axis[i]) / (axis[i + 1] - axis[i])


def interpolate(times: list[float], lats: list[float], lons: list[float], values: Any,
                t: float, lat: float, lon: float) -> tuple[float, float]:
    """(u, v) at one point of a (nt, ny, nx, 2) grid, as SciPy's linear interpolator gives it.

    On each axis the cell index i and the weight w = (x - axis[i]) / (axis[i+1] - axis[i]);
    the value is the sum over the cell's corners of value x prod(w or 1 - w), so a NaN corner
    gives NaN (land) even at weight 0, and a point outside an axis gives NaN
    (`fill_value=nan`). A single time level (nt = 1) is a steady field: t is not used.
    """
    cy, cx = _cell(lats, lat), _cell(lons, lon)
    if cy is None or cx is None:
        return math.nan, math.nan
    (i, wy), (j, wx) = cy, cx
    if len(times) == 1:
        block = values[0, i:i + 2, j:j + 2]
        corners = [(block[a, b], (wy if a else 1.0 - wy) * (wx if b else 1.0 - wx))
                   for a in (0, 1) for b in (0, 1)]
    else:
        ct = _cell(times, t)
        if ct is None:
            return math.nan, math.nan
        k, wt = ct
        block = values[k:k + 2, i:i + 2, j:j + 2]
        corners = [(block[c, a, b], (wt if c else 1.0 - wt) * (wy if a else 1.0 - wy)
                    * (wx if b else 1.0 - wx))
                   for c in (0, 1) for a in (0, 1) for b in (0, 1)]
    u = v = 0.0
    for uv, w in corners:
        u += float(uv[0]) * w
        v += float(uv[1]) * w
    return u, v
