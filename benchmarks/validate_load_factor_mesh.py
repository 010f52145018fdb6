"""Validation: the chapter 6 planner's costs are converged in the mesh.

For each of the dissertation's three examples (section 6.8, Figs 6.11-6.13) the planner's
final collocation cost is compared with a re-solve on a mesh twice as fine started from the
planner's path; the relative change must stay below the planner's own stopping tolerance
mesh_tol = 1e-5 (its refinement stopped at a change below that). The test suite keeps
the corner example (tests/load_factor/test_load_factor_planner.py).

    .venv/bin/python benchmarks/validate_load_factor_mesh.py
"""

from __future__ import annotations

import math

from glideplan import LoadFactorGlider, Pose, plan
from glideplan.planners.direct import solve_direct
from glideplan.planners.load_factor import control_system

EXAMPLES = {
    "fig6.11": (-2.0, 4.0, 7 * math.pi / 4),
    "fig6.12": (0.0, -0.5, math.pi),
    "fig6.13": (1.1, 2.0, 0.0),
}
TOLERANCE = 1e-5


def main() -> None:
    glider = LoadFactorGlider()
    worst = 0.0
    for name, goal_xyh in EXAMPLES.items():
        goal = Pose(*goal_xyh)
        sol = plan(Pose(), goal, glider)
        if not sol.ok:
            print(f"{name}: the planner failed: {sol.message}")
            raise SystemExit(1)
        sizes = sol.stats["mesh_sizes"]
        fine = solve_direct(
            goal,
            control_system(glider),
            guesses=[sol.path],
            n_intervals=2 * sizes[-1],
            max_refinements=0,
        )
        final = sol.extras["collocation_cost"]
        change = abs(fine.cost - final) / final if fine.ok else math.inf
        worst = max(worst, change)
        print(
            f"{name}: cost {final:.6f} on {sizes[-1]} intervals, {fine.cost:.6f} on "
            f"{2 * sizes[-1]}: relative change {change:.1e}"
        )
    print(f"largest change {worst:.1e} (tolerance {TOLERANCE:g})")
    print("PASS" if worst < TOLERANCE else "FAIL")
    if worst >= TOLERANCE:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
