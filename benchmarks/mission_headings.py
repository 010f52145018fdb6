"""Benchmark: headings of multi-leg missions — DP + refinement against two heuristics.

Issue 13: on random missions of 10-200 waypoints spaced 0.5-5 turn radii, total Dubins length
and run time of
- DP + refine: dynamic programming over K headings per waypoint (O(n K^2), one K x K leg
  matrix per leg), then L-BFGS-B and golden-section refinement (glideplan.missions);
- alternating (bisector): headings along the bisector of consecutive legs (the issue's
  "alternating algorithm");
- Savla alternating: every other leg flown straight (Savla, Frazzoli & Bullo 2008);
- point at next: each heading toward the next waypoint.
Targets: never longer than either heuristic; within 0.1 % of a 1-degree brute force on 3-4
waypoint missions; 200 waypoints with K = 360 in <= 2 s on one core. Issue 28: the heading
DP of a 3,000-waypoint mission (K = 360) in <= 5 s with the same answers: the compiled DP step
(`StillAirCost.dp_step`, no K x K matrix; vectorised blocks, `planners._dubins_dp`) against the
previous compiled step (scalar, bounded: the same headings and total expected), against the
NumPy matrix step (float32, the default before the compiled step; timed on the first
`--long-baseline` legs of the same mission, in the same run, and scaled to the whole
mission), and against the float64 matrix step on the first 100 legs (the same headings and
values expected).

Usage: python benchmarks/mission_headings.py [--seeds N] [--brute N] [--long N]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np
from _peers import count, report_peers

from glideplan.missions import (
    StillAirCost,
    alternating_headings,
    bisector_headings,
    headings_cost,
    optimise_headings,
    point_at_next_headings,
)
from glideplan.planners.dubins import dubins_distance

HEURISTICS = {
    "alternating (bisector)": bisector_headings,
    "Savla alternating": alternating_headings,
    "point at next": point_at_next_headings,
}


def mission(rng: np.random.Generator, n: int, radius: float = 1.0) -> np.ndarray:
    steps = rng.uniform(0.5, 5.0, n - 1) * radius
    ang = rng.uniform(0.0, 2 * math.pi, n - 1)
    d = np.column_stack([steps * np.cos(ang), steps * np.sin(ang)])
    return np.vstack([[0.0, 0.0], np.cumsum(d, axis=0)])


def brute_force(pts: np.ndarray, fixed: np.ndarray) -> float:
    """Exhaustive 1-degree minimum for 3 free or 4 (first fixed) waypoints, core kernel."""
    grid = np.arange(360) * (2 * math.pi / 360)
    sets = [grid if math.isnan(h) else np.array([h]) for h in fixed]

    def mat(i: int) -> np.ndarray:
        s = np.zeros((sets[i].size, 1, 3))
        s[:, 0, :2], s[:, 0, 2] = pts[i], sets[i]
        g = np.zeros((1, sets[i + 1].size, 3))
        g[0, :, :2], g[0, :, 2] = pts[i + 1], sets[i + 1]
        return np.asarray(dubins_distance(s, g, 1.0))

    mats = [mat(i) for i in range(len(pts) - 1)]
    if len(mats) == 2:
        return float(min((mats[0][a][:, None] + mats[1]).min() for a in range(sets[0].size)))
    best = math.inf
    for j in range(sets[1].size):
        tot = mats[0][:, j, None, None] + mats[1][j][None, :, None] + mats[2][None, :, :]
        best = min(best, float(tot.min()))
    return best


class _MatrixOnly:
    """A leg cost with the NumPy matrix step only (the DP before the compiled step)."""

    def __init__(self, cost: StillAirCost) -> None:
        self.matrix = cost.matrix


def long_mission(n: int, baseline_legs: int) -> None:
    """Issue 28: the heading DP alone (K = 360) of an n-waypoint mission, compiled vs NumPy."""
    import os

    from glideplan.missions import leg_costs
    from glideplan.missions.headings import _candidates, _dynamic_programme

    rng = np.random.default_rng(28)
    pts = mission(rng, n)
    fixed = np.full(n, np.nan)
    extra = [f(pts, fixed) for f in HEURISTICS.values()]
    sets = _candidates(fixed, 360, extra)
    _dynamic_programme(StillAirCost(pts[:3], 1.0), sets[:3])  # compile or load the cache
    load = os.getloadavg()[0]
    t0, w0 = time.process_time(), time.perf_counter()
    h_all, best = _dynamic_programme(StillAirCost(pts, 1.0), sets)
    cpu, wall = time.process_time() - t0, time.perf_counter() - w0
    leg_costs.DP_BLOCKS = False  # the previous compiled step (scalar, bounded), whole mission
    _dynamic_programme(StillAirCost(pts[:3], 1.0), sets[:3])
    t0 = time.process_time()
    h_scalar, best_scalar = _dynamic_programme(StillAirCost(pts, 1.0), sets)
    cpu_scalar = time.process_time() - t0
    leg_costs.DP_BLOCKS = True
    m = min(baseline_legs, n - 1) + 1
    t0 = time.process_time()
    _dynamic_programme(_MatrixOnly(StillAirCost(pts[:m], 1.0)), sets[:m])
    old = (time.process_time() - t0) * (n - 1) / (m - 1)
    p = min(100, n - 1) + 1
    h_new, v_new = _dynamic_programme(StillAirCost(pts[:p], 1.0), sets[:p])
    h_ref, v_ref = _dynamic_programme(
        _MatrixOnly(StillAirCost(pts[:p], 1.0, precision="double")), sets[:p])
    same = bool(np.array_equal(h_new, h_ref)) and abs(v_new - v_ref) <= 1e-12 * v_ref
    print(f"\nheading DP alone, {n} waypoints, K = 360 (+ heuristic headings), load average "
          f"{load:.1f} on {os.cpu_count()} cores:")
    print(f"  compiled DP step: {cpu:.2f} s CPU ({wall:.2f} s wall) [target <= 5 s]: "
          f"{'PASS' if cpu <= 5.0 else 'FAIL'}; total {best:.6f} R")
    same_all = bool(np.array_equal(h_all, h_scalar)) and best == best_scalar
    print(f"  previous compiled step (scalar, bounded): {cpu_scalar:.2f} s CPU, whole mission "
          f"-> vectorised blocks {cpu_scalar / cpu:.2f} x; same headings and total: "
          f"{'PASS' if same_all else 'FAIL'}")
    print(f"  NumPy float32 matrix step (before): {old:.1f} s CPU, scaled from the first "
          f"{m - 1} legs of the same mission -> compiled {old / cpu:.1f} x")
    print(f"  compiled vs float64 matrix step, first {p - 1} legs: same headings and total "
          f"(1e-12): {'PASS' if same else 'FAIL'}")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--seeds", type=count(1), default=5, help="missions per size")
    ap.add_argument("--brute", type=count(1), default=20, help="brute-force missions")
    ap.add_argument("--long", type=count(0), default=3000,
                    help="waypoints of the long mission (0 skips it)")
    ap.add_argument("--long-baseline", type=count(2), default=300,
                    help="legs of the long mission timed with the NumPy matrix step")
    ap.add_argument("--long-only", action="store_true", help="only the long mission")
    args = ap.parse_args()
    if args.long:
        long_mission(args.long, args.long_baseline)
    if args.long_only:
        return
    print("random missions, spacing 0.5-5 R (R = 1), all headings free; mean over "
          f"{args.seeds} missions per size; times on this (shared) machine, one process\n")
    header = ("| n | method | K | total length (mean) | vs DP+refine | worst vs DP | "
              "CPU time [s] (median) |")
    print(header)
    print("|---|---|---|---|---|---|---|")
    never_longer = True
    t200: list[float] = []
    for n in (10, 20, 50, 100, 200):
        rows: dict[str, list[tuple[float, float]]] = {}
        for seed in range(args.seeds):
            rng = np.random.default_rng(1000 * n + seed)
            pts = mission(rng, n)
            fixed = np.full(n, np.nan)
            cost = StillAirCost(pts, 1.0)
            for k in (72, 360):
                t0 = time.process_time()
                res = optimise_headings(cost, pts, fixed, k)
                dt = time.process_time() - t0
                rows.setdefault(f"DP + refine|{k}", []).append((res.total, dt))
                if k == 360 and n == 200:
                    t200.append(dt)
            for name, fn in HEURISTICS.items():
                t0 = time.process_time()
                h = fn(pts, fixed)
                total, _ = headings_cost(cost, h)
                dt = time.process_time() - t0
                rows.setdefault(f"{name}|-", []).append((total, dt))
        dp = np.array([c for c, _ in rows["DP + refine|360"]])
        for key, vals in rows.items():
            name, k = key.split("|")
            c = np.array([v for v, _ in vals])
            t = np.array([v for _, v in vals])
            ratio = c / dp
            if name != "DP + refine":
                never_longer &= bool(np.all(ratio >= 1 - 1e-12))
                dp72 = np.array([v for v, _ in rows["DP + refine|72"]])
                never_longer &= bool(np.all(c >= dp72 * (1 - 1e-12)))
            print(f"| {n} | {name} | {k} | {c.mean():.3f} | {ratio.mean():.4f} | "
                  f"{ratio.max():.4f} | {np.median(t):.4f} |")
    # brute force
    worst = {72: -math.inf, 360: -math.inf}
    rng = np.random.default_rng(7)
    for b in range(args.brute):
        n = 3 if b % 2 == 0 else 4
        pts = mission(rng, n)
        fixed = np.full(n, np.nan)
        if n == 4:
            fixed[0] = rng.uniform(0, 2 * math.pi)
        bf = brute_force(pts, fixed)
        for k in worst:
            res = optimise_headings(StillAirCost(pts, 1.0), pts, fixed, k)
            worst[k] = max(worst[k], (res.total - bf) / bf)
    med = float(np.median(t200))
    for k, wk in worst.items():
        print(f"\nbrute force (1 degree, {args.brute} missions of 3-4 waypoints): DP + refine "
              f"with K = {k} is at most {100 * wk:+.4f} % from it (target <= +0.1 %): "
              f"{'PASS' if wk <= 1e-3 else 'FAIL'}{' (default K)' if k == 360 else ''}")
    print(f"never longer than a heuristic (K = 72 and 360, all missions): "
          f"{'PASS' if never_longer else 'FAIL'}")
    print(f"200 waypoints, K = 360: median CPU time {med:.2f} s over {len(t200)} missions "
          f"(target <= 2 s on one core; process CPU time, as the machine is shared): "
          f"{'PASS' if med <= 2.0 else 'FAIL'}")
    report_peers([
        "bisector, Savla alternating and point-at-next heuristics (implemented here, "
        "run in this process on the same missions)",
        "1-degree brute force (core `dubins_distance`, exhaustive sums)",
    ], [])


if __name__ == "__main__":
    main()
