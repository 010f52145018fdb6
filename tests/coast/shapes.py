"""Land masks built of rectangles near the equator, and an independent shortest way round.

The field: still water on a regular lat/lon grid of spacing dx (m) about (0 N, 0 E), x east
and y north in km of the equirectangular plane x = R lon, y = R lat (radians); at |lat| <=
0.6 deg its distances are the sphere's to 1e-4. A node is land (NaN) when it lies in one of
the rectangles (x0, x1, y0, y1) in km.

`shortest_way_round`: the route keeps c from every land node, so the obstacle is the union
of the disks of radius c about the nodes. For land made of rectangles, the node set of each
rectangle spans a rectangle Q (its extreme nodes); the union of its nodes' disks lies inside
Q grown by c (the rounded rectangle: Q's corners' disks and Q grown by c along x and along
y) and touches its boundary at the corner disks and along the sides up to scallops of depth
dx^2 / 8c between the nodes. A shortest path that wraps the rounded rectangles only at their
corners (all the shapes here) is therefore the polygon geodesic of the inflated land. It is
found here independently of `glideplan.routing.coast`: the exact tangent graph of the corner
circles (point-circle tangents and the outer and inner bitangents of equal circles, arcs
along the circles), Dijkstra, with every tangent checked against every grown rectangle.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Sequence

import numpy as np

from glideplan.fields.synthetic import copernicus_dataset

R = 6_371_008.8
KM = 1000.0
T0 = np.datetime64("2026-01-01T00:00", "ns")

Rect = tuple[float, float, float, float]

#: The shapes of the tests (km): name -> (field width, height, rectangles, start, goal).
SHAPES: dict[str, tuple[float, float, list[Rect], tuple[float, float], tuple[float, float]]] = {
    # a rectangular cape from the west edge; start and goal 17 km west of its tip either side
    "cape": (60.0, 50.0, [(0.0, 35.0, 22.0, 28.0)], (18.0, 12.0), (18.0, 38.0)),
    # a hooked peninsula (a spit) from the west edge; the goal in the hook's bay
    "spit": (64.0, 64.0, [(0.0, 40.0, 20.0, 23.0), (37.0, 40.0, 20.0, 40.0),
                          (24.0, 40.0, 37.0, 40.0)], (16.0, 12.0), (28.0, 31.0)),
    # a chain of three 5 km islands with 2 km gaps between them
    "islands": (60.0, 44.0, [(16.0, 21.0, 20.0, 25.0), (23.0, 28.0, 20.0, 25.0),
                             (30.0, 35.0, 20.0, 25.0)], (29.0, 8.0), (20.0, 36.0)),
    # a 3 km strait between two coasts that fill the field's width
    "strait": (60.0, 44.0, [(0.0, 28.5, 18.0, 26.0), (31.5, 60.0, 18.0, 26.0)],
               (20.0, 6.0), (42.0, 38.0)),
}


def lat_lon(x_km: float, y_km: float) -> tuple[float, float]:
    return math.degrees(y_km * KM / R), math.degrees(x_km * KM / R)


def mask(name: str, dx: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lat, lon, land) of the shape on a grid of spacing dx (m)."""
    w, h, rects, _, _ = SHAPES[name]
    lat = np.degrees(np.arange(round(h * KM / dx) + 1) * dx / R)
    lon = np.degrees(np.arange(round(w * KM / dx) + 1) * dx / R)
    y = np.radians(lat) * R / KM
    x = np.radians(lon) * R / KM
    X, Y = np.meshgrid(x, y)
    land = np.zeros(X.shape, dtype=bool)
    for x0, x1, y0, y1 in rects:
        land |= (X >= x0 - 1e-6) & (X <= x1 + 1e-6) & (Y >= y0 - 1e-6) & (Y <= y1 + 1e-6)
    return lat, lon, land


def write(path: object, lat: np.ndarray, lon: np.ndarray, land: np.ndarray) -> None:
    """Still water with NaN on land, a Copernicus-like NetCDF file."""
    u = np.where(land, np.nan, 0.0)[None, None]
    copernicus_dataset(lat, lon, [T0], [0.5], u, u).to_netcdf(path)


def node_rects(name: str, dx: float) -> list[Rect]:
    """Each rectangle's extreme land nodes (m): Q of the module docstring."""
    lat, lon, _ = mask(name, dx)
    x = np.radians(lon) * R
    y = np.radians(lat) * R
    out = []
    far = 1e9  # land at the field's edge goes on beyond it: no way round there
    for x0, x1, y0, y1 in SHAPES[name][2]:
        xi = x[(x >= x0 * KM - 1e-3) & (x <= x1 * KM + 1e-3)]
        yi = y[(y >= y0 * KM - 1e-3) & (y <= y1 * KM + 1e-3)]
        q = [float(xi.min()), float(xi.max()), float(yi.min()), float(yi.max())]
        for k, edge in enumerate((x[0], x[-1], y[0], y[-1])):
            if abs(q[k] - edge) < 1.0:
                q[k] = -far if k % 2 == 0 else far
        out.append((q[0], q[1], q[2], q[3]))
    return out


