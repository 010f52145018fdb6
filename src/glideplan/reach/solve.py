"""`glide_reach`: the minimum altitude loss to every point over terrain in wind, verified.

Pipeline: `ReachProblem` -> front grid (`reach.grid`: terrain cropped to the reach and
max-pooled, block times = the state constraint) -> the front in altitude (`glideplan.fronts`,
H(p) = max_k a_k |p| + b_k . p from `Glide.front_terms`) -> per landable: the path
backtracked along the characteristics (`fronts.backtrack`), its points kept within a cell of
reached nodes (`snap_to_reached`), string-pulled against the true terrain, and flown through
the wind with the polar (`reach.flight`): the arrival altitude reported is the flown one,
and a landable is reachable only when a flown path keeps the safety height all along. The
straight glide is flown too and kept when it is better (a landable the grid's first-order
error would call out of reach by a few metres is still found). Footprint: the clearance
margin's contour (`reach.footprint`).
"""

from __future__ import annotations

import math
import pathlib
import time
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.reach.flight import FlownPath, fly, front_candidates
from glideplan.reach.footprint import clearance_margin, footprint_polygons
from glideplan.reach.grid import ReachGrid, reach_grid
from glideplan.reach.model import Glide
from glideplan.reach.problem import Landable, ReachProblem
from glideplan.reach.result import ReachPoint, ReachResult, flown_track
from glideplan.sailplane.polar import SailplanePolar
from glideplan.solution import Status
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = ["descend_reached", "front_problem", "glide_reach", "interp_arrival", "snap_to_reached",
           "solve_front"]

FloatArray = NDArray[np.float64]

#: Radius of the exact start disk, in grid spacings: 6 makes the front's first-order error
#: near the source negligible (a 2-cell disk costs about one cell of altitude everywhere);
#: smaller when the terrain near the start would block inside the disk.
START_CELLS = (6.0, 4.0, 2.0, 1.0)


def _terms(glide: Glide) -> tuple[FloatArray, FloatArray]:
    """The front's terms; when all are points (a = 0; MC > 0 in wind) one disk inscribed in
    their hull is added (it changes no support value, and the solver needs one a > 0)."""
    a, b = glide.front_terms()
    if np.any(a > 0):
        return a, b
    c = b.mean(axis=0)
    th = np.linspace(0.0, 2 * np.pi, 2880, endpoint=False)
    n = np.stack([np.cos(th), np.sin(th)], axis=-1)
    rho = float(np.min(np.max((b - c) @ n.T, axis=0)))
    if not rho > 0:
        raise InvalidParameterError("wind", glide.wind, "leaves the glider no set of velocities "
                                    "with an interior (cannot propagate a front)")
    return np.append(a, rho * (1 - 1e-9)), np.vstack([b, c])


def front_problem(grid: ReachGrid, glide: Glide, *, block_time: FloatArray | None = None
                  ) -> Any:
    """The `glideplan.fronts.FrontProblem` of a reach grid (block_time: the grid's own by
    default)."""
    from glideplan.fronts import FrontProblem, LatLonGrid

    a, b = _terms(glide)
    lg = LatLonGrid(lat=grid.lat, lon=grid.lon)
    tb = grid.block_time if block_time is None else block_time
    return FrontProblem(lg, speeds=a, drifts=b, block_time=tb)


