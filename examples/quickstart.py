"""Plan a Dubins path, print its cost, word and endpoint error, and save a figure."""

import math
import os
import pathlib

from glideplan import DubinsCar, Pose, plan

car = DubinsCar(speed=20.0, turn_radius=66.7)  # 20 m/s, |u| <= 0.3 rad/s
goal = Pose(-200.0, 400.0, math.radians(315))
sol = plan(Pose(0.0, 0.0, 0.0), goal, car, disturbance_ratio=0.25)  # R0' = R0 (1.25)^2
print(f"cost {sol.cost:.2f} m, word {sol.word}, endpoint error {sol.endpoint_error.max:.1e}")
out = pathlib.Path(os.environ.get("GLIDEPLAN_OUT", "out"))
out.mkdir(parents=True, exist_ok=True)
sol.path.plot().figure.savefig(out / "quickstart.png")
print(f"figure: {out / 'quickstart.png'}")
