"""The glide reach on the terrain's own grid: a state-constrained Dijkstra (numba).

Why this and not the front on a pooled grid: max-pooling the terrain per front cell closes
every col narrower than a cell (a 1 km pass vanishes at a 463 m grid); any pooling that
keeps a pass open (min, or a "passable" bottleneck height) also opens walls that are closed
at the data's resolution, so the answer would depend on the grid either way. Searching the
DEM's own nodes keeps exactly what the data keeps open or closed, and a Dijkstra with a
wide stencil is O(N log N) (the narrow-band front is ~O(N^1.5): 51 s on an SRTM3 tile).

Graph: the nodes of the DEM (lat/lon grid, spacings hx(lat) = R cos(lat) dlon, hy = R dlat);
edges to the 48 neighbours (di, dj) with max(|di|, |dj|) <= 4 and gcd(|di|, |dj|) = 1 (the
directions 0, 14.0, 18.4, 26.6, 33.7, 36.9, 45 deg and their mirrors). An edge of ground
length d in direction chi costs the altitude d / r(chi) (r: the ground glide ratio in the
wind, `Glide.ratio_fast`, relative error ~1e-7; exact for a straight glide in a steady
wind). A straight line between two stencil directions costs at most 1 / cos(delta / 2)
times its true loss, delta the largest gap (14.0 deg): <= 0.76 % more altitude lost in
still air (never less), 0.97 % in an 8 m/s wind, 1.2 % at 15 m/s (the gauge is not round;
max over directions of the bracketing edges' cost per unit step), so the search is
conservative; the straight glides from the start are then made exact where they keep the
clearance (`_native_kernel.straight_from_start`); verified paths are string-pulled and
flown exactly (`reach.flight`). Edges from a node far from the constraint are relaxed only in a cone
round the direction it was entered by; the queue is Dial's buckets, exact here
(`_native_kernel.dial_chunk`).

State constraint (the safety height en route): at loss L the glider is at ALT - L, which
must stay >= z + clearance, i.e. L <= B = ALT - z - clearance along every edge. B is
checked at the edge's end node and, along the edge, at half-cell samples of the bilinear
terrain -- skipped when the edge's end loss is below the smallest B within 4 cells of its
start (a bilinear surface never goes below its lowest corner sample), which is most edges.
NaN terrain: B = -inf (never entered).

Seeds: the nodes within SEED_CELLS of the start get the straight glide's loss from the start
when that glide clears (sampled at half cells); the search runs in chunks of pops so the
caller can show progress.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.model import Glide
from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain

__all__ = [
    "SEED_CELLS",
    "STENCIL",
    "BackSearch",
    "NativeSearch",
    "back_path",
    "native_back_search",
    "native_search",
    "need_at",
    "node_path",
]

FloatArray = NDArray[np.float64]
IntArray = NDArray[np.int64]

#: Radius (cells) of the straight-glide seed disk round the start.
SEED_CELLS = 3
#: Blocked border (cells) round the grid: the stencil's reach, so no bounds checks.
PAD = 4


def _stencil() -> IntArray:
    out = []
    for di in range(-4, 5):
        for dj in range(-4, 5):
            if (di or dj) and math.gcd(abs(di), abs(dj)) == 1:
                out.append((di, dj))
    return np.array(out, dtype=np.int64)


#: The 48 neighbour offsets (row, column).
STENCIL = _stencil()


@dataclass(frozen=True, eq=False)
class NativeSearch:
    """loss (ny, nx): least altitude lost to each node (inf: not reached); parent: flat index
    of the previous node (-1: a seed; -2: not reached); block B = ALT - z - clearance;
    pops: nodes settled; pushes: heap pushes; coned: nodes relaxed only in a cone."""

    loss: FloatArray
    parent: IntArray
    block: FloatArray
    pops: int
    pushes: int = 0
    coned: int = 0


def _costs(glide: Glide, lat: FloatArray, dlat: float, dlon: float, reverse: bool = False
           ) -> FloatArray:
    """Loss per edge (ny, 48): d / r(chi) at the mid latitude of each edge (inf: no
    progress); reverse: flown the other way (end to start: the backward search)."""
    hy = EARTH_RADIUS_M * math.radians(dlat)
    di, dj = STENCIL[:, 0].astype(float), STENCIL[:, 1].astype(float)
    mid = np.radians(lat[:, None] + 0.5 * di[None, :] * dlat)
    hx = EARTH_RADIUS_M * np.cos(mid) * math.radians(dlon)
    east, north = dj[None, :] * hx, di[None, :] * hy
    d = np.hypot(east, north)
    chi = np.arctan2(-north, -east) if reverse else np.arctan2(north, east)
    r = np.asarray(glide.ratio_fast(chi.ravel()), dtype=float).reshape(chi.shape)
    ok = np.isfinite(r) & (r > 0)
    return np.where(ok, d / np.where(ok, r, 1.0), np.inf)


def native_search(terrain: Terrain, start: tuple[float, float, float], glide: Glide,
                  clearance: float, *, chunk: int = 400_000,
                  on_chunk: Callable[[float], None] | None = None) -> NativeSearch:
    """The state-constrained Dijkstra from `start` = (lat, lon, ALT) (module docstring).

    on_chunk(fraction): called between chunks of `chunk` pops with the fraction of the
    largest possible loss reached so far, squared (an area: the progress estimate).
    """
    from scipy.ndimage import minimum_filter

    from glideplan.reach._native_kernel import dial_chunk

    alt = start[2]
    z = np.asarray(terrain.z, dtype=float)
    ny, nx = z.shape
    block = np.full((ny + 2 * PAD, nx + 2 * PAD), -np.inf)
    inner = alt - z - clearance
    block[PAD:-PAD, PAD:-PAD] = np.where(np.isfinite(inner), inner, -np.inf)
    bmin = minimum_filter(block, size=2 * PAD + 1, mode="nearest")
    lat_p = terrain.lat[0] + terrain.dlat * np.arange(-PAD, ny + PAD)
    costs = _costs(glide, lat_p, terrain.dlat, terrain.dlon)
    nxp = nx + 2 * PAD
    loss = np.full(block.size, np.inf)
    parent = np.full(block.size, -2, dtype=np.int64)
    seeds, seed_loss = _seeds(terrain, start, glide, clearance)
    seeds = (seeds // nx + PAD) * nxp + seeds % nx + PAD
    for k, v in zip(seeds, seed_loss, strict=True):
        if v <= block.flat[k] and v < loss[k]:
            loss[k], parent[k] = v, -1
    done = np.zeros(block.size, dtype=np.bool_)
    counts = np.zeros(3, dtype=np.int64)
    aspect = math.cos(math.radians(float(np.mean(terrain.lat)))) * terrain.dlon / terrain.dlat
    top = float(np.max(block))
    finite = costs[np.isfinite(costs)]
    delta = float(np.min(finite)) * (1 - 1e-9) if finite.size else 1.0
    nb = max(int(top / delta) + 2, 1) if top > 0 else 1
    head = np.full(nb, -1, dtype=np.int64)
    ent_node = np.empty(1 << 16, dtype=np.int64)
    ent_next = np.empty(1 << 16, dtype=np.int64)
    n_ent, free = 0, -1
    for k in np.flatnonzero(parent == -1):
        if n_ent >= ent_node.size:
            ent_node = np.concatenate([ent_node, np.empty_like(ent_node)])
            ent_next = np.concatenate([ent_next, np.empty_like(ent_next)])
        b = int(loss[k] / delta)
        ent_node[n_ent], ent_next[n_ent], head[b] = k, head[b], n_ent
        n_ent += 1
    cur = pops = 0
    while cur < nb:
        ent_node, ent_next, free, n_ent, cur, n, last = dial_chunk(
            block, bmin, costs, STENCIL, loss, parent, done, head, ent_node, ent_next, free,
            n_ent, cur, delta, chunk, aspect, counts)
        pops += n
        if on_chunk is not None and top > 0:
            on_chunk(min(max(last / top, 0.0), 1.0) ** 2)
    inner_loss = loss.reshape(block.shape)[PAD:-PAD, PAD:-PAD].copy()
    par = parent.reshape(block.shape)[PAD:-PAD, PAD:-PAD].ravel()
    ok = par >= 0
    par = np.where(ok, (par // nxp - PAD) * nx + par % nxp - PAD, par)
    inner_block = block[PAD:-PAD, PAD:-PAD].copy()
    _straight(terrain, start, glide, inner_block, inner_loss, par)
    return NativeSearch(inner_loss, par, inner_block, pops, int(counts[1]), int(counts[2]))


def _straight(terrain: Terrain, start: tuple[float, float, float], glide: Glide,
              block: FloatArray, loss: FloatArray, parent: IntArray) -> None:
    """Where the straight glide from the start keeps the clearance, its loss (exact, not the
    stencil's up to 0.76 % more): `_native_kernel.straight_from_start`, in place."""
    from glideplan.reach._native_kernel import straight_from_start

    fi0 = (start[0] - terrain.lat[0]) / terrain.dlat
    fj0 = (start[1] - terrain.lon[0]) / terrain.dlon
    reached = np.isfinite(loss)
    rows = np.flatnonzero(reached.any(axis=1))
    cols = np.flatnonzero(reached.any(axis=0))
    if rows.size == 0:
        return
    aspect = math.cos(math.radians(float(start[0]))) * terrain.dlon / terrain.dlat
    radius = max(math.hypot(a - fi0, (b - fj0) * aspect) for a in (rows[0], rows[-1])
                 for b in (cols[0], cols[-1])) + 2  # the reached nodes' bounding box
    chi = np.radians(np.arange(3601) / 10.0)
    rtab = np.asarray(glide.ratio_fast(chi), dtype=float)
    rtab = np.where(np.isfinite(rtab) & (rtab > 0), rtab, 0.0)
    straight_from_start(block, loss, parent, fi0, fj0, float(start[0]), terrain.dlat,
                        terrain.dlon, radius, rtab)


def _seeds(terrain: Terrain, start: tuple[float, float, float], glide: Glide,
           clearance: float) -> tuple[IntArray, FloatArray]:
    """Flat indices and straight-glide losses of the nodes within SEED_CELLS of the start
    whose straight glide from the start keeps the clearance (half-cell samples)."""
    from glideplan.reach.flight import rhumb

    lat0, lon0, alt = start
    ny, nx = terrain.shape
    fi = (lat0 - terrain.lat[0]) / terrain.dlat
    fj = (lon0 - terrain.lon[0]) / terrain.dlon
    i0, j0 = round(fi), round(fj)
    ii, jj = np.meshgrid(np.arange(i0 - SEED_CELLS, i0 + SEED_CELLS + 1),
                         np.arange(j0 - SEED_CELLS, j0 + SEED_CELLS + 1), indexing="ij")
    ok = (ii >= 0) & (ii < ny) & (jj >= 0) & (jj < nx)
    ii, jj = ii[ok], jj[ok]
    la, lo = terrain.lat[ii], terrain.lon[jj]
    d, chi = rhumb(np.full(la.shape, lat0), np.full(lo.shape, lon0), la, lo)
    r = np.asarray(glide.ratio(chi), dtype=float)
    with np.errstate(invalid="ignore", divide="ignore"):
        lossv = np.where(d > 0, d / r, 0.0)
    f = np.linspace(0.0, 1.0, 4 * SEED_CELLS + 3)[None, :]
    sla = lat0 + f * (la[:, None] - lat0)
    slo = lon0 + f * (lo[:, None] - lon0)
    h = alt - f * lossv[:, None]
    zz = terrain.elevation(sla, slo)
    clear = np.all(np.where(np.isfinite(zz), h - zz >= clearance - 1e-6, False), axis=1)
    keep = clear & np.isfinite(lossv)
    return (ii[keep] * nx + jj[keep]).astype(np.int64), lossv[keep]


def _parent_chain(parent: NDArray[np.int64], k: int) -> NDArray[np.int64]:
    """Flat node indices from node k along `parent` (-1 ends the chain), k first."""
    out = []
    while k >= 0:
        out.append(k)
        k = int(parent[k])
    return np.array(out, dtype=np.int64)


def node_path(search: NativeSearch, terrain: Terrain, i: int, j: int
              ) -> tuple[FloatArray, FloatArray]:
    """The nodes from the seed to node (i, j) along the parents (lat, lon, start first)."""
    nx = terrain.shape[1]
    idx = _parent_chain(search.parent, i * nx + j)[::-1]
    return terrain.lat[idx // nx], terrain.lon[idx % nx]


@dataclass(frozen=True, eq=False)
class BackSearch:
    """need (ny, nx): the least altitude (m MSL) at each node from which the target is
    reached keeping the clearance en route and arriving at `target altitude` (inf: not
    from below `ceiling`); parent: flat index of the next node towards the target (-1: the
    target's own nodes)."""

    need: FloatArray
    parent: IntArray


def native_back_search(terrain: Terrain, target: tuple[float, float, float], glide: Glide,
                       clearance: float, ceiling: float, *, chunk: int = 400_000
                       ) -> BackSearch:
    """The backward search from `target` = (lat, lon, least arrival altitude): over the
    terrain's own nodes and the 48-stencil of `native_search`, the least altitude needed
    at every node below `ceiling` (`_native_kernel.dial_back_chunk`). Seeds: the nodes
    within SEED_CELLS of the target, by the straight glide to it (altitude at the node =
    arrival + d / r, and the floor along it)."""
    from scipy.ndimage import maximum_filter

    from glideplan.reach._native_kernel import dial_back_chunk
    from glideplan.reach.flight import rhumb

    la_t, lo_t, arrive = target
    z = np.asarray(terrain.z, dtype=float)
    ny, nx = z.shape
    floor = np.full((ny + 2 * PAD, nx + 2 * PAD), np.inf)
    inner = z + clearance
    floor[PAD:-PAD, PAD:-PAD] = np.where(np.isfinite(inner), inner, np.inf)
    fmax = maximum_filter(floor, size=2 * PAD + 1, mode="nearest")
    lat_p = terrain.lat[0] + terrain.dlat * np.arange(-PAD, ny + PAD)
    costs = _costs(glide, lat_p, terrain.dlat, terrain.dlon, reverse=True)
    nxp = nx + 2 * PAD
    need = np.full(floor.size, np.inf)
    parent = np.full(floor.size, -2, dtype=np.int64)
    fi = (la_t - terrain.lat[0]) / terrain.dlat
    fj = (lo_t - terrain.lon[0]) / terrain.dlon
    i0, j0 = round(fi), round(fj)
    for i in range(max(i0 - SEED_CELLS, 0), min(i0 + SEED_CELLS, ny - 1) + 1):
        for j in range(max(j0 - SEED_CELLS, 0), min(j0 + SEED_CELLS, nx - 1) + 1):
            d, chi = rhumb(np.array(terrain.lat[i]), np.array(terrain.lon[j]),
                           np.array(la_t), np.array(lo_t))
            r = float(glide.ratio_fast(float(chi)))
            c = float(d) / r if float(d) > 0 else 0.0
            f = np.linspace(0.0, 1.0, 4 * SEED_CELLS + 3)
            zz = terrain.elevation(terrain.lat[i] + f * (la_t - terrain.lat[i]),
                                   terrain.lon[j] + f * (lo_t - terrain.lon[j]))
            if not (np.all(np.isfinite(zz)) and math.isfinite(c)):
                continue
            k = (i + PAD) * nxp + j + PAD
            need[k] = max(arrive + c, float(np.max(zz + clearance + f * c)))
            parent[k] = -1
    finite = costs[np.isfinite(costs)]
    delta = float(np.min(finite)) * (1 - 1e-9) if finite.size else 1.0
    base = float(np.min(need))
    if not math.isfinite(base):
        return BackSearch(np.full((ny, nx), np.inf), np.full(ny * nx, -2, dtype=np.int64))
    nb = max(int((ceiling - base) / delta) + 2, 1)
    head = np.full(nb, -1, dtype=np.int64)
    seeds = np.flatnonzero(parent == -1)
    ent_node = np.empty(max(1 << 16, 2 * seeds.size), dtype=np.int64)
    ent_next = np.empty_like(ent_node)
    n_ent, free = 0, -1
    for k in seeds:
        b = int((need[k] - base) / delta)
        if b < nb:
            ent_node[n_ent], ent_next[n_ent], head[b] = k, head[b], n_ent
            n_ent += 1
    done = np.zeros(floor.size, dtype=np.bool_)
    aspect = math.cos(math.radians(float(np.mean(terrain.lat)))) * terrain.dlon / terrain.dlat
    cur = 0
    while cur < nb:
        ent_node, ent_next, free, n_ent, cur, _ = dial_back_chunk(
            floor, fmax, costs, STENCIL, need, parent, done, head, ent_node, ent_next, free,
            n_ent, cur, delta, base, chunk, aspect)
    inner_need = need.reshape(floor.shape)[PAD:-PAD, PAD:-PAD].copy()
    par = parent.reshape(floor.shape)[PAD:-PAD, PAD:-PAD].ravel()
    par = np.where(par >= 0, (par // nxp - PAD) * nx + par % nxp - PAD, par)
    return BackSearch(inner_need, par)


def need_at(back: BackSearch, terrain: Terrain, glide: Glide, lat: float, lon: float
            ) -> tuple[float, int, int]:
    """(altitude needed at (lat, lon), row, column of the node to glide to first): the least
    over the nodes within 2 cells of need + the straight glide's loss to the node (the
    straight leg's terrain is left to the flight that verifies it); (inf, -1, -1): none."""
    from glideplan.reach.flight import rhumb

    fi = (lat - terrain.lat[0]) / terrain.dlat
    fj = (lon - terrain.lon[0]) / terrain.dlon
    ny, nx = terrain.shape
    i0, j0 = round(fi), round(fj)
    best = (math.inf, -1, -1)
    for i in range(max(i0 - 2, 0), min(i0 + 2, ny - 1) + 1):
        for j in range(max(j0 - 2, 0), min(j0 + 2, nx - 1) + 1):
            v = float(back.need[i, j])
            if not math.isfinite(v):
                continue
            d, chi = rhumb(np.array(lat), np.array(lon), np.array(terrain.lat[i]),
                           np.array(terrain.lon[j]))
            r = float(glide.ratio_fast(float(chi)))
            tot = v + (float(d) / r if float(d) > 0 else 0.0)
            if tot < best[0]:
                best = (tot, i, j)
    return best


def back_path(back: BackSearch, terrain: Terrain, i: int, j: int
              ) -> tuple[FloatArray, FloatArray]:
    """The nodes from (i, j) along the parents to the target's nodes (lat, lon)."""
    nx = terrain.shape[1]
    idx = _parent_chain(back.parent, i * nx + j)
    return terrain.lat[idx // nx], terrain.lon[idx % nx]