def solve_front(fp: Any, lat0: float, lon0: float, t_max: float, spacing: float,
                min_ratio: float, goal: tuple[float, float] | None = None) -> Any:
    """Propagate from (lat0, lon0) at "time" 0 until the front stalls or t_max.

    The start disk (exact, terrain-blind) is the largest of START_CELLS whose nodes could all
    be entered when the disk reaches them (block time > radius / min ground glide ratio);
    nodes the disk still gives an arrival after their block time are taken out of it.
    """
    from dataclasses import replace

    from glideplan.fronts import propagate, start_state

    lat, lon = fp.grid.lat, fp.grid.lon
    x, y = fp.grid.local_xy(lat0, lon0)
    dist = np.hypot(x, y)
    tb = fp.block_time
    radius = START_CELLS[-1] * spacing
    for cells in START_CELLS:
        r = cells * spacing
        near = dist <= 1.5 * r + 2 * spacing
        if not np.any(near) or float(np.min(tb[near])) > 1.5 * r / max(min_ratio, 1e-9):
            radius = r
            break
    state = start_state(fp, 0.0, lat0, lon0, radius_m=radius)
    bad = np.isfinite(state.arrival) & (state.arrival > tb)
    if np.any(bad):
        arrival = state.arrival.copy()
        phi = state.phi.copy()
        arrival[bad] = np.inf
        phi[bad] = fp.band
        state = replace(state, arrival=arrival, phi=phi)
    del lat, lon
    return state, propagate(fp, state, max(t_max, state.t + 1e-9), goal=goal)


def interp_arrival(arrival: FloatArray, lat: FloatArray, lon: FloatArray, la: float,
                   lo: float) -> float:
    """Bilinear arrival at (la, lo) over the reached corners of its cell (inf: none)."""
    fi = (la - lat[0]) / (lat[1] - lat[0])
    fj = (lo - lon[0]) / (lon[1] - lon[0])
    if not (0 <= fi <= lat.size - 1 and 0 <= fj <= lon.size - 1):
        return math.inf
    i, j = min(int(fi), lat.size - 2), min(int(fj), lon.size - 2)
    wy, wx = fi - i, fj - j
    acc = wsum = 0.0
    for di, wi in ((0, 1 - wy), (1, wy)):
        for dj, wj in ((0, 1 - wx), (1, wx)):
            v = arrival[i + di, j + dj]
            if math.isfinite(v) and wi * wj > 0:
                acc += wi * wj * v
                wsum += wi * wj
    return acc / wsum if wsum > 0 else math.inf


def snap_to_reached(lat: FloatArray, lon: FloatArray, arrival: FloatArray, glat: FloatArray,
                    glon: FloatArray) -> tuple[FloatArray, FloatArray]:
    """The backtracked path with every point whose nearest node the front never reached
    moved onto the nearest reached node of its 5 x 5 neighbourhood (metric: the grid's
    degrees scaled by cos(lat) in longitude).

    Why: a node's pooled terrain bounds the terrain within a whole cell of it, so a point
    within a cell of a reached node is as high above the terrain as that node (to a cell's
    glide); near the tip of an obstacle a characteristic integrated backwards in half-cell
    steps can cut into blocked cells, where nothing bounds the terrain.
    """
    la, lo = np.array(lat, dtype=float), np.array(lon, dtype=float)
    dla, dlo = glat[1] - glat[0], glon[1] - glon[0]
    ny, nx = arrival.shape
    reached = np.isfinite(arrival)
    fi, fj = (la - glat[0]) / dla, (lo - glon[0]) / dlo
    ii = np.clip(np.round(fi).astype(int), 0, ny - 1)
    jj = np.clip(np.round(fj).astype(int), 0, nx - 1)
    c = math.cos(math.radians(float(np.mean(la))))
    for k in np.flatnonzero(~reached[ii, jj]):
        best, where = math.inf, None
        for di in range(-2, 3):
            for dj in range(-2, 3):
                i, j = ii[k] + di, jj[k] + dj
                if 0 <= i < ny and 0 <= j < nx and reached[i, j]:
                    d = math.hypot((i - fi[k]) * dla, (j - fj[k]) * dlo * c)
                    if d < best:
                        best, where = d, (i, j)
        if where is not None:
            la[k], lo[k] = glat[where[0]], glon[where[1]]
    return la, lo


