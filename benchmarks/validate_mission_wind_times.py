"""Validation: the mission optimiser's vectorised wind times against the known-wind planner.

`glideplan.missions.wind_costs.convected_times` (scan + batched bisection over many queries)
must give the same minimum arrival time as `glideplan.planners.wind.convected_dubins`
(per-query Brent polishing, the planner `plan()` uses) on random legs of 0-8 turn radii in
three winds (|w| / v = 0.36, 0.6, 0.46). Tolerance 1e-6 relative (both solve to ~1e-12).

Usage: python benchmarks/validate_mission_wind_times.py [--queries N]
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np
from _peers import count, report_peers

from glideplan.missions.wind_costs import convected_times
from glideplan.planners.wind import convected_dubins


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--queries", type=count(1), default=1500, help="queries per wind")
    args = ap.parse_args()
    rng = np.random.default_rng(11)
    m = args.queries
    bad, worst = 0, 0.0
    t_vec = t_ref = 0.0
    for wind in [(0.3, -0.2), (0.0, 0.6), (-0.45, 0.1)]:
        starts = np.zeros((m, 3))
        starts[:, 2] = rng.uniform(-math.pi, math.pi, m)
        dist, bearing = rng.uniform(0.0, 8.0, m), rng.uniform(-math.pi, math.pi, m)
        goals = np.column_stack([dist * np.cos(bearing), dist * np.sin(bearing),
                                 rng.uniform(-math.pi, math.pi, m)])
        t0 = time.process_time()
        got = convected_times(starts, goals, speed=1.0, radius=1.0, wind=wind)
        t_vec += time.process_time() - t0
        t0 = time.process_time()
        for s, g, t in zip(starts, goals, got, strict=True):
            c, sn = math.cos(s[2]), math.sin(s[2])
            local = (c * g[0] + sn * g[1], -sn * g[0] + c * g[1], g[2] - s[2])
            wl = (c * wind[0] + sn * wind[1], -sn * wind[0] + c * wind[1])
            ref = convected_dubins(local, speed=1.0, radius=1.0, wind=wl).time
            err = abs(t - ref) / max(ref, 1e-9)
            worst = max(worst, err)
            bad += err > 1e-6
        t_ref += time.process_time() - t0
    n = 3 * m
    print(f"{n} queries: worst relative difference {worst:.2e}, {bad} above 1e-6: "
          f"{'PASS' if bad == 0 else 'FAIL'}")
    print(f"CPU time: vectorised {1e3 * t_vec / n:.3f} ms/query, planner "
          f"{1e3 * t_ref / n:.3f} ms/query")
    report_peers(["glideplan.planners.wind.convected_dubins (the reference, same process)"],
                 [])
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
