"""Synthesis time per goal for minimum altitude loss (chapter 5 planner), one core.

Random goals uniform in the disc of radius 4 R_stf with uniform headings (DG-1001M). Times
`synthesize` (every candidate of the sufficient set, paths built) per goal after a warm-up.
Targets (issue 5): median <= 50 ms and p99 <= 500 ms over 200 goals.

    .venv/bin/python benchmarks/min_altitude.py [--n 200] [--seed 0]
"""

from __future__ import annotations

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_var] = "1"

import argparse  # noqa: E402
import collections  # noqa: E402
import math  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402
from _peers import count, report_peers  # noqa: E402

from glideplan.planners.min_altitude import synthesize  # noqa: E402
from glideplan.pose import Pose  # noqa: E402
from glideplan.vehicles import dg1001m  # noqa: E402


def random_goals(n: int, seed: int, radius: float) -> list[Pose]:
    """Goals uniform in the disc of `radius` (m) with headings uniform in [-pi, pi)."""
    rng = np.random.default_rng(seed)
    r = radius * np.sqrt(rng.uniform(size=n))
    a = rng.uniform(0.0, 2 * math.pi, n)
    h = rng.uniform(-math.pi, math.pi, n)
    return [Pose(float(ri * math.cos(ai)), float(ri * math.sin(ai)), float(hi))
            for ri, ai, hi in zip(r, a, h, strict=True)]  # fmt: skip


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=count(1), default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    glider = dg1001m()
    goals = random_goals(args.n, args.seed, 4.0 * glider.radius_stf)
    synthesize(goals[0], glider)  # warm-up (imports, caches)
    times, best = [], collections.Counter()
    for goal in goals:
        t0 = time.perf_counter()
        cands = synthesize(goal, glider)
        times.append(time.perf_counter() - t0)
        best[f"{cands[0].family} {cands[0].word}" if cands else "none"] += 1
    t = np.array(times) * 1e3
    median, p99 = float(np.median(t)), float(np.percentile(t, 99))
    print(f"synthesis over {args.n} random goals within 4 R_stf (DG-1001M, one core)")
    print(f"  median {median:.1f} ms   p90 {np.percentile(t, 90):.1f} ms   "
          f"p99 {p99:.1f} ms   max {t.max():.1f} ms   mean {t.mean():.1f} ms")  # fmt: skip
    print(f"  targets: median <= 50 ms {'PASS' if median <= 50 else 'FAIL'}, "
          f"p99 <= 500 ms {'PASS' if p99 <= 500 else 'FAIL'}")  # fmt: skip
    print("  best family and word:", ", ".join(f"{k} {v}" for k, v in best.most_common()))
    report_peers([], [])  # targets only: no peer timing exists for this planner


if __name__ == "__main__":
    main()