def descend_reached(arrival: FloatArray, glat: FloatArray, glon: FloatArray, la: float,
                    lo: float) -> tuple[FloatArray, FloatArray] | None:
    """A path of reached nodes from the node nearest (la, lo) down the arrival field to its
    minimum (the start's disk): each step to the 8-neighbour of least arrival, while that
    decreases; returned start first (None when no reached node is near the point).

    The fallback when the backtracked characteristic cuts through blocked nodes (near the
    tip of an obstacle, where the arrival field has a kink, it can cut a corner by several
    cells, farther than `snap_to_reached` moves points): every node of this path was
    reached, so its pooled terrain bounds the terrain within a cell of it; it is then
    string-pulled and flown like the characteristic (the flight decides).
    """
    ny, nx = arrival.shape
    dla, dlo = glat[1] - glat[0], glon[1] - glon[0]
    i0 = int(np.clip(np.round((la - glat[0]) / dla), 0, ny - 1))
    j0 = int(np.clip(np.round((lo - glon[0]) / dlo), 0, nx - 1))
    best = None
    for di in range(-1, 2):
        for dj in range(-1, 2):
            i, j = i0 + di, j0 + dj
            if 0 <= i < ny and 0 <= j < nx and math.isfinite(arrival[i, j]) and (
                    best is None or arrival[i, j] < arrival[best]):
                best = (i, j)
    if best is None:
        return None
    nodes = [best]
    i, j = best
    for _ in range(ny * nx):
        win = arrival[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2]
        k = np.unravel_index(int(np.argmin(win)), win.shape)
        ni, nj = max(i - 1, 0) + int(k[0]), max(j - 1, 0) + int(k[1])
        if not arrival[ni, nj] < arrival[i, j]:
            break
        i, j = ni, nj
        nodes.append((i, j))
    nodes.reverse()
    return (np.array([glat[a] for a, _ in nodes]), np.array([glon[b] for _, b in nodes]))


def _offset_m(path: FlownPath, lat0: float, lon0: float, lat1: float, lon1: float) -> float:
    """Largest distance (m) of the path's waypoints from the straight line start -> goal."""
    c = math.cos(math.radians(lat0))
    x = EARTH_RADIUS_M * c * np.radians(path.waypoints_lon - lon0)
    y = EARTH_RADIUS_M * np.radians(path.waypoints_lat - lat0)
    gx = EARTH_RADIUS_M * c * math.radians(lon1 - lon0)
    gy = EARTH_RADIUS_M * math.radians(lat1 - lat0)
    L = math.hypot(gx, gy)
    if L == 0:
        return float(np.max(np.hypot(x, y)))
    s = np.clip((x * gx + y * gy) / L**2, 0.0, 1.0)
    return float(np.max(np.hypot(x - s * gx, y - s * gy)))


