"""Benchmark: time-optimal planning in a steady wind (convected Dubins), time per query.

The issue's budget: median at most 2 ms per query (the author's C++ ConvectedDubins takes
about 9 ms for airspeed 1, R = 1, wind 0.3). Measured: the solver alone (all six words'
arrival times), `plan()` without and with verification by integration (A.4).

Usage: python benchmarks/wind.py [--queries N]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from _peers import Quoted, count, report_peers

from glideplan import DubinsCarInWind, Pose, plan
from glideplan.planners.wind import convected_dubins

CPP_QUOTE = Quoted(
    "the author's C++ ConvectedDubins, time per query (airspeed 1, R = 1, wind 0.3)",
    "about 9 ms",
    "the issue that asked for the wind planner (issue 7; not re-run: the library is not "
    "installed here)",
    "quoted 2026-11-22, commit 9181686",
)


def _median_ms(fn, goals) -> float:
    times = []
    for g in goals:
        t0 = time.perf_counter()
        fn(g)
        times.append(time.perf_counter() - t0)
    return 1e3 * float(np.median(times))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--queries", type=count(1), default=2000)
    args = ap.parse_args()
    rng = np.random.default_rng(0)
    n = args.queries
    goals = np.column_stack([rng.uniform(-4, 4, (n, 2)), rng.uniform(-math.pi, math.pi, n)])
    vehicle = DubinsCarInWind(speed=1.0, turn_radius=1.0, wind=(0.3, 0.0))
    start = Pose(0.0, 0.0, 0.0)
    sol = plan(start, Pose(3.0, 3.0, math.pi / 2), vehicle)
    print(
        f"example (3, 3, pi/2), w = 0.3 +x: T* = {sol.cost:.5f} ({sol.word}), "
        f"endpoint error {sol.endpoint_error.max:.1e}"
    )
    for _ in range(50):  # warm up
        plan(start, Pose(*goals[0]), vehicle, verify=False)
    core = _median_ms(lambda g: convected_dubins(g, speed=1.0, radius=1.0, wind=(0.3, 0.0)), goals)
    planner = _median_ms(lambda g: plan(start, Pose(*g), vehicle, verify=False), goals)
    verified = _median_ms(lambda g: plan(start, Pose(*g), vehicle), goals[: max(1, n // 10)])
    print(f"median per query over {n} random goals in [-4, 4]^2 (R = 1, v = 1, w = 0.3):")
    print(f"  solver (six words' times)        {core:6.3f} ms")
    print(f"  plan(verify=False) (with paths)  {planner:6.3f} ms   budget 2 ms")
    print(f"  plan() verified by integration   {verified:6.3f} ms")
    report_peers([], [CPP_QUOTE])


if __name__ == "__main__":
    main()
