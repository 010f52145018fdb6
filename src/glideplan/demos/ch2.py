"""Chapter 2-3 examples: Dubins paths (section 2.7, Fig 2.2) and the feasible radius (eq. 3.3).

Reference costs are derived by hand (circle-centre geometry, unit radius unless stated):
- Fig 2.2(a), goal (-3, 2, 3pi/2): LSL, left circles (0, 1) and (-2, 2), straight sqrt 5,
  turns summing to 3pi/2 -> sqrt 5 + 3pi/2 = 6.9485.
- Fig 2.2(b), goal (1, 1, pi): RLR, right circles (0, -1) and (1, 2) sqrt 10 apart, middle arc
  2pi - acos(1 - 10/8), outer arcs summing to (middle - pi) -> 3pi - 2 acos(-1/4) = 5.7778.
- Goal (0, 4, pi): LSL, quarter turn, 2 straight, quarter turn -> 2 + pi.
- Reversing in place, goal (0, 0, pi): RLR (tie LRL), 5pi/3 + pi/3 + pi/3 = 7pi/3.
- Feasible radius, chapter 3 vehicle (v = 20 m/s, |u| <= 0.3 rad/s -> R0 = 66.67 m), eps = 0.25:
  R0' = R0 * 1.25^2 = 104.17 m; goal (0, 4 R0', pi) -> (2 + pi) R0' = 535.58 m; in time,
  that length / 20 m/s = 26.78 s.
"""

from __future__ import annotations

import math

from glideplan.demos import DemoCase, register_demo_case
from glideplan.pose import Pose
from glideplan.vehicles.dubins_car import DubinsCar

_R0 = 20.0 / 0.3
_R0_FEASIBLE = _R0 * 1.25**2

for name, source, goal, cost, word in (
    ("Dubins Fig 2.2(a)", "section 2.7, Fig 2.2(a)", Pose(-3.0, 2.0, 3 * math.pi / 2),
     math.sqrt(5.0) + 1.5 * math.pi, "LSL"),
    ("Dubins Fig 2.2(b)", "section 2.7, Fig 2.2(b)", Pose(1.0, 1.0, math.pi),
     3 * math.pi - 2 * math.acos(-0.25), "RLR"),
    ("Dubins LSL quarter turns", "section 2.7 (hand check)", Pose(0.0, 4.0, math.pi),
     2 + math.pi, "LSL"),
    ("Dubins reversal in place", "section 2.7 (hand check)", Pose(0.0, 0.0, math.pi),
     7 * math.pi / 3, "RLR"),
):  # fmt: skip
    register_demo_case(
        DemoCase(name, source, Pose(), goal, DubinsCar(), reference_cost=cost, reference_word=word)
    )
# the feasible radius, in length and in time (length / 20 m/s)
for objective, suffix, cost_unit in ((None, "", 1.0), ("time", ", time", 20.0)):
    register_demo_case(
        DemoCase(
            name=f"Feasible radius eps=0.25{suffix}",
            source="section 3.2, eq. 3.3",
            start=Pose(),
            goal=Pose(0.0, 4 * _R0_FEASIBLE, math.pi),
            vehicle=DubinsCar(speed=20.0, turn_radius=_R0),
            objective=objective,
            options={"disturbance_ratio": 0.25},
            reference_cost=(2 + math.pi) * _R0_FEASIBLE / cost_unit,
            reference_word="LSL",
        )
    )