def _point(problem: ReachProblem, grid: ReachGrid, fp: Any, res: Any, state: Any,
           lnd: Landable) -> tuple[ReachPoint, str | None]:
    from glideplan.fronts import backtrack

    lat0, lon0, alt = problem.start
    safety = problem.safety_height
    glide, terrain = problem.glide, problem.terrain

    def empty(note: str, front_alt: float | None = None) -> ReachPoint:
        return ReachPoint(lnd, False, None, None, None, False, None, False, front_alt, None,
                          None, None, note)

    if not math.isfinite(float(terrain.elevation(lnd.lat, lnd.lon))):
        return empty("outside the terrain"), f"{lnd.name}: outside the terrain"
    T = interp_arrival(res.arrival, grid.lat, grid.lon, lnd.lat, lnd.lon)
    front_alt = alt - T if math.isfinite(T) else None
    candidates: list[FlownPath] = []
    front_path: FlownPath | None = None
    if math.isfinite(T):
        ch = backtrack(fp, res.arrival, (lnd.lat, lnd.lon), T, 0.0, (lat0, lon0),
                       state.start_radius_m)
        if ch.complete:
            sla, slo = snap_to_reached(ch.lat, ch.lon, res.arrival, grid.lat, grid.lon)
            sla[0], slo[0], sla[-1], slo[-1] = lat0, lon0, lnd.lat, lnd.lon
            found = front_candidates(glide, terrain, safety, sla, slo, alt)
            candidates += found
            front_path = found[-1]  # the last pulled path: what is reported if none is clear
    straight = fly(glide, terrain, safety, np.array([lat0, lnd.lat]),
                   np.array([lon0, lnd.lon]), alt)
    candidates.append(straight)
    clear = [c for c in candidates if c.clear and math.isfinite(c.arrival_altitude)]
    if not clear and math.isfinite(T):
        down = descend_reached(res.arrival, grid.lat, grid.lon, lnd.lat, lnd.lon)
        if down is not None:
            dla = np.concatenate([[lat0], down[0], [lnd.lat]])
            dlo = np.concatenate([[lon0], down[1], [lnd.lon]])
            found = front_candidates(glide, terrain, safety, dla, dlo, alt)
            candidates += found
            clear = [c for c in found if c.clear and math.isfinite(c.arrival_altitude)]
    warning = None
    if clear:
        best = max(clear, key=lambda c: c.arrival_altitude)
        verified = True
    else:
        # none keeps the safety height all along: report the best that at least stays above
        # the terrain (out of reach over open ground: it says by how much), else the front's
        above = [c for c in candidates if c.min_clearance_m >= 0.0
                 and math.isfinite(c.arrival_altitude)]
        if above:
            best = max(above, key=lambda c: c.arrival_altitude)
        elif front_path is not None and math.isfinite(front_path.arrival_altitude):
            best = front_path
        else:
            why = "beyond reach" if front_alt is None else "no verified path"
            return empty(why + " (the straight glide meets the terrain)", front_alt), None
        verified = False
        if front_alt is not None and front_alt >= lnd.elevation_m + safety:
            warning = (f"{lnd.name}: the front reaches it but no path flown keeps the safety "
                       f"height (best clearance {best.min_clearance_m:.1f} m < {safety:g} m): "
                       "reported unreachable")
    margin = best.arrival_altitude - lnd.elevation_m - safety
    reachable = verified and margin >= -1e-6
    offset = _offset_m(best, lat0, lon0, lnd.lat, lnd.lon)
    note = "" if reachable else (
        "arrives below the safety height" if margin < 0 else
        "no path found keeps the safety height over the terrain")
    return ReachPoint(lnd, reachable, best.arrival_altitude, margin, best.distance_m,
                      offset > grid.spacing_m, best, verified, front_alt, best.min_clearance_m,
                      best.endpoint_error_m, offset, note,
                      flown_track(best, lat0, lon0)), warning


