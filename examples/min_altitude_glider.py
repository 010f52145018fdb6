"""Minimum altitude loss for a DG-1001M glider (dissertation chapter 5) in a few lines.

Plans the path to a goal one turn radius away, compares it with the Dubins path flown at the
speed to fly, prints every candidate of the sufficient set, and draws the candidates and the
control history to $GLIDEPLAN_OUT/min_altitude.png (default: the current directory).
"""

import math
import os
import pathlib

import glideplan as gp
from glideplan.figures.ch5 import draw_solution
from glideplan.planners.min_altitude import flight_profile
from glideplan.vehicles import dg1001m

glider = dg1001m()  # polar (5.26), v_stall = 75.6 km/h, u_max = pi/15 rad/s
R = glider.radius_stf  # 139.5 m, the turn radius at the speed to fly
goal = gp.Pose(0.0, 1.0 * R, 2 * math.pi / 3)

solution = gp.plan(gp.Pose(0.0, 0.0, 0.0), goal, glider)  # objective "altitude" by default
dubins = solution.extras["dubins_cost"]
print(f"best: {solution.family} {solution.word}, altitude loss {solution.cost:.3f} m")
print(f"Dubins path at v_stf: {dubins:.3f} m -> {dubins - solution.cost:.2f} m saved")
for cand in solution.candidates:
    print(f"  {cand.family:>5} {cand.word:<5} {cand.cost:8.3f} m")

profile = flight_profile(solution.path)
stall = sum(s.duration for s in solution.path.segments if s.label == "Bsat")
print(f"flight time {profile['t'][-1]:.1f} s, of which {stall:.1f} s at the stall speed")
print(f"speed range {min(profile['speed']) * 3.6:.1f}-{max(profile['speed']) * 3.6:.1f} km/h")

out = pathlib.Path(os.environ.get("GLIDEPLAN_OUT", "."))
draw_solution(solution, out / "min_altitude.png")
print(f"wrote {out / 'min_altitude.png'}")
