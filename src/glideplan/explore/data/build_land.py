"""Build `land_10m.npz` (the explorer's land and coastline) from Natural Earth's 1:10m land.

Source: the npm package `world-atlas` 2.0.2 (`npm pack world-atlas@2.0.2`), file
`land-10m.json`: Natural Earth 4.1.0 "land" (1:10m physical vectors, public domain) as
TopoJSON, quantized to a 1e5 x 1e5 grid over its bounding box (0.0036 deg of longitude,
0.00169 deg of latitude per step). This script decodes its arcs into rings and stores the
same integer grid: per ring the first point and then the steps (int32, zlib by
`np.savez_compressed`), the rings of each polygon (the outer ring first, then its holes),
and the grid's scale/translate. Nothing is simplified: the package's coast is the file's.

Run: `python src/glideplan/explore/data/build_land.py package/land-10m.json`.
"""

from __future__ import annotations

import json
import pathlib
import sys

import numpy as np


def _arc_points(arcs: list[list[list[int]]], index: int) -> np.ndarray:
    """The absolute quantized points of arc `index` (~index: reversed), as int64 (n, 2)."""
    arc = np.cumsum(np.asarray(arcs[index if index >= 0 else ~index], dtype=np.int64), axis=0)
    return arc if index >= 0 else arc[::-1]


def _ring(arcs: list[list[list[int]]], refs: list[int]) -> np.ndarray:
    """A ring's points from its arc references (each arc's first point is the last one's end)."""
    parts = [_arc_points(arcs, r) for r in refs]
    out = [parts[0]] + [p[1:] for p in parts[1:]]
    return np.concatenate(out)


def build(src: pathlib.Path, dst: pathlib.Path) -> None:
    """Decode `src` (TopoJSON land) and write `dst` (npz, see the module docstring)."""
    topo = json.loads(src.read_text())
    arcs = topo["arcs"]
    geoms = topo["objects"]["land"]["geometries"]
    polygons: list[list[list[int]]] = []
    for g in geoms:
        polygons += g["arcs"] if g["type"] == "MultiPolygon" else [g["arcs"]]
    rings = [_ring(arcs, refs) for poly in polygons for refs in poly]
    ring_len = np.array([len(r) for r in rings], dtype=np.int64)
    first = np.array([r[0] for r in rings], dtype=np.int32)
    steps = np.concatenate([np.diff(r, axis=0) for r in rings]).astype(np.int32)
    poly_rings = np.array([len(p) for p in polygons], dtype=np.int32)
    t = topo["transform"]
    np.savez_compressed(
        dst, first=first, steps=steps, ring_len=ring_len.astype(np.int32),
        poly_rings=poly_rings, scale=np.asarray(t["scale"], dtype=np.float64),
        translate=np.asarray(t["translate"], dtype=np.float64),
    )
    print(f"{len(polygons)} polygons, {len(rings)} rings, {int(ring_len.sum())} points, "
          f"{dst.stat().st_size} bytes")


if __name__ == "__main__":
    build(pathlib.Path(sys.argv[1]), pathlib.Path(__file__).with_name("land_10m.npz"))
