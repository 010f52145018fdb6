"""Validation: the closed-loop simulation's default time step dt = 0.05 s is converged.

The claim (`glideplan.simulation.closed_loop`): the mean final cross-track error at
dt = 0.05 s is within 3% of its value at finer steps. Checked for five (eps, R_plan / R0)
cases of the Fig 3.4 study (40 goals within 4 R0, steady wind, random directions) against
dt = 0.025, 0.0125 and 0.00625 s; prints the relative differences and PASS/FAIL. The test
suite keeps the slowest-converging case against dt = 0.0125 s
(tests/simulation/test_following.py::test_time_step_converged).

    .venv/bin/python benchmarks/validate_time_step.py
"""

from __future__ import annotations

import math

import numpy as np

from glideplan.simulation import FollowerSettings, PathArrays, SteadyDisturbance, follow_paths

SPEED = 20.0  # m/s, the study's vehicle
R0 = SPEED / 0.3  # m, its minimum turn radius
CASES = ((0.25, 1.0), (0.25, 1.5625), (0.5, 2.0), (0.75, 1.0), (0.95, 3.8))
STEPS = (0.05, 0.025, 0.0125, 0.00625)
TOLERANCE = 0.03


def main() -> None:
    rng = np.random.default_rng(5)
    xy = rng.uniform(-4, 4, (40, 2)) * R0
    goals = np.column_stack([xy, rng.choice([0.0, 2 * math.pi / 3, math.pi], 40)])
    dirs = np.random.default_rng(6).uniform(0, 2 * math.pi, 40)
    worst = 0.0
    for eps, r_plan in CASES:
        means = []
        for dt in STEPS:
            res = follow_paths(
                PathArrays.dubins(goals, r_plan * R0),
                SteadyDisturbance(
                    eps * SPEED * np.column_stack([np.cos(dirs), np.sin(dirs)])).stream(40, dt),
                settings=FollowerSettings(dt=dt),
                disturbance_bound=eps * SPEED,
            )
            means.append(float(np.nanmean(res.error)))
        rel = [means[0] / m - 1.0 for m in means[1:]]
        worst = max(worst, *(abs(r) for r in rel))
        print(
            f"eps {eps:4.2f}, R_plan {r_plan:6.4f} R0: mean error at dt = 0.05 s "
            f"{means[0]:.4f} m; relative to dt = "
            + ", ".join(f"{dt:g} s: {r:+.2%}" for dt, r in zip(STEPS[1:], rel, strict=True))
        )
    print(f"largest difference {worst:.2%} (tolerance {TOLERANCE:.0%})")
    print("PASS" if worst <= TOLERANCE else "FAIL")
    if worst > TOLERANCE:
        raise SystemExit(1)


if __name__ == "__main__":
    main()
