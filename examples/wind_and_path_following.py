"""Paths in currents (dissertation chapter 3): plan in a known wind, then follow a Dubins path
planned with the feasible radius R0' = R0 (1 + eps)^2 through an unknown steady wind and
through Dryden gusts, thousands of vehicles at once."""

import math

import numpy as np

from glideplan import DubinsCarInWind, Pose, plan
from glideplan.simulation import (
    DrydenTurbulence,
    FollowerSettings,
    PathArrays,
    SteadyDisturbance,
    follow_paths,
)

# 1. Time-optimal path in a known 0.3 m/s current (airspeed 1 m/s, turn radius 1 m).
vehicle = DubinsCarInWind(speed=1.0, turn_radius=1.0, wind=(0.3, 0.0))
sol = plan(Pose(0, 0, 0), Pose(3, 3, math.pi / 2), vehicle).raise_for_status()
print(
    f"known wind: T* = {sol.cost:.5f} s via {sol.word}, endpoint error {sol.endpoint_error.max:.1e}"
)

# 2. Unknown disturbance of at most eps v: follow Dubins paths planned with R0 and with R0'.
settings = FollowerSettings()  # v = 20 m/s, u_max = 0.3 rad/s, R0 = 66.7 m
r0, eps, n = settings.min_radius, 0.5, 2000
rng = np.random.default_rng(0)
goals = np.column_stack([rng.uniform(-4, 4, (n, 2)) * r0, rng.choice([0, 2 * np.pi / 3, np.pi], n)])
dirs = rng.uniform(0, 2 * np.pi, n)
steady = SteadyDisturbance(eps * settings.speed * np.column_stack([np.cos(dirs), np.sin(dirs)]))
gusts = DrydenTurbulence(sigma=eps * settings.speed, saturation=eps * settings.speed)
for name, radius in (("R0", r0), ("R0'", r0 * (1 + eps) ** 2)):
    paths = PathArrays.dubins(goals, radius)
    for label, stream in (
        ("steady wind", steady.stream(n, settings.dt)),
        ("Dryden gusts", gusts.stream(n, settings.dt, np.random.default_rng(1))),
    ):
        res = follow_paths(paths, stream, settings=settings, disturbance_bound=eps * settings.speed)
        print(
            f"planned with {name:4s}, {label:12s}: mean final cross-track error "
            f"{np.nanmean(res.error) / r0:.3f} R0, failures {res.failures}"
        )
