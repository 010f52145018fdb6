"""Validation: a grid the user made coarse, in a current stronger than the vehicle.

The claim (`glideplan.routing.finer_grid`): where the current is faster than the vehicle and
the route found on the user's grid cannot be flown, `route()` runs again on finer grids
(halving, down to the default grid) and answers solved on the first that verifies, with a
warning naming it; it never hands back a held-legs duration as the route's. The case of the
third session's closing note: the double gyre (L = 100 km, 0.3 m/s; `--example
double-gyre`) from (30.2, -39.8) to (30.7, -38.3) at 0.05 and 0.07 m/s, on a 3000 m grid
(before: not_verified, 24,959 h and 33,134 h), 1000 m and the default (617 m). Prints each
case (status, duration, the grid that answered, the grids tried, wall time) and PASS/FAIL:
PASS when every route is solved and no duration exceeds 1.25x the default grid's (about a
minute on a quiet 2-core machine).

    .venv/bin/python benchmarks/validate_coarse_grid.py
"""

from __future__ import annotations

import sys
import time

from glideplan.fields import double_gyre
from glideplan.routing import route

START, GOAL = (30.2, -39.8), (30.7, -38.3)


def main() -> int:
    fld = double_gyre()
    ok = True
    print("| speed (m/s) | --resolution | status | duration (h) | answered on | grids tried "
          "| wall (s) |")
    print("|---|---|---|---|---|---|---|")
    for speed in (0.05, 0.07):
        rows = []
        for res in (None, 1000.0, 3000.0):
            t = time.perf_counter()
            r = route(fld, START, GOAL, speed, resolution=res)
            wall = time.perf_counter() - t
            tried = [f"{g['spacing_m']:.0f} {g['status']}" for g in r.stats.get("grids", [])]
            dur = None if r.duration_s is None else r.duration_s / 3600
            rows.append((res, r, dur))
            print(f"| {speed} | {'default' if res is None else f'{res:.0f}'} | "
                  f"{r.status.value} | {'-' if dur is None else f'{dur:.1f}'} | "
                  f"{r.stats['spacing_m']:.0f} m | {', '.join(tried) or '-'} | {wall:.1f} |",
                  flush=True)
        ref = rows[0][2]
        for _res, r, dur in rows:
            if not r.ok or ref is None or dur is None or dur > 1.25 * ref:
                ok = False
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
