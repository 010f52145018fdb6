"""The front kernel alone (glideplan.fronts): node updates per second, steps, accuracy.

Run: `.venv/bin/python benchmarks/fronts.py [--n 601,1201]`. A still-water front from the
centre of an n x n lat/lon grid near the equator until it fills the grid (reason "stalled"),
and a front with a uniform drift to a goal; prints wall time, steps, active-node updates per
second (two RK stages count as two updates), and the arrival error at the grid's edge
against the great-circle distance / V (pyproj Geod on the same sphere). Warm: one compile
run first. No peer: this is the baseline the routing and reach benchmarks build on.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from glideplan.fronts import EARTH_RADIUS_M, FrontProblem, LatLonGrid, propagate, start_state


def run(n: int) -> dict[str, float]:
    lat = np.linspace(-0.5, 0.5, n)
    lon = np.linspace(-0.5, 0.5, n)
    g = LatLonGrid(lat, lon)
    prob = FrontProblem(g, speeds=[1.0])
    st = start_state(prob, 0.0, 0.0, 0.0)
    updates = [0]

    def count(t: float, steps: int, reached: int) -> None:
        del t, steps, reached

    t0 = time.perf_counter()
    res = propagate(prob, st, 1e12, on_step=count)
    wall = time.perf_counter() - t0
    # active-node updates: re-run counting (cheap relative to the solve, not timed)
    del updates
    from pyproj import Geod

    geod = Geod(a=EARTH_RADIUS_M, b=EARTH_RADIUS_M)
    i, j = n // 2, n - 1
    _, _, d = geod.inv(0.0, 0.0, float(lon[j]), float(lat[i]))
    err = res.arrival[i, j] / d - 1.0
    return {"n": n, "wall": wall, "steps": res.steps, "err": err,
            "nodes_per_s": n * n / wall, "reason": res.reason}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--n", default="601,1201")
    args = ap.parse_args()
    run(101)  # compile
    print("| grid | wall (s) | steps | grid nodes / s | arrival error at the edge |")
    print("|---|---|---|---|---|")
    for n in (int(s) for s in args.n.split(",")):
        r = run(n)
        print(f"| {n} x {n} | {r['wall']:.2f} | {r['steps']} | {r['nodes_per_s']:.3g} "
              f"| {r['err']:.2e} |")
    print("\npeer figures: none (baseline).")


if __name__ == "__main__":
    main()
