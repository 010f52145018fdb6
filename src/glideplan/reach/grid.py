"""The front's grid for a glide reach: terrain cropped to the reach, max-pooled, block times.

Since issue 24 `glide_reach` and `turnback` search the terrain's own grid (`native_terrain`
below, `reach.native`); `reach_grid` (the pooled front's grid) remains for containment
checks and other callers.

Domain: the terrain's nodes within the largest possible reach of the start,
(ALT - safety - lowest terrain) x max ground glide ratio, plus a margin; the footprint is
clipped to the terrain's extent (the front's `edges` say where it was).

Resolution: the terrain pooled by an integer factor f (`Terrain.pooled_max`) over one whole
coarse cell each side of a node (f fine samples), so every coarse node carries the highest
bilinear terrain of its cell and of the half cells beyond it: a backtracked path, which can
cut up to half a cell into the cell of a blocked node, still never meets the terrain that
blocked it. Clearance is never overstated; the price is about one cell of free space lost
next to terrain the front must avoid (the flown, string-pulled path is checked against the
true terrain and may pass closer).
Default f: the smallest giving at most DEFAULT_MAX_NODES nodes along the longer side (speed;
`resolution_m` overrides it: f = round(resolution / terrain spacing), at least 1).

State constraint: at altitude lost h the glider is at ALT - h, which must stay >= terrain +
safety, so a node not yet reached cannot be entered once h > ALT - terrain - safety:
block_time = ALT - z_pooled - safety (-inf where there is no terrain data). The nodes of the
start's cell and of each landable's cell use the point terrain at the node instead of the
pooled cell (a field in a valley narrower than a cell stays enterable; the flown path is
checked against the true terrain anyway).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.problem import ReachProblem
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = ["DEFAULT_MAX_NODES", "MAX_NATIVE_NODES", "ReachGrid", "cell_nodes", "native_terrain",
           "reach_grid"]

FloatArray = NDArray[np.float64]

#: Default front grid: at most this many nodes along the longer side of the domain (an SRTM3
#: tile: 241 x 241 nodes 460 m apart at 46 N; the front's cost grows with the square).
DEFAULT_MAX_NODES = 300


@dataclass(frozen=True, eq=False)
class ReachGrid:
    """The front's nodes lat (ny,), lon (nx,); pooled terrain z (ny, nx); block_time;
    the cropped fine terrain; pooling factor; spacing (m, the larger of east and north)."""

    lat: FloatArray
    lon: FloatArray
    z: FloatArray
    block_time: FloatArray
    terrain: Terrain
    factor: int
    spacing_m: float
    notes: tuple[str, ...]


def cell_nodes(lat: FloatArray, lon: FloatArray, points: Iterable[tuple[float, float]]
               ) -> list[tuple[int, int]]:
    """(row, column) of the 4 nodes of the cell holding each point (points outside skipped)."""
    out = []
    dlat, dlon = lat[1] - lat[0], lon[1] - lon[0]
    for la, lo in points:
        fi, fj = (la - lat[0]) / dlat, (lo - lon[0]) / dlon
        if not (0 <= fi <= lat.size - 1 and 0 <= fj <= lon.size - 1):
            continue
        i0, j0 = min(math.floor(fi), lat.size - 2), min(math.floor(fj), lon.size - 2)
        out += [(i0 + di, j0 + dj) for di in (0, 1) for dj in (0, 1)]
    return out


def reach_grid(problem: ReachProblem, max_ratio: float) -> ReachGrid:
    """Build the front's grid (module docstring); `max_ratio` = largest ground glide ratio."""
    lat0, lon0, alt = problem.start
    t = problem.terrain
    notes: list[str] = []
    zmin = float(np.nanmin(t.z))
    reach = max(alt - problem.safety_height - zmin, 0.0) * max_ratio
    margin = reach * 1.05 + 5000.0  # beyond the reach: the front's band and a few cells
    dlat = math.degrees(margin / EARTH_RADIUS_M)
    coslat = max(math.cos(math.radians(min(abs(lat0) + dlat, 89.0))), 1e-3)
    dlon = math.degrees(margin / (EARTH_RADIUS_M * coslat))
    fine = t.crop(lat0 - dlat, lat0 + dlat, lon0 - dlon, lon0 + dlon)
    ny, nx = fine.shape
    if problem.resolution_m is None:
        factor = max(1, math.ceil(max(ny, nx) / DEFAULT_MAX_NODES))
    else:
        factor = max(1, round(problem.resolution_m / max(fine.spacing_m[1], 1e-9)))
        if problem.resolution_m < 0.5 * fine.spacing_m[1]:
            notes.append(f"resolution {problem.resolution_m:g} m is finer than the terrain "
                         f"({fine.spacing_m[1]:.0f} m): the terrain's own grid is used")
    factor = min(factor, max(1, (min(ny, nx) - 1) // 3))  # at least 4 nodes a side
    lat, lon, z = fine.pooled_max(factor, reach=factor)
    if not (lat[0] <= lat0 <= lat[-1] and lon[0] <= lon0 <= lon[-1]):
        from glideplan.errors import InvalidParameterError

        raise InvalidParameterError(
            "start", (lat0, lon0), f"lies within one front cell ({factor} terrain samples) of "
            "the terrain's edge, outside the front's grid; use a finer --resolution or more "
            "terrain")
    block = alt - z - problem.safety_height
    block = np.where(np.isfinite(block), block, -np.inf)
    special = [(lat0, lon0)] + [(p.lat, p.lon) for p in problem.landables]
    for i, j in cell_nodes(lat, lon, special):
        zp = float(fine.elevation(lat[i], lon[j]))
        if math.isfinite(zp):
            block[i, j] = alt - zp - problem.safety_height
    spacing = EARTH_RADIUS_M * math.radians(float(lat[1] - lat[0]))
    spacing = max(spacing, EARTH_RADIUS_M * math.cos(math.radians(float(np.min(np.abs(lat)))))
                  * math.radians(float(lon[1] - lon[0])))
    return ReachGrid(lat, lon, z, block, fine, factor, spacing, tuple(notes))


#: The native search (`reach.native`) runs on at most this many terrain nodes by default;
#: more (an SRTM1 tile with a high start) are max-pooled by the smallest factor that fits.
MAX_NATIVE_NODES = 14_000_000


def native_terrain(problem: ReachProblem, max_ratio: float, clearance: float
                   ) -> tuple[Terrain, int, list[str], Terrain]:
    """The terrain the native search runs on: cropped to the largest possible reach,
    (ALT - clearance - lowest terrain) x max ground glide ratio + 5 %, + 5 km; pooled (max,
    so closed stays closed) only when `resolution_m` asks for a coarser grid or the crop has
    more than MAX_NATIVE_NODES nodes. Returns (search terrain, pooling factor, notes, the
    unpooled crop: paths are flown over it)."""
    lat0, lon0, alt = problem.start
    t = problem.terrain
    notes: list[str] = []
    zmin = float(np.nanmin(t.z))
    reach = max(alt - clearance - zmin, 0.0) * max_ratio
    margin = reach * 1.05 + 5000.0
    dlat = math.degrees(margin / EARTH_RADIUS_M)
    coslat = max(math.cos(math.radians(min(abs(lat0) + dlat, 89.0))), 1e-3)
    dlon = math.degrees(margin / (EARTH_RADIUS_M * coslat))
    fine = t.crop(lat0 - dlat, lat0 + dlat, lon0 - dlon, lon0 + dlon)
    ny, nx = fine.shape
    factor = max(1, math.ceil(math.sqrt(ny * nx / MAX_NATIVE_NODES)))
    if problem.resolution_m is not None:
        asked = max(1, round(problem.resolution_m / max(fine.spacing_m[1], 1e-9)))
        if problem.resolution_m < 0.5 * fine.spacing_m[1]:
            notes.append(f"resolution {problem.resolution_m:g} m is finer than the terrain "
                         f"({fine.spacing_m[1]:.0f} m): the terrain's own grid is used")
        factor = asked
    factor = min(factor, max(1, (min(ny, nx) - 1) // 3))
    if factor == 1:
        return fine, 1, notes, fine
    lat, lon, z = fine.pooled_max(factor, reach=factor)
    notes.append(f"the terrain is max-pooled by {factor} ({factor * fine.spacing_m[1]:.0f} m "
                 "cells): a pass or gap narrower than about two cells is closed; run at the "
                 "terrain's own resolution (no --resolution) to judge passes")
    return Terrain(lat, lon, z, fine.sources, fine.warnings), factor, notes, fine
