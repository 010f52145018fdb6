"""The footprint: where the glider arrives at least the safety height above the terrain.

Clearance margin on the front's nodes, m = ALT - T - z - safety (T the altitude lost, z the
pooled terrain); the footprint is {m >= 0}, one (Multi)Polygon from the filled contour
(contourpy) of m at 0 in lon/lat. Beyond the front T is infinite; so that the contour sits
between a reached node and its unreached neighbour, not on the reached node, each unreached
node next to the front gets the margin the glide from that neighbour would give,
ALT - (T_n + d / r(chi)) - z - safety (r the ground glide ratio along the grid direction
chi), never above 0 (exact on flat ground along the grid's axes; elsewhere within a cell).
Rings are closed; exteriors counter-clockwise and holes clockwise (RFC 7946 right-hand rule).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.model import Glide

__all__ = ["Polygon", "clearance_margin", "footprint_polygons", "ring_area"]

FloatArray = NDArray[np.float64]
Polygon = list[FloatArray]  # rings (n, 2) lon, lat: the exterior then its holes

_FLOOR = -1e6  # margin of nodes with no data / far beyond the front (m)


def clearance_margin(arrival: FloatArray, z: FloatArray, alt: float, safety: float,
                     hx: FloatArray, hy: float, glide: Glide) -> FloatArray:
    """Margin m (ny, nx) in metres (module docstring); _FLOOR where undefined."""
    with np.errstate(invalid="ignore"):
        m = alt - arrival - z - safety
    m = np.where(np.isfinite(m), m, np.nan)
    ratio = glide.ratio(np.array([0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi]))  # E, N, W, S
    out = m.copy()
    reached = np.isfinite(m)
    best = np.full(m.shape, np.inf)
    T = np.where(np.isfinite(arrival), arrival, np.inf)
    hxc = np.asarray(hx, float)[:, None] * np.ones((1, m.shape[1]))
    ny, nx = m.shape
    # (di, dj): the reached neighbour's offset from the node; the glide from it runs the
    # other way: a neighbour to the west glides east (ratio[0]), to the south north, ...
    for (di, dj), r, dist in (((0, -1), ratio[0], hxc), ((-1, 0), ratio[1], hy),
                              ((0, 1), ratio[2], hxc), ((1, 0), ratio[3], hy)):
        if not (np.isfinite(r) and r > 0):
            continue
        rows = slice(max(-di, 0), ny - max(di, 0))
        cols = slice(max(-dj, 0), nx - max(dj, 0))
        nrows = slice(max(-di, 0) + di, ny - max(di, 0) + di)
        ncols = slice(max(-dj, 0) + dj, nx - max(dj, 0) + dj)
        dd = dist if np.isscalar(dist) else np.asarray(dist)[rows, cols]
        src = np.full(m.shape, np.inf)
        src[rows, cols] = T[nrows, ncols] + dd / r
        best = np.minimum(best, src)
    with np.errstate(invalid="ignore"):
        ext = alt - best - z - safety
    edge = ~reached & np.isfinite(ext)
    out[edge] = np.minimum(ext[edge], -1e-9)
    return np.where(np.isfinite(out), out, _FLOOR)


def ring_area(ring: FloatArray) -> float:
    """Signed shoelace area (deg^2; > 0 counter-clockwise) of a closed ring (n, 2)."""
    x, y = ring[:, 0], ring[:, 1]
    return 0.5 * float(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]))


def footprint_polygons(lat: FloatArray, lon: FloatArray, margin: FloatArray) -> list[Polygon]:
    """Polygons {margin >= 0}: each a list of closed rings (lon, lat), exterior first."""
    if not np.any(margin >= 0):
        return []
    import contourpy

    gen = contourpy.contour_generator(lon, lat, margin, fill_type=contourpy.FillType.OuterOffset)
    top = float(np.max(margin)) + 1.0
    points, offsets = gen.filled(0.0, top)[:2]
    polys: list[Polygon] = []
    for pts, off in zip(points, offsets, strict=True):
        assert pts is not None and off is not None
        rings: list[FloatArray] = []
        for k in range(len(off) - 1):
            ring = np.asarray(pts[off[k]:off[k + 1]], dtype=float)
            if ring.shape[0] < 4:
                continue
            if not np.array_equal(ring[0], ring[-1]):
                ring = np.vstack([ring, ring[:1]])
            area = ring_area(ring)
            if area == 0.0:
                continue
            want_ccw = not rings  # exterior first
            if (area > 0) != want_ccw:
                ring = ring[::-1]
            rings.append(ring)
        if rings:
            polys.append(rings)
    return polys
