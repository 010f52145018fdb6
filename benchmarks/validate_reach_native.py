"""Validation: the glide reach at the DEM's own resolution (issue 24) on bigger cases than the
unit tests.

1. Rough synthetic range (valleys, gaps, cols; 260 x 260 nodes at 92.6 m, wind 6 m/s):
   `glide_reach`'s footprint nodes against the independent reference search of the tests
   (tests/reach/native_reference.py: heapq Dijkstra, 32-neighbour stencil, its own
   overestimate `reference_error`: 1.3 % in still air, more in wind): area difference
   (budget 3 %) and nodes in the footprint the reference cannot reach even with its loss
   deflated by its own error (budget 0).
2. The benchmark's alpine SRTM3 tile (benchmarks/glide_reach.py): on 24 bearings the straight
   glide from the start, flown with the polar (`reach.flight.fly`, the en-route clearance,
   arriving with the arrival height above the terrain), against the drawn footprint along the
   same ray: bearings where the polygon stops more than one DEM cell short of the verified
   straight glide (issue: 21 of 24, 0.4-3.3 km short).

Usage: python benchmarks/validate_reach_native.py
"""

from __future__ import annotations

import math
import pathlib
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "tests" / "reach"))
sys.path.insert(0, str(HERE))


def rough_range() -> tuple[object, tuple[float, float, float]]:
    """Valleys, ridges with gaps and cols: sums of ridged sinusoids, 260 x 260 at 92.6 m."""
    from glideplan.terrain.grid import Terrain

    n = 260
    dlat = 3 / 3600
    dlon = dlat / math.cos(math.radians(46.0))
    lat = 46.0 + dlat * np.arange(n)
    lon = 7.0 + dlon * np.arange(n)
    y, x = np.meshgrid(np.arange(n) * 0.0926, np.arange(n) * 0.0926, indexing="ij")  # km
    ridges = np.abs(np.sin(0.45 * x + 0.2 * y)) ** 0.5 * 700
    gaps = 1 - 0.6 * np.exp(-((np.sin(0.9 * y + 0.3 * x)) ** 2) / 0.02)
    z = 500 + ridges * gaps + 120 * np.sin(1.7 * x) * np.cos(1.3 * y)
    start = (float(lat[n // 2]), float(lon[n // 2]), 1500.0)
    return Terrain(lat, lon, z.astype(np.float32)), start


def check_rough(polar) -> bool:
    from native_reference import reference_error, reference_loss

    from glideplan.reach import Glide, glide_reach

    t, start = rough_range()
    wind = (4.0, 4.5)
    t0 = time.perf_counter()
    r = glide_reach(t, start, polar, wind=wind, terrain_clearance=150, arrival_height=300)
    t_ours = time.perf_counter() - t0
    t0 = time.perf_counter()
    ref = reference_loss(t, start, Glide(polar, 0.0, wind), 150.0)
    err = reference_error(Glide(polar, 0.0, wind))
    t_ref = time.perf_counter() - t0
    z = np.asarray(t.z, dtype=float)
    alt = start[2]
    if r.margin.shape != ref.shape:
        print(f"  grid shapes differ: {r.margin.shape} vs {ref.shape}")
        return False
    ours = r.margin >= 0
    theirs = alt - ref - z - 300 >= 0
    generous = alt - ref / (1 + err) - z - 300 >= 0
    diff = (ours.sum() - theirs.sum()) / theirs.sum()
    beyond = int(np.sum(ours & ~generous))
    ok = abs(diff) <= 0.03 and beyond == 0
    print(f"  rough range 260x260 at 92.6 m: footprint {ours.sum()} nodes, reference "
          f"{theirs.sum()} ({100 * diff:+.2f} %, budget 3 %); beyond the reference "
          f"{beyond} nodes (budget 0; reference error {100 * err:.2f} %); glide_reach "
          f"{t_ours:.2f} s, reference {t_ref:.1f} s: "
          f"{'PASS' if ok else 'FAIL'}")
    return ok


def check_straight(polar) -> bool:
    import glide_reach as bench
    from matplotlib.path import Path

    from glideplan.geodesy import rhumb_destination as destination
    from glideplan.reach import Glide, glide_reach
    from glideplan.reach.flight import fly
    from glideplan.terrain.grid import Terrain
    from glideplan.units import wind_from_compass

    n = 1201
    lat = 46.0 + np.arange(n) / (n - 1)
    lon = 7.0 + np.arange(n) / (n - 1)
    t = Terrain(lat, lon, bench.relief(n).astype(np.float32))
    wind = wind_from_compass(*bench.WIND)
    r = glide_reach(t, bench.START, polar, wind=wind, terrain_clearance=150,
                    arrival_height=300)
    g = Glide(polar, wind=wind)
    lat0, lon0, alt = bench.START
    paths = [Path(poly[0]) for poly in r.footprint]
    short = []
    cell = r.resolution_m
    for brg in np.arange(0.0, 360.0, 15.0):
        chi = math.radians(90.0 - brg)
        rr = float(g.ratio(np.array([chi]))[0])
        s = np.arange(cell, 120e3, cell / 2)
        la, lo = destination(lat0, lon0, chi, s)
        zz = t.elevation(la, lo)
        h = alt - s / rr
        ok = (h - zz >= 150) & (h - zz >= 300)
        if not ok[0]:
            continue
        last = int(np.argmin(ok)) - 1 if not ok.all() else s.size - 1
        s_ok = float(s[last])
        f = fly(g, t, 150.0, np.array([lat0, la[last]]), np.array([lon0, lo[last]]), alt)
        if not (f.clear and f.arrival_altitude - float(zz[last]) >= 300 - 1e-6):
            continue
        inside = [any(p.contains_point((b, a)) for p in paths) for a, b in zip(la, lo,
                                                                                strict=True)]
        far = float(s[np.flatnonzero(inside)[-1]]) if any(inside) else 0.0
        if far < s_ok - cell:
            short.append((brg, (s_ok - far) / 1000))
    ok = not short
    print(f"  alpine SRTM3 tile, 24 bearings: polygon short of the verified straight glide "
          f"by > 1 cell on {len(short)} bearing(s)"
          + (f" (max {max(d for _, d in short):.2f} km)" if short else "")
          + f": {'PASS' if ok else 'FAIL'}")
    return ok


def main() -> int:
    from glideplan.sailplane import polar_from_file, read_plr

    polar = polar_from_file(read_plr(HERE.parent / "tests" / "data" / "polars"
                                     / "DG-1001M_ch5.plr"))
    print("glide reach at the DEM's resolution (issue 24):")
    ok = check_rough(polar)
    ok = check_straight(polar) and ok
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
