"""Gaps between land open at the land mask's resolution that the front's grid closes.

A gap's pass is a saddle of the distance to land d on the mask's own grid: a ridge across
the gap (d >= both neighbours along one of the 4 grid directions, > one of them) and a
minimum along it (d <= both neighbours along the perpendicular direction). The gap is open
at the mask's resolution when d > c (the land clearance: water 2 (d - c) wide beyond it),
and the front's grid closes it when the front node nearest the pass is an obstacle. An open
coast has no such saddle (d grows away from it); the bisector of a concave corner is a ridge
but d grows along it. `closed_gap` returns the narrowest such pass: the way the front cannot
take although the water at the mask's resolution is open (a shortcut, when the water is
connected the long way round, that the route then silently misses).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

FloatArray = NDArray[np.float64]

#: (direction across, direction along) pairs of grid steps (row, column).
_PAIRS = (((0, 1), (1, 0)), ((1, 0), (0, 1)), ((1, 1), (1, -1)), ((1, -1), (1, 1)))
#: Tolerance (m) of the comparisons of distances (rounding of the great-circle distances).
_TOL = 1e-6


def _shift(a: FloatArray, di: int, dj: int) -> FloatArray:
    """a[i + di, j + dj], NaN beyond the edges."""
    out = np.full(a.shape, np.nan)
    ny, nx = a.shape
    out[max(-di, 0):ny - max(di, 0), max(-dj, 0):nx - max(dj, 0)] = \
        a[max(di, 0):ny + min(di, 0), max(dj, 0):nx + min(dj, 0)]
    return out


def saddles(d: FloatArray) -> NDArray[np.bool_]:
    """The saddle nodes of the distance to land d (module docstring; NaN never a saddle)."""
    out = np.zeros(d.shape, dtype=bool)
    for (ai, aj), (bi, bj) in _PAIRS:
        p, m = _shift(d, ai, aj), _shift(d, -ai, -aj)
        ridge = (d >= p - _TOL) & (d >= m - _TOL) & ((d > p + _TOL) | (d > m + _TOL))
        q, n = _shift(d, bi, bj), _shift(d, -bi, -bj)
        out |= ridge & (d <= q + _TOL) & (d <= n + _TOL)
    return out


def closed_gap(fld: Any, window: Any, mask: NDArray[np.bool_], pts: FloatArray,
               clearance: float) -> tuple[float, float, float] | None:
    """The narrowest gap open at the gridded field's resolution (a saddle of the distance to
    land with d > clearance) whose nearest front node is an obstacle of `mask` (inside the
    window): (d at its pass (m), lat, lon), or None. pts: the coast points (3-D, m)."""
    from glideplan.fields.field import GriddedField
    from glideplan.routing.sphere import unwrap_lon
    from glideplan.routing.window import distance_to_land

    if not isinstance(fld, GriddedField) or pts.shape[0] == 0 or window.periodic:
        return None
    lat_w, lon_w = window.lat, window.lon
    rows = (fld.lat >= lat_w[0]) & (fld.lat <= lat_w[-1])
    lo = unwrap_lon(fld.lon, 0.5 * (lon_w[0] + lon_w[-1]))
    cols = (lo >= lon_w[0]) & (lo <= lon_w[-1])
    if rows.sum() < 3 or cols.sum() < 3:
        return None
    land = ~(np.isfinite(fld.u[0]) & np.isfinite(fld.v[0]))[np.ix_(rows, cols)]
    LA, LO = np.meshgrid(fld.lat[rows], lo[cols], indexing="ij")
    upper = clearance + 2.0 * window.lattice.spacing_m
    d = distance_to_land(pts, LA, LO, upper)
    d[land] = 0.0
    d[~np.isfinite(d)] = np.nan  # far from land: no gap there
    cand = saddles(d) & (d > clearance)
    if not cand.any():
        return None
    la, lo_c, dc = LA[cand], LO[cand], d[cand]
    lat0, dlat = window.lattice.lat0, window.lattice.dlat
    lon0, dlon = window.lattice.lon0, window.lattice.dlon
    i = np.rint((la - lat0) / dlat).astype(np.intp) - window.i0
    j = np.rint((lo_c - lon0) / dlon).astype(np.intp) - window.j0
    ok = (i >= 0) & (i < mask.shape[0]) & (j >= 0) & (j < mask.shape[1])
    i, j, la, lo_c, dc = i[ok], j[ok], la[ok], lo_c[ok], dc[ok]
    shut = mask[i, j] & window.inside[i, j]
    if not shut.any():
        return None
    dmin = float(np.min(dc[shut]))
    tied = np.flatnonzero(shut & (dc <= dmin + 1.0))  # a channel: its middle node
    k = int(tied[np.argmin(np.hypot(la[tied] - la[tied].mean(), lo_c[tied] - lo_c[tied].mean()))])
    return float(dc[k]), float(la[k]), float(lo_c[k])
