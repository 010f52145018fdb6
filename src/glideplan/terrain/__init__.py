"""Terrain elevation: SRTM `.hgt` and GeoTIFF tiles merged onto one WGS84 lat/lon grid.

`read_terrain(paths)` reads and merges files, folders and globs (`.hgt`, `.hgt.gz`, `.zip` of
`.hgt`s, GeoTIFF in any CRS, reprojected to lat/lon); `Terrain.elevation(lat, lon)` is bilinear;
`Terrain.pooled_max(f)` gives a coarser grid that never understates the terrain of a cell.
"""

from glideplan.terrain.grid import EARTH_RADIUS_M, Terrain
from glideplan.terrain.hgt import read_hgt, read_hgt_tiles, write_hgt
from glideplan.terrain.merge import merge_tiles, read_terrain, terrain_files
from glideplan.terrain.voids import VOID_MODES, fill_voids

__all__ = [
    "EARTH_RADIUS_M",
    "VOID_MODES",
    "Terrain",
    "fill_voids",
    "merge_tiles",
    "read_hgt",
    "read_hgt_tiles",
    "read_terrain",
    "terrain_files",
    "write_hgt",
]