def glide_reach(
    terrain: Terrain | Sequence[str | pathlib.Path],
    start: tuple[float, float, float],
    polar: SailplanePolar,
    *,
    landables: Sequence[Landable] | str | pathlib.Path = (),
    mc: float = 0.0,
    wind: tuple[float, float] = (0.0, 0.0),
    safety_height: float = 300.0,
    safety_glide_ratio: float | None = None,
    resolution_m: float | None = None,
    voids: str = "refuse",
) -> ReachResult:
    """Where the glider at `start` = (lat, lon, altitude m MSL) can glide to, over `terrain`
    in the steady `wind` (east, north m/s, towards), keeping `safety_height` (m) above the
    terrain all along; each landable's path verified (module docstring).

    terrain: a `Terrain` or .hgt/GeoTIFF paths (merged; `voids` as in `read_terrain`);
    landables: `Landable`s or a SeeYou .cup file; mc: MacCready setting (m/s);
    safety_glide_ratio: cap on the still-air glide ratio (`reach.model`); resolution_m: the
    front grid's spacing (None: chosen for speed).
    """
    t_all = time.perf_counter()
    warnings: list[str] = []
    if not isinstance(terrain, Terrain):
        from glideplan.terrain.merge import read_terrain

        terrain = read_terrain(list(terrain), voids=voids)
    warnings += list(terrain.warnings)
    if isinstance(landables, (str, pathlib.Path)):
        from glideplan.reach.landables import read_cup_landables

        landables, skipped = read_cup_landables(landables, terrain, warnings)
        if skipped:
            warnings.append(f"{skipped} waypoint(s) of the .cup file are not landable "
                            "(SeeYou style not 2-5) and were skipped")
    glide = Glide(polar, mc, wind, safety_glide_ratio)
    problem = ReachProblem(terrain, start, glide, tuple(landables), safety_height, resolution_m)
    lat0, lon0, alt = problem.start
    timings: dict[str, float] = {}
    t = time.perf_counter()
    grid = reach_grid(problem, glide.max_ratio)
    warnings += list(grid.notes)
    fp = front_problem(grid, glide)
    timings["grid_s"] = time.perf_counter() - t
    t = time.perf_counter()
    t_max = alt - safety_height - float(np.nanmin(grid.z)) + 1.0
    min_ratio = float(np.nanmin(glide.ratio(np.linspace(0, 2 * np.pi, 72, endpoint=False))))
    state, res = solve_front(fp, lat0, lon0, t_max, grid.spacing_m, min_ratio)
    timings["front_s"] = time.perf_counter() - t
    t = time.perf_counter()
    points = []
    for lnd in problem.landables:
        pt, warning = _point(problem, grid, fp, res, state, lnd)
        points.append(pt)
        if warning:
            warnings.append(warning)
    timings["paths_s"] = time.perf_counter() - t
    t = time.perf_counter()
    margin = clearance_margin(res.arrival, grid.z, alt, safety_height, fp.grid.hx, fp.grid.hy,
                              glide)
    polys = footprint_polygons(grid.lat, grid.lon, margin)
    timings["footprint_s"] = time.perf_counter() - t
    timings["total_s"] = time.perf_counter() - t_all
    clipped = _clipped(margin, grid, terrain)
    if clipped:
        warnings.append("the footprint is clipped to the terrain's extent (it reaches the "
                        f"terrain's {', '.join(clipped)} edge(s) and may continue beyond)")
    n_ok = sum(p.reachable for p in points)
    message = (f"{n_ok} of {len(points)} landable(s) reachable; footprint "
               f"{len(polys)} polygon(s) on a {grid.spacing_m:.0f} m grid"
               + (f", clipped at the terrain's {'/'.join(clipped)} edge" if clipped else ""))
    return ReachResult(
        status=Status.SOLVED, message=message, start=problem.start,
        safety_height=safety_height, glide=glide, points=tuple(points), footprint=polys,
        lat=grid.lat, lon=grid.lon, arrival=res.arrival, margin=margin, z=grid.z,
        terrain=grid.terrain, clipped=clipped, resolution_m=grid.spacing_m,
        pooling=grid.factor, stop_reason=res.reason, front_steps=int(res.steps), timings=timings,
        warnings=tuple(warnings))


def _clipped(margin: FloatArray, grid: ReachGrid, terrain: Terrain) -> tuple[str, ...]:
    """The terrain's sides the footprint touches (margin >= 0 on the grid's outer nodes that
    lie on the terrain's edge)."""
    s, n, w, e = terrain.extent
    tol_lat, tol_lon = 1.01 * terrain.dlat * grid.factor, 1.01 * terrain.dlon * grid.factor
    sides = []
    for name, line, at_edge in (
        ("south", margin[0, :], grid.lat[0] - s <= tol_lat),
        ("north", margin[-1, :], n - grid.lat[-1] <= tol_lat),
        ("west", margin[:, 0], grid.lon[0] - w <= tol_lon),
        ("east", margin[:, -1], e - grid.lon[-1] <= tol_lon),
    ):
        if at_edge and np.any(line >= 0):
            sides.append(name)
    return tuple(sides)