def _seg_rect_hits(p: np.ndarray, q: np.ndarray, r: Rect) -> bool:
    """Whether the open segment p -> q meets the open rectangle r (Liang-Barsky)."""
    x0, x1, y0, y1 = r
    d = q - p
    lo, hi = 0.0, 1.0
    for pk, dk, a, b in ((p[0], d[0], x0, x1), (p[1], d[1], y0, y1)):
        if abs(dk) < 1e-12:
            if not (a < pk < b):
                return False
            continue
        t1, t2 = (a - pk) / dk, (b - pk) / dk
        lo, hi = max(lo, min(t1, t2)), min(hi, max(t1, t2))
    return hi - lo > 1e-9


def _clear(p: np.ndarray, q: np.ndarray, rects: Sequence[Rect], c: float) -> bool:
    """Whether the segment keeps c (to 1e-6 relative) from every rectangle's corner disks and
    stays out of its x- and y-grown rectangles."""
    e = c * (1 - 1e-6)
    d = q - p
    L2 = float(d @ d)
    for x0, x1, y0, y1 in rects:
        if _seg_rect_hits(p, q, (x0 - e, x1 + e, y0, y1)) or \
                _seg_rect_hits(p, q, (x0, x1, y0 - e, y1 + e)):
            return False
        for cx, cy in ((x0, y0), (x0, y1), (x1, y0), (x1, y1)):
            s = np.array([cx, cy])
            t = 0.0 if L2 == 0 else min(max(float((s - p) @ d) / L2, 0.0), 1.0)
            if math.hypot(*(p + t * d - s)) < e:
                return False
    return True


def _tangents(p: np.ndarray, s: np.ndarray, c: float) -> list[np.ndarray]:
    """The two tangent points on the circle (s, c) seen from p."""
    v = p - s
    d = math.hypot(*v)
    if d <= c:
        return []
    a = math.atan2(v[1], v[0])
    b = math.acos(c / d)
    return [s + c * np.array([math.cos(a + k * b), math.sin(a + k * b)]) for k in (-1, 1)]


def _bitangents(s1: np.ndarray, s2: np.ndarray, c: float) -> list[tuple[np.ndarray, np.ndarray]]:
    """Outer and inner bitangents of two circles of radius c: pairs of tangent points."""
    v = s2 - s1
    d = math.hypot(*v)
    if d < 1e-9:
        return []
    n = np.array([-v[1], v[0]]) / d
    out = [(s1 + c * n, s2 + c * n), (s1 - c * n, s2 - c * n)]
    if d > 2 * c:
        a = math.atan2(v[1], v[0])
        b = math.acos(2 * c / d)
        for k in (-1, 1):
            u = np.array([math.cos(a + k * b), math.sin(a + k * b)])
            out.append((s1 + c * u, s2 - c * u))
    return out


def shortest_way_round(name: str, dx: float, c: float) -> float:
    """The length (m) of the shortest way from start to goal keeping c from the land nodes
    (module docstring)."""
    rects = node_rects(name, dx)
    _, _, _, start, goal = SHAPES[name]
    p0 = np.array(start) * KM
    p1 = np.array(goal) * KM
    circles = [np.array([cx, cy]) for x0, x1, y0, y1 in rects
               for cx, cy in ((x0, y0), (x0, y1), (x1, y0), (x1, y1))]
    pts: list[np.ndarray] = [p0, p1]
    on: list[int] = [-1, -1]  # the circle each point lies on
    edges: list[tuple[int, int, float]] = []

    def add(p: np.ndarray, k: int) -> int:
        pts.append(p)
        on.append(k)
        return len(pts) - 1

    if _clear(p0, p1, rects, c):
        edges.append((0, 1, float(math.hypot(*(p1 - p0)))))
    for k, s in enumerate(circles):
        for e, p in ((0, p0), (1, p1)):
            for t in _tangents(p, s, c):
                if _clear(p, t, rects, c):
                    edges.append((e, add(t, k), float(math.hypot(*(t - p)))))
        for m in range(k + 1, len(circles)):
            for a, b in _bitangents(s, circles[m], c):
                if _clear(a, b, rects, c):
                    edges.append((add(a, k), add(b, m), float(math.hypot(*(b - a)))))
    # arcs between the points on each circle (the shorter way round)
    by_circle: dict[int, list[int]] = {}
    for i, k in enumerate(on):
        if k >= 0:
            by_circle.setdefault(k, []).append(i)
    for k, idx in by_circle.items():
        s = circles[k]
        for ii, i in enumerate(idx):
            for j in idx[ii + 1:]:
                a = math.atan2(*(pts[i] - s)[::-1])
                b = math.atan2(*(pts[j] - s)[::-1])
                da = abs((b - a + math.pi) % (2 * math.pi) - math.pi)
                edges.append((i, j, c * da))
    adj: dict[int, list[tuple[int, float]]] = {}
    for i, j, w in edges:
        adj.setdefault(i, []).append((j, w))
        adj.setdefault(j, []).append((i, w))
    dist = {0: 0.0}
    heap = [(0.0, 0)]
    while heap:
        d, i = heapq.heappop(heap)
        if i == 1:
            return d
        if d > dist.get(i, math.inf):
            continue
        for j, w in adj.get(i, []):
            if d + w < dist.get(j, math.inf):
                dist[j] = d + w
                heapq.heappush(heap, (d + w, j))
    return math.inf
