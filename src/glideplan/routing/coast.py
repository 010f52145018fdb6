"""Routes round coasts at the data's own resolution: the taut path among clearance disks.

The obstacle a route keeps clear of is the union of disks of radius c (the land clearance)
about the field's own land (NaN) nodes -- at the field's resolution, never the front's. In
still water the shortest way round it is a chain of tangent segments and arcs of those
circles (the polygon geodesic of the clearance-inflated land). `taut_path` finds it, in the
way round (homotopy) the front's grid route chose, on a visibility graph:

- the plane: the gnomonic projection about the route's middle (great circles are straight
  lines; distances grow by at most 1/cos^2(rho) at angular distance rho from the centre, so
  the planar clearance is c times that at the region's edge: never closer than c on the
  sphere);
- vertices: the start, the goal, and for every land node the K-gon circumscribing its disk of
  radius c (vertices at c / cos(pi / K)), kept where no other node is closer than c; a path
  round a circle along the K-gon is longer than the arc by tan(pi/K) / (pi/K) - 1 (0.6 % of
  the arcs at K = 24, ~0.05 % of a route round a cape);
- edges: straight segments at distance >= c from every land node (exact point-segment
  distances) and within the corridor of width `corridor_m` about the grid route (which keeps
  the front's way round each island);
- search: A* with the straight-line distance to the goal (admissible).

`clearance_of` measures a polyline's least distance to the land nodes on the sphere (dense
great-circle samples, a k-d tree of 3-D positions), the check the tests and `route()` use.

The front's side: `descent_path` (the front's way round, the corridor), `front_obstacles`
(the front's obstacles one spacing inside the clearance, so a way open at the mask's
resolution stays open on any grid) and `narrowest_gap` (the warning naming a gap the grid
does not resolve).

Why this module is long: ~600 lines because these pieces are one idea -- the route near land
at the data's resolution -- and share its geometry; each function is short.
"""

from __future__ import annotations

import heapq
import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.sphere import EARTH_RADIUS_M

__all__ = ["Gnomonic", "clearance_of", "descent_path", "round_coast", "taut_path"]

FloatArray = NDArray[np.float64]

#: Sides of the polygon circumscribing each clearance circle.
K_SIDES = 24
#: Relative margin kept beyond the clearance by the graph's vertices and edges.
MARGIN = 1e-4


def _unit(lat: Any, lon: Any) -> FloatArray:
    p, lam = np.radians(np.asarray(lat, dtype=float)), np.radians(np.asarray(lon, dtype=float))
    return np.stack([np.cos(p) * np.cos(lam), np.cos(p) * np.sin(lam), np.sin(p)], axis=-1)


@dataclass(frozen=True)
class Gnomonic:
    """Gnomonic plane about (lat0, lon0) on the sphere of radius R: x east, y north (m);
    x = R (p . e) / (p . n0), y = R (p . n) / (p . n0) for the unit vector p of a point."""

    lat0: float
    lon0: float

    def _basis(self) -> tuple[FloatArray, FloatArray, FloatArray]:
        n0 = _unit(self.lat0, self.lon0)
        lam = math.radians(self.lon0)
        e = np.array([-math.sin(lam), math.cos(lam), 0.0])
        return n0, e, np.cross(n0, e)

    def from_xyz(self, p: FloatArray) -> FloatArray:
        """(n, 2) plane points of (n, 3) positions (any length; the near hemisphere)."""
        n0, e, nn = self._basis()
        d = p @ n0
        return EARTH_RADIUS_M * np.stack([(p @ e) / d, (p @ nn) / d], axis=-1)

    def to_latlon(self, xy: FloatArray) -> tuple[FloatArray, FloatArray]:
        """(lat, lon) deg of (n, 2) plane points."""
        n0, e, nn = self._basis()
        p = n0[None, :] + (xy[:, :1] * e[None, :] + xy[:, 1:2] * nn[None, :]) / EARTH_RADIUS_M
        p /= np.linalg.norm(p, axis=1, keepdims=True)
        return (np.degrees(np.arcsin(np.clip(p[:, 2], -1, 1))),
                np.degrees(np.arctan2(p[:, 1], p[:, 0])))

    def scale(self, xy: FloatArray) -> float:
        """The largest distance scale 1 / cos^2(rho) at the points (>= 1)."""
        rho2 = np.sum(np.asarray(xy) ** 2, axis=-1) / EARTH_RADIUS_M ** 2
        return float(1.0 + np.max(rho2, initial=0.0))


