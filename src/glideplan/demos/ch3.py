"""Chapter 3 examples: time-optimal paths in a known steady wind (section 3.2, appendix A).

Reference costs:
- Airspeed 1, R = 1, wind 0.3 along +x, goal (3, 3, pi/2): T* = 3.75342 (the project's
  reference value; also an independent virtual-target solve, REFERENCE_NOTES §3.4), word LSL.
- Straight downwind, goal (10, 0, 0), wind 0.3 along +x: T = 10 / 1.3 = 7.6923 (LSL with
  empty arcs, tied with RSR).
- Straight upwind, same goal, wind 0.3 towards -x: T = 10 / 0.7 = 14.2857.
- Chapter 3 vehicle (v = 20 m/s, R0 = 66.67 m) in a 5 m/s wind towards 45 degrees, planned
  with R0' = R0 (1 + 0.25)^2 for an extra unknown disturbance eps = 0.25 (Corollary A.2):
  no printed reference; the time is checked by integration like every demo.
"""

from __future__ import annotations

import math

from glideplan.demos import DemoCase, register_demo_case
from glideplan.pose import Pose
from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind

# the straight cases: LSL with zero-length turns, whose word drops them ("S")
for name, source, goal, wind_direction, cost, word in (
    ("Wind: convected Dubins (3, 3, pi/2)",
     "section 3.2 / appendix A (Techy & Woolsey 2009); virtual-target solve",
     Pose(3.0, 3.0, math.pi / 2), 0.0, 3.75342, "LSL"),
    ("Wind: straight downwind", "section 3.2, hand derivation 10 / (v + w)",
     Pose(10.0, 0.0, 0.0), 0.0, 10.0 / 1.3, "S"),
    ("Wind: straight upwind", "section 3.2, hand derivation 10 / (v - w)",
     Pose(10.0, 0.0, 0.0), math.pi, 10.0 / 0.7, "S"),
):  # fmt: skip
    car = DubinsCarInWind(speed=1.0, turn_radius=1.0,
                          wind=(0.3 * math.cos(wind_direction), 0.3 * math.sin(wind_direction)))
    register_demo_case(
        DemoCase(name, source, Pose(), goal, car, reference_cost=cost, reference_word=word)
    )
register_demo_case(
    DemoCase(
        name="Wind + unknown gusts: R0' in the air frame",
        source="appendix A, Corollary A.2 (eps = 0.25, chapter 3 vehicle)",
        start=Pose(),
        goal=Pose(300.0, 200.0, math.pi),
        vehicle=DubinsCarInWind(
            speed=20.0, turn_radius=20.0 / 0.3,
            wind=(5.0 * math.cos(math.pi / 4), 5.0 * math.sin(math.pi / 4))),
        options={"disturbance_ratio": 0.25},
    )
)
