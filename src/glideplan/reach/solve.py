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
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.reach.footprint import clearance_margin, footprint_polygons
from glideplan.reach.grid import ReachGrid, cell_nodes
from glideplan.reach.model import Glide
from glideplan.reach.native import native_search
from glideplan.reach.points import native_point
from glideplan.reach.problem import Landable, ReachProblem
from glideplan.reach.result import ReachPoint, ReachResult
from glideplan.sailplane.polar import SailplanePolar
from glideplan.solution import Status
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = ["DEFAULT_ARRIVAL_HEIGHT_M", "DEFAULT_TERRAIN_CLEARANCE_M", "descend_reached",
           "front_problem", "glide_reach", "interp_arrival", "snap_to_reached",
           "solve_front"]

FloatArray = NDArray[np.float64]

#: XCSoar's defaults: terrain clearance en route and arrival height above a field (m).
DEFAULT_TERRAIN_CLEARANCE_M = 150.0
DEFAULT_ARRIVAL_HEIGHT_M = 300.0

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


def glide_reach(
    terrain: Terrain | Sequence[str | pathlib.Path],
    start: tuple[float, float, float],
    polar: SailplanePolar,
    *,
    landables: Sequence[Landable] | str | pathlib.Path = (),
    mc: float = 0.0,
    wind: tuple[float, float] = (0.0, 0.0),
    safety_height: float | None = None,
    safety_glide_ratio: float | None = None,
    resolution_m: float | None = None,
    voids: str = "refuse",
    terrain_clearance: float | None = None,
    arrival_height: float | None = None,
    progress: bool = False,
) -> ReachResult:
    """Where the glider at `start` = (lat, lon, altitude m MSL) can glide to, over `terrain`
    in the steady `wind` (east, north m/s, towards), keeping `terrain_clearance` (m, default
    150, XCSoar's) above the terrain all along and arriving `arrival_height` (m, default 300)
    above a field; each landable's path verified (module docstring; `reach.native`).

    safety_height: the former single height: sets both (an explicit terrain_clearance or
    arrival_height wins). terrain: a `Terrain` or .hgt/GeoTIFF paths (merged; `voids` as in
    `read_terrain`); landables: `Landable`s or a SeeYou .cup file; mc: MacCready setting
    (m/s); safety_glide_ratio: cap on the still-air glide ratio (`reach.model`);
    resolution_m: a coarser search grid (max-pooled terrain: passes narrower than ~2 cells
    close; None: the terrain's own). progress: a Rich bar on stderr after ~2 s.
    """
    from glideplan.reach.grid import native_terrain

    t_all = time.perf_counter()
    warnings: list[str] = []
    terrain, landables = _read_inputs(terrain, landables, voids, warnings)
    clear_h, arrive_h = two_heights(safety_height, terrain_clearance, arrival_height)
    glide = Glide(polar, mc, wind, safety_glide_ratio)
    start = (start[0], wrap_lon(terrain, start[1]), start[2])
    problem = ReachProblem(terrain, start, glide, tuple(landables), arrive_h, resolution_m)
    timings: dict[str, float] = {}
    t = time.perf_counter()
    fine, factor, notes, crop = native_terrain(problem, glide.max_ratio, clear_h)
    warnings += notes
    timings["grid_s"] = time.perf_counter() - t
    t = time.perf_counter()
    bar = _SearchProgress(progress)
    try:
        search = native_search(fine, problem.start, glide, clear_h, on_chunk=bar)
    finally:
        bar.close()
    timings["front_s"] = time.perf_counter() - t
    if factor > 1 and problem.resolution_m is not None:
        t = time.perf_counter()
        warnings += _pass_check(fine, crop, search, problem, glide, clear_h, arrive_h)
        timings["pass_check_s"] = time.perf_counter() - t
    t = time.perf_counter()
    points = _landable_points(problem, fine, crop, search, clear_h, arrive_h)
    timings["paths_s"] = time.perf_counter() - t
    t = time.perf_counter()
    z, margin, polys = _footprint(fine, search, problem, arrive_h, points)
    timings["footprint_s"] = time.perf_counter() - t
    timings["total_s"] = time.perf_counter() - t_all
    spacing = max(fine.spacing_m)
    grid = ReachGrid(fine.lat, fine.lon, z, search.block, fine, factor, spacing, ())
    clipped = _clipped(margin, grid, terrain) + _voids_touched(search.loss, z)
    if clipped:
        warnings.append("the footprint is clipped to the terrain's extent (it reaches the "
                        f"terrain's {', '.join(clipped)} edge(s) and may continue beyond)")
    n_ok = sum(p.reachable for p in points)
    message = (f"{n_ok} of {len(points)} landable(s) reachable; footprint "
               f"{len(polys)} polygon(s) on a {spacing:.0f} m grid"
               + (f", clipped at the terrain's {'/'.join(clipped)} edge" if clipped else ""))
    return ReachResult(
        status=Status.SOLVED, message=message, start=problem.start,
        safety_height=arrive_h, glide=glide, points=tuple(points), footprint=polys,
        lat=fine.lat, lon=fine.lon, arrival=search.loss, margin=margin, z=z,
        terrain=fine, clipped=clipped, resolution_m=spacing, pooling=factor,
        stop_reason="the search settled every node it can reach", front_steps=search.pops,
        timings=timings, warnings=tuple(warnings), terrain_clearance=clear_h,
        arrival_height=arrive_h)


