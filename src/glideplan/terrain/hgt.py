"""SRTM `.hgt` tiles: one 1 deg x 1 deg cell named by its south-west corner (`N46E007.hgt`).

Big-endian signed 16-bit metres above the geoid, rows from north to south, columns from west
to east; 1201 x 1201 samples (3 arc-second) or 3601 x 3601 (1 arc-second); the edge rows and
columns repeat the neighbouring tiles'; voids are -32768 (refused, or filled with a warning).

Tiles come as people download them: plain `N46E007.hgt`, gzipped `N46E007.hgt.gz` (the AWS
"skadi" tiles), or zipped (`N46E007.SRTMGL1.hgt.zip` from NASA holds `N46E007.hgt`; a
viewfinderpanoramas `M32.zip` holds a folder of them): `read_hgt_tiles` reads every `.hgt`
in a zip. A member's size is checked before it is inflated (no zip bomb is expanded).
"""

from __future__ import annotations

import pathlib
import re

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.terrain.grid import Terrain
from glideplan.terrain.voids import fill_voids

__all__ = ["HGT_SIZES", "VOID", "hgt_corner", "hgt_from_bytes", "read_hgt", "read_hgt_tiles",
           "write_hgt"]

HGT_SIZES = {1201: 3, 3601: 1}  # samples per side -> arc-seconds
VOID = -32768

_NAME = re.compile(r"^([NS])(\d{2})([EW])(\d{3})$", re.I)


def hgt_corner(path: str | pathlib.Path, source: str | None = None) -> tuple[int, int]:
    """(lat, lon) in whole degrees of the south-west corner, from a name like `N46E007.hgt`
    (or `N46E007.SRTMGL1.hgt.zip`); errors name `source` (default: `path`)."""
    stem = pathlib.Path(path).name.split(".")[0]
    where = str(path) if source is None else source
    m = _NAME.match(stem)
    if m is None:
        raise InvalidParameterError(
            where, pathlib.Path(path).name,
            "an SRTM tile must be named by its south-west corner, like N46E007.hgt "
            "(N/S, 2 digits of latitude, E/W, 3 digits of longitude)")
    lat = int(m.group(2)) * (1 if m.group(1).upper() == "N" else -1)
    lon = int(m.group(4)) * (1 if m.group(3).upper() == "E" else -1)
    if not (-90 <= lat < 90 and -180 <= lon < 180):
        raise InvalidParameterError(where, stem, "the tile's corner is not on the Earth")
    return lat, lon


_SIZE_RULE = ("an SRTM .hgt tile holds 1201x1201 (3 arc-second) or 3601x3601 (1 arc-second) "
              "big-endian 16-bit samples (2884802 or 25934402 bytes)")
_BYTES = frozenset(2 * n * n for n in HGT_SIZES)


def hgt_from_bytes(raw: bytes, name: str, source: str, *, voids: str = "refuse") -> Terrain:
    """A tile's samples `raw` as a `Terrain`; `name` gives its corner (`N46E007.hgt`),
    `source` names it in messages (a file, or `archive.zip member N46E007.hgt`)."""
    lat0, lon0 = hgt_corner(name, source)
    n = round((len(raw) / 2) ** 0.5)
    if n not in HGT_SIZES or 2 * n * n != len(raw):
        raise InvalidParameterError(source, f"{len(raw)} bytes", _SIZE_RULE)
    z = np.frombuffer(raw, dtype=">i2").reshape(n, n)[::-1]  # rows south to north
    void = z == VOID
    filled, warning = fill_voids(z, void, voids, source)
    step = 1.0 / (n - 1)
    lat = lat0 + step * np.arange(n)
    lon = lon0 + step * np.arange(n)
    lat[-1], lon[-1] = lat0 + 1.0, lon0 + 1.0
    return Terrain(np.asarray(lat, dtype=np.float64), np.asarray(lon, dtype=np.float64), filled,
                   (source,), (warning,) if warning else ())


def read_hgt(path: str | pathlib.Path, *, voids: str = "refuse") -> Terrain:
    """The tile as a `Terrain` (latitudes ascending). `voids`: "refuse" (an error naming the
    file), "nearest" or "linear" (filled, with a warning in `Terrain.warnings`). A `.hgt.gz`
    is inflated; a `.zip` must hold exactly one tile here (`read_hgt_tiles` reads several)."""
    tiles = read_hgt_tiles(path, voids=voids)
    if len(tiles) != 1:
        raise InvalidParameterError(str(path), f"{len(tiles)} tiles",
                                    "read_hgt reads one tile; use read_hgt_tiles or read_terrain")
    return tiles[0]


def read_hgt_tiles(path: str | pathlib.Path, *, voids: str = "refuse") -> list[Terrain]:
    """Every tile in `path`: a `.hgt` (one), a `.hgt.gz` (one) or a `.zip` (its `.hgt`s)."""
    p = pathlib.Path(path)
    low = p.name.lower()
    if low.endswith(".zip"):
        return _zip_tiles(p, voids)
    if low.endswith(".gz"):
        import gzip
        import zlib

        try:
            with gzip.open(p, "rb") as fp:
                raw = fp.read(max(_BYTES) + 1)  # enough to tell a wrong size, no more
        except (OSError, EOFError, zlib.error) as exc:
            raise InvalidParameterError(str(p), str(p), f"not a gzip file ({exc})") from None
        return [hgt_from_bytes(raw, p.name, str(p), voids=voids)]
    hgt_corner(p)  # the name first: it says which tile the samples are
    return [hgt_from_bytes(p.read_bytes(), p.name, str(p), voids=voids)]


def _zip_tiles(p: pathlib.Path, voids: str) -> list[Terrain]:
    """The `.hgt` members of a zip archive (folders inside it included)."""
    import zipfile

    try:
        zf = zipfile.ZipFile(p)
    except (zipfile.BadZipFile, OSError) as exc:
        raise InvalidParameterError(str(p), str(p), f"not a zip archive ({exc})") from None
    with zf:
        members = [m for m in zf.infolist()
                   if not m.is_dir() and m.filename.lower().endswith(".hgt")]
        if not members:
            names = [m.filename for m in zf.infolist()][:5]
            raise InvalidParameterError(
                str(p), str(p), "the zip archive holds no SRTM .hgt tile (it holds "
                f"{', '.join(names) if names else 'nothing'})")
        tiles = []
        for m in members:
            name = pathlib.PurePosixPath(m.filename).name
            source = f"{p} member {m.filename}"
            if m.file_size not in _BYTES:
                raise InvalidParameterError(source, f"{m.file_size} bytes", _SIZE_RULE)
            try:
                raw = zf.read(m)
            except (zipfile.BadZipFile, OSError, EOFError) as exc:
                raise InvalidParameterError(source, m.filename,
                                            f"cannot be inflated ({exc})") from None
            tiles.append(hgt_from_bytes(raw, name, source, voids=voids))
    return tiles


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
