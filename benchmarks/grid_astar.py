"""Baseline: time-dependent grid A* with the correct crab-angle kinematics (issue 12).

The usual grid A* for gliders (e.g. mlearn14/GGS) sums distance and ignores the crab angle.
This baseline is the fair version: on the same routing grid as `glideplan.routing` (same
local plane, same current on the nodes), each move to one of the 16 neighbours (8 plus the
knight moves, for 22.5-degree headings) is flown holding the straight edge with a crab angle,

    along speed s = sqrt(V^2 - c_n^2) + c_t   (c at the edge midpoint, at the departure time),

impossible if |c_n| >= V or s <= 0; the cost is the edge's time, and arrival times are
labels of a time-dependent Dijkstra/A* (FIFO network). Heuristic: straight distance to the
goal / (V + max |c|), admissible. Land (NaN) nodes are not entered.
"""

from __future__ import annotations

import heapq
import math
import time
from dataclasses import dataclass

import numpy as np

from glideplan.routing.grid import CurrentSampler, RouteGrid

MOVES = [(1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (-1, 1), (-1, -1), (1, -1),
         (2, 1), (1, 2), (-1, 2), (-2, 1), (-2, -1), (-1, -2), (1, -2), (2, -1)]


@dataclass(frozen=True)
class AStarResult:
    arrival_s: float | None  # seconds after departure at the goal node
    expanded: int
    run_s: float  # CPU seconds (process time)


def grid_astar(grid: RouteGrid, sampler: CurrentSampler, speed: float, t0: float,
               goal_xy: tuple[float, float]) -> AStarResult:
    """Time-optimal path on the 16-connected grid from the node nearest (0, 0) to the goal."""
    t_start = time.process_time()
    h = grid.spacing
    ny, nx = grid.shape
    j0 = round((0.0 - grid.x[0]) / h)
    i0 = round((0.0 - grid.y[0]) / h)
    jg = round((goal_xy[0] - grid.x[0]) / h)
    ig = round((goal_xy[1] - grid.y[0]) / h)
    levels = sampler.levels
    cache: dict[int, tuple[list[list[float]], list[list[float]]]] = {}

    def current(i: float, j: float, t: float) -> tuple[float, float]:
        k, w = sampler.bracket(t)
        out = []
        for kk in ((k,) if levels.size == 1 else (k, k + 1)):
            if kk not in cache:
                cx, cy = sampler.level(kk)
                cache[kk] = (cx.tolist(), cy.tolist())
            cx_l, cy_l = cache[kk]
            # Bilinear at the edge midpoint (half-integer node coordinates).
            a, b = int(i), int(j)
            fi, fj = i - a, j - b
            a1, b1 = min(a + 1, ny - 1), min(b + 1, nx - 1)
            vx = ((1 - fi) * ((1 - fj) * cx_l[a][b] + fj * cx_l[a][b1])
                  + fi * ((1 - fj) * cx_l[a1][b] + fj * cx_l[a1][b1]))
            vy = ((1 - fi) * ((1 - fj) * cy_l[a][b] + fj * cy_l[a][b1])
                  + fi * ((1 - fj) * cy_l[a1][b] + fj * cy_l[a1][b1]))
            out.append((vx, vy))
        if len(out) == 1:
            return out[0]
        return ((1 - w) * out[0][0] + w * out[1][0], (1 - w) * out[0][1] + w * out[1][1])

    cx0, _ = sampler.level(0)
    land = (~np.isfinite(cx0)).tolist()
    cmax = float(np.nanmax(np.hypot(*sampler.level(0))))
    hspeed = speed + cmax
    best: dict[tuple[int, int], float] = {(i0, j0): t0}
    heap = [(math.hypot(jg - j0, ig - i0) * h / hspeed + t0, t0, i0, j0)]
    expanded = 0
    move_len = [math.hypot(di, dj) * h for di, dj in MOVES]
    move_dir = [(dj / math.hypot(di, dj), di / math.hypot(di, dj)) for di, dj in MOVES]
    while heap:
        _, t, i, j = heapq.heappop(heap)
        if t > best.get((i, j), math.inf):
            continue
        expanded += 1
        if i == ig and j == jg:
            return AStarResult(t - t0, expanded, time.process_time() - t_start)
        for (di, dj), length, (ux, uy) in zip(MOVES, move_len, move_dir, strict=True):
            a, b = i + di, j + dj
            if not (0 <= a < ny and 0 <= b < nx) or land[a][b]:
                continue
            if abs(di) + abs(dj) == 3 and (land[i + di // 2 if abs(di) == 2 else i][
                    j + dj // 2 if abs(dj) == 2 else j]):
                continue
            cx, cy = current(i + 0.5 * di, j + 0.5 * dj, t)
            if cx != cx:  # NaN: the edge touches land
                continue
            ct = cx * ux + cy * uy
            cn = -cx * uy + cy * ux
            if abs(cn) >= speed:
                continue
            s = math.sqrt(speed * speed - cn * cn) + ct
            if s <= 0.0:
                continue
            tn = t + length / s
            if tn < best.get((a, b), math.inf):
                best[(a, b)] = tn
                heapq.heappush(heap, (tn + math.hypot(jg - b, ig - a) * h / hspeed, tn, a, b))
    return AStarResult(None, expanded, time.process_time() - t_start)
