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
times its true loss, delta the largest gap (14.0 deg): <= 0.76 % more altitude lost (never
less), so the search is conservative; verified paths are string-pulled and flown exactly
(`reach.flight`). Edges from a node far from the constraint are relaxed only in a cone
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

__all__ = ["SEED_CELLS", "STENCIL", "NativeSearch", "native_search", "node_path"]

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


def _costs(glide: Glide, lat: FloatArray, dlat: float, dlon: float) -> FloatArray:
    """Loss per edge (ny, 48): d / r(chi) at the mid latitude of each edge (inf: no
    progress)."""
    hy = EARTH_RADIUS_M * math.radians(dlat)
    di, dj = STENCIL[:, 0].astype(float), STENCIL[:, 1].astype(float)
    mid = np.radians(lat[:, None] + 0.5 * di[None, :] * dlat)
    hx = EARTH_RADIUS_M * np.cos(mid) * math.radians(dlon)
    east, north = dj[None, :] * hx, di[None, :] * hy
    d = np.hypot(east, north)
    chi = np.arctan2(north, east)
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
    return NativeSearch(inner_loss, par, block[PAD:-PAD, PAD:-PAD].copy(), pops,
                        int(counts[1]), int(counts[2]))


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


def node_path(search: NativeSearch, terrain: Terrain, i: int, j: int
              ) -> tuple[FloatArray, FloatArray]:
    """The nodes from the seed to node (i, j) along the parents (lat, lon, start first)."""
    nx = terrain.shape[1]
    k = i * nx + j
    out = []
    while k >= 0:
        out.append(k)
        k = int(search.parent[k])
    out.reverse()
    idx = np.array(out, dtype=np.int64)
    return terrain.lat[idx // nx], terrain.lon[idx % nx]
