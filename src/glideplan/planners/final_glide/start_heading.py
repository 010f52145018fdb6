"""The start heading of a glide whose start heading is free (the pilot may turn at once).

With a free initial heading the Minimum Principle's transversality condition gives
eta_psi(0) = 0: an optimal path starts on a straight. The surrogate is the constant-airspeed
model of the known-wind planner (airspeed v and turn radius R of
`direct.guess_speed_and_radius`): in the frame drifting with the wind the goal pose moves,
g(T) = G - w T, and the fastest "straight, then one turn" path from the start to g(T) is a
tangent to one of the two turn circles ending at g(T) (centre c = g + d R (-sin psi1, cos psi1),
d = +1 left, -1 right), of air length L(T) = sqrt(|c|^2 - R^2) + R dpsi. Its arrival time is
the smallest root of L(T) = v T (bracketed on a grid, bisected), and the start heading is the
tangent's direction angle(c) -+ atan2(R, sqrt(|c|^2 - R^2)). When the start lies inside both
circles the known-wind planner's full arrival time is minimised over a grid of headings.
"""

from __future__ import annotations

import math

import numpy as np

from glideplan.planners.final_glide.direct import guess_speed_and_radius
from glideplan.planners.wind import convected_dubins
from glideplan.pose import TWO_PI, Pose, mod_2pi, wrap_to_pi
from glideplan.vehicles.sailplane import Sailplane

__all__ = ["best_start_heading", "straight_turn_arrival"]


def straight_turn_arrival(
    goal: Pose, speed: float, radius: float, wind: tuple[float, float], direction: int
) -> tuple[float, float]:
    """(arrival time T (s), start heading (rad)) of the straight-then-turn path, or (inf, nan).

    The start is the origin; `direction` +1 ends with a left turn, -1 with a right turn.
    """
    d = float(direction)
    nx, ny = -math.sin(goal.heading), math.cos(goal.heading)
    wmag = math.hypot(*wind)
    t_max = (math.hypot(goal.x, goal.y) + radius * (2.0 + TWO_PI)) / (speed - wmag)
    T = np.linspace(0.0, t_max, 2001)
    cx = goal.x - wind[0] * T + d * radius * nx
    cy = goal.y - wind[1] * T + d * radius * ny
    dc2 = cx**2 + cy**2
    ok = dc2 > radius**2
    t = np.sqrt(np.where(ok, dc2 - radius**2, 1.0))
    theta = np.arctan2(cy, cx) - d * np.arctan2(radius, t)
    arc = mod_2pi(d * (goal.heading - theta))
    F = np.where(ok, t + radius * arc - speed * T, np.nan)
    # first cell where F goes from > 0 to <= 0 without an arc wrap (a jump of 2 pi R)
    cells = np.nonzero((F[:-1] > 0.0) & (F[1:] <= 0.0) & (np.abs(F[1:] - F[:-1]) < np.pi * radius))[
        0
    ]
    if cells.size == 0:
        return math.inf, math.nan
    i = int(cells[0])
    lo, hi = float(T[i]), float(T[i + 1])

    def f(tt: float) -> tuple[float, float]:
        cxx = goal.x - wind[0] * tt + d * radius * nx
        cyy = goal.y - wind[1] * tt + d * radius * ny
        tl = math.sqrt(max(cxx**2 + cyy**2 - radius**2, 0.0))
        th = math.atan2(cyy, cxx) - d * math.atan2(radius, tl)
        ar = float(mod_2pi(d * (goal.heading - th)))
        return tl + radius * ar - speed * tt, th

    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if f(mid)[0] > 0.0:
            lo = mid
        else:
            hi = mid
    return hi, float(wrap_to_pi(f(hi)[1]))


def best_start_heading(
    start: tuple[float, float], goal: Pose, vehicle: Sailplane, *, mc: float = 0.0, grid: int = 24
) -> float:
    """Start heading (rad, world frame) of the fastest straight-then-turn path (see module)."""
    v, radius = guess_speed_and_radius(vehicle, mc)
    local = Pose(goal.x - start[0], goal.y - start[1], goal.heading)
    wind = vehicle.wind
    best = min(straight_turn_arrival(local, v, radius, wind, d) for d in (1, -1))
    if math.isfinite(best[0]):
        return best[1]
    headings = np.linspace(-math.pi, math.pi, int(grid), endpoint=False)
    times = []
    for h in headings:
        frame = Pose(start[0], start[1], float(h))
        w = vehicle.wind_in_frame(float(h))
        times.append(convected_dubins(goal.relative_to(frame), speed=v, radius=radius, wind=w).time)
    return float(headings[int(np.argmin(times))])
