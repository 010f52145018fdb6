"""Chapter 5 examples: minimum altitude loss for the DG-1001M (section 5.9, Figs 5.5-5.7)."""

from __future__ import annotations

import math
from typing import Any

from glideplan.demos import DemoCase, register_demo_case
from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.vehicles.quadratic_polar_glider import dg1001m

GLIDER = dg1001m()


def _report(solution: Solution) -> dict[str, Any]:
    from glideplan.planners.min_altitude import flight_profile

    assert solution.path is not None
    dubins = solution.extras.get("dubins_cost")
    out: dict[str, Any] = {"profile": flight_profile(solution.path, n=101)}
    if isinstance(dubins, float):
        out["improvement"] = dubins - solution.cost
        out["improvement_percent"] = 100.0 * (dubins - solution.cost) / dubins
    return out


# goal in units of R_stf, independent direct-method altitude loss (m), dissertation's best
for label, goal, cost, word in (
    ("fig5.5 (0, 1, 2pi/3)", (0.0, 1.0, 2 * math.pi / 3), 19.4289, "RLR"),
    ("fig5.6 (-3, 4, 0)", (-3.0, 4.0, 0.0), 25.8483, "LSR"),
    ("fig5.7 (0, 2, 7pi/4)", (0.0, 2.0, 7 * math.pi / 4), 20.1252, "LSL"),
):
    x, y, heading = goal
    register_demo_case(
        DemoCase(
            f"ch5 {label} R_stf",
            "section 5.9, DG-1001M (cost: independent direct solve; the dissertation "
            "reports only the gain over the Dubins path at v_stf)",
            Pose(0.0, 0.0, 0.0),
            Pose(x * GLIDER.radius_stf, y * GLIDER.radius_stf, heading),
            GLIDER,
            "altitude",
            "synthesis",
            reference_cost=cost, reference_word=word, postprocess=_report,
        )
    )  # fmt: skip