def _footprint(fine: Terrain, search: Any, problem: ReachProblem, arrive_h: float,
               points: list[Any]) -> tuple[np.ndarray, np.ndarray, Any]:
    """The terrain heights (m), the clearance margin of every node (m; the landables' paths
    burnt in) and the footprint's polygons."""
    z = np.asarray(fine.z, dtype=float)
    hx = EARTH_RADIUS_M * np.cos(np.radians(fine.lat)) * math.radians(fine.dlon)
    hy = EARTH_RADIUS_M * math.radians(fine.dlat)
    margin = clearance_margin(search.loss, z, problem.start[2], arrive_h, hx, hy, problem.glide)
    burn_in_points(margin, fine, points)
    return z, margin, footprint_polygons(fine.lat, fine.lon, margin)


def _read_inputs(terrain: Terrain | Sequence[str | pathlib.Path],
                 landables: Sequence[Landable] | str | pathlib.Path, voids: str,
                 warnings: list[str]) -> tuple[Terrain, Sequence[Landable]]:
    """The terrain (files merged) and the landables (a .cup file read), their warnings
    appended to `warnings`."""
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
    return terrain, landables


def _landable_points(problem: ReachProblem, fine: Terrain, crop: Terrain, search: Any,
                     clear_h: float, arrive_h: float) -> list[Any]:
    """Each landable's verified path (or the straight glide to one beyond the crop), then
    the shortfalls of those out of reach."""
    glide = problem.glide
    spacing = max(fine.spacing_m)
    points = []
    for lnd in problem.landables:
        comp = replace(lnd, lon=wrap_lon(fine, lnd.lon))
        if (math.isfinite(float(problem.terrain.elevation(comp.lat, comp.lon)))
                and not math.isfinite(float(crop.elevation(comp.lat, comp.lon)))):
            pt = _beyond_crop(problem.start, glide, comp, arrive_h)
        else:
            pt = native_point(fine, problem.start, glide, search, comp, clear_h, arrive_h,
                              spacing, crop)
        points.append(replace(pt, landable=lnd))
    return list(_shortfalls(points, fine, problem.start, glide, clear_h, arrive_h))


def _pass_check(pooled: Terrain, crop: Terrain, search: Any, problem: ReachProblem,
                glide: Glide, clear_h: float, arrive_h: float) -> list[str]:
    """The warning naming the pass the pooled grid closes (`reach.passes`): the native
    search on the unpooled crop (when it has at most MAX_NATIVE_NODES nodes), compared."""
    from glideplan.reach.grid import MAX_NATIVE_NODES
    from glideplan.reach.passes import closed_pass, pass_warning

    if crop.z.size > MAX_NATIVE_NODES:
        return []
    native = native_search(crop, problem.start, glide, clear_h)
    found = closed_pass(crop, pooled, search.loss, native, problem.start, clear_h,
                        problem.landables, arrive_h,
                        2.0 * max(pooled.spacing_m) / max(glide.max_ratio, 1.0))
    if found is None:
        return []
    return [pass_warning(max(pooled.spacing_m), max(crop.spacing_m), found)]


def _beyond_crop(start: tuple[float, float, float], glide: Glide, lnd: Landable,
                 arrive_h: float) -> ReachPoint:
    """A field on the terrain but beyond the largest possible glide (outside the searched
    crop): out of reach, short by at least the straight glide's deficit over flat ground,
    elevation + arrival height + d / r(chi) - ALT (a lower bound: terrain only adds)."""
    from glideplan.reach.flight import rhumb

    d, chi = rhumb(np.array(start[0]), np.array(start[1]), np.array(lnd.lat),
                   np.array(lnd.lon))
    r = float(glide.ratio(float(chi))[0])
    short = lnd.elevation_m + arrive_h + float(d) / r - start[2] if r > 0 else None
    note = "beyond reach: farther than the longest glide over the lowest terrain" + (
        f" (short by at least {short:.0f} m)" if short is not None else "")
    return ReachPoint(lnd, False, None, None, None, False, None, False, None, None, None,
                      None, note, None, short_by_m=short, terrain_missing=False)


