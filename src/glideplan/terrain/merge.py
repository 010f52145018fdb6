"""Several DEM tiles on one lat/lon grid: `merge_tiles`, and `read_terrain` for a file list.

`read_terrain` takes terrain as people keep it: files (`.hgt`, `.hgt.gz`, `.zip` of `.hgt`s,
GeoTIFF `.tif`/`.tiff` in any CRS), folders (every such file directly in it) and glob patterns
(`tiles/N4*.hgt`, for a shell that did not expand them); see `terrain_files`.

Tiles must share one sample step (within 1e-6 of a step) and sit on one lattice (their
nodes' offsets are whole steps apart); the merged grid spans the union of their extents.
Where tiles overlap (SRTM tiles repeat their neighbours' edge rows) the first tile's sample
is kept; the largest disagreement is reported when it exceeds 1 m. Nodes no tile covers are
NaN: outside the terrain, and a warning says how much of the rectangle that is.
"""

from __future__ import annotations

import pathlib
from collections.abc import Sequence

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.terrain.grid import Terrain

__all__ = ["TERRAIN_SUFFIXES", "merge_tiles", "read_terrain", "terrain_files"]

#: File names read as terrain (lower case), as a folder is searched for them.
TERRAIN_SUFFIXES = (".hgt", ".hgt.gz", ".hgt.zip", ".zip", ".tif", ".tiff")
_KINDS = "SRTM .hgt (also .hgt.gz, or .zip holding .hgt tiles) or GeoTIFF (.tif, .tiff)"


def _offset(value: float, origin: float, step: float, what: str) -> int:
    k = (value - origin) / step
    if abs(k - round(k)) > 1e-3:
        raise InvalidParameterError(
            "terrain", what, "the tiles' samples are not on one lattice (offset by a "
            f"fraction {k - round(k):+.3f} of a step); resample them to a common grid")
    return round(k)


def _unwrap_antimeridian(tiles: Sequence[Terrain]) -> list[Terrain]:
    """Tiles on both sides of 180 deg (west edge < 0 and east edge near +180) are put on one
    side: the western hemisphere's get longitude + 360 (S17W180 then follows S17E179)."""
    west = min(float(t.lon[0]) for t in tiles)
    east = max(float(t.lon[-1]) for t in tiles)
    if east - west <= 180.0:
        return list(tiles)
    return [Terrain(t.lat, t.lon + 360.0, t.z, t.sources, t.warnings) if t.lon[-1] <= 0.0
            else t for t in tiles]


def merge_tiles(tiles: Sequence[Terrain]) -> Terrain:
    """One `Terrain` holding every tile (see the module docstring)."""
    if not tiles:
        raise InvalidParameterError("terrain", [], "needs at least one tile")
    if len(tiles) == 1:
        return tiles[0]
    tiles = _unwrap_antimeridian(tiles)
    dlat, dlon = tiles[0].dlat, tiles[0].dlon
    for t in tiles[1:]:
        if abs(t.dlat - dlat) > 1e-6 * dlat or abs(t.dlon - dlon) > 1e-6 * dlon:
            raise InvalidParameterError(
                "terrain", (t.sources, t.dlat * 3600, t.dlon * 3600),
                f"tiles must share one sample step ({dlat * 3600:.4g}\" x {dlon * 3600:.4g}\" "
                "in the first); resample them to one resolution")
    south = min(t.lat[0] for t in tiles)
    west = min(t.lon[0] for t in tiles)
    north = max(t.lat[-1] for t in tiles)
    east = max(t.lon[-1] for t in tiles)
    ny = _offset(north, south, dlat, "north edge") + 1
    nx = _offset(east, west, dlon, "east edge") + 1
    z = np.full((ny, nx), np.nan, dtype=np.float32)
    worst = 0.0
    warnings: list[str] = []
    sources: list[str] = []
    for t in tiles:
        i0 = _offset(float(t.lat[0]), south, dlat, f"{t.sources} south edge")
        j0 = _offset(float(t.lon[0]), west, dlon, f"{t.sources} west edge")
        block = z[i0:i0 + t.lat.size, j0:j0 + t.lon.size]
        tz = np.asarray(t.z, dtype=np.float32)
        both = np.isfinite(block) & np.isfinite(tz)
        if both.any():
            worst = max(worst, float(np.max(np.abs(block[both] - tz[both]))))
        z[i0:i0 + t.lat.size, j0:j0 + t.lon.size] = np.where(np.isfinite(block), block, tz)
        warnings += list(t.warnings)
        sources += list(t.sources)
    if worst > 1.0:
        warnings.append(f"overlapping tiles disagree by up to {worst:.1f} m (the first is kept)")
    missing = float(np.isnan(z).mean())
    if missing > 0:
        warnings.append(f"the tiles leave {100 * missing:.3g} % of their bounding rectangle "
                        "uncovered (outside the terrain)")
    lat = south + dlat * np.arange(ny)
    lon = west + dlon * np.arange(nx)
    return Terrain(lat, lon, z, tuple(sources), tuple(warnings))


def _is_terrain_name(name: str) -> bool:
    return name.lower().endswith(TERRAIN_SUFFIXES)


def terrain_files(paths: Sequence[str | pathlib.Path]) -> list[pathlib.Path]:
    """The terrain files `paths` name, each once, in order: a file as given (its kind is
    checked when read), a folder's terrain files (sorted; other files ignored), a glob
    pattern's matches. An empty folder, a pattern matching nothing or a missing file is an
    `InvalidParameterError` naming it."""
    import glob

    out: list[pathlib.Path] = []
    for path in paths:
        p = pathlib.Path(path)
        if p.is_dir():
            found = sorted(f for f in p.iterdir() if f.is_file() and _is_terrain_name(f.name))
            if not found:
                raise InvalidParameterError(
                    str(p), str(p), f"the folder holds no terrain file ({_KINDS})")
        elif p.exists():
            found = [p]
        elif glob.has_magic(str(p)):
            found = sorted(pathlib.Path(f) for f in glob.glob(str(p))
                           if pathlib.Path(f).is_file())
            if not found:
                raise InvalidParameterError(str(p), str(p), "the pattern matches no file")
        else:
            raise InvalidParameterError(str(p), str(p), "no such file or folder")
        out += [f for f in found if f.resolve() not in {g.resolve() for g in out}]
    if not out:
        raise InvalidParameterError("terrain", [], "needs at least one file or folder")
    return out


def read_terrain(paths: Sequence[str | pathlib.Path], *, voids: str = "refuse") -> Terrain:
    """Read terrain files and folders (`terrain_files`) and merge them (`merge_tiles`).

    `voids`: "refuse" (an error naming the file), "nearest" or "linear" (filled, warned).
    """
    from glideplan.terrain.geotiff import read_geotiff
    from glideplan.terrain.hgt import read_hgt_tiles

    tiles = []
    for p in terrain_files(paths):
        name = p.name.lower()
        if name.endswith((".hgt", ".hgt.gz", ".zip")):
            tiles += read_hgt_tiles(p, voids=voids)
        elif name.endswith((".tif", ".tiff")):
            tiles.append(read_geotiff(p, voids=voids))
        else:
            raise InvalidParameterError(str(p), str(p), f"terrain files are {_KINDS}")
    return merge_tiles(tiles)
