"""Minimum-time paths when the speed is a control (dissertation chapter 4) in a few lines.

An underwater glider that can fly between 0.15 and 0.5 m/s and turn at up to 0.1 rad/s:
fast turns (B) have radius R = 5 m, slow cornering turns (C) r = 1.5 m. Plans the path to a
goal, compares it with the Dubins path at full speed, prints the candidates of the
sufficient set (4.26), checks the answer with the direct method, and draws the path with
its switching points to $GLIDEPLAN_OUT/min_time.png (default: the current directory).
"""

import math
import os
import pathlib

import glideplan as gp
from glideplan.plotting import plot_solution, save_figure

car = gp.VariableSpeedCar(v_min=0.15, v_max=0.5, u_max=0.1)
goal = gp.Pose(0.0, 10.0, 2 * math.pi / 3)  # Table 4.3's goal, scaled by R = 5 m

solution = gp.plan(gp.Pose(0.0, 0.0, 0.0), goal, car)  # objective "time" by default
print(f"best: {solution.family} {solution.word}, {solution.cost:.3f} s")
for seg in solution.path.segments:
    print(f"  {seg.label} {seg.letter} {seg.duration:6.2f} s at {seg.controls([0.0])[0][0]} m/s")
dubins = gp.dubins_path(gp.Pose(), goal, car.bang_radius, car.v_max)
print(f"Dubins path at v_max: {dubins.duration:.3f} s ({dubins.duration / solution.cost:.2f} x)")
print("candidates (type, time):")
for cand in solution.candidates:
    print(f"  {cand.info['type']:<16} {cand.cost:8.3f} s")

check = gp.plan(gp.Pose(), goal, car, method="direct")  # collocation, multi-start
print(f"direct method: {check.family} {check.word}, {check.cost:.3f} s")

out = pathlib.Path(os.environ.get("GLIDEPLAN_OUT", "."))
save_figure(plot_solution(solution), str(out / "min_time.png"))
