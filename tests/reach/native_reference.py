"""An independent reference for the glide reach: a state-constrained Dijkstra on the DEM's own
grid, written plainly (heapq, Python loops) apart from `glideplan.reach.native`.

Nodes: the terrain's samples. Edges: the 32 neighbours (di, dj), max(|di|, |dj|) <= 3,
gcd = 1; an edge of ground length d in direction chi costs d / r(chi) metres of altitude
(r: `Glide.ratio`, the model's ground glide ratio in the wind). A node is entered only when
the loss there is <= ALT - z - clearance, and every edge's midpoint and quarter points
(bilinear terrain) must keep it too. Its own accuracy: a straight line between two stencil
directions costs up to 1 / cos(9.2 deg) - 1 = 1.3 % more than its true loss in still air
(the largest gap, 0 to 18.4 deg), never less; in wind the gauge is not round and the bound
is `reference_error(glide)` (the largest ratio, over directions, of the cost of the two
bracketing stencil edges that add up to a unit step, to the true cost): tolerances in the
tests come from this.
"""

from __future__ import annotations

import heapq
import math

import numpy as np

from glideplan.terrain.grid import EARTH_RADIUS_M

#: the reference's largest relative overestimate of the altitude lost in still air
REFERENCE_ERROR = 1 / math.cos(math.radians(18.435 / 2)) - 1


def reference_error(glide):
    """The largest relative overestimate of a straight line's loss by the 32-stencil in this
    glide's wind (square cells): max over directions theta of (a c(u1) + b c(u2)) / c(theta)
    - 1 where a u1 + b u2 = the unit vector of theta (u1, u2 the bracketing stencil
    directions, a, b >= 0) and c = |v| / r(direction of v)."""
    offs = sorted({math.atan2(a, b) % (2 * math.pi) for a in range(-3, 4)
                   for b in range(-3, 4) if (a or b) and math.gcd(abs(a), abs(b)) == 1})
    dirs = np.array([*offs, offs[0] + 2 * math.pi])
    th = np.linspace(0.0, 2 * math.pi, 7200, endpoint=False)
    k = np.searchsorted(dirs, th, side="right") - 1
    t1, t2 = dirs[k], dirs[k + 1]
    # theta's unit vector = a u(t1) + b u(t2) (unit u): Cramer's rule
    det = np.sin(t2 - t1)
    a = np.sin(t2 - th) / det
    b = np.sin(th - t1) / det
    cost = a / glide.ratio(t1) + b / glide.ratio(t2)
    return float(np.max(cost * glide.ratio(th)) - 1.0)


def reference_loss(terrain, start, glide, clearance):
    """Least altitude lost (ny, nx) to every node from `start` = (lat, lon, ALT); inf: not
    reached. Seeds: the 4 nodes of the start's cell by their straight glide."""
    lat0, lon0, alt = start
    z = np.asarray(terrain.z, dtype=float)
    ny, nx = z.shape
    allowed = alt - z - clearance
    hy = EARTH_RADIUS_M * math.radians(terrain.dlat)
    offs = [(a, b) for a in range(-3, 4) for b in range(-3, 4)
            if (a or b) and math.gcd(abs(a), abs(b)) == 1]
    cost = np.empty((ny, len(offs)))
    for k, (a, b) in enumerate(offs):
        hx = EARTH_RADIUS_M * np.cos(np.radians(terrain.lat + 0.5 * a * terrain.dlat)) \
            * math.radians(terrain.dlon)
        chi = np.arctan2(a * hy, b * hx)
        cost[:, k] = np.hypot(a * hy, b * hx) / glide.ratio(chi)

    def zb(fi, fj):
        i, j = min(int(fi), ny - 2), min(int(fj), nx - 2)
        wy, wx = fi - i, fj - j
        return ((1 - wy) * ((1 - wx) * z[i, j] + wx * z[i, j + 1])
                + wy * ((1 - wx) * z[i + 1, j] + wx * z[i + 1, j + 1]))

    loss = np.full((ny, nx), np.inf)
    heap = []
    fi0 = (lat0 - terrain.lat[0]) / terrain.dlat
    fj0 = (lon0 - terrain.lon[0]) / terrain.dlon
    for i in (int(fi0), int(fi0) + 1):
        for j in (int(fj0), int(fj0) + 1):
            hx = EARTH_RADIUS_M * math.cos(math.radians(lat0)) * math.radians(terrain.dlon)
            dy, dx = (i - fi0) * hy, (j - fj0) * hx
            v = math.hypot(dx, dy) / float(glide.ratio(math.atan2(dy, dx))[0])
            if v <= allowed[i, j]:
                loss[i, j] = v
                heapq.heappush(heap, (v, i, j))
    done = np.zeros((ny, nx), dtype=bool)
    while heap:
        lu, i, j = heapq.heappop(heap)
        if done[i, j]:
            continue
        done[i, j] = True
        for k, (a, b) in enumerate(offs):
            vi, vj = i + a, j + b
            if not (0 <= vi < ny and 0 <= vj < nx) or done[vi, vj]:
                continue
            c = cost[i, k]
            lv = lu + c
            if lv >= loss[vi, vj] or lv > allowed[vi, vj]:
                continue
            if any(lu + s * c > alt - clearance - zb(i + s * a, j + s * b)
                   for s in (0.25, 0.5, 0.75)):
                continue
            loss[vi, vj] = lv
            heapq.heappush(heap, (lv, vi, vj))
    return loss