#: At most this many fields out of reach get their shortfall from a backward search.
MAX_SHORTFALL_SEARCHES = 8


def _shortfalls(points: list[ReachPoint], t: Terrain, start: tuple[float, float, float],
                glide: Glide, clear_h: float, arrive_h: float) -> list[ReachPoint]:
    """`short_by_m` of the fields out of reach from a backward search from each
    (`native.native_back_search`: the least start altitude that reaches it with both
    heights, on the search's grid) when that is less than the flown estimate (the straight
    glide's bound, or a clear path's arrival deficit). Up to MAX_SHORTFALL_SEARCHES
    fields; the rest keep the flown estimate."""
    from glideplan.reach.native import native_back_search, need_at

    out = []
    budget = MAX_SHORTFALL_SEARCHES
    for p in points:
        if p.reachable or p.terrain_missing or budget == 0:
            out.append(p)
            continue
        budget -= 1
        lnd = p.landable
        lon = wrap_lon(t, lnd.lon)
        ceiling = start[2] + (p.short_by_m if p.short_by_m is not None else 5000.0) + 1.0
        back = native_back_search(t, (lnd.lat, lon, lnd.elevation_m + arrive_h), glide,
                                  clear_h, ceiling)
        need = need_at(back, t, glide, start[0], start[1])[0]
        short = max(need - start[2], 0.0)
        if math.isfinite(need) and (p.short_by_m is None or short < p.short_by_m):
            note = f"out of reach: short by {short:.0f} m (the least start altitude that " \
                   "reaches it, on the terrain's grid)"
            p = replace(p, short_by_m=short, note=note)
        out.append(p)
    return out


def two_heights(safety_height: float | None, terrain_clearance: float | None,
                arrival_height: float | None) -> tuple[float, float]:
    """(en-route terrain clearance, arrival height) m: explicit values, else the former
    single `safety_height` for both, else XCSoar's defaults (150, 300)."""
    from glideplan.validation import check_physical

    if safety_height is not None:  # validation.PHYSICAL_RANGES["height"], as final_glide
        check_physical("safety_height", safety_height, "height")
    clear_h = terrain_clearance if terrain_clearance is not None else (
        safety_height if safety_height is not None else DEFAULT_TERRAIN_CLEARANCE_M)
    arrive_h = arrival_height if arrival_height is not None else (
        safety_height if safety_height is not None else DEFAULT_ARRIVAL_HEIGHT_M)
    return (check_physical("terrain_clearance", clear_h, "height"),
            check_physical("arrival_height", arrive_h, "height"))


def wrap_lon(terrain: Terrain, lon: float) -> float:
    """`lon` + 360 k nearest the terrain's middle (a merged tile pair over 180 deg runs to
    181 E; a field at 179.9 W is then at 180.1 E)."""
    mid = 0.5 * (float(terrain.lon[0]) + float(terrain.lon[-1]))
    return float(lon + 360.0 * round((mid - lon) / 360.0))


def burn_in_points(margin: FloatArray, t: Terrain, points: Sequence[ReachPoint]) -> None:
    """The 4 nodes round each reachable field get at least its verified arrival margin, so
    the drawn footprint holds every field a flown path reaches (the search is conservative
    by up to 0.76 %, `reach.native`)."""
    for p in points:
        if not (p.reachable and p.arrival_margin_m is not None):
            continue
        lon = wrap_lon(t, p.landable.lon)
        for i, j in cell_nodes(t.lat, t.lon, [(p.landable.lat, lon)]):
            margin[i, j] = max(margin[i, j], p.arrival_margin_m)


def _voids_touched(loss: FloatArray, z: FloatArray) -> tuple[str, ...]:
    """("missing terrain",) when a reached node neighbours a node with no data."""
    nan = ~np.isfinite(z)
    if not nan.any():
        return ()
    from scipy.ndimage import binary_dilation

    return ("missing terrain",) if bool(np.any(binary_dilation(nan) & np.isfinite(loss))) \
        else ()


class _SearchProgress:
    """The native search's bar (`glideplan.progress.DelayedBar`, shown once it has run
    ~2 s): the fraction (loss reached / largest loss)^2 and the time remaining."""

    def __init__(self, enabled: bool) -> None:
        from glideplan.progress import DelayedBar

        self.bar = DelayedBar("glide reach: search", 1000.0, enabled=enabled, delay=2.0)

    def __call__(self, fraction: float) -> None:
        self.bar.update(completed=round(1000 * fraction))

    def close(self) -> None:
        self.bar.close()


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
