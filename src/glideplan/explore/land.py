"""Land and coastline on the explorer's maps, offline: Natural Earth 1:10m land, bundled.

Data: Natural Earth 4.1.0 "land" at 1:10m (public domain; `data/LICENSE-naturalearth.txt`),
taken from the npm package `world-atlas` 2.0.2 (`land-10m.json`) and stored by
`data/build_land.py` as `data/land_10m.npz` (830 kB: 4,061 polygons, 408,940 points on the
file's 1e5 x 1e5 integer grid, 0.0036 deg of longitude by 0.00169 deg of latitude). Why this
set: it is the standard small-scale world coast, kept by the Natural Earth project, public
domain (no attribution or share-alike to carry), and small enough to ship; a GSHHG or
OpenStreetMap coast would be finer but ten to a hundred times larger (and OSM is ODbL).
Accuracy: drawn for 1:10,000,000 (0.1 mm on such a map is 1 km), plus half a grid step
(<= 0.0018 deg lon, 0.00085 deg lat): a coast point lies within ~1-2 km of the drawn line.

`land_shapes(west, south, east, north)`: the land polygons (with holes) clipped to that box
(Sutherland-Hodgman, exact for the box's straight sides in lon/lat) and the coastline as
polylines (NaN between pieces, no edge along the box), thinned to ~1/1500 of the box's
width when the data is finer than that. `add_land(fig, x_range, y_range)`: draws the land
under every layer and the coast over the images only, of a lon/lat figure (the maps are
lon/lat with equal metres per pixel at the view's latitude, as the tracks) for 3 x 3 views
about the view, and again whenever the view leaves the middle of that region.
`distance_to_coast_m` and `on_land` serve the tests.
"""

from __future__ import annotations

import functools
import math
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = [
    "LAND_FILE",
    "add_land",
    "distance_to_coast_m",
    "land_shapes",
    "on_land",
    "view_with_coast",
]

LAND_FILE = pathlib.Path(__file__).with_name("data") / "land_10m.npz"
LAND_FILL = "#ece4cf"  # a chart's land tint
COAST = "#6b6250"
SEA = "#dcebf5"
_THIN = 1500  # coast samples kept across the box's width, at most
FloatArray = NDArray[np.float64]


@dataclass(frozen=True)
class _Land:
    lon: FloatArray  # every ring's points, rings one after another (closed: first == last)
    lat: FloatArray
    start: NDArray[np.int64]  # ring k is points start[k]:start[k + 1]
    poly: NDArray[np.int64]  # polygon p is rings poly[p]:poly[p + 1] (outer ring first)
    box: FloatArray  # per ring: lon min, lat min, lon max, lat max


@functools.lru_cache(maxsize=1)
def _land() -> _Land:
    """The bundled land, decoded (grid -> degrees: translate + scale * q)."""
    d = np.load(LAND_FILE)
    n = d["ring_len"].astype(np.int64)
    start = np.concatenate([[0], np.cumsum(n)])
    # D: each ring's first point, then its steps; q = cumsum(D) less the sum before the ring
    total = int(start[-1])
    rows = np.delete(np.arange(total), start[:-1])
    d_all = np.zeros((total, 2), dtype=np.int64)
    d_all[rows] = d["steps"]
    d_all[start[:-1]] = d["first"]
    c = np.cumsum(d_all, axis=0)
    before = np.vstack([np.zeros((1, 2), dtype=np.int64), c[start[1:-1] - 1]])
    q = c - np.repeat(before, n, axis=0)
    lon = d["translate"][0] + d["scale"][0] * q[:, 0]
    lat = d["translate"][1] + d["scale"][1] * q[:, 1]
    box = np.stack(
        [
            np.minimum.reduceat(lon, start[:-1]),
            np.minimum.reduceat(lat, start[:-1]),
            np.maximum.reduceat(lon, start[:-1]),
            np.maximum.reduceat(lat, start[:-1]),
        ],
        axis=1,
    )
    poly = np.concatenate([[0], np.cumsum(d["poly_rings"].astype(np.int64))])
    return _Land(lon, lat, start, poly, box)


