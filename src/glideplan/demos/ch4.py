"""Chapter 4 examples: minimum-time paths with variable speed (section 4.9).

Reference costs:
- Table 4.3, x1 = (0, 2, 2pi/3), R = 1, r = 0.3: the dissertation's best, CBSB LSR 2.875
  (our synthesis and the direct method agree on 2.874650).
- The same goal for a glider-like vehicle (v in [0.15, 0.5] m/s, u_max = 0.1 rad/s, so
  R = 5 m, r = 1.5 m): the problem scales with R, so the goal (0, 10 m, 2pi/3) takes
  2.874650 / u_max = 28.7465 s.
- Goal (0.5, 0.5, pi/2): a single left turn reaches it (heading change pi/2, speed profile
  not unique), so the time is the lower bound |Delta psi| / u_max = pi/2.
- Goal (0.09, 0.16, 0.22), next to the start: no path with a reversal is shorter than one
  right turn at maximum rate through 2 pi - 0.22 (time 2 pi - 0.22 = 6.063185).
"""

from __future__ import annotations

import math

from glideplan.demos import DemoCase, register_demo_case
from glideplan.pose import Pose
from glideplan.vehicles.variable_speed_car import VariableSpeedCar

_CAR = VariableSpeedCar(v_min=0.3, v_max=1.0, u_max=1.0)
_TABLE_4_3_GOAL = Pose(0.0, 2.0, 2 * math.pi / 3)

# Table 4.3 by the synthesis (the dissertation's value) and by the direct method
for label, source, method, cost in (
    ("synthesis", "section 4.9, Table 4.3, Fig 4.7", None, 2.875),
    ("direct method", "section 4.9, independent collocation check", "direct", 2.874650),
):
    register_demo_case(
        DemoCase(f"Min-time Table 4.3 ({label})", source, Pose(), _TABLE_4_3_GOAL, _CAR,
                 method=method, reference_cost=cost, reference_word="LSR")
    )  # fmt: skip
register_demo_case(
    DemoCase(
        name="Min-time glider scale (R = 5 m)",
        source="section 4.9 example in SI units (scale invariance)",
        start=Pose(),
        goal=Pose(0.0, 10.0, 2 * math.pi / 3),
        vehicle=VariableSpeedCar(v_min=0.15, v_max=0.5, u_max=0.1),
        reference_cost=28.7465,
        reference_word="LSR",
    )
)
register_demo_case(
    DemoCase(
        name="Min-time single turn",
        source="section 4.6: one turn at u_max, speed not unique",
        start=Pose(),
        goal=Pose(0.5, 0.5, math.pi / 2),
        vehicle=_CAR,
        reference_cost=math.pi / 2,
        reference_word="L",
    )
)
register_demo_case(
    DemoCase(
        name="Min-time goal next to the start",
        source="chapter 4, goal (0.09, 0.16, 0.22)",
        start=Pose(),
        goal=Pose(0.09, 0.16, 0.22),
        vehicle=_CAR,
        reference_cost=2 * math.pi - 0.22,
        reference_word="R",
    )
)