def _seg_dist(a: FloatArray, b: FloatArray, s: FloatArray) -> FloatArray:
    """Distances (m, b.shape[0] x s.shape[0]) from sites s to the segments a -> b[k]."""
    d = b - a  # (m, 2)
    L2 = np.maximum(np.sum(d * d, axis=1), 1e-12)  # (m,)
    w = s[None, :, :] - a[None, None, :]  # (1, n, 2)
    t = np.clip(np.einsum("mk,mnk->mn", d, np.broadcast_to(w, (d.shape[0], *w.shape[1:])))
                / L2[:, None], 0.0, 1.0)
    px = a[0] + t * d[:, 0:1] - s[None, :, 0]
    py = a[1] + t * d[:, 1:2] - s[None, :, 1]
    return np.asarray(np.hypot(px, py), dtype=float)


def _densify(xy: FloatArray, step: float) -> FloatArray:
    """The polyline's points every <= `step` (m) along each leg (ends kept)."""
    out = [xy[:1]]
    for a, b in itertools.pairwise(xy):
        n = max(math.ceil(float(np.hypot(*(b - a))) / step), 1)
        s = np.linspace(0.0, 1.0, n + 1)[1:, None]
        out.append(a + s * (b - a))
    return np.concatenate(out)


def _vertices(sites: FloatArray, radius: FloatArray, tree: Any) -> tuple[FloatArray,
                                                                         FloatArray]:
    """The circumscribed K-gons' vertices that no site's disk covers (module docstring), and
    each one's centre (its site)."""
    ang = 2 * np.pi * (np.arange(K_SIDES) + 0.5) / K_SIDES
    ring = np.stack([np.cos(ang), np.sin(ang)], axis=-1) / math.cos(math.pi / K_SIDES)
    v = (sites[:, None, :] + radius[:, None, None] * ring[None, :, :]).reshape(-1, 2)
    centre = np.repeat(sites, K_SIDES, axis=0)
    rmax = float(np.max(radius))
    near = tree.query_ball_point(v, rmax * (1 - 1e-9))
    keep = np.ones(v.shape[0], dtype=bool)
    for k, idx in enumerate(near):
        if idx:
            d = np.hypot(*(sites[idx] - v[k]).T)
            keep[k] = bool(np.all(d >= radius[idx] * (1 - 0.5 * MARGIN)))
    return np.asarray(v[keep], dtype=float), np.asarray(centre[keep], dtype=float)


def taut_path(start: tuple[float, float], goal: tuple[float, float], sites_xyz: FloatArray,
              clearance: float, route_lat: FloatArray, route_lon: FloatArray,
              corridor_m: float, wall_xyz: FloatArray | None = None,
              wall_m: float = 0.0) -> tuple[FloatArray, FloatArray] | None:
    """The shortest path from `start` to `goal` (lat, lon deg) keeping `clearance` (m) from
    every land node (3-D positions, m) in the corridor of half-width `corridor_m` about the
    grid route (module docstring); `wall_xyz`: points (the field's edge) kept `wall_m` off
    without vertices of their own. (lat, lon) deg of its vertices, or None (no such path)."""
    from scipy.spatial import cKDTree

    mid = _unit(*start) + _unit(*goal)
    mid /= np.linalg.norm(mid)
    plane = Gnomonic(float(np.degrees(np.arcsin(mid[2]))),
                     float(np.degrees(np.arctan2(mid[1], mid[0]))))
    ends = plane.from_xyz(_unit(np.array([start[0], goal[0]]), np.array([start[1], goal[1]])))
    route = _densify(plane.from_xyz(_unit(route_lat, route_lon)), 0.25 * corridor_m)
    route_tree = cKDTree(route)
    sites = plane.from_xyz(sites_xyz / EARTH_RADIUS_M)
    radius = np.full(sites.shape[0], clearance)
    wall = np.zeros((0, 2))
    if wall_xyz is not None and wall_xyz.shape[0] and wall_m > 0:
        wall = plane.from_xyz(wall_xyz / EARTH_RADIUS_M)
    reach = corridor_m + max(clearance, wall_m) * 1.1
    sites, radius = _within(sites, radius, route_tree, reach)
    wall_r = np.full(wall.shape[0], wall_m)
    wall, wall_r = _within(wall, wall_r, route_tree, reach)
    scale = plane.scale(np.concatenate([route, sites, wall])) * (1 + MARGIN)
    radius = radius * scale
    wall_r = wall_r * scale
    if sites.shape[0] == 0:
        return None
    site_tree = cKDTree(sites)
    verts, centre = _vertices(sites, radius * (1 + MARGIN), site_tree)
    if verts.shape[0]:
        d_route, _ = route_tree.query(verts)
        near = d_route <= corridor_m
        verts, centre = verts[near], centre[near]
    if wall.shape[0] and verts.shape[0]:
        dw, _ = cKDTree(wall).query(verts)
        clear = dw >= wall_r[0]
        verts, centre = verts[clear], centre[clear]
    blockers = np.concatenate([sites, wall])
    block_r = np.concatenate([radius, wall_r])
    nodes = np.concatenate([ends, verts])
    centres = np.concatenate([np.full((2, 2), np.nan), centre])
    path = _astar(nodes, centres, blockers, block_r, route_tree, corridor_m)
    if path is None:
        return None
    return plane.to_latlon(nodes[path])


