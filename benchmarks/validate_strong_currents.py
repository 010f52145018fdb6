"""Validation: routes where the current is stronger than the vehicle (issue 25, part 0).

The claim (`glideplan.routing.extract`): where the current reaches or exceeds the vehicle's
speed, `route()` answers solved (verified through the field) or unreachable with a reason,
never not_verified, and a drift-cone answer comes without a front. Cases:
- the double gyre scaled to 1.0 m/s with a 0.3 m/s vehicle, two crossings (spatially
  varying, time-periodic, currents 3x the vehicle);
- a 0.6 m/s M2 tide with a 0.3 m/s vehicle, 30 km east, departures 0, 3 and 5 h after the
  field's start: against the drift disk's first time (closed form, within h / V);
- a steady 0.5 m/s current: the goal upstream -> outside_drift_cone with no front.
Prints each case and PASS/FAIL (minutes on a loaded 2-core machine).

    .venv/bin/python benchmarks/validate_strong_currents.py
"""

from __future__ import annotations

import math
import sys
import time

import numpy as np

from glideplan.fields import AnalyticField, UniformField, double_gyre
from glideplan.fields.field import Extent
from glideplan.routing import route
from glideplan.routing.sphere import gc_distance

A, V = 0.6, 0.3
OMEGA = 2 * math.pi / (12.42 * 3600.0)


def tide_first_time(d: float, t0: float) -> float:
    """First t - t0 with |d - (D(t) - D(t0))| <= V (t - t0), D = A / w (1 - cos w t)."""
    t = np.arange(t0, t0 + 80 * 3600.0, 1.0)
    drift = A / OMEGA * (np.cos(OMEGA * t0) - np.cos(OMEGA * t))
    ok = np.abs(d - drift) <= V * (t - t0)
    return float(t[int(np.argmax(ok))] - t0)


def main() -> None:
    failed = []
    gyre = double_gyre(max_speed=1.0)
    for a, b in (((30.2, -39.8), (30.6, -38.4)), ((30.7, -38.3), (30.2, -39.7))):
        clock = time.perf_counter()
        r = route(gyre, a, b, V, max_duration=10 * 86400.0)
        ok = r.status in ("solved", "unreachable")
        print(f"double gyre 1.0 m/s {a} -> {b}: {r.status} {r.unreachable_reason or ''} "
              f"{(r.duration_s or 0) / 3600:.2f} h, miss {r.endpoint_error_m} m, {r.method}, "
              f"{time.perf_counter() - clock:.0f} s  {'PASS' if ok else 'FAIL'}")
        if not ok:
            failed.append("gyre")

    def fn(t, lat, lon):
        c = A * np.sin(OMEGA * t) + 0 * lat
        return c, 0 * c

    tide = AnalyticField(fn=fn, extent=Extent(39.5, 41.5, -71.0, -69.0),
                         time_span=(0.0, 72 * 3600.0), name="tide")
    start, goal = (40.5, -70.2), (40.5, -69.84)
    d = float(gc_distance(*start, *goal))
    for depart_h in (0.0, 3.0, 5.0):
        clock = time.perf_counter()
        r = route(tide, start, goal, V, depart=depart_h * 3600.0, cells=80)
        ref = tide_first_time(d, depart_h * 3600.0)
        tol = r.stats["spacing_m"] / V
        ok = r.status == "solved" and abs((r.duration_s or 0) - ref) <= tol
        print(f"tide, depart +{depart_h:g} h: {r.status} {(r.duration_s or 0) / 3600:.4f} h vs "
              f"{ref / 3600:.4f} h exact (tolerance {tol:.0f} s), {r.method}, "
              f"{time.perf_counter() - clock:.0f} s  {'PASS' if ok else 'FAIL'}")
        if not ok:
            failed.append(f"tide {depart_h}")

    clock = time.perf_counter()
    r = route(UniformField(0.5, 0.0), goal, start, V)
    ok = r.unreachable_reason == "outside_drift_cone" and "front_s" not in r.stats
    print(f"steady 0.5 m/s, goal upstream: {r.unreachable_reason}, "
          f"{time.perf_counter() - clock:.3f} s  {'PASS' if ok else 'FAIL'}")
    if not ok:
        failed.append("upstream")
    if failed:
        print("FAIL:", ", ".join(failed))
        sys.exit(1)
    print("PASS")


if __name__ == "__main__":
    main()
