"""Chapter 3 examples: time-optimal paths in a known steady wind (section 3.2, appendix A).

Reference costs:
- Airspeed 1, R = 1, wind 0.3 along +x, goal (3, 3, pi/2): T* = 3.75342 (the issue's value;
  also an independent virtual-target solve, REFERENCE_NOTES §3.4), word LSL.
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

register_demo_case(
    DemoCase(
        name="Wind: convected Dubins (3, 3, pi/2)",
        source="section 3.2 / appendix A (Techy & Woolsey 2009); issue 7 reference",
        start=Pose(),
        goal=Pose(3.0, 3.0, math.pi / 2),
        vehicle=DubinsCarInWind(speed=1.0, turn_radius=1.0, wind_speed=0.3, wind_direction=0.0),
        reference_cost=3.75342,
        reference_word="LSL",
    )
)
register_demo_case(
    DemoCase(
        name="Wind: straight downwind",
        source="section 3.2, hand derivation 10 / (v + w)",
        start=Pose(),
        goal=Pose(10.0, 0.0, 0.0),
        vehicle=DubinsCarInWind(speed=1.0, turn_radius=1.0, wind_speed=0.3, wind_direction=0.0),
        reference_cost=10.0 / 1.3,
        reference_word="S",  # LSL with zero-length turns: the word drops them
    )
)
register_demo_case(
    DemoCase(
        name="Wind: straight upwind",
        source="section 3.2, hand derivation 10 / (v - w)",
        start=Pose(),
        goal=Pose(10.0, 0.0, 0.0),
        vehicle=DubinsCarInWind(speed=1.0, turn_radius=1.0, wind_speed=0.3, wind_direction=math.pi),
        reference_cost=10.0 / 0.7,
        reference_word="S",  # LSL with zero-length turns: the word drops them
    )
)
register_demo_case(
    DemoCase(
        name="Wind + unknown gusts: R0' in the air frame",
        source="appendix A, Corollary A.2 (eps = 0.25, chapter 3 vehicle)",
        start=Pose(),
        goal=Pose(300.0, 200.0, math.pi),
        vehicle=DubinsCarInWind(
            speed=20.0, turn_radius=20.0 / 0.3, wind_speed=5.0, wind_direction=math.pi / 4
        ),
        options={"disturbance_ratio": 0.25},
    )
)