def _within(pts: FloatArray, r: FloatArray, tree: Any, reach: float) -> tuple[FloatArray,
                                                                              FloatArray]:
    if pts.shape[0] == 0:
        return pts, r
    d, _ = tree.query(pts, distance_upper_bound=reach)
    keep = np.isfinite(d)
    return pts[keep], r[keep]


def _visible(a: FloatArray, b: FloatArray, blockers: FloatArray, block_r: FloatArray,
             route_tree: Any, corridor_m: float) -> NDArray[np.bool_]:
    """Which segments a -> b[k] keep every blocker's distance and stay in the corridor."""
    ok = np.ones(b.shape[0], dtype=bool)
    if blockers.shape[0]:
        # only blockers within reach of the segments' box matter
        lo = np.minimum(a, b.min(axis=0)) - block_r.max()
        hi = np.maximum(a, b.max(axis=0)) + block_r.max()
        inbox = np.all((blockers >= lo) & (blockers <= hi), axis=1)
        s, r = blockers[inbox], block_r[inbox]
        for k0 in range(0, b.shape[0], 256):
            sl = slice(k0, k0 + 256)
            if s.shape[0]:
                ok[sl] = np.all(_seg_dist(a, b[sl], s) >= r[None, :], axis=1)
    idx = np.flatnonzero(ok)
    if idx.size:  # inner samples every half corridor, all segments in one query
        length = np.hypot(*(b[idx] - a).T)
        n = np.maximum(np.ceil(length / (0.5 * corridor_m)).astype(int), 1)
        inner = n - 1
        has = inner > 0
        if has.any():
            seg = np.repeat(np.flatnonzero(has), inner[has])
            first = np.cumsum(inner[has]) - inner[has]
            k = np.arange(seg.size) - np.repeat(first, inner[has]) + 1
            t = (k / np.repeat(n[has], inner[has]))[:, None]
            d, _ = route_tree.query(a + t * (b[idx[seg]] - a), distance_upper_bound=corridor_m
                                    * (1 + 1e-9))
            inside = np.isfinite(d)
            bad = np.zeros(idx.size, dtype=bool)
            np.logical_or.at(bad, seg, ~inside)
            ok[idx[bad]] = False
    return ok


def _supports(p: FloatArray, centre: FloatArray, d: FloatArray) -> NDArray[np.bool_]:
    """Whether the lines through vertices p along d support their K-gons (about `centre`;
    NaN: no K-gon, always): the direction within pi/K of the tangent. A shortest path among
    convex polygons leaves and meets their vertices along such lines only (a bitangent)."""
    radial = p - centre
    cos = np.abs(np.sum(d * radial, axis=-1)) / np.maximum(
        np.hypot(*d.T) * np.hypot(*radial.T), 1e-300)
    return np.asarray(~(cos > math.sin(math.pi / K_SIDES) + 1e-9), dtype=bool)


