"""Land near a route: the default land clearance, the land points (the field's own NaN nodes
and the window's, at their coasts), great-circle distances to them (a k-d tree on 3-D
positions, chord radius 2 R sin(c / 2R)) and the obstacle nodes within the clearance
(`glideplan.routing.window` states the rules)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from glideplan.fields.field import FlowField, GriddedField
from glideplan.routing.sphere import EARTH_RADIUS_M, unwrap_lon

if TYPE_CHECKING:
    from glideplan.routing.window import Window

FloatArray = NDArray[np.float64]
BoolArray = NDArray[np.bool_]


def land_clearance_default(fld: FlowField, spacing: float, lat_ref: float) -> float:
    """The default clearance (m): a gridded field with land: its cell's diagonal at lat_ref plus
    one routing spacing (the NaN stencil reaches one cell from a land node; the grid places the
    route within one spacing of its obstacles); otherwise one routing spacing."""
    if isinstance(fld, GriddedField) and not np.all(np.isfinite(fld.u[0])):
        dy = EARTH_RADIUS_M * math.radians(float(np.mean(np.diff(fld.lat))))
        dx = EARTH_RADIUS_M * math.cos(math.radians(min(abs(lat_ref), 85.0))) * math.radians(
            float(np.mean(np.diff(fld.lon))))
        return math.hypot(dx, dy) + spacing
    return spacing


def _xyz(lat: FloatArray, lon: FloatArray) -> FloatArray:
    p, lam = np.radians(lat), np.radians(lon)
    return EARTH_RADIUS_M * np.stack([np.cos(p) * np.cos(lam), np.cos(p) * np.sin(lam),
                                      np.sin(p)], axis=-1)


def _coast(mask: BoolArray) -> BoolArray:
    """Land nodes with a water node among their 8 neighbours (edges count as land)."""
    from scipy.ndimage import binary_erosion

    inner = binary_erosion(mask, structure=np.ones((3, 3), dtype=bool), border_value=1)
    return mask & ~inner


def land_points(fld: FlowField, window: Window, land: BoolArray, pad_m: float) -> FloatArray:
    """3-D positions (m) of the coast points near the window: a gridded field's coastal NaN
    nodes (its linear interpolation is NaN within a cell of them: the window's NaN nodes there
    are that stencil band, obstacles of their own), else the window's coastal NaN nodes."""
    if not isinstance(fld, GriddedField):
        if not land.any():
            return np.zeros((0, 3))
        LA, LO = np.meshgrid(window.lat, window.lon, indexing="ij")
        c = _coast(land)
        return _xyz(LA[c], LO[c])
    nan = ~(np.isfinite(fld.u[0]) & np.isfinite(fld.v[0]))
    if not nan.any():
        return np.zeros((0, 3))
    pad_deg = math.degrees(pad_m / EARTH_RADIUS_M)
    lat = fld.lat
    rows = (lat >= window.lat[0] - pad_deg) & (lat <= window.lat[-1] + pad_deg)
    centre = 0.5 * (window.lon[0] + window.lon[-1])
    half = 0.5 * (window.lon[-1] - window.lon[0])
    lat_max = min(max(abs(window.lat[0]), abs(window.lat[-1])) + pad_deg, 89.0)
    pad_lon = pad_deg / math.cos(math.radians(lat_max))
    lo = unwrap_lon(fld.lon, centre)
    cols = (np.abs(lo - centre) <= half + pad_lon) if not window.periodic else np.ones(
        lo.size, dtype=bool)
    if not (rows.any() and cols.any()):
        return np.zeros((0, 3))
    sub = nan[np.ix_(rows, cols)]
    c = _coast(sub) if sub.any() else sub
    if not c.any():
        return np.zeros((0, 3))
    LA, LO = np.meshgrid(lat[rows], lo[cols], indexing="ij")
    return _xyz(LA[c], LO[c])


def distance_to_land(points: FloatArray, lat: FloatArray, lon: FloatArray,
                     upper: float) -> FloatArray:
    """Great-circle distance (m) from each (lat, lon) to the nearest land point, inf beyond
    `upper` (or with no land points)."""
    out = np.full(np.shape(lat), np.inf)
    if points.shape[0] == 0:
        return out
    from scipy.spatial import cKDTree

    tree = cKDTree(points)
    chord_max = 2 * EARTH_RADIUS_M * math.sin(min(upper / (2 * EARTH_RADIUS_M), math.pi / 2))
    d, _ = tree.query(_xyz(np.ravel(lat), np.ravel(lon)), distance_upper_bound=chord_max * 1.0001)
    d = np.asarray(d, dtype=float)
    fin = np.isfinite(d)
    d[fin] = 2 * EARTH_RADIUS_M * np.arcsin(np.clip(d[fin] / (2 * EARTH_RADIUS_M), 0, 1))
    return d.reshape(np.shape(lat))


def obstacles(fld: FlowField, window: Window, land: BoolArray, clearance: float,
              keep_free: Sequence[tuple[float, float, float]] = (),
              pts: FloatArray | None = None) -> tuple[BoolArray, FloatArray]:
    """Obstacle nodes: land, or within `clearance` (m) of a land point; nodes within each
    (lat, lon, radius m) of `keep_free` are freed unless they are land themselves.
    Returns (mask, the coast points used: `pts`, or `land_points`)."""
    if pts is None:
        pts = land_points(fld, window, land, clearance + window.lattice.spacing_m)
    LA, LO = np.meshgrid(window.lat, window.lon, indexing="ij")
    mask = land.copy()
    if clearance > 0 and pts.shape[0]:
        mask |= distance_to_land(pts, LA, LO, clearance) < clearance
    if keep_free:
        from glideplan.routing.sphere import gc_distance

        for la, lo, r in keep_free:
            near = gc_distance(LA, LO, la, lo) <= r
            mask &= ~(near & ~land)
    return mask, pts
