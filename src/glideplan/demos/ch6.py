"""Chapter 6 examples: minimum altitude loss with speed and load-factor controls (6.8)."""

from __future__ import annotations

import math
from typing import Any

from glideplan.demos import DemoCase, register_demo_case
from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.vehicles.load_factor_glider import LoadFactorGlider

GLIDER = LoadFactorGlider()  # parameters (6.21)


def _arcs(solution: Solution) -> dict[str, Any]:
    arcs = solution.extras.get("arcs", {})
    return {
        "arc_fractions": arcs.get("fractions", {}),
        "reaches_corner": arcs.get("reaches_corner"),
    }


# goal, independent multi-start collocation cost, turn word (Figs 6.11-6.13)
for name, goal, cost, word in (
    ("ch6 fig6.11 (-2, 4, 7pi/4)", (-2.0, 4.0, 7 * math.pi / 4), 0.36138, "L"),
    ("ch6 fig6.12 (0, -0.5, pi)", (0.0, -0.5, math.pi), 0.26256, "LRL"),
    ("ch6 fig6.13 (1.1, 2, 0)", (1.1, 2.0, 0.0), 0.20926, "LR"),
):
    register_demo_case(
        DemoCase(name, "section 6.8, Figs 6.11-6.13 (cost: independent collocation)",
                 Pose(0.0, 0.0, 0.0), Pose(*goal), GLIDER, "altitude", "direct",
                 reference_cost=cost, reference_word=word, postprocess=_arcs)
    )  # fmt: skip