def _astar(nodes: FloatArray, centres: FloatArray, blockers: FloatArray, block_r: FloatArray,
           route_tree: Any, corridor_m: float) -> list[int] | None:
    """A* from node 0 to node 1 on the visibility graph of bitangent edges (`_supports`,
    found lazily per node)."""
    goal = nodes[1]
    h = np.hypot(*(nodes - goal).T)
    n = nodes.shape[0]
    g = np.full(n, np.inf)
    g[0] = 0.0
    prev = np.full(n, -1)
    done = np.zeros(n, dtype=bool)
    heap = [(h[0], 0)]
    while heap:
        _, u = heapq.heappop(heap)
        if done[u]:
            continue
        done[u] = True
        if u == 1:
            break
        todo = np.flatnonzero(~done)
        if todo.size == 0:
            continue
        step = np.hypot(*(nodes[todo] - nodes[u]).T)
        better = g[u] + step < g[todo] - 1e-9
        todo, step = todo[better], step[better]
        d = nodes[todo] - nodes[u]
        tangent = _supports(nodes[u][None, :], centres[u][None, :], d) & \
            _supports(nodes[todo], centres[todo], d)
        todo, step = todo[tangent], step[tangent]
        if todo.size == 0:
            continue
        vis = _visible(nodes[u], nodes[todo], blockers, block_r, route_tree, corridor_m)
        for v, s in zip(todo[vis], step[vis], strict=True):
            g[v] = g[u] + s
            prev[v] = u
            heapq.heappush(heap, (g[v] + h[v], int(v)))
    if not np.isfinite(g[1]):
        return None
    path = [1]
    while path[-1] != 0:
        path.append(int(prev[path[-1]]))
    return path[::-1]


def clearance_of(lat: FloatArray, lon: FloatArray, sites_xyz: FloatArray,
                 step_m: float) -> float:
    """The least great-circle distance (m) from the polyline (its legs sampled every <=
    `step_m` along the great circle) to the land nodes (3-D positions, m); inf without."""
    if sites_xyz.shape[0] == 0 or lat.size == 0:
        return math.inf
    from scipy.spatial import cKDTree

    p = _unit(lat, lon)
    pts = [p[:1]]
    for a, b in itertools.pairwise(p):
        ang = math.acos(min(max(float(a @ b), -1.0), 1.0))
        n = max(math.ceil(ang * EARTH_RADIUS_M / step_m), 1)
        s = np.linspace(0.0, 1.0, n + 1)[1:, None]
        q = a + s * (b - a)
        pts.append(q / np.linalg.norm(q, axis=1, keepdims=True))
    d, _ = cKDTree(sites_xyz).query(np.concatenate(pts) * EARTH_RADIUS_M)
    chord = float(np.min(d))
    return 2 * EARTH_RADIUS_M * math.asin(min(chord / (2 * EARTH_RADIUS_M), 1.0))



def field_cell_diagonal(fld: Any, lat_ref: float) -> float:
    """Half the diagonal (m) of a gridded field's cell at lat_ref (0 for other fields): a
    point farther than this from every land node lies in no land cell."""
    from glideplan.fields.field import GriddedField

    if not isinstance(fld, GriddedField) or fld.lat.size < 2 or fld.lon.size < 2:
        return 0.0
    dy = EARTH_RADIUS_M * math.radians(float(np.max(np.abs(np.diff(fld.lat)))))
    dx = EARTH_RADIUS_M * math.cos(math.radians(min(abs(lat_ref), 85.0))) * math.radians(
        float(np.max(np.abs(np.diff(fld.lon)))))
    return 0.5 * math.hypot(dx, dy)


