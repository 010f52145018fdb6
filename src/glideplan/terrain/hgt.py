"""SRTM `.hgt` tiles: one 1 deg x 1 deg cell named by its south-west corner (`N46E007.hgt`).

Big-endian signed 16-bit metres above the geoid, rows from north to south, columns from west
to east; 1201 x 1201 samples (3 arc-second) or 3601 x 3601 (1 arc-second); the edge rows and
columns repeat the neighbouring tiles'; voids are -32768 (refused, or filled with a warning).
"""

from __future__ import annotations

import pathlib
import re

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.terrain.grid import Terrain
from glideplan.terrain.voids import fill_voids

__all__ = ["HGT_SIZES", "VOID", "hgt_corner", "read_hgt", "write_hgt"]

HGT_SIZES = {1201: 3, 3601: 1}  # samples per side -> arc-seconds
VOID = -32768

_NAME = re.compile(r"^([NS])(\d{2})([EW])(\d{3})$", re.I)


def hgt_corner(path: str | pathlib.Path) -> tuple[int, int]:
    """(lat, lon) in whole degrees of the south-west corner, from a name like `N46E007.hgt`."""
    stem = pathlib.Path(path).name.split(".")[0]
    m = _NAME.match(stem)
    if m is None:
        raise InvalidParameterError(
            str(path), pathlib.Path(path).name,
            "an SRTM tile must be named by its south-west corner, like N46E007.hgt")
    lat = int(m.group(2)) * (1 if m.group(1).upper() == "N" else -1)
    lon = int(m.group(4)) * (1 if m.group(3).upper() == "E" else -1)
    if not (-90 <= lat < 90 and -180 <= lon < 180):
        raise InvalidParameterError(str(path), stem, "the tile's corner is not on the Earth")
    return lat, lon


def read_hgt(path: str | pathlib.Path, *, voids: str = "refuse") -> Terrain:
    """The tile as a `Terrain` (latitudes ascending). `voids`: "refuse" (an error naming the
    file), "nearest" or "linear" (filled, with a warning in `Terrain.warnings`)."""
    p = pathlib.Path(path)
    lat0, lon0 = hgt_corner(p)
    raw = p.read_bytes()
    n = round((len(raw) / 2) ** 0.5)
    if n not in HGT_SIZES or 2 * n * n != len(raw):
        raise InvalidParameterError(
            str(p), f"{len(raw)} bytes",
            "an SRTM .hgt tile holds 1201x1201 (3 arc-second) or 3601x3601 (1 arc-second) "
            "big-endian 16-bit samples (2884802 or 25934402 bytes)")
    z = np.frombuffer(raw, dtype=">i2").reshape(n, n)[::-1]  # rows south to north
    void = z == VOID
    filled, warning = fill_voids(z, void, voids, str(p))
    step = 1.0 / (n - 1)
    lat = lat0 + step * np.arange(n)
    lon = lon0 + step * np.arange(n)
    lat[-1], lon[-1] = lat0 + 1.0, lon0 + 1.0
    return Terrain(np.asarray(lat, dtype=np.float64), np.asarray(lon, dtype=np.float64), filled,
                   (str(p),), (warning,) if warning else ())


def write_hgt(path: str | pathlib.Path, z: np.ndarray) -> pathlib.Path:
    """Write an (n, n) array (rows south to north, n 1201 or 3601) as an SRTM tile; NaN -> void.

    For tests and synthetic benchmarks; the name must be the tile's corner (`N46E007.hgt`).
    """
    p = pathlib.Path(path)
    hgt_corner(p)
    a = np.asarray(z, dtype=float)
    if a.ndim != 2 or a.shape[0] != a.shape[1] or a.shape[0] not in HGT_SIZES:
        raise InvalidParameterError("z", a.shape, "must be 1201x1201 or 3601x3601")
    out = np.where(np.isfinite(a), np.round(a), VOID).astype(">i2")[::-1]
    p.write_bytes(out.tobytes())
    return p
