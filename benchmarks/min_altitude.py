"""Synthesis time per goal for minimum altitude loss (chapter 5 planner), one core.

Random goals uniform in the disc of radius 4 R_stf with uniform headings (DG-1001M). Times
`synthesize` (every candidate of the sufficient set, paths built) per goal after a warm-up.
Targets (issue 5): median <= 50 ms and p99 <= 500 ms over 200 goals; issue 28: median <= 10
ms, p99 <= 20 ms with the same costs. The NumPy path (`extremals.COMPILED = False`: the
heading primitives and the chain solver's grid, cell test and Newton polish on NumPy, the
previous kernels) is timed on the same goals in the same run as the baseline, and every
goal's candidates (families, words, costs) are compared with it; CPU time per goal (the
machine is shared; its load is printed).

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


def _run(goals: list[Pose], glider, compiled: bool) -> tuple[np.ndarray, np.ndarray, list]:
    """CPU ms per goal, best cost and the candidates, with the compiled or the NumPy
    kernels."""
    from glideplan.planners.min_altitude import extremals

    extremals.COMPILED = compiled
    times, costs, all_cands = [], [], []
    try:
        for goal in goals:
            t0 = time.process_time()
            cands = synthesize(goal, glider)
            times.append(time.process_time() - t0)
            costs.append(cands[0].cost if cands else math.nan)
            all_cands.append(cands)
    finally:
        extremals.COMPILED = True
    return np.array(times) * 1e3, np.array(costs), all_cands


def _same_candidates(a: list, b: list) -> tuple[int, float]:
    """Goals whose candidate lists differ in families and words (ties in either order), and
    the largest relative cost difference over the others."""
    bad, worst = 0, 0.0
    for ca, cb in zip(a, b, strict=True):
        ca, cb = (sorted(cs, key=lambda c: (c.family, c.word, c.cost)) for cs in (ca, cb))
        if [(c.family, c.word) for c in ca] != [(c.family, c.word) for c in cb]:
            bad += 1
            continue
        for x, y in zip(ca, cb, strict=True):
            worst = max(worst, abs(x.cost - y.cost) / max(1.0, abs(y.cost)))
    return bad, worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=count(1), default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    if hasattr(os, "sched_setaffinity"):
        os.sched_setaffinity(0, {sorted(os.sched_getaffinity(0))[0]})
    glider = dg1001m()
    goals = random_goals(args.n, args.seed, 4.0 * glider.radius_stf)
    synthesize(goals[0], glider)  # warm-up (imports, caches, compiled kernels)
    print(f"load average (1 min): {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    t_old, cost_old, cands_old = _run(goals, glider, compiled=False)
    t, costs, cands_new = _run(goals, glider, compiled=True)
    best = collections.Counter(f"{c[0].family} {c[0].word}" if c else "none" for c in cands_new)
    median, p99 = float(np.median(t)), float(np.percentile(t, 99))
    print(f"synthesis over {args.n} random goals within 4 R_stf (DG-1001M, one core, CPU time)")
    print(f"  median {median:.1f} ms   p90 {np.percentile(t, 90):.1f} ms   "
          f"p99 {p99:.1f} ms   max {t.max():.1f} ms   mean {t.mean():.1f} ms")  # fmt: skip
    print(f"  NumPy path (before), same goals: median {np.median(t_old):.1f} ms   "
          f"p99 {np.percentile(t_old, 99):.1f} ms")
    diff = np.nanmax(np.abs(np.array(costs) - cost_old) / np.abs(cost_old))
    bad, worst = _same_candidates(cands_new, cands_old)
    print(f"  best cost vs NumPy path: max relative difference {diff:.1e}; all candidates: "
          f"{bad} goals differ in families/words, costs within {worst:.1e}")
    print(f"  targets: median <= 50 ms {'PASS' if median <= 50 else 'FAIL'}, "
          f"p99 <= 500 ms {'PASS' if p99 <= 500 else 'FAIL'}; issue 28: median <= 10 ms "
          f"{'PASS' if median <= 10 else 'FAIL'}, p99 <= 20 ms "
          f"{'PASS' if p99 <= 20 else 'FAIL'}")  # fmt: skip
    print("  best family and word:", ", ".join(f"{k} {v}" for k, v in best.most_common()))
    report_peers([], [])  # targets only: no peer timing exists for this planner


if __name__ == "__main__":
    main()