def round_coast(problem: Any, rg: Any, arrival: FloatArray) -> tuple[
        FloatArray, FloatArray] | None:
    """The shortest way round the coast in the homotopy of the front's way (`descent_path`
    on its `arrival` map; `taut_path` in a corridor of max(8 h, 2 c) about it, h the routing
    spacing, c the clearance), checked on the sphere (>= c from every land node); None when
    it does not apply: no land near, the start or goal within the clearance (relaxed there),
    a clearance under half a field cell's diagonal (a path clear of the nodes could enter a
    land cell), or no such path in the corridor."""
    from glideplan.routing.window import _coast, _xyz, distance_to_land

    c, pts, h = float(rg.clearance_m), rg.coast_xyz, float(rg.spacing_m)
    lat_ref = 0.5 * (problem.start[0] + problem.goal[0])
    if c <= 0 or pts.shape[0] == 0 or rg.window.periodic or \
            c < field_cell_diagonal(problem.field_, lat_ref):
        return None
    ends = distance_to_land(pts, np.array([problem.start[0], problem.goal[0]]),
                            np.array([problem.start[1], problem.goal[1]]), c)
    if np.any(ends < c):
        return None
    hard = ~rg.window.inside
    wall = None
    if hard.any():
        LA, LO = np.meshgrid(rg.window.lat, rg.window.lon, indexing="ij")
        edge = _coast(hard)
        wall = _xyz(LA[edge], LO[edge])
    fi, fj = rg.window.frac_index(problem.goal[0], problem.goal[1])
    ny, nx = arrival.shape
    gij = (int(np.clip(np.rint(fi), 0, ny - 1)), int(np.clip(np.rint(fj), 0, nx - 1)))
    ij = descent_path(arrival, ~rg.obstacle | np.isfinite(arrival), gij)
    lat, lon = rg.window.lat[ij[:, 0]], rg.window.lon[ij[:, 1]]
    got = None
    for widen in (1.0, 4.0):  # a corridor too narrow for the way round: once 4x wider
        got = taut_path(problem.start, problem.goal, pts, c, lat, lon,
                        widen * max(8 * h, 2 * c), wall_xyz=wall, wall_m=1.5 * h)
        if got is not None:
            break
    if got is None:
        return None
    la, lo = got
    from glideplan.routing.sphere import unwrap_lon

    lo = unwrap_lon(lo, problem.start[1])
    la[0], lo[0] = problem.start[0], problem.start[1]
    la[-1], lo[-1] = problem.goal[0], problem.goal[1]
    if clearance_of(la, lo, pts, min(c, h) / 8) < c * (1 - 1e-3):
        return None
    return la, lo


def descent_path(arrival: FloatArray, free: NDArray[np.bool_],
                 goal_ij: tuple[int, int]) -> NDArray[np.intp]:
    """The front's way to the goal on its own nodes, pulled taut among them: from the goal's
    node, steps to the 8-neighbour of least arrival time until none is earlier (the start's
    disk; T falls at every step, so it ends and never enters a node the front did not reach:
    the way round each obstacle the front chose, where the characteristic may stall at a
    corner); then, greedily from the start's end, the farthest node in a straight line over
    `free` nodes (samples every quarter cell). (k, 2) node indices, start's end first."""
    ny, nx = arrival.shape
    i, j = goal_ij
    T = np.where(np.isfinite(arrival), arrival, np.inf)
    if not np.isfinite(T[i, j]):  # the goal's nearest node unreached: its best neighbour
        i0, j0 = max(i - 1, 0), max(j - 1, 0)
        blk = T[i0:i + 2, j0:j + 2]
        k = np.unravel_index(int(np.argmin(blk)), blk.shape)
        i, j = i0 + int(k[0]), j0 + int(k[1])
    path = [(i, j)]
    for _ in range(ny * nx):
        i0, j0 = max(i - 1, 0), max(j - 1, 0)
        blk = T[i0:i + 2, j0:j + 2]
        k = np.unravel_index(int(np.argmin(blk)), blk.shape)
        if not blk[k] < T[i, j]:
            break
        i, j = i0 + int(k[0]), j0 + int(k[1])
        path.append((i, j))
    nodes = np.array(path[::-1], dtype=float)
    free = free.copy()
    free[nodes[:, 0].astype(int), nodes[:, 1].astype(int)] = True
    # pulled from either end (8-neighbour steps run diagonally first: the pull from the end
    # they left late shortcuts it); the shorter (nodes are near square: dlon = dlat / cos)
    ways = [_pull(nodes, free), _pull(nodes[::-1], free)[::-1]]
    return min(ways, key=lambda w: float(np.sum(np.hypot(*np.diff(w, axis=0).T))))


def _pull(nodes: FloatArray, free: NDArray[np.bool_]) -> NDArray[np.intp]:
    """Greedily from the first node, the farthest later node in a straight line over `free`
    nodes (samples every quarter cell); the kept nodes."""
    keep = [0]
    while keep[-1] < nodes.shape[0] - 1:
        a = nodes[keep[-1]]
        rest = nodes[keep[-1] + 1:]
        n = np.maximum(np.ceil(4 * np.max(np.abs(rest - a), axis=1)).astype(int), 1)
        ok = np.ones(rest.shape[0], dtype=bool)
        for m in range(rest.shape[0]):
            t = np.linspace(0.0, 1.0, n[m] + 1)[:, None]
            q = np.rint(a + t * (rest[m] - a)).astype(int)
            ok[m] = bool(np.all(free[q[:, 0], q[:, 1]]))
        ok[0] = True  # the next node: a step of the descent
        keep.append(keep[-1] + 1 + int(np.flatnonzero(ok)[-1]))
    return np.asarray(nodes[keep], dtype=np.intp)


