"""The front phase of `route()`: the reachable front (`glideplan.fronts`) on a window that
grows whenever the front's band reaches a side that is not the field's edge (`FrontOutcome`;
`glideplan.routing.phases`)."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from glideplan.routing.problem import FloatArray, FrontOutcome, RouteGrid, RouteProblem
from glideplan.routing.route_grid import regrid
from glideplan.routing.sphere import gc_distance
from glideplan.routing.window import Window, WindowCurrents


def kernel_problem(problem: RouteProblem, rg: RouteGrid) -> Any:
    """The front kernel's `FrontProblem` for routing: one normal speed V, no constant drift,
    the current as the drift field (NaN at obstacles), obstacles blocked always."""
    from glideplan.fronts import DriftLevels, FrontProblem

    cur = rg.currents
    obstacle = rg.obstacle

    def level(k: int) -> tuple[FloatArray, FloatArray]:
        u, v = cur.level(k)
        return np.where(obstacle, np.nan, u), np.where(obstacle, np.nan, v)

    drift = DriftLevels(level_times(cur, problem.t_max), level, max_cached=4)
    block = np.where(rg.obstacle, -np.inf, np.inf)
    return FrontProblem(rg.window.grid(), speeds=np.array([problem.speed]), drift=drift,
                        block_time=block)


def level_times(cur: WindowCurrents, t_max: float) -> FloatArray:
    """The time levels of the current the front uses: the field's own, one for a steady
    field, or every sample_dt from t0 to past t_max (analytic fields)."""
    if cur.levels is not None:
        return cur.levels
    n = max(math.ceil((t_max - cur.t0) / cur.sample_dt), 1) + 1
    return np.asarray(cur.t0 + np.arange(n + 1) * cur.sample_dt, dtype=float)


def _closest(arrival: FloatArray, window: Window, goal: tuple[float, float],
             start_dist: float) -> float:
    reached = np.isfinite(arrival)
    if not reached.any():
        return start_dist
    LA, LO = np.meshgrid(window.lat, window.lon, indexing="ij")
    d = gc_distance(LA[reached], LO[reached], goal[0], goal[1])
    return float(min(np.min(d), start_dist))


class _Progress:
    """Rich progress on stderr for the front, shown once it has run ~2 s (the kernel's
    on_step(t, steps, reached)): simulated time against the expected arrival (`expected` s
    after t0: the straight line's still-water time, grown to 1.05 x the simulated time once
    that passes it), steps, elapsed time and an estimate of the time left."""

    def __init__(self, enabled: bool, t0: float, t_max: float,
                 expected: float | None = None) -> None:
        self.enabled = enabled
        self.t0, self.t_max = t0, t_max
        self.expected = min(expected, t_max - t0) if expected else t_max - t0
        self.started = time.perf_counter()
        self.bar: Any = None
        self.task: Any = None
        self.last = 0.0

    def __call__(self, t: float, steps: int, reached: int) -> None:
        if not self.enabled:
            return
        now = time.perf_counter()
        if now - self.last < 0.1:
            return
        self.last = now
        if self.bar is None:
            if now - self.started < 2.0:
                return
            from glideplan.progress import start_progress_bar

            self.bar, self.task = start_progress_bar(
                "routing: front", self.expected, info=True, count=False, remaining="left",
                transient=True)
        done = max(t - self.t0, 0.0)
        if done > self.expected:  # later than the straight line: expect a little more
            self.expected = min(1.05 * done, self.t_max - self.t0)
            self.bar.update(self.task, total=self.expected)
        self.bar.update(self.task, completed=min(done, self.expected),
                        info=f"step {steps}, simulated {done / 3600:.1f} h, "
                             f"{reached} nodes reached")

    def close(self) -> None:
        if self.bar is not None:
            self.bar.stop()
            self.bar = None


def front(problem: RouteProblem, rg: RouteGrid,
          on_step: Callable[[float, int, int], None] | None = None) -> tuple[
              FrontOutcome, RouteGrid]:
    """Propagate the front from the start until the goal, growing the window (docstring)."""
    from glideplan.fronts import propagate, start_state

    kp = kernel_problem(problem, rg)
    with np.errstate(invalid="ignore"):  # the kernel's start disk: inf x 0 where unreachable
        state = start_state(kp, problem.t0, problem.start[0], problem.start[1])
    growths = 0
    limited = False
    progress = _Progress(problem.settings.progress, problem.t0, problem.t_max,
                         problem.distance_m / problem.speed)
    callback = on_step if on_step is not None else progress
    cfl = min(problem.settings.cfl, 0.9)
    try:
        while True:
            res = propagate(kp, state, problem.t_max, goal=problem.goal, cfl=cfl,
                            stop_on_edge=True, on_step=callback)
            if res.reason != "edge":
                break
            sides = set(res.edges) - rg.window.fixed_sides()
            if not sides:  # cannot happen with the edge pad; stop rather than loop
                break
            bigger = rg.window.grown(sides)
            if bigger.nodes > problem.settings.max_nodes:
                limited = True
                break
            old = rg.window
            rg = regrid(problem, rg, bigger)
            kp = kernel_problem(problem, rg)
            row0, col0 = old.offset_in(bigger)
            state = res.state.embedded(bigger.shape, row0, col0, kp.band)
            growths += 1
    finally:
        progress.close()
    arrival = np.asarray(res.arrival, dtype=float)
    closest = 0.0
    why = None
    if res.reason != "goal":
        closest = _closest(arrival, rg.window, problem.goal, problem.distance_m)
        if limited:
            why = "window_limit"
        elif res.reason == "t_max":
            why = problem.limit_reason
        elif _goal_connected(arrival, rg, problem.goal) and _touches_edge(arrival, rg.window):
            why = "field_extent"
        else:  # stalled inside the field, or land (and its clearance) cut the goal off
            why = "front_stopped"
    goal_time = float(res.goal_time) if (res.reason == "goal" and res.goal_time is not None) \
        else None
    return FrontOutcome(arrival, goal_time, res.reason, why, closest, kp, int(res.steps),
                        growths, res.state), rg


def _goal_connected(arrival: FloatArray, rg: RouteGrid, goal: tuple[float, float]) -> bool:
    """Whether free water connects the goal's node to the reached nodes (8-neighbours)."""
    from scipy.ndimage import label

    labels, _ = label(~rg.obstacle, structure=np.ones((3, 3), dtype=bool))
    fi, fj = rg.window.frac_index(goal[0], goal[1])
    i, j = int(np.rint(fi)), int(np.rint(fj))
    ny, nx = labels.shape
    if not (0 <= i < ny and 0 <= j < nx):
        return True
    near = labels[max(i - 1, 0):i + 2, max(j - 1, 0):j + 2]
    ids = set(np.unique(near[near > 0]).tolist())
    reached = np.unique(labels[np.isfinite(arrival) & (labels > 0)])
    return bool(ids & set(reached.tolist()))


def _touches_edge(arrival: FloatArray, window: Window) -> bool:
    """Whether reached nodes lie next to the outside of the field (its edge)."""
    from scipy.ndimage import binary_dilation

    outside = ~window.inside
    if not outside.any():
        return False
    near = binary_dilation(outside, structure=np.ones((3, 3), dtype=bool), iterations=2)
    return bool(np.any(np.isfinite(arrival) & near))
