"""numba kernel of `reach.native`: chunks of the state-constrained Dijkstra (Dial's bucket
queue). Imported only by `reach.native.native_search` (numba start-up).

The grid is padded: `block` (ny, nx) has PAD = 4 rows/columns of -inf on every side (never
entered), so neighbours need no bounds check; flat indices are into the padded grid.

Cone pruning: from a node u whose every stencil edge is free (lu + the row's largest edge
loss <= the smallest B within 4 cells: no neighbour blocked, no edge to check), only the
edges within CONE of the direction it was entered by (parent -> u) are relaxed. An optimal
path turns only where it touches the state constraint; in free space it is straight and its
discrete edges stay within a stencil gap (14 deg) of its direction, so the edge that gives a
node its least loss is not pruned (on the SRTM3 benchmark tile the losses are identical to
the unpruned search's).

The two kernels (`dial_chunk`, `dial_back_chunk`) are ~80 lines each on purpose: each is one
loop nest compiled by numba as a whole (the bucket queue, the stencil and the edge check
share registers in the inner loop); split into calls, the same speed would rest on LLVM
inlining them back (not measured here).
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np

from glideplan.geodesy import EARTH_RADIUS_M  # a global: numba compiles it as a constant

__all__ = ["CONE", "dial_chunk"]

#: cos of the half-angle of the cone of edges relaxed from a free node (60 deg).
CONE = 0.5


@numba.njit(cache=True)
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
def dial_chunk(block: Any, bmin: Any, costs: Any, stencil: Any, loss: Any, parent: Any,
               done: Any, head: Any, ent_node: Any, ent_next: Any, free: int, n_ent: int,
               cur: int, delta: float, chunk: int, aspect: float, counts: Any
               ) -> tuple[Any, Any, int, int, int, int, float]:
    """Settle up to `chunk` nodes (module docstring); loss/parent/done (flat) and head are
    updated in place; counts (3,) += nodes settled, queue pushes, nodes relaxed in a cone.
    aspect = hx / hy (east over north spacing) for the directions.

    Dial's bucket queue: bucket b holds the nodes of loss in
    [b delta, (b + 1) delta); with delta <= the least edge loss no node of a bucket can
    improve another of the same bucket, so each bucket's nodes are final when it is taken
    (exact Dijkstra, O(1) queue operations). Buckets are linked lists (head[b], ent_next)
    of entries (ent_node), freed entries chained from `free`. Returns (ent_node, ent_next,
    free, n_ent, cur bucket, nodes settled, last loss settled)."""
    ny, nx = block.shape
    m = stencil.shape[0]
    nb = head.size
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
    settled = pushes = coned = 0
    last = 0.0
    while cur < nb and settled < chunk:
        en = head[cur]
        if en < 0:
            cur += 1
            continue
        head[cur] = ent_next[en]
        u = ent_node[en]
        ent_next[en] = free
        free = en
        if done[u]:
            continue
        done[u] = True
        lu = loss[u]
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
            coned += 1
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
            b = int(lv / delta)
            if b >= nb:
                continue  # beyond every block time: never entered
            if free >= 0:
                en = free
                free = ent_next[en]
            else:
                if n_ent >= ent_node.size:
                    nn = np.empty(2 * ent_node.size, dtype=np.int64)
                    nn[:n_ent] = ent_node[:n_ent]
                    nx2 = np.empty(2 * ent_node.size, dtype=np.int64)
                    nx2[:n_ent] = ent_next[:n_ent]
                    ent_node, ent_next = nn, nx2
                en = n_ent
                n_ent += 1
            ent_node[en] = v
            ent_next[en] = head[b]
            head[b] = en
            pushes += 1
    counts[0] += settled
    counts[1] += pushes
    counts[2] += coned
    return ent_node, ent_next, free, n_ent, cur, settled, last


@numba.njit(cache=True)
def _bilinear_up(f: Any, fi: float, fj: float) -> float:
    """Bilinear floor at fractional (row, column); +inf when a corner with weight is +inf."""
    ny, nx = f.shape
    i = min(int(fi), ny - 2)
    j = min(int(fj), nx - 2)
    wy, wx = fi - i, fj - j
    acc = 0.0
    for di, w1 in ((0, 1.0 - wy), (1, wy)):
        for dj, w2 in ((0, 1.0 - wx), (1, wx)):
            w = w1 * w2
            if w > 0.0:
                v = f[i + di, j + dj]
                if v == np.inf:
                    return np.inf
                acc += w * v
    return acc


@numba.njit(cache=True)
def _edge_floor(floor: Any, i: int, j: int, di: int, dj: int, c: float) -> float:
    """Least altitude at node (i, j) for the straight flight to (i + di, j + dj) (loss c)
    to keep the floor at its half-cell samples: max_s floor(s) + s c (its ends excluded)."""
    n = 2 * max(abs(di), abs(dj))
    worst = -np.inf
    for k in range(1, n):
        s = k / n
        f = _bilinear_up(floor, i + s * di, j + s * dj) + s * c
        worst = max(worst, f)
    return worst


@numba.njit(cache=True)
def dial_back_chunk(floor: Any, fmax: Any, costs: Any, stencil: Any, need: Any, parent: Any,
                    done: Any, head: Any, ent_node: Any, ent_next: Any, free: int, n_ent: int,
                    cur: int, delta: float, base: float, chunk: int, aspect: float
                    ) -> tuple[Any, Any, int, int, int, int]:
    """The backward search (`reach.native.native_back_search`): need[v] = the least altitude
    at v from which the target is reached keeping the floor (terrain + clearance) along
    every edge: need_v = max(need_u + c(v -> u), floor_v, max_s floor(s) + s c) relaxed from
    u to v = u + offset; costs[i, e] is the loss of flying from v back to u. Non-decreasing
    and >= need_u + c, so Dial's buckets (key need - base, width delta <= least c) stay
    exact. Cone pruning as `dial_chunk` where the floor cannot bind within 4 cells
    (need_u >= fmax, the largest floor there: every edge from u is then free). Returns
    (ent_node, ent_next, free, n_ent, cur, settled)."""
    nx = floor.shape[1]
    m = stencil.shape[0]
    nb = head.size
    flat = np.empty(m, dtype=np.int64)
    ux = np.empty(m)
    uy = np.empty(m)
    for e in range(m):
        flat[e] = stencil[e, 0] * nx + stencil[e, 1]
        ex, ey = stencil[e, 1] * aspect, float(stencil[e, 0])
        n = math.hypot(ex, ey)
        ux[e], uy[e] = ex / n, ey / n
    fflat = floor.ravel()
    settled = 0
    while cur < nb and settled < chunk:
        en = head[cur]
        if en < 0:
            cur += 1
            continue
        head[cur] = ent_next[en]
        u = ent_node[en]
        ent_next[en] = free
        free = en
        if done[u]:
            continue
        done[u] = True
        nu = need[u]
        settled += 1
        i = u // nx
        j = u - i * nx
        crow = costs[i]
        cone = False
        px = py = 0.0
        pu = parent[u]
        free_u = nu >= fmax[i, j]
        if pu >= 0 and free_u:
            pi = pu // nx
            px, py = (j - (pu - pi * nx)) * aspect, float(i - pi)
            n = math.hypot(px, py)
            px, py, cone = px / n, py / n, True
        for e in range(m):
            if cone and ux[e] * px + uy[e] * py < CONE:
                continue
            v = u + flat[e]
            if fflat[v] == np.inf:
                continue
            nv = max(nu + crow[e], fflat[v])
            if not free_u:
                # the flight v -> u starts at v: samples measured from v
                nv = max(nv, _edge_floor(floor, i + stencil[e, 0], j + stencil[e, 1],
                                         -stencil[e, 0], -stencil[e, 1], crow[e]))
            if nv >= need[v]:
                continue
            need[v] = nv
            parent[v] = u
            b = int((nv - base) / delta)
            if b >= nb:
                continue
            if free >= 0:
                en = free
                free = ent_next[en]
            else:
                if n_ent >= ent_node.size:
                    nn = np.empty(2 * ent_node.size, dtype=np.int64)
                    nn[:n_ent] = ent_node[:n_ent]
                    nx2 = np.empty(2 * ent_node.size, dtype=np.int64)
                    nx2[:n_ent] = ent_next[:n_ent]
                    ent_node, ent_next = nn, nx2
                en = n_ent
                n_ent += 1
            ent_node[en] = v
            ent_next[en] = head[b]
            head[b] = en
    return ent_node, ent_next, free, n_ent, cur, settled


@numba.njit(cache=True)
def _ratio(rtab: Any, th: float) -> float:
    """The ratio table (0.1 deg steps from 0 to 360 deg inclusive) at th (rad, 0..2 pi),
    linear between entries; 0 where a neighbour entry is 0 (no progress)."""
    a = math.degrees(th) * 10.0
    k = min(max(int(a), 0), 3599)
    w = a - k
    r0, r1 = rtab[k], rtab[k + 1]
    if r0 <= 0.0 or r1 <= 0.0:
        return 0.0
    return (1.0 - w) * r0 + w * r1


@numba.njit(cache=True)
def straight_from_start(block: Any, loss: Any, parent: Any, fi0: float, fj0: float,
                        lat0: float, dlat: float, dlon: float, radius: float,
                        rtab: Any) -> int:
    """Lower `loss` (inner grid, not padded; flat parent -1) to the straight glide's from the
    start where that glide keeps the clearance: rays from the start (fi0, fj0) a cell apart
    at the largest radius `radius` (cells; a node lies within a cell of both rays
    bracketing it), each marched in half-cell steps to where the
    glide first meets B (bilinear); a node at distance d between two rays is in sight when
    d <= both rays' clear length. Metric: east = R cos(mid lat) dlon, north = R dlat (mid
    lat between the start and the point: the rhumb line to 1e-6). rtab: the ground glide
    ratio at 0.1 deg steps of chi (3601 values, CCW from east). Returns nodes lowered."""
    ny, nx = block.shape
    rr = EARTH_RADIUS_M
    hy = rr * math.radians(dlat)
    hxr = np.empty(ny)  # east spacing at the mid latitude between the start and each row
    for i in range(ny):
        hxr[i] = rr * math.cos(math.radians(lat0 + 0.5 * (i - fi0) * dlat)) * math.radians(dlon)
    nray = max(8, int(2.0 * math.pi * radius) + 1)
    clear = np.zeros(nray)
    for k in range(nray):
        th = 2.0 * math.pi * k / nray
        r = _ratio(rtab, th)
        if not r > 0.0:
            continue
        s_, c_ = math.sin(th), math.cos(th) * hy
        t = 0.0
        while True:
            t += 0.5
            fi = fi0 + t * s_
            if fi < 0.0 or fi > ny - 1:
                break
            fj = fj0 + t * c_ / hxr[min(int(fi + 0.5), ny - 1)]
            if fj < 0.0 or fj > nx - 1:
                break
            if t * hy / r > _bilinear(block, fi, fj):
                break
            clear[k] = t
    cmax = np.max(clear)
    i_lo = max(int(fi0 - cmax) - 1, 0)
    i_hi = min(int(fi0 + cmax) + 2, ny)
    lowered = 0
    for i in range(i_lo, i_hi):
        hx = hxr[i]
        y = (i - fi0) * hy
        w = cmax * hy / hx + 2.0
        for j in range(max(int(fj0 - w), 0), min(int(fj0 + w) + 1, nx)):
            x = (j - fj0) * hx
            d = math.hypot(x, y)
            th = math.atan2(y, x)
            if th < 0.0:
                th += 2.0 * math.pi
            a = th / (2.0 * math.pi) * nray
            k0 = int(a) % nray
            k1 = (k0 + 1) % nray
            if d / hy > min(clear[k0], clear[k1]):
                continue
            r = _ratio(rtab, th)
            if not r > 0.0:
                continue
            v = d / r
            u = i * nx + j
            if v < loss[i, j] and v <= block[i, j]:
                loss[i, j] = v
                parent[u] = -1
                lowered += 1
    return lowered