def applies(fld: Any, clearance: float, lat_ref: float, periodic: bool) -> bool:
    """Whether routes keep the clearance at the land mask's resolution (`round_coast`): a
    clearance of at least half a field cell's diagonal, on a window that is not the whole
    circle (the start and goal outside the clearance are checked by the caller)."""
    return clearance > 0 and not periodic and clearance >= field_cell_diagonal(fld, lat_ref)


def front_clearance(clearance: float, spacing: float) -> float:
    """The clearance of the front's obstacles when the route keeps the exact one at the mask's
    resolution: c - h, at least c / 2. A way whose water beyond the clearance is w > 0 wide
    is then w + 2 h >= 2 h wide on the front's grid: open to its 8-neighbour steps (the front
    is an accelerator that picks the way round; `round_coast` is the judge, and a way that is
    closed at the full clearance sends the route back to a front at the full clearance)."""
    return max(clearance - spacing, 0.5 * clearance)


def narrowest_gap(dist: FloatArray, land: NDArray[np.bool_], inside: NDArray[np.bool_],
                  clearance: float, relaxed: float) -> tuple[float, int, int] | None:
    """The narrowest way between land that the front's nodes close at the full clearance but
    not at `relaxed`: (its width between land ~ 2 x the distance to land at its pass (m),
    row, column of the pass), or None. dist: each node's distance to land (m, inf beyond
    the clearance). The nodes free at `relaxed` only are added from the farthest from land
    down (union-find, 8-neighbours); each time two regions free at the full clearance first
    join, the node that joins them is a gap's pass."""
    from scipy.ndimage import label

    eight = np.ones((3, 3), dtype=bool)
    strict = inside & ~land & (dist >= clearance)
    bridge = inside & ~land & (dist >= relaxed) & ~strict
    if not bridge.any():
        return None
    s_lab, ns = label(strict, structure=eight)
    if ns < 2:
        return None
    ny, nx = dist.shape
    parent = list(range(ns + 1))

    def find(a: int) -> int:
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    node_set = np.zeros(dist.shape, dtype=np.int64)  # 0: not added; else its set id
    node_set[strict] = s_lab[strict]
    # a strict region's nodes carry its label; a bridge node a new id, owned by no region yet
    owned = [True] * (ns + 1)
    flat = np.flatnonzero(bridge.ravel())
    order = flat[np.argsort(-dist.ravel()[flat], kind="stable")]
    best: tuple[float, int, int] | None = None
    for f in order:
        i, j = divmod(int(f), nx)
        parent.append(len(parent))
        owned.append(False)
        me = len(parent) - 1
        node_set[i, j] = me
        for di in (-1, 0, 1):
            for dj in (-1, 0, 1):
                a, b = i + di, j + dj
                if (di or dj) and 0 <= a < ny and 0 <= b < nx and node_set[a, b]:
                    ra, rb = find(me), find(int(node_set[a, b]))
                    if ra == rb:
                        continue
                    if owned[ra] and owned[rb]:  # two free regions join here: a pass
                        w = 2.0 * float(dist[i, j])
                        if best is None or w < best[0]:
                            best = (w, i, j)
                    parent[rb] = ra
                    owned[ra] = owned[ra] or owned[rb]
    return best


