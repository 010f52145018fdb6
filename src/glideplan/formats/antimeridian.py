"""Lines across the antimeridian: split per RFC 7946 section 3.1.9, joined again on reading.

A track is continuous on the sphere but its longitudes jump by 360 degrees where it crosses
180 E/W. GeoJSON (RFC 7946 section 3.1.9) and KML viewers draw a LineString with such a jump
the long way round the globe, so a line that crosses is written as several parts (a
MultiLineString / MultiGeometry), each inside [-180, 180], that meet on the antimeridian:
one part ends at longitude +-180 and the next starts at -+180 at the same latitude.

Each segment is taken the short way (|dlon| <= 180 deg) and is straight in (lat, lon): where
it crosses the seam at longitude s = +-180 (unwrapped lon_a + dlon passes s), the crossing
latitude is the linear interpolation

    lat_s = lat_a + (lat_b - lat_a) (s - lon_a) / dlon,

the closed form the tests check. Formats that take any longitude per point (GPX, CSV) need no
split; `wrap_longitude` puts them in [-180, 180).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
from numpy.typing import ArrayLike, NDArray

__all__ = ["join_at_antimeridian", "split_at_antimeridian", "split_polygon_at_antimeridian",
           "wrap_longitude"]

Part = tuple[NDArray[np.float64], NDArray[np.float64]]


def wrap_longitude(lon: ArrayLike) -> NDArray[np.float64]:
    """Longitudes (deg) in [-180, 180): ((lon + 180) mod 360) - 180; values already in
    (-180, 180) are returned unchanged (bit for bit), +180 becomes -180."""
    x = np.asarray(lon, dtype=float)
    inside = (x >= -180.0) & (x < 180.0)
    return np.asarray(np.where(inside, x, (x + 180.0) % 360.0 - 180.0), dtype=float)


def _on_side(value: float, approx: float) -> float:
    """`value` (in [-180, 180)) written as +180 instead of -180 when `approx` is near +180."""
    return 180.0 if value == -180.0 and approx > 0.0 else value


def _unwrap(lon: NDArray[np.float64]) -> NDArray[np.float64]:
    """Continuous longitudes: the first in [-180, 180), each step the short way (<= 180)."""
    if lon.size == 0:
        return lon.copy()
    step = wrap_longitude(np.diff(lon))
    out = np.empty_like(lon)
    out[0] = wrap_longitude(lon[:1])[0]
    out[1:] = out[0] + np.cumsum(step)
    return out


def _cell(lon: float) -> int:
    """Index k of the 360-degree band [-180 + 360 k, 180 + 360 k) holding `lon`."""
    return math.floor((lon + 180.0) / 360.0)


def split_at_antimeridian(lat: ArrayLike, lon: ArrayLike) -> list[Part]:
    """The parts (lat, lon) of a line (degrees), each inside [-180, 180], split at +-180.

    One part (longitudes wrapped) when the line does not cross; otherwise consecutive parts
    share the interpolated crossing point, written +180 on one side and -180 on the other.
    A vertex exactly on the seam ends one part and starts the next.
    """
    la = np.atleast_1d(np.asarray(lat, dtype=float))
    lo = np.atleast_1d(np.asarray(lon, dtype=float))
    if la.shape != lo.shape or la.ndim != 1:
        raise ValueError("lat and lon must be 1-D arrays of the same length")
    if la.size < 2:
        return [(la.copy(), wrap_longitude(lo))]
    u = _unwrap(lo)
    w = wrap_longitude(lo)  # the vertices' own longitudes (exact), written as given
    parts: list[tuple[int, list[float], list[float]]] = []  # (band, lats, unwrapped lons)
    exact: dict[tuple[int, int], float] = {}  # (part, index in part) -> a vertex's longitude

    def add(band: int, a: tuple[float, float], b: tuple[float, float], ia: int, ib: int) -> None:
        """Segment a -> b in `band`; ia, ib the vertex indices of a and b (-1: a seam point)."""
        if not (parts and parts[-1][0] == band):
            parts.append((band, [a[0]], [a[1]]))
            if ia >= 0:
                exact[(len(parts) - 1, 0)] = float(w[ia])
        parts[-1][1].append(b[0])
        parts[-1][2].append(b[1])
        if ib >= 0:
            exact[(len(parts) - 1, len(parts[-1][1]) - 1)] = float(w[ib])

    for i in range(la.size - 1):
        a = (float(la[i]), float(u[i]))
        b = (float(la[i + 1]), float(u[i + 1]))
        lo_a, lo_b = a[1], b[1]
        seam = 180.0 + 360.0 * _cell(min(lo_a, lo_b))  # the first seam east of the lower end
        if min(lo_a, lo_b) < seam < max(lo_a, lo_b):  # crosses strictly: split there
            t = (seam - lo_a) / (lo_b - lo_a)
            c = (a[0] + (b[0] - a[0]) * t, seam)
            add(_cell(0.5 * (lo_a + seam)), a, c, i, -1)
            add(_cell(0.5 * (seam + lo_b)), c, b, -1, i + 1)
        else:
            add(_cell(0.5 * (lo_a + lo_b)), a, b, i, i + 1)
    out: list[Part] = []
    for k, (band, lats, lons) in enumerate(parts):
        shifted = np.clip(np.asarray(lons, dtype=float) - 360.0 * band, -180.0, 180.0)
        for j in range(shifted.size):
            if (k, j) in exact:
                shifted[j] = _on_side(exact[(k, j)], float(shifted[j]))
        out.append((np.asarray(lats, dtype=float), shifted))
    return out


def join_at_antimeridian(
    parts: Sequence[tuple[ArrayLike, ArrayLike]], tol_deg: float = 1e-9
) -> tuple[list[float], list[float], list[bool]]:
    """Concatenate line parts (lat, lon) in order, merging the seam points they share.

    A part's last point and the next part's first point are one point when they are the same
    place (latitudes within `tol_deg`, longitudes equal modulo 360, e.g. +180 and -180): it is
    kept once. Returns lat, lon and, per point, whether it is such a merged seam point.
    """
    lat: list[float] = []
    lon: list[float] = []
    seam: list[bool] = []
    for k, (part_lat, part_lon) in enumerate(parts):
        pl = [float(v) for v in np.atleast_1d(np.asarray(part_lat, dtype=float))]
        po = [float(v) for v in np.atleast_1d(np.asarray(part_lon, dtype=float))]
        start = 0
        if k and lat and pl:
            dlon = abs(((po[0] - lon[-1]) + 180.0) % 360.0 - 180.0)
            if abs(pl[0] - lat[-1]) <= tol_deg and dlon <= tol_deg:
                seam[-1] = True
                start = 1
        lat += pl[start:]
        lon += po[start:]
        seam += [False] * (len(pl) - start)
    return lat, lon, seam


def _clip_ring(ring: NDArray[np.float64], seam: float, keep_west: bool) -> NDArray[np.float64]:
    """Sutherland-Hodgman: the closed ring (n, 2) lon, lat clipped to lon <= seam (west) or
    lon >= seam (east); an edge crossing the seam gets the point at lon = seam, latitude
    linear along the edge (as `split_at_antimeridian`). Empty (0, 2) when nothing is left."""
    def inside(p: NDArray[np.float64]) -> bool:
        return bool(p[0] <= seam) if keep_west else bool(p[0] >= seam)

    out: list[NDArray[np.float64]] = []
    pts = ring[:-1] if np.array_equal(ring[0], ring[-1]) else ring
    for k in range(len(pts)):
        a, b = pts[k - 1], pts[k]
        if inside(b):
            if not inside(a):
                out.append(np.array([seam, a[1] + (b[1] - a[1]) * (seam - a[0]) / (b[0] - a[0])]))
            out.append(b)
        elif inside(a):
            out.append(np.array([seam, a[1] + (b[1] - a[1]) * (seam - a[0]) / (b[0] - a[0])]))
    if len(out) < 3:
        return np.zeros((0, 2))
    arr = np.asarray(out, dtype=float)
    return np.vstack([arr, arr[:1]])


def split_polygon_at_antimeridian(rings: Sequence[NDArray[np.float64]]
                                  ) -> list[list[NDArray[np.float64]]]:
    """A polygon (closed rings (n, 2) lon, lat; exterior first; longitudes continuous, may
    pass +-180) as one or more polygons inside [-180, 180] (RFC 7946 section 3.1.9): the
    part beyond +180 (or -180) clipped off at the seam and shifted by -+360 degrees. Each
    ring is clipped to each side (Sutherland-Hodgman against the meridian); a hole stays with
    the side it lies on; a polygon inside [-180, 180] comes back unchanged."""
    rs = [np.asarray(r, dtype=float) for r in rings]
    if not rs:
        return []
    lo = min(float(r[:, 0].min()) for r in rs)
    hi = max(float(r[:, 0].max()) for r in rs)
    shift = -360.0 * math.floor((0.5 * (lo + hi) + 180.0) / 360.0)  # centre into [-180, 180)
    rs = [r + np.array([shift, 0.0]) for r in rs]
    lo, hi = lo + shift, hi + shift
    if lo >= -180.0 and hi <= 180.0:
        return [rs]
    seam = 180.0 if hi > 180.0 else -180.0
    out = []
    for keep_west in (True, False):
        parts = [_clip_ring(r, seam, keep_west) for r in rs]
        if parts[0].size == 0:
            continue
        off = 0.0 if (seam > 0) == keep_west else (-360.0 if seam > 0 else 360.0)
        out.append([p + np.array([off, 0.0]) for p in parts if p.size])
    return out
