"""Several DEM tiles on one lat/lon grid: `merge_tiles`, and `read_terrain` for a file list.

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

__all__ = ["merge_tiles", "read_terrain"]


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


def read_terrain(paths: Sequence[str | pathlib.Path], *, voids: str = "refuse") -> Terrain:
    """Read `.hgt` and GeoTIFF (`.tif`, `.tiff`) files and merge them (`merge_tiles`)."""
    from glideplan.terrain.geotiff import read_geotiff
    from glideplan.terrain.hgt import read_hgt

    tiles = []
    for path in paths:
        p = pathlib.Path(path)
        suffix = p.suffix.lower()
        if suffix == ".hgt":
            tiles.append(read_hgt(p, voids=voids))
        elif suffix in (".tif", ".tiff"):
            tiles.append(read_geotiff(p, voids=voids))
        else:
            raise InvalidParameterError(
                str(p), str(p), "terrain files are SRTM .hgt or GeoTIFF (.tif, .tiff)")
    return merge_tiles(tiles)