def _clip_side(x: FloatArray, y: FloatArray, axis: int, c: float, keep_above: bool
               ) -> tuple[FloatArray, FloatArray]:
    """One Sutherland-Hodgman pass: the closed ring (x, y) cut by the line (x or y) = c."""
    if x.size == 0:
        return x, y
    v = x if axis == 0 else y
    inside = v >= c if keep_above else v <= c
    xp, yp, vp = np.roll(x, 1), np.roll(y, 1), np.roll(v, 1)
    cross = inside != np.roll(inside, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(cross, (c - vp) / (v - vp), 0.0)
    ix, iy = xp + t * (x - xp), yp + t * (y - yp)
    if axis == 0:
        ix = np.where(cross, c, ix)
    else:
        iy = np.where(cross, c, iy)
    pick = np.stack([cross, inside], axis=1).ravel()
    return np.stack([ix, x], axis=1).ravel()[pick], np.stack([iy, y], axis=1).ravel()[pick]


def _clip_ring(x: FloatArray, y: FloatArray, box: tuple[float, float, float, float]
               ) -> tuple[FloatArray, FloatArray]:
    """The ring clipped to box (west, south, east, north)."""
    w, s, e, n = box
    for axis, c, above in ((0, w, True), (0, e, False), (1, s, True), (1, n, False)):
        x, y = _clip_side(x, y, axis, c, above)
    return x, y


def _thin(x: FloatArray, y: FloatArray, tol: float) -> NDArray[np.bool_]:
    """Keep a point where its tol x tol cell differs from the previous point's (ends kept)."""
    cx, cy = np.floor(x / tol), np.floor(y / tol)
    keep = np.ones(x.shape, dtype=bool)
    keep[1:] = (cx[1:] != cx[:-1]) | (cy[1:] != cy[:-1])
    keep[-1] = True
    return keep


def land_shapes(west: float, south: float, east: float, north: float
                ) -> tuple[dict[str, list[Any]], dict[str, FloatArray]]:
    """Land polygons clipped to the box ({"xs", "ys"} for `multi_polygons`) and the coast in
    it ({"x", "y"}: one polyline, NaN between pieces) -- lon/lat degrees."""
    land = _land()
    box = (west, south, east, north)
    hit = (land.box[:, 0] <= east) & (land.box[:, 2] >= west)
    hit &= (land.box[:, 1] <= north) & (land.box[:, 3] >= south)
    tol = (east - west) / _THIN
    xs: list[Any] = []
    ys: list[Any] = []
    cx: list[FloatArray] = []
    cy: list[FloatArray] = []
    nan = np.array([np.nan])
    for p in range(len(land.poly) - 1):
        r0, r1 = int(land.poly[p]), int(land.poly[p + 1])
        if not hit[r0]:
            continue
        px: list[FloatArray] = []
        py: list[FloatArray] = []
        for r in range(r0, r1):
            if not hit[r]:
                continue
            a, b = int(land.start[r]), int(land.start[r + 1])
            x, y = land.lon[a:b], land.lat[a:b]
            keep = _thin(x, y, tol)
            x, y = x[keep], y[keep]
            inside = (x >= west) & (x <= east) & (y >= south) & (y <= north)
            near = inside | np.roll(inside, 1) | np.roll(inside, -1)
            if near.any():
                cx += [np.where(near, x, np.nan), nan]
                cy += [np.where(near, y, np.nan), nan]
            qx, qy = _clip_ring(x, y, box)
            if qx.size >= 3:
                px.append(qx)
                py.append(qy)
        if px:
            xs.append([px])
            ys.append([py])
    line_x = np.concatenate(cx) if cx else np.zeros(0)
    line_y = np.concatenate(cy) if cy else np.zeros(0)
    gap = np.isnan(line_x)
    keep = ~(gap & np.roll(gap, 1))  # one NaN between pieces
    return {"xs": xs, "ys": ys}, {"x": line_x[keep], "y": line_y[keep]}


def on_land(lat: float, lon: float) -> bool:
    """Whether (lat, lon) lies on the bundled land (inside an outer ring, not in a hole)."""
    from matplotlib.path import Path

    land = _land()
    inside_rings = []
    hit = (land.box[:, 0] <= lon) & (land.box[:, 2] >= lon)
    hit &= (land.box[:, 1] <= lat) & (land.box[:, 3] >= lat)
    for r in np.flatnonzero(hit):
        a, b = int(land.start[r]), int(land.start[r + 1])
        ring = np.stack([land.lon[a:b], land.lat[a:b]], axis=1)
        if Path(ring).contains_point((lon, lat)):
            inside_rings.append(int(r))
    holes = set(range(len(land.start) - 1)) - {int(v) for v in land.poly[:-1]}
    return sum(-1 if r in holes else 1 for r in inside_rings) > 0


def distance_to_coast_m(lat: float, lon: float, search_deg: float = 0.5) -> float:
    """The least distance (m, local equirectangular plane, the one Earth radius) from (lat, lon) to
    the bundled coastline's segments within `search_deg`; inf if none there."""
    _, line = land_shapes(lon - search_deg, lat - search_deg, lon + search_deg, lat + search_deg)
    x, y = line["x"], line["y"]
    if x.size < 2:
        return math.inf
    from glideplan.geodesy import EARTH_RADIUS_M

    r = EARTH_RADIUS_M * math.pi / 180.0
    k = math.cos(math.radians(lat))
    ax, ay, bx, by = x[:-1], y[:-1], x[1:], y[1:]
    ok = np.isfinite(ax) & np.isfinite(bx)
    ax, ay = (ax[ok] - lon) * k * r, (ay[ok] - lat) * r
    bx, by = (bx[ok] - lon) * k * r, (by[ok] - lat) * r
    dx, dy = bx - ax, by - ay
    ll = dx * dx + dy * dy
    with np.errstate(invalid="ignore", divide="ignore"):
        t = np.clip(np.where(ll > 0, -(ax * dx + ay * dy) / ll, 0.0), 0.0, 1.0)
    return float(np.min(np.hypot(ax + t * dx, ay + t * dy)))


def view_with_coast(west: float, south: float, east: float, north: float,
                    max_km: float = 40.0) -> tuple[float, float, float, float]:
    """The box (same centre) grown, if no coast is in it, until it reaches 1.3 x the centre's
    distance to the nearest coast (as a square in metres), at most `max_km` across."""
    lat, lon = 0.5 * (south + north), 0.5 * (west + east)
    if land_shapes(west, south, east, north)[1]["x"].size:
        return west, south, east, north
    d = distance_to_coast_m(lat, lon, search_deg=max_km / 111.0)
    half = min(1.3 * d, 500.0 * max_km) / 111_320.0  # deg of latitude
    k = max(math.cos(math.radians(lat)), 1e-6)
    half_lat = max(half, 0.5 * (north - south))
    half_lon = max(half / k, 0.5 * (east - west))
    return lon - half_lon, lat - half_lat, lon + half_lon, lat + half_lat


class _LandLayer:
    """The land and coast sources of one figure, refilled when the view leaves the middle
    of the region they cover (3 x 3 views about the view at the last fill)."""

    def __init__(self, x_range: Any, y_range: Any, land_src: Any, coast_src: Any) -> None:
        self.x_range, self.y_range = x_range, y_range
        self.land_src, self.coast_src = land_src, coast_src
        self.inner = (math.inf, math.inf, -math.inf, -math.inf)
        self.fill()

    def fill(self, *_: Any) -> None:
        xr, yr = self.x_range, self.y_range
        try:
            w, e, s, n = float(xr.start), float(xr.end), float(yr.start), float(yr.end)
        except (TypeError, ValueError):
            return
        if not all(map(math.isfinite, (w, e, s, n))) or e <= w or n <= s:
            return
        iw, is_, ie, in_ = self.inner
        if w >= iw and e <= ie and s >= is_ and n <= in_:
            return
        dx, dy = e - w, n - s
        box = (w - dx, max(-90.0, s - dy), e + dx, min(90.0, n + dy))
        polys, coast = land_shapes(*box)
        self.land_src.data = polys
        self.coast_src.data = coast
        self.inner = (w - 0.5 * dx, s - 0.5 * dy, e + 0.5 * dx, n + 0.5 * dy)


def add_land(fig: Any, x_range: Any, y_range: Any) -> Any:
    """Land (filled) under every other layer of the lon/lat figure `fig` and the coastline
    over its images only (a field's own land mask, a terrain's relief), the sea as its
    background, and a one-line attribution; returns the layer (its sources are
    `land_src`, `coast_src`, named "gp-land" and "gp-coast")."""
    from bokeh.models import ColumnDataSource
    from bokeh.models.annotations import Label

    land_src = ColumnDataSource({"xs": [], "ys": []}, name="gp-land")
    coast_src = ColumnDataSource({"x": [], "y": []}, name="gp-coast")
    land = fig.multi_polygons("xs", "ys", source=land_src, fill_color=LAND_FILL,
                              line_color=None, name="gp-land")
    coast = fig.line("x", "y", source=coast_src, line_color=COAST, line_width=1.2,
                     name="gp-coast")
    # land under everything, the coast over the page's images (a field's land mask, relief)
    others = [r for r in fig.renderers if r is not land and r is not coast]
    images = [r for r in others if type(getattr(r, "glyph", None)).__name__ == "ImageRGBA"]
    fig.renderers = [land, *images, coast, *(r for r in others if r not in images)]
    fig.background_fill_color = SEA
    fig.add_layout(Label(x=4, y=4, x_units="screen", y_units="screen",
                         text="land: Natural Earth 1:10m", text_font_size="9px",
                         text_color="#7a7466", background_fill_color="white",
                         background_fill_alpha=0.6))
    layer = _LandLayer(x_range, y_range, land_src, coast_src)
    for r in (x_range, y_range):
        r.on_change("start", lambda attr, old, new: layer.fill())
        r.on_change("end", lambda attr, old, new: layer.fill())
    return layer
