"""A coastal survey through a forecast field: many short legs (issue 28, "missions through a
field at the speed of their legs").

Run: `.venv/bin/python benchmarks/mission_field.py [--legs 1200] [--router-legs 10]`.

Field: a Copernicus-like file at 1/12 deg (39.5-41.5 N, 71-69 W), hourly for 120 days: a
tidal current (M2, <= 0.15 m/s east, <= 0.05 m/s north, varying in space over a few cells),
written to NetCDF and read back with `open_field`. Route: `--legs` legs of 1-5 km (random
bearings, kept inside 40.0-41.0 N, 70.6-69.4 W; seed 28) at 0.5 m/s through the water,
departing at the file's first time.

Measures `plan_mission_in_field` on all the legs (each short leg by Zermelo shooting in its
own cube of field nodes, `missions.field_legs`), and on the first `--router-legs` legs with
the fast path switched off (every leg through `glideplan.routing.route`: window, front,
backtrack, refinement, verification) -- the time per leg before and after, and the largest
difference in leg duration between the two (the answers are the same to within it).
"""

from __future__ import annotations

import argparse
import math
import pathlib
import tempfile
import time

import numpy as np


def write_field(path: pathlib.Path, days: int = 120) -> None:
    from glideplan.fields.synthetic import copernicus_dataset

    lat = np.arange(39.5, 41.5001, 1 / 12)
    lon = np.arange(-71.0, -68.999, 1 / 12)
    t = np.arange(0, days * 86400 + 1, 3600.0)
    times = np.datetime64("2026-01-01T00:00", "ns") + (t * 1e9).astype("timedelta64[ns]")
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ph = 2 * np.pi * t / 44712.0
    u = 0.15 * np.sin(ph)[:, None, None, None] * np.cos((LA - 40) * 3)[None, None]
    v = 0.05 * np.cos(ph)[:, None, None, None] * np.sin((LO + 70) * 2)[None, None]
    copernicus_dataset(lat, lon, times, [0.5], u, v * np.ones_like(u)).to_netcdf(path)


def survey(n: int, seed: int = 28) -> tuple[np.ndarray, np.ndarray]:
    """n legs of 1-5 km with random bearings, bounced to stay inside the survey box."""
    rng = np.random.default_rng(seed)
    lat, lon = [40.5], [-70.0]
    for _ in range(n):
        d = rng.uniform(1000.0, 5000.0)
        b = rng.uniform(0.0, 2 * math.pi)
        la = lat[-1] + math.degrees(d * math.cos(b) / 6_371_008.8)
        lo = lon[-1] + math.degrees(d * math.sin(b) / (6_371_008.8 * math.cos(math.radians(
            lat[-1]))))
        if not 40.0 < la < 41.0:
            la = lat[-1] - (la - lat[-1])
        if not -70.6 < lo < -69.4:
            lo = lon[-1] - (lo - lon[-1])
        lat.append(la)
        lon.append(lo)
    return np.array(lat), np.array(lon)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--legs", type=int, default=1200)
    ap.add_argument("--router-legs", type=int, default=10)
    args = ap.parse_args()
    from glideplan.fields import open_field
    from glideplan.missions import field_legs, plan_mission_in_field
    from glideplan.missions.route import Route

    with tempfile.TemporaryDirectory() as tmp:
        path = pathlib.Path(tmp) / "coast.nc"
        write_field(path)
        fld = open_field(path)
        lat, lon = survey(args.legs)
        route = Route.from_geographic([f"W{i}" for i in range(lat.size)], lat, lon)
        fld.velocity(0.0, 40.5, -70.0)  # build the interpolator (once per field)
        clock = time.perf_counter()
        fast = plan_mission_in_field(route, fld, speed=0.5, progress=True)
        t_fast = time.perf_counter() - clock
        methods = [leg.result.method for leg in fast.legs]
        n_local = sum(m == "zermelo-local" for m in methods)
        for leg in fast.legs:
            if not leg.ok:
                print(f"leg {leg.index + 1}: {leg.result.status}: {leg.result.message}")
        print(f"{len(fast.legs)} legs, status {fast.status}: {t_fast:.1f} s, "
              f"{t_fast / len(fast.legs):.3f} s per leg ({n_local} by local shooting)")
        k = args.router_legs
        if k:
            sub = Route.from_geographic([f"W{i}" for i in range(k + 1)], lat[:k + 1],
                                        lon[:k + 1])
            saved = field_legs.FAST_MAX_DISTANCE_M
            field_legs.FAST_MAX_DISTANCE_M = 0.0  # every leg through the router
            try:
                clock = time.perf_counter()
                slow = plan_mission_in_field(sub, fld, speed=0.5)
                t_slow = time.perf_counter() - clock
            finally:
                field_legs.FAST_MAX_DISTANCE_M = saved
            diff = max(abs(a.duration_s - b.duration_s) / b.duration_s
                       for a, b in zip(fast.legs[:k], slow.legs, strict=True))
            print(f"router on the first {k} legs: {t_slow:.1f} s, {t_slow / k:.3f} s per leg; "
                  f"largest relative duration difference {diff:.2e}")


if __name__ == "__main__":
    main()
