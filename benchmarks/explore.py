"""Benchmark: `glideplan explore`, server-side time from a changed goal to updated figure data.

The issue's budget (median): <= 50 ms for Dubins and wind, <= 150 ms for minimum time,
minimum altitude and the load-factor synthesis (issue 28: "interactive"). Measured in one
process on the page's own code path: an `Explorer` (the page object of one browser session,
planning synchronously) receives a goal as a drag does
(`set_goal`), plans it with `plan()` (verification by integration included), samples the
optimal path and every candidate, and writes the Bokeh data sources and the text panes. The
time of `plan()` alone on the same goals is shown beside it, so that the page's own overhead
(sampling, sources) is the difference. No browser: the transfer to the browser is not
included (it is local and asynchronous).

Usage: python benchmarks/explore.py [--goals N]
"""

from __future__ import annotations

import argparse
import math
import time
from urllib.parse import parse_qsl

import numpy as np

CASES = (
    # (name, URL query, goal box half-width in length scales, budget ms)
    ("dubins", "planner=dubins&goal=4,3,90&radius=1", 1.0, 50.0),
    ("wind", "planner=wind&goal=4,3,90&speed=1&radius=1&wind=0.5,30", 1.0, 50.0),
    ("time-optimal", "planner=time-optimal&goal=2,1,90&v_min=0.3&v_max=1&u_max=1", 1.0, 150.0),
    ("min-altitude", "planner=min-altitude&goal=400,300,90", 139.47, 150.0),
    ("load-factor", "planner=load-factor&goal=3,2,60", 0.5, 150.0),  # ch. 6 synthesis
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--goals", type=int, default=25, help="goals per planner (default 25)")
    args = parser.parse_args()

    from glideplan import plan
    from glideplan.explore.app import Explorer

    rng = np.random.default_rng(15)
    print(
        f"{'planner':<14} {'page (ms)':>10} {'plan() (ms)':>12} {'overhead':>9} "
        f"{'budget':>7}  verdict"
    )
    failed = False
    for name, query, scale, budget in CASES:
        page = Explorer(query=dict(parse_qsl(query)), sync=True)
        x0, y0 = (float(v) for v in page.state.goal.split(",")[:2])
        goals = [
            (x0 + scale * rng.uniform(-1.0, 1.0), y0 + scale * rng.uniform(-1.0, 1.0))
            for _ in range(args.goals)
        ]
        page.set_goal(*goals[0])  # warm caches and imports
        t_page, t_plan = [], []
        for gx, gy in goals:
            t0 = time.perf_counter()
            page.set_goal(gx, gy)
            t_page.append(time.perf_counter() - t0)
            assert page.view is not None and page.view.ok, page.view.status if page.view else ""
            req = page.view.request
            assert req is not None
            t0 = time.perf_counter()
            sol = plan(req.start, req.goal, req.vehicle, req.entry.objective, req.entry.method)
            t_plan.append(time.perf_counter() - t0)
            assert math.isclose(sol.cost, page.view.solution.cost, rel_tol=1e-9)
        med_page = 1e3 * float(np.median(t_page))
        med_plan = 1e3 * float(np.median(t_plan))
        ok = med_page <= budget
        failed |= not ok
        print(
            f"{name:<14} {med_page:>10.1f} {med_plan:>12.1f} {med_page - med_plan:>9.1f} "
            f"{budget:>7.0f}  {'PASS' if ok else 'FAIL'}"
        )
    print(
        "\npeer figures: none (the issue's budgets only); medians over "
        f"{args.goals} goals, machine load affects every number"
    )
    if failed:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