def front_obstacles(problem: Any, window: Any, land: NDArray[np.bool_], clearance: float,
                    pts: FloatArray, strict: bool = False) -> tuple[NDArray[np.bool_], float,
                                                                    list[str]]:
    """The front's obstacle nodes when the route keeps the clearance at the mask's resolution
    (`applies`): land, or nearer land than `front_clearance` (`strict`: the full clearance);
    with the front's clearance used and a warning naming the narrowest gap between land that
    the grid closes at the full clearance (`narrowest_gap`)."""
    from glideplan.routing.window import distance_to_land

    h = window.lattice.spacing_m
    relaxed = front_clearance(clearance, h)
    LA, LO = np.meshgrid(window.lat, window.lon, indexing="ij")
    dist = distance_to_land(pts, LA, LO, clearance)
    c_front = clearance if strict else relaxed
    mask = land | (dist < c_front)
    warn: list[str] = []
    gap = narrowest_gap(dist, land, window.inside, clearance, relaxed)
    if gap is not None:
        w, i, j = gap
        w = _gap_width(pts, float(window.lat[i]), float(window.lon[j]), w)
        lon = float((window.lon[j] + 180.0) % 360.0 - 180.0)
        lat = float(window.lat[i])
        water = w - 2 * clearance
        where = f"a gap {w / 1000:.3g} km wide between land near {lat:.4f}, {lon:.4f}"
        if water <= 0:
            if strict:
                warn.append(f"{where} is closed by the land clearance ({clearance:.0f} m on "
                            f"either side); a --land-clearance under {w / 2:.0f} m opens it")
        elif strict:
            warn.append(f"{GAP_WARNING} ({h:.0f} m) closes {where} ({water:.0f} m of water "
                        f"beyond the {clearance:.0f} m land clearance): a finer resolution "
                        "may open it")
        else:
            warn.append(f"{GAP_WARNING} ({h:.0f} m) does not resolve {where} ({water:.0f} m "
                        f"of water beyond the {clearance:.0f} m land clearance): the front "
                        "passes it at a reduced clearance, the route keeps the full "
                        "clearance at the land mask's resolution")
    warn += _closed_gap_warning(problem, window, mask, pts, clearance)
    return mask, c_front, warn


def _closed_gap_warning(problem: Any, window: Any, mask: NDArray[np.bool_], pts: FloatArray,
                        clearance: float) -> list[str]:
    """The warning naming the narrowest gap open at the land mask's resolution that the
    front's obstacles `mask` close (`routing.gaps.closed_gap`): the route may go the long
    way round."""
    from glideplan.routing.gaps import closed_gap

    gap = closed_gap(problem.field_, window, mask, pts, clearance)
    if gap is None:
        return []
    d, lat, lon = gap
    w = _gap_width(pts, lat, lon, 2.0 * d)
    lon = float((lon + 180.0) % 360.0 - 180.0)
    h = window.lattice.spacing_m
    return [f"{GAP_WARNING} ({h:.0f} m) closes a gap {w / 1000:.3g} km wide between land "
            f"near {lat:.4f}, {lon:.4f} that is open at the land mask's resolution "
            f"({w - 2 * clearance:.0f} m of water beyond the {clearance:.0f} m land "
            "clearance): the route may go the long way round; a finer --resolution may "
            "open it"]


def _gap_width(pts: FloatArray, lat: float, lon: float, guess: float) -> float:
    """The width (m) of a gap at its pass node (lat, lon): the distance between the nearest
    land node and the nearest one on the other side (the angle at the node over 90 deg);
    `guess` (twice the distance to land) when there is none."""
    from scipy.spatial import cKDTree

    q = _unit(lat, lon) * EARTH_RADIUS_M
    tree = cKDTree(pts)
    _d1, k1 = tree.query(q)
    near = tree.query_ball_point(q, 2.0 * guess + 1.0)
    a = pts[k1] - q
    other = [k for k in near if float((pts[k] - q) @ a) < 0.0]
    if not other:
        return guess
    b = pts[other]
    k2 = int(np.argmin(np.linalg.norm(b - q, axis=1)))
    return float(np.linalg.norm(b[k2] - pts[k1]))


#: The start of the warning about a gap the routing grid does not resolve.
GAP_WARNING = "the routing grid"
#: The start of the note on a gap the land clearance closes.
GAP_CLOSED = "a gap "


def track_clearance(problem: Any, rg: Any, lat: FloatArray, lon: FloatArray) -> float | None:
    """The least distance (m) from the route's track (its legs sampled on the great circle)
    to the field's land nodes, or None without land near or when the start or goal lies
    within the clearance (which is relaxed there)."""
    from glideplan.routing.window import distance_to_land

    c, pts = float(rg.clearance_m), rg.coast_xyz
    if pts.shape[0] == 0:
        return None
    ends = distance_to_land(pts, np.array([problem.start[0], problem.goal[0]]),
                            np.array([problem.start[1], problem.goal[1]]), max(c, 1.0))
    if c > 0 and np.any(ends < c):
        return None
    step = max(min(c if c > 0 else rg.spacing_m, rg.spacing_m) / 4, 1.0)
    return clearance_of(np.asarray(lat, dtype=float), np.asarray(lon, dtype=float), pts, step)
