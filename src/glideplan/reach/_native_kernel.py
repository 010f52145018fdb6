"""numba kernel of `reach.native`: chunks of the state-constrained Dijkstra (binary heap with
lazy deletion). Imported only by `reach.native.native_search` (numba start-up)."""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

__all__ = ["CONE", "dijkstra_chunk"]

#: cos of the half-angle of the cone of edges relaxed from a free node (60 deg).
CONE = 0.5


@numba.njit(cache=True, inline="always")
def _bilinear(b: Any, fi: float, fj: float) -> float:
    """Bilinear B at fractional (row, column); -inf when a corner with weight is -inf."""
    ny, nx = b.shape
    i = min(int(fi), ny - 2)
    j = min(int(fj), nx - 2)
    wy, wx = fi - i, fj - j
    acc = 0.0
    for di, w1 in ((0, 1.0 - wy), (1, wy)):
        for dj, w2 in ((0, 1.0 - wx), (1, wx)):
            w = w1 * w2
            if w > 0.0:
                v = b[i + di, j + dj]
                if v == -np.inf:
                    return -np.inf
                acc += w * v
    return acc


@numba.njit(cache=True)
def _edge_clear(b: Any, i: int, j: int, di: int, dj: int, lu: float, c: float) -> bool:
    """B >= the loss at half-cell samples along the edge (its ends excluded)."""
    n = 2 * max(abs(di), abs(dj))
    for k in range(1, n):
        s = k / n
        if lu + s * c > _bilinear(b, i + s * di, j + s * dj):
            return False
    return True


@numba.njit(cache=True)
def _push(key: Any, node: Any, size: int, k: float, v: int) -> tuple[Any, Any, int]:
    if size >= key.size:
        nk = np.empty(2 * key.size)
        nn = np.empty(2 * key.size, dtype=np.int64)
        nk[:size] = key[:size]
        nn[:size] = node[:size]
        key, node = nk, nn
    i = size
    while i > 0:
        p = (i - 1) >> 1
        if key[p] <= k:
            break
        key[i] = key[p]
        node[i] = node[p]
        i = p
    key[i] = k
    node[i] = v
    return key, node, size + 1


@numba.njit(cache=True)
def _pop(key: Any, node: Any, size: int) -> tuple[float, int, int]:
    k0, v0 = key[0], node[0]
    size -= 1
    if size > 0:
        k, v = key[size], node[size]
        i = 0
        while True:
            c = 2 * i + 1
            if c >= size:
                break
            if c + 1 < size and key[c + 1] < key[c]:
                c += 1
            if key[c] >= k:
                break
            key[i] = key[c]
            node[i] = node[c]
            i = c
        key[i] = k
        node[i] = v
    return k0, v0, size


@numba.njit(cache=True)
def dijkstra_chunk(block: Any, bmin: Any, costs: Any, stencil: Any, loss: Any, parent: Any,
                   done: Any, key: Any, node: Any, size: int, chunk: int, aspect: float,
                   counts: Any) -> tuple[Any, Any, int, int, float]:
    """Settle up to `chunk` nodes; returns (heap keys, heap nodes, heap size, nodes settled,
    last loss settled). loss/parent/done (flat) are updated in place; counts (3,) += nodes
    settled, heap pushes, nodes relaxed in a cone.

    The grid is padded: `block` (ny, nx) has PAD = 4 rows/columns of -inf on every side
    (never entered), so neighbours need no bounds check; flat indices are into the padded
    grid.

    Cone pruning: from a node u whose every stencil edge is free (lu + the row's largest
    edge loss <= the smallest B within 4 cells: no neighbour blocked, no edge to check),
    only the edges within CONE of the direction it was entered by (parent -> u) are
    relaxed. An optimal path turns only where it touches the state constraint; in free
    space it is straight and its discrete edges stay within a stencil gap (14 deg) of its
    direction, so the edge that gives a node its least loss is never pruned.
    aspect = hx / hy (east over north spacing) for the directions."""
    ny, nx = block.shape
    m = stencil.shape[0]
    flat = np.empty(m, dtype=np.int64)
    ux = np.empty(m)
    uy = np.empty(m)
    for e in range(m):
        flat[e] = stencil[e, 0] * nx + stencil[e, 1]
        ex, ey = stencil[e, 1] * aspect, float(stencil[e, 0])
        n = math.hypot(ex, ey)
        ux[e], uy[e] = ex / n, ey / n
    bflat = block.ravel()
    cmax = np.empty(ny)
    for r in range(ny):
        cmax[r] = np.max(costs[r])
    settled = 0
    pushes = 0
    coned = 0
    last = 0.0
    while size > 0 and settled < chunk:
        lu, u, size = _pop(key, node, size)
        if done[u] or lu > loss[u]:
            continue
        done[u] = True
        settled += 1
        last = lu
        i = u // nx
        j = u - i * nx
        bm = bmin[i, j]
        crow = costs[i]
        cone = False
        px = py = 0.0
        pu = parent[u]
        if pu >= 0 and lu + cmax[i] <= bm:
            pi = pu // nx
            px, py = (j - (pu - pi * nx)) * aspect, float(i - pi)
            n = math.hypot(px, py)
            px, py, cone = px / n, py / n, True
        for e in range(m):
            if cone and ux[e] * px + uy[e] * py < CONE:
                continue
            v = u + flat[e]
            lv = lu + crow[e]
            if lv >= loss[v] or lv > bflat[v]:
                continue
            if lv > bm and not _edge_clear(block, i, j, stencil[e, 0], stencil[e, 1], lu,
                                           crow[e]):
                continue
            loss[v] = lv
            parent[v] = u
            key, node, size = _push(key, node, size, lv, v)
            pushes += 1
        if cone:
            coned += 1
    counts[0] += settled
    counts[1] += pushes
    counts[2] += coned
    return key, node, size, settled, last
