"""A 20-member ensemble of a 300 km route, end to end from the CLI (issue 25 part 3).

Run: `.venv/bin/python benchmarks/route_ensemble.py [--members 20] [--workers 2]`.

Members: Copernicus-like NetCDF files (`glideplan.fields.synthetic.copernicus_dataset`) on one
1/12 deg grid (36-42 N, 22-14 W), 6-hourly for 12 days: a uniform eastward drift of 0.10 m/s
plus a field of eddies (amplitude 0.25 m/s, 60 km scale) drifting west, each member with its
own eddy phase and drift strength (a forecast ensemble's spread). Route: 39 N 21 W to
39 N 17.53 W (~300 km) at 0.5 m/s. The command timed is exactly what a user runs:

    glideplan route --ensemble 'DIR/member_*.nc' --from 39 -21 --to 39 -17.53 --speed 0.5
        --workers W --json

(member routes in W local processes; then statistics, corridor, and the closed loop of every
solved member route through every member). Target: <= 30 s on this 2-core machine.
"""

from __future__ import annotations

import argparse
import json
import os
import pathlib
import resource
import subprocess
import sys
import tempfile
import time

import numpy as np

START, GOAL = (39.0, -21.0), (39.0, -17.53)


def write_members(folder: pathlib.Path, n: int, seed: int = 1) -> None:
    """n member files with their own eddy phases and drift (module docstring)."""
    from glideplan.fields.synthetic import copernicus_dataset

    rng = np.random.default_rng(seed)
    lat = np.arange(36.0, 42.0 + 1e-9, 1 / 12)
    lon = np.arange(-22.0, -14.0 + 1e-9, 1 / 12)
    times = np.datetime64("2026-03-01T00") + np.arange(49) * np.timedelta64(6, "h")
    ts = ((times - times[0]) / np.timedelta64(1, "s"))[:, None, None]
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    k = 2 * np.pi / 1.1  # one eddy every ~1.1 deg (~60 km radius)
    for m in range(n):
        px, py = rng.uniform(0, 2 * np.pi, 2)
        drift = 0.10 + 0.05 * rng.standard_normal()
        c = k * 0.02 / (111e3 * np.cos(np.radians(39.0)))  # eddies drift west at 0.02 m/s
        phase_x = k * lo[None] + px + c * ts
        phase_y = k * la[None] + py
        u = drift + 0.25 * np.sin(phase_x) * np.cos(phase_y)
        v = -0.25 * np.cos(phase_x) * np.sin(phase_y)
        copernicus_dataset(lat, lon, times, [0.494], u[:, None], v[:, None]).to_netcdf(
            folder / f"member_{m:02d}.nc")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--members", type=int, default=20)
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    exe = pathlib.Path(sys.executable).with_name("glideplan")
    with tempfile.TemporaryDirectory() as tmp:
        folder = pathlib.Path(tmp)
        write_members(folder, args.members)
        load = os.getloadavg()[0]
        cmd = [str(exe), "route", "--ensemble", str(folder / "member_*.nc"), "--from",
               *map(str, START), "--to", *map(str, GOAL), "--speed", "0.5", "--workers",
               str(args.workers), "--json"]
        t0 = time.perf_counter()
        c0 = resource.getrusage(resource.RUSAGE_CHILDREN)
        proc = subprocess.run(cmd, capture_output=True, text=True, check=False)
        wall = time.perf_counter() - t0
        c1 = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (c1.ru_utime - c0.ru_utime) + (c1.ru_stime - c0.ru_stime)
    if proc.returncode not in (0, 1):
        print(proc.stderr)
        sys.exit(1)
    out = json.loads(proc.stdout)
    e = out["ensemble"]
    print(f"# {args.members}-member ensemble, {out['distance_m'] / 1e3:.0f} km route, "
          f"{args.workers} workers (1-min load average before: {load:.1f})\n")
    print("| members | wall (s) | CPU (s) | p_arrival | P10 (h) | P50 (h) | P90 (h) | chosen "
          "| its p |")
    print("|---|---|---|---|---|---|---|---|---|")
    c = e["chosen"] or {}
    fmt = lambda v: "n/a" if v is None else f"{v:.1f}"  # noqa: E731
    print(f"| {e['members']} | {wall:.1f} | {cpu:.1f} | {e['p_arrival']:.2f} | {fmt(e['p10_h'])} | "
          f"{fmt(e['p50_h'])} | {fmt(e['p90_h'])} | {c.get('member')} | "
          f"{c.get('p_arrival', float('nan')):.2f} |")
    print(f"\ntarget <= 30 s: {'met' if wall <= 30 else 'NOT met'} at this load; the CPU "
          f"seconds over {args.workers} cores: >= {cpu / args.workers:.1f} s on an idle machine")


if __name__ == "__main__":
    main()
