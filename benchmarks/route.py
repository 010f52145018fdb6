"""Benchmarks of `glideplan.routing` (issue 12): speed, scaling, convergence, A*, sweeps.

Run: `.venv/bin/python benchmarks/route.py [--quick] [--phases]`. Prints Markdown tables:

1. a 300 x 300 routing grid through a field with 48 time levels (target <= 20 s, one core);
2. scaling over 100^2, 200^2, 300^2, 400^2 grids, and the convergence of the arrival time
   when the grid spacing halves (grid and refined times);
3. the grid A* baseline with crab-angle kinematics (`grid_astar.py`) on the same grids:
   arrival time and run time side by side;
4. a sweep of 48 departure times through `glideplan.run_batch` (processes);
5. (`--phases`, issue 18) seconds per phase of `route()` (setup, grid, front, backtrack,
   refine, verify) and the error against closed forms on the sphere: still-water transects
   (D / V), a tailwind along the equator (D / (V + W)), an island (tangent-arc-tangent round
   the clearance circle), a linear shear current (Zermelo's extremal), the double gyre at
   1 km and 500 m.

The field: the time-periodic double gyre (L = 150 km, max 0.4 m/s, period ~9.1 days)
sampled onto a 0.02-degree grid with 48 levels, 3 hours apart (6 days), as a GriddedField —
what a forecast file gives. Vehicle: 0.5 m/s through the water.
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import time
from typing import Any

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).parent))

from grid_astar import grid_astar

from glideplan.fields import GriddedField, double_gyre
from glideplan.geodesy import LocalProjection
from glideplan.routing import route
from glideplan.routing.grid import CurrentSampler, build_grid  # the plane A* baseline

SPEED = 0.5
START = (30.25, -39.75)
GOAL = (31.05, -38.82)
LEVELS = 48
STEP_S = 3 * 3600.0


def gridded_gyre() -> GriddedField:
    """The analytic double gyre sampled like a forecast file: 48 levels, 0.02 degrees."""
    g = double_gyre(length_m=150_000.0, max_speed=0.4)
    lat = np.arange(29.5, 32.0001, 0.02)
    lon = np.arange(-41.0, -37.0001, 0.02)
    times = np.arange(LEVELS) * STEP_S
    T, LA, LO = np.meshgrid(times, lat, lon, indexing="ij")
    u, v = g.fn(T, LA, LO)
    return GriddedField(times=np.asarray(times, dtype=float), lat=lat, lon=lon,
                        u=np.asarray(u), v=np.asarray(v),
                        epoch=g.epoch, info={"kind": "gridded", "source": "double gyre x48"})


def one_route(cells: int, field: GriddedField, depart: float = 0.0) -> dict[str, Any]:
    t = time.perf_counter()
    c0 = time.process_time()
    r = route(field, START, GOAL, SPEED, depart=depart, cells=cells)
    wall = time.perf_counter() - t
    cpu = time.process_time() - c0
    n = r.stats["grid_nodes"]
    return {"cells": cells, "cpu": cpu, "nodes": n[0] * n[1],
            "shape": r.stats["grid_nodes"], "spacing": r.stats["spacing_m"], "wall": wall,
            "front": r.stats["front_s"], "grid_T": r.grid_duration_s or math.nan,
            "T": r.duration_s or math.nan, "method": r.method, "err": r.endpoint_error_m,
            "straight": r.straight_line_duration_s}


def astar_on(cells: int, field: GriddedField) -> tuple[float | None, float]:
    proj = LocalProjection(*START)
    gx, gy = (float(a) for a in proj.to_local(*GOAL))
    grid = build_grid(field, proj, (gx, gy), None, cells=cells)
    sampler = CurrentSampler.for_span(grid, field, 0.0, field.times[-1], 3600.0)
    res = grid_astar(grid, sampler, SPEED, 0.0, (gx, gy))
    return res.arrival_s, res.run_s


def _sweep_item(depart: float) -> float | None:
    field = _FIELD if _FIELD is not None else gridded_gyre()
    return route(field, START, GOAL, SPEED, depart=depart, cells=120).duration_s


_FIELD: GriddedField | None = None


def _phase_row(name: str, r: Any, ref: float | None, wall: float) -> str:
    s = r.stats
    ph = [s.get(k, 0.0) for k in ("setup_s", "grid_s", "front_s", "backtrack_s")]
    refine = s.get("refine_s", 0.0)
    verify = s.get("verify_refined_s", 0.0) + s.get("verify_grid_s", 0.0)
    err = "" if ref is None or r.duration_s is None else f"{r.duration_s / ref - 1:+.2e}"
    gerr = "" if ref is None or r.grid_duration_s is None else \
        f"{r.grid_duration_s / ref - 1:+.2e}"
    return (f"| {name} | {r.status.value} | {s['grid_nodes'][0]}x{s['grid_nodes'][1]} | "
            f"{s['spacing_m']:.0f} | {s.get('window_growths', 0)} | "
            + " | ".join(f"{x:.2f}" for x in ph) + f" | {refine:.2f} | {verify:.2f} | "
            f"{wall:.2f} | {r.method} | {gerr} | {err} | {r.endpoint_error_m or 0:.2g} |")


def phases() -> None:
    """Section 5 (module docstring)."""
    from glideplan.fields import AnalyticField, Extent, UniformField
    from glideplan.routing.sphere import EARTH_RADIUS_M, gc_distance

    print("## 5. Phases (s) and closed forms on the sphere (issue 18)\n")
    print("| case | status | grid | h (m) | growths | setup | grid | front | backtrack | "
          "refine | verify | whole (s) | method | grid T err | T err | endpoint (m) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")

    def run(name: str, field: Any, a: Any, b: Any, v: float, ref: float | None,
            **kw: Any) -> None:
        t = time.perf_counter()
        r = route(field, a, b, v, **kw)
        print(_phase_row(name, r, ref, time.perf_counter() - t), flush=True)

    still = UniformField(0.0, 0.0)
    for a, b, v in (((30.0, -40.0), (30.5, -39.5), 1.0), ((20.0, -60.0), (40.0, -20.0), 1.0),
                    ((10.0, 175.0), (12.0, -170.0), 25.0)):
        d = float(gc_distance(*a, *b))
        run(f"still water {d / 1000:.0f} km", still, a, b, v, d / v)
    d = float(gc_distance(0.0, -5.0, 0.0, 5.0))
    run("tailwind 10 m/s, equator", UniformField(10.0, 0.0), (0.0, -5.0), (0.0, 5.0), 25.0,
        d / 35.0)
    s_shear, R = 1e-5, EARTH_RADIUS_M
    shear = AnalyticField(fn=lambda t, la, lo: (s_shear * R * np.radians(la), 0.0 * la),
                          extent=Extent(-1.0, 1.0, 9.0, 11.0), name="shear")
    run("linear shear (ref 129655.81 s)", shear, (-0.1, 10.0), (0.1, 10.3), 0.3, 129655.81)
    field = gridded_gyre()
    for h in (1000.0, 500.0):
        run(f"double gyre x48, {h:.0f} m", field, START, GOAL, SPEED, None, resolution=h)
    print()


def main() -> None:
    global _FIELD
    ap = argparse.ArgumentParser()
    ap.add_argument("--quick", action="store_true", help="skip 400^2 and the A* on 300^2+")
    ap.add_argument("--phases", action="store_true", help="only section 5 (issue 18)")
    args = ap.parse_args()
    if args.phases:
        phases()
        return
    field = gridded_gyre()
    _FIELD = field
    print("Machine shared with other jobs: wall times are inflated.\n")

    print("## 1-2. Scaling and convergence (48 time levels; V = 0.5 m/s)\n")
    print("| cells | grid | spacing (m) | route CPU (s) | route wall (s) | front wall (s) | "
          "grid T (h) | refined T (h) | method | endpoint err (m) | dT grid vs previous (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    rows: list[dict[str, Any]] = []
    for cells in ([100, 200, 300] if args.quick else [100, 200, 300, 400]):
        row = one_route(cells, field)
        prev = rows[-1]["grid_T"] if rows else math.nan
        rows.append(row)
        print(f"| {cells} | {row['shape'][0]}x{row['shape'][1]} | {row['spacing']:.0f} | "
              f"{row['cpu']:.2f} | {row['wall']:.2f} | {row['front']:.2f} | "
              f"{row['grid_T'] / 3600:.4f} | "
              f"{row['T'] / 3600:.4f} | {row['method']} | {row['err']:.1f} | "
              f"{row['grid_T'] - prev:+.0f} |")
    straight = rows[-1]["straight"]
    print(f"\nStraight line with crab angle: "
          f"{'n/a' if straight is None else f'{straight / 3600:.4f} h'}\n")

    print("## Halving the spacing (convergence)\n")
    print("| cells | spacing (m) | grid T (h) | |change| (s) | refined T (h) |")
    print("|---|---|---|---|---|")
    prev_T = None
    for cells in (75, 150, 300):
        row = one_route(cells, field)
        change = "" if prev_T is None else f"{abs(row['grid_T'] - prev_T):.0f}"
        prev_T = row["grid_T"]
        print(f"| {cells} | {row['spacing']:.0f} | {row['grid_T'] / 3600:.4f} | {change} | "
              f"{row['T'] / 3600:.4f} |")

    print("\n## 3. Grid A* baseline (16-connected, crab-angle edge times) vs front propagation\n")
    print("| cells | A* arrival (h) | A* CPU (s) | front grid T (h) | refined T (h) | "
          "route CPU (s) |")
    print("|---|---|---|---|---|---|")
    for row in rows:
        if args.quick and row["cells"] > 200:
            continue
        arr, run_s = astar_on(row["cells"], field)
        print(f"| {row['cells']} | {'n/a' if arr is None else f'{arr / 3600:.4f}'} | "
              f"{run_s:.2f} | {row['grid_T'] / 3600:.4f} | {row['T'] / 3600:.4f} | "
              f"{row['cpu']:.2f} |")

    print("\n## 4. 48 departure times through run_batch (processes=2, 120-cell grids)\n")
    from glideplan import run_batch

    departs = list(np.linspace(0.0, 2.0 * 86400.0, 48))
    t = time.perf_counter()
    out = run_batch(_sweep_item, departs, processes=2, progress=False)
    wall = time.perf_counter() - t
    durs = np.array([np.nan if d is None else d for d in out]) / 3600.0
    print(f"48 routes in {wall:.1f} s wall ({wall / 48:.2f} s per route on 2 processes); "
          f"duration {np.nanmin(durs):.2f} .. {np.nanmax(durs):.2f} h, best departure "
          f"+{departs[int(np.nanargmin(durs))] / 3600:.1f} h; unreachable: "
          f"{int(np.isnan(durs).sum())}")


if __name__ == "__main__":
    main()
