"""numba kernel of `reach.native`: chunks of the state-constrained Dijkstra (binary heap with
lazy deletion). Imported only by `reach.native.native_search` (numba start-up)."""

from __future__ import annotations

from typing import Any

import numba
import numpy as np

__all__ = ["dijkstra_chunk"]


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
                   done: Any, key: Any, node: Any, size: int, chunk: int
                   ) -> tuple[Any, Any, int, int, float]:
    """Settle up to `chunk` nodes; returns (heap keys, heap nodes, heap size, nodes settled,
    last loss settled). loss/parent/done (flat) are updated in place."""
    ny, nx = block.shape
    m = stencil.shape[0]
    settled = 0
    last = 0.0
    while size > 0 and settled < chunk:
        lu, u, size = _pop(key, node, size)
        if done[u] or lu > loss[u]:
            continue
        done[u] = True
        settled += 1
        last = lu
        i, j = u // nx, u % nx
        bm = bmin[i, j]
        for e in range(m):
            di, dj = stencil[e, 0], stencil[e, 1]
            vi, vj = i + di, j + dj
            if vi < 0 or vi >= ny or vj < 0 or vj >= nx:
                continue
            v = vi * nx + vj
            if done[v]:
                continue
            c = costs[i, e]
            lv = lu + c
            if not lv < loss[v] or lv > block[vi, vj]:
                continue
            if lv > bm and not _edge_clear(block, i, j, di, dj, lu, c):
                continue
            loss[v] = lv
            parent[v] = u
            key, node, size = _push(key, node, size, lv, v)
    return key, node, size, settled, last
