"""A basin-scale transect: 2,500 km through a 1/12 deg Copernicus-like field (issue 18).

Run: `.venv/bin/python benchmarks/route_basin.py [--speed 0.5] [--halvings 2]`.

Field: `glideplan.fields.synthetic.basin_dataset()` -- 260 x 500 nodes at 1/12 deg (20-41.6 N,
70-28.4 W), 13 levels 10 days apart, a meandering jet and westward waves (<= 0.48 m/s),
written to NetCDF and read back with `open_field` like a downloaded product. Route: from
24.0 N 66.0 W to 36.0 N 42.5 W (the geodesic distance is printed; ~2,500 km) at `--speed`
m/s through the water, departing at the file's first time.

Target (issue 18): the whole route <= 60 s on 2 cores, arrival within 0.5 % of the
converged answer. The converged answer: the same route at the spacing halved `--halvings`
times (each verified: its heading controls flown through the field end within the
tolerance); the table shows how the arrival changes as the spacing halves.
"""

from __future__ import annotations

import argparse
import pathlib
import tempfile
import time

from glideplan.fields.io import open_field
from glideplan.fields.synthetic import basin_dataset
from glideplan.routing import route

START = (24.0, -66.0)
GOAL = (36.0, -42.5)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--speed", type=float, default=0.5, help="through-water speed (m/s)")
    ap.add_argument("--halvings", type=int, default=2, help="reference: spacing halved N times")
    ap.add_argument("--spacing", type=float, default=None,
                    help="routing spacing (m); default: the router's own choice")
    args = ap.parse_args()
    from pyproj import Geod

    _, _, dist = Geod(ellps="WGS84").inv(START[1], START[0], GOAL[1], GOAL[0])
    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "basin.nc"
        basin_dataset().to_netcdf(path)
        t0 = time.perf_counter()
        field = open_field(path)
        t_read = time.perf_counter() - t0
    print(f"# Basin transect: {dist / 1e3:.0f} km geodesic, {args.speed} m/s\n")
    print(f"read the 260 x 500 x 13 file: {t_read:.2f} s\n")
    print("| spacing (m) | status | arrival (days) | wall (s) | change vs previous |")
    print("|---|---|---|---|---|")
    spacing = args.spacing
    prev = None
    rows = []
    for k in range(args.halvings + 1):
        t0 = time.perf_counter()
        r = route(field, START, GOAL, args.speed, resolution=spacing)
        wall = time.perf_counter() - t0
        h = float(r.stats.get("spacing_m", spacing or 0.0))
        T = r.duration_s
        change = "" if prev is None or T is None else f"{T / prev - 1:+.3%}"
        print(f"| {h:.0f} | {r.status} | {T / 86400 if T else float('nan'):.3f} | {wall:.1f} "
              f"| {change} |")
        rows.append((h, T, wall))
        prev = T
        spacing = h / 2.0
        del k
    h0, T0, wall0 = rows[0]
    Tref = rows[-1][1]
    if T0 and Tref:
        print(f"\nfirst spacing {h0:.0f} m: {wall0:.1f} s (target <= 60 s), arrival "
              f"{abs(T0 / Tref - 1):.3%} from the finest ({rows[-1][0]:.0f} m; target <= 0.5 %)")
    print("\npeer figures: none (targets from issue 18).")


if __name__ == "__main__":
    main()
