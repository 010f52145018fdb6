"""Routes round a 1 km land mask of a coastline (issue 24): time and accuracy, before and after.

Run: `.venv/bin/python benchmarks/route_coast.py [--quick]`. Prints a Markdown table.

The field: still water on a 1 km (0.009 deg) grid near the equator, 160 x 120 km, with a
coastline built here (seeded): a wavy south coast, a long narrow peninsula with a hooked
tip, a chain of islands off it. Three routes: round the peninsula, across the island chain,
along the coast. For each, in one process, interleaved (best of `REPEATS`):

- "main": today's default route (commit 3025bce's behaviour, reproduced by switching
  `glideplan.routing.coast` off: the clearance one cell's diagonal plus one grid spacing,
  the front's obstacles at it, the grid route pulled taut among the front's nodes);
- "coast": the default route now: the clearance one cell's diagonal kept at the mask's
  resolution (the taut path among the land nodes' clearance disks, `routing.coast`).

Columns: wall time, status, duration, the least distance of the track to a land node
against the clearance (checked on the mask itself), and the ratio of times. The target:
coast <= 1.5 x main. Timings on a shared 2-core machine: under load, say so.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import tempfile
import time
from typing import Any

import numpy as np

R = 6_371_008.8
KM = 1000.0
DX = 1000.0
REPEATS = 2


def coastline() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(lat, lon, land) of the 1 km mask (module docstring)."""
    rng = np.random.default_rng(24)
    lat = np.degrees(np.arange(121) * DX / R)
    lon = np.degrees(np.arange(161) * DX / R)
    X, Y = np.meshgrid(np.radians(lon) * R / KM, np.radians(lat) * R / KM)
    coast = 25.0 + sum(a * np.sin(2 * np.pi * X / w + p) for a, w, p in zip(
        rng.uniform(1, 4, 6), rng.uniform(8, 60, 6), rng.uniform(0, 6.3, 6), strict=True))
    land = Y < coast
    # a peninsula 6 km wide to y = 85 km, hooked east at its tip
    land |= (np.abs(X - 70) < 3) & (Y < 85)
    land |= (X > 70) & (X < 88) & (Y > 80) & (Y < 85)
    land |= (X > 84) & (X < 88) & (Y > 70) & (Y < 85)
    for cx, cy, r in ((110, 60, 3.5), (118, 66, 2.5), (125, 72, 3.0), (40, 70, 4.0)):
        land |= np.hypot(X - cx, Y - cy) < r
    return lat, lon, land


ROUTES = {
    "round the peninsula": ((50.0, 60.0), (80.0, 72.0)),
    "across the islands": ((100.0, 45.0), (135.0, 95.0)),
    "along the coast": ((10.0, 40.0), (150.0, 40.0)),
}


def _ll(p: tuple[float, float]) -> tuple[float, float]:
    return math.degrees(p[1] * KM / R), math.degrees(p[0] * KM / R)


def _least_distance(r: Any, lat: np.ndarray, lon: np.ndarray, land: np.ndarray) -> float:
    from glideplan.routing.coast import _unit, clearance_of

    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    return clearance_of(np.asarray(r.lat), np.asarray(r.lon),
                        _unit(LA[land], LO[land]) * R, 20.0)


def _main_behaviour(on: bool) -> Any:
    """Switch `routing.coast` off (main's behaviour) or back on; returns the restorer."""
    from glideplan.routing import coast

    saved = (coast.applies, coast.round_coast)
    if on:
        coast.applies = lambda *a, **k: False  # type: ignore[assignment]
        coast.round_coast = lambda *a, **k: None  # type: ignore[assignment]

    def restore() -> None:
        coast.applies, coast.round_coast = saved

    return restore


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="one route, one repeat")
    args = ap.parse_args()
    from glideplan.fields import open_field
    from glideplan.fields.synthetic import copernicus_dataset
    from glideplan.routing import route

    lat, lon, land = coastline()
    tmp = pathlib.Path(tempfile.mkdtemp())
    path = tmp / "coast.nc"
    u = np.where(land, np.nan, 0.0)[None, None]
    copernicus_dataset(lat, lon, [np.datetime64("2026-01-01T00:00", "ns")], [0.5], u,
                       u).to_netcdf(path)
    fld = open_field(path)
    route(fld, _ll((50, 60)), _ll((52, 62)), 1.0)  # compile the kernels
    names = list(ROUTES)[:1] if args.quick else list(ROUTES)
    repeats = 1 if args.quick else REPEATS
    print(f"# Routes round a 1 km coastline mask ({land.sum()} land nodes, 160 x 120 km)\n")
    print("| route | variant | wall s | status | duration h | clearance m | least distance "
          "to land m | coast / main time |")
    print("|---|---|---|---|---|---|---|---|")
    for name in names:
        a, b = ROUTES[name]
        best: dict[str, tuple[float, Any]] = {}
        for _ in range(repeats):
            for variant in ("main", "coast"):
                restore = _main_behaviour(variant == "main")
                try:
                    t = time.perf_counter()
                    r = route(fld, _ll(a), _ll(b), 1.0)
                    el = time.perf_counter() - t
                finally:
                    restore()
                if variant not in best or el < best[variant][0]:
                    best[variant] = (el, r)
        for variant in ("main", "coast"):
            el, r = best[variant]
            ratio = f"{el / best['main'][0]:.2f}" if variant == "coast" else ""
            dur = f"{r.duration_s / 3600:.3f}" if r.duration_s else "-"
            near = _least_distance(r, lat, lon, land) if r.lat is not None else math.nan
            print(f"| {name} | {variant} | {el:.2f} | {r.status} | {dur} | "
                  f"{r.land_clearance_m:.0f} | {near:.0f} | {ratio} |")
    print("\nPeer figures: none (main's behaviour, measured in the same run).")


if __name__ == "__main__":
    main()
