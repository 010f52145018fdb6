"""Why a front that never reached the goal stopped, when the cause is not the time or the
field's edge: an all-NaN time step (`nan_time_step`), or land and its clearance cutting the
goal off from the start's water (`field_cut_off`).

An all-NaN time step (a forecast day with no data) stops every front that reaches it: the
field's linear interpolation in time gives NaN from the step before it to the step after.

A route whose front runs out of time ("time_span", "max_duration") may never have had a way
to the goal: the land clearance can close the only strait. This check answers at the field's
own resolution, over the whole field (not the front's window): water nodes are the finite
ones at the departure's time level; a node is free when its distance to the nearest land
node exceeds the clearance; free water is joined through 8-neighbours. The distance is
`scipy.ndimage.distance_transform_edt` with the node spacings in metres at the node's own
latitude: rows are taken in bands over which the east-west spacing R dlon cos(lat) varies
by at most 1 % (each band's transform over its rows and the rows within the clearance of
them, where any land within the clearance lies), so a strait at 75 N of a global file is
measured in its own metres, not in the equator's (3.9 times wider). The goal is
cut off when no free component holds both the start's and the goal's nodes (or their
neighbours); "clearance" when water alone joins them, "land" when nothing does. A global
field whose columns close the circle (`periodic_lon`) wraps: the distance to land is taken
across the seam (the field padded with its own columns from the other side, as far as the
clearance reaches) and components that meet across it are one.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from glideplan.routing.sphere import EARTH_RADIUS_M

__all__ = ["field_cut_off", "nan_time_step"]


def _ids(labels: np.ndarray, lat: np.ndarray, lon: np.ndarray, point: tuple[float, float],
         periodic: bool = False) -> set[int]:
    """Labels (> 0) of the node nearest `point` and its 8 neighbours (across the seam when
    `periodic`)."""
    i = int(np.argmin(np.abs(lat - point[0])))
    lo = lon[0] + np.mod(point[1] - lon[0], 360.0)
    if periodic:  # the seam: lo past the last column may be nearest the first
        j = int(np.argmin(np.minimum(np.abs(lon - lo), np.abs(lon + 360.0 - lo))))
        cols = [(j + d) % lon.size for d in (-1, 0, 1)]
        near = labels[max(i - 1, 0):i + 2][:, cols]
    else:
        j = int(np.argmin(np.abs(lon - lo)))
        near = labels[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2]
    return set(np.unique(near[near > 0]).tolist())


def _distance_by_band(water: np.ndarray, dy: float, dx_rows: np.ndarray, reach_m: float,
                      periodic: bool, band_ratio: float = 0.01) -> np.ndarray:
    """Distance (m) from each node to the nearest non-water node, exact to `band_ratio` within
    `reach_m` (beyond it: at least reach_m, or inf): row i's east-west spacing dx_rows[i] (m),
    rows in bands whose spacings lie within `band_ratio` of the band's first, each band's
    transform over its rows and ceil(reach / dy) + 1 rows on either side."""
    ny = water.shape[0]
    pad = min(ny, math.ceil(reach_m / dy) + 1)
    out = np.empty(water.shape)
    i = 0
    while i < ny:
        j = i + 1
        while j < ny and abs(dx_rows[j] / dx_rows[i] - 1.0) <= band_ratio:
            j += 1
        lo, hi = max(0, i - pad), min(ny, j + pad)
        window = water[lo:hi]
        if window.all():
            out[i:j] = np.inf  # no land within the clearance of these rows
        else:
            dx = float(np.mean(dx_rows[i:j]))
            out[i:j] = _distance_to_land(window, dy, dx, reach_m, periodic)[i - lo:j - lo]
        i = j
    return out


def _distance_to_land(water: np.ndarray, dy: float, dx: float, reach_m: float,
                      periodic: bool) -> np.ndarray:
    """Distance (m) from each node to the nearest non-water node (Euclidean, node spacings
    dy, dx); periodic: through the seam, the field padded with ceil(reach / dx) + 1 of its
    own columns from the other side."""
    from scipy.ndimage import distance_transform_edt

    if not periodic:
        return np.asarray(distance_transform_edt(water, sampling=(dy, dx)))
    nx = water.shape[1]
    m = min(nx, math.ceil(reach_m / dx) + 1)
    padded = np.pad(water, ((0, 0), (m, m)), mode="wrap")
    return np.asarray(distance_transform_edt(padded, sampling=(dy, dx)))[:, m:m + nx]


def _label(mask: np.ndarray, periodic: bool) -> np.ndarray:
    """8-connected component labels (0 = not in the mask); periodic: components that touch
    across the seam (last column to first, rows i and i +- 1) get one label."""
    from scipy.ndimage import label

    labels, n = label(mask, structure=np.ones((3, 3), dtype=bool))
    if not periodic or n == 0:
        return np.asarray(labels)
    parent = np.arange(n + 1)

    def root(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = int(parent[a])
        return a

    last, first = labels[:, -1], labels[:, 0]
    ny = labels.shape[0]
    for d in (-1, 0, 1):
        rows = np.arange(max(0, -d), min(ny, ny - d))
        for a, b in zip(last[rows], first[rows + d], strict=True):
            if a > 0 and b > 0:
                ra, rb = root(int(a)), root(int(b))
                if ra != rb:
                    parent[max(ra, rb)] = min(ra, rb)
    return np.array([root(k) for k in range(n + 1)])[labels]


def field_cut_off(field_: Any, t: float, start: tuple[float, float],
                  goal: tuple[float, float], clearance_m: float) -> str | None:
    """"clearance", "land" or None (module docstring); None for fields without a land grid."""
    u = getattr(field_, "u", None)
    times = getattr(field_, "times", None)
    if u is None or times is None:
        return None
    periodic = bool(getattr(field_, "periodic_lon", False))
    k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, times.size - 1))
    water = np.isfinite(field_.u[k]) & np.isfinite(field_.v[k])
    if water.all() or not water.any():
        return None
    lat, lon = np.asarray(field_.lat, float), np.asarray(field_.lon, float)
    dy = math.radians(abs(float(np.mean(np.diff(lat))))) * EARTH_RADIUS_M
    dx_rows = math.radians(abs(float(np.mean(np.diff(lon))))) * EARTH_RADIUS_M * np.maximum(
        np.cos(np.radians(lat)), 1e-6)  # a pole's row: a metre-scale spacing, not zero
    distance = _distance_by_band(water, dy, dx_rows, clearance_m, periodic)
    free = water & (distance > clearance_m)
    labels = _label(free, periodic)
    if _ids(labels, lat, lon, start, periodic) & _ids(labels, lat, lon, goal, periodic):
        return None
    wet = _label(water, periodic)
    joined = _ids(wet, lat, lon, start, periodic) & _ids(wet, lat, lon, goal, periodic)
    return "clearance" if joined else "land"


def nan_time_step(field_: Any, t0: float, arrival: np.ndarray) -> float | None:
    """The first all-NaN time level (s since epoch) of a gridded field at or after `t0` that
    the front reached (its latest finite arrival is at or past the level before it); None."""
    u = getattr(field_, "u", None)
    times = getattr(field_, "times", None)
    if u is None or times is None or times.size < 2:
        return None
    reached = np.asarray(arrival, dtype=float)
    reached = reached[np.isfinite(reached)]
    t_end = float(reached.max()) if reached.size else t0
    for k in range(times.size):
        if times[k] < t0 or (k > 0 and times[k - 1] > t_end + 1.0):
            continue
        if not (np.isfinite(u[k]).any() and np.isfinite(field_.v[k]).any()):
            return float(times[k])
    return None
