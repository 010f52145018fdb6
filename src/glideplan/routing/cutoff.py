"""Whether land, or land and its clearance, cut the goal off from the start's water.

A route whose front runs out of time ("time_span", "max_duration") may never have had a way
to the goal: the land clearance can close the only strait. This check answers at the field's
own resolution, over the whole field (not the front's window): water nodes are the finite
ones at the departure's time level; a node is free when its distance to the nearest land
node (`scipy.ndimage.distance_transform_edt` with the node spacings in metres at the field's
mean latitude) exceeds the clearance; free water is joined through 8-neighbours. The goal is
cut off when no free component holds both the start's and the goal's nodes (or their
neighbours); "clearance" when water alone joins them, "land" when nothing does.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from glideplan.routing.sphere import EARTH_RADIUS_M

__all__ = ["field_cut_off"]


def _ids(labels: np.ndarray, lat: np.ndarray, lon: np.ndarray, point: tuple[float, float]
         ) -> set[int]:
    """Labels (> 0) of the node nearest `point` and its 8 neighbours."""
    i = int(np.argmin(np.abs(lat - point[0])))
    lo = lon[0] + np.mod(point[1] - lon[0], 360.0)
    j = int(np.argmin(np.abs(lon - lo)))
    near = labels[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2]
    return set(np.unique(near[near > 0]).tolist())


def field_cut_off(field_: Any, t: float, start: tuple[float, float],
                  goal: tuple[float, float], clearance_m: float) -> str | None:
    """"clearance", "land" or None (module docstring); None for fields without a land grid
    and for fields that close the circle in longitude (not decided here)."""
    from scipy.ndimage import distance_transform_edt, label

    u = getattr(field_, "u", None)
    times = getattr(field_, "times", None)
    if u is None or times is None or getattr(field_, "periodic_lon", True):
        return None
    k = int(np.clip(np.searchsorted(times, t, side="right") - 1, 0, times.size - 1))
    water = np.isfinite(field_.u[k]) & np.isfinite(field_.v[k])
    if water.all() or not water.any():
        return None
    lat, lon = np.asarray(field_.lat, float), np.asarray(field_.lon, float)
    dy = math.radians(float(np.mean(np.diff(lat)))) * EARTH_RADIUS_M
    dx = math.radians(float(np.mean(np.diff(lon)))) * EARTH_RADIUS_M * math.cos(
        math.radians(float(np.mean(lat))))
    free = water & (distance_transform_edt(water, sampling=(dy, dx)) > clearance_m)
    eight = np.ones((3, 3), dtype=bool)
    labels, _ = label(free, structure=eight)
    if _ids(labels, lat, lon, start) & _ids(labels, lat, lon, goal):
        return None
    wet, _ = label(water, structure=eight)
    return "clearance" if _ids(wet, lat, lon, start) & _ids(wet, lat, lon, goal) else "land"
