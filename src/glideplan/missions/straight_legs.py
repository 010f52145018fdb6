"""Straight-leg waypoint lists for vehicles that fly from waypoint to waypoint.

Slocum and Seaglider gliders and ArduPilot fly straight legs between waypoints, so a curved
plan is exported as a polyline whose every point of the planned track lies within
`max_deviation` metres of it. The polyline keeps the mission's own waypoints and, on each leg,
the vertices a Douglas-Peucker split of the dense track selects (the track sample farthest
from the current chord is added until every sample is within the tolerance). The samples are
spaced so that an arc between two samples leaves its chord by at most 1 % of the tolerance
(`MissionPlan.track_spacing`); a route through a current field uses the router's samples.
"""

from __future__ import annotations

import itertools
import math
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import heading_to_compass
from glideplan.missions.plan import MissionPlan

if TYPE_CHECKING:
    from glideplan.missions.field_mission import FieldMission

__all__ = ["StraightLegList", "segment_distances", "straight_leg_list"]


@dataclass(frozen=True, eq=False)
class StraightLegList:
    """Waypoints to fly straight between: names, local x, y (m), lat/lon (deg or None),
    whether each is a mission waypoint, the compass bearing of the track there (deg), the
    largest distance (m) of the sampled track from the polyline and the sample spacing (m);
    eta_s: when the track reaches each (s after departure; a mission waypoint's is the legs'
    durations summed)."""

    names: tuple[str, ...]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    lat: NDArray[np.float64] | None
    lon: NDArray[np.float64] | None
    mission: NDArray[np.bool_]
    bearing_deg: NDArray[np.float64]
    max_deviation_m: float
    tolerance_m: float
    sample_spacing_m: float
    eta_s: NDArray[np.float64] = field(default_factory=lambda: np.zeros(0))


def segment_distances(
    px: NDArray[np.float64], py: NDArray[np.float64],
    ax: float, ay: float, bx: float, by: float,
) -> NDArray[np.float64]:
    """Distance (m) of points (px, py) to the segment from (ax, ay) to (bx, by)."""
    dx, dy = bx - ax, by - ay
    d2 = dx * dx + dy * dy
    if d2 == 0.0:
        return np.hypot(px - ax, py - ay)
    t = np.clip(((px - ax) * dx + (py - ay) * dy) / d2, 0.0, 1.0)
    return np.hypot(px - (ax + t * dx), py - (ay + t * dy))


def _split(x: NDArray[np.float64], y: NDArray[np.float64], tol: float) -> list[int]:
    """Douglas-Peucker: indices (first and last included) whose chords stay within `tol`."""
    keep = {0, len(x) - 1}
    stack = [(0, len(x) - 1)]
    while stack:
        i, j = stack.pop()
        if j - i < 2:
            continue
        d = segment_distances(x[i + 1 : j], y[i + 1 : j], x[i], y[i], x[j], y[j])
        k = int(np.argmax(d))
        if d[k] > tol:
            m = i + 1 + k
            keep.add(m)
            stack += [(i, m), (m, j)]
    return sorted(keep)


def _safe(name: str) -> str:
    return re.sub(r"[^A-Za-z0-9_]+", "_", name).strip("_") or "WP"


def straight_leg_list(
    plan: MissionPlan | FieldMission, max_deviation: float
) -> StraightLegList:
    """The straight-leg waypoint list of `plan` within `max_deviation` (m) of its track."""
    tol = float(max_deviation)
    if not (math.isfinite(tol) and tol > 0.0):
        raise InvalidParameterError("max-deviation", max_deviation, "must be finite and > 0 (m)")
    spacing = plan.track_spacing(tol)
    tr = plan.track(spacing)
    names: list[str] = []
    xs: list[float] = []
    ys: list[float] = []
    hs: list[float] = []
    ts: list[float] = []
    mission: list[bool] = []
    worst = 0.0
    route = plan.route
    for leg in plan.legs:
        sel = np.nonzero(tr.leg == leg.index)[0]
        if leg.index > 0:  # the leg starts where the previous one ended
            sel = np.concatenate([[sel[0] - 1], sel])
        lx, ly, lh = tr.x[sel], tr.y[sel], tr.heading[sel]
        idx = _split(lx, ly, tol)
        for a, b in itertools.pairwise(idx):
            if b - a > 1:
                d = segment_distances(lx[a + 1 : b], ly[a + 1 : b], lx[a], ly[a], lx[b], ly[b])
                worst = max(worst, float(d.max()))
        start = 0 if leg.index == 0 else 1
        base = _safe(route.names[leg.start])
        for n, k in enumerate(idx[start:], start=start):
            last = k == idx[-1]
            first = k == 0
            if first or last:
                wp = leg.start if first else leg.end
                names.append(route.names[wp])
                xs.append(float(route.x[wp]))
                ys.append(float(route.y[wp]))
                mission.append(True)
            else:
                names.append(f"{base}_{n}")
                xs.append(float(lx[k]))
                ys.append(float(ly[k]))
                mission.append(False)
            hs.append(float(lh[k]))
            ts.append(float(tr.t[sel][k]))
    x = np.array(xs)
    y = np.array(ys)
    lat = lon = None
    if route.projection is not None:
        lat, lon = route.projection.to_geographic(x, y)
        m = np.array(mission)
        lat[m] = route.lat  # the mission's own coordinates, not their round trip
        lon[m] = route.lon
    return StraightLegList(
        tuple(names), x, y, lat, lon, np.array(mission),
        np.atleast_1d(np.asarray(heading_to_compass(np.array(hs)), dtype=float)),
        worst, tol, spacing, np.array(ts),
    )
