"""The phases of `route()`, each a function of the previous phases' outputs (testable alone):

    setup -> grid -> front -> backtrack -> refine -> verify

- `setup`: checks the inputs, reads files, fixes the departure, the time limit and its
  reason ("time_span" or "max_duration"), the start and goal in the frame unwrapped about the
  start (`RouteProblem`).
- `grid`: the lattice and first window (`routing.window`), the field on it, the land
  clearance and the obstacle nodes (`RouteGrid`).
- `front`: the reachable front (`glideplan.fronts`), on a window that grows whenever the
  front's band reaches a side that is not the field's edge (`FrontOutcome`).
- `backtrack`: the kernel's characteristic backwards from the goal, then the headings that
  hold its polyline leg by leg (`sphere.crab_controls`) -- the "grid" route (`Candidate`).
- `refine`: Zermelo shooting on the sphere (`routing.zermelo`) in open water, started from the
  grid route; kept by `route()` only if it verifies and is not slower.
- `verify`: the controls flown through the field itself (`sphere.fly_headings`).
"""

from __future__ import annotations

import math
import pathlib
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, to_seconds
from glideplan.routing.settings import RouteSettings
from glideplan.routing.sphere import (
    EARTH_RADIUS_M,
    FlownRoute,
    crab_controls,
    fly_headings,
    gc_distance,
    unwrap_lon,
)
from glideplan.routing.window import (
    Lattice,
    Window,
    WindowCurrents,
    build_lattice,
    initial_window,
    land_clearance_default,
    obstacles,
)

__all__ = [
    "Candidate",
    "FrontOutcome",
    "RouteGrid",
    "RouteProblem",
    "backtrack",
    "front",
    "grid",
    "refine",
    "setup",
    "verify",
]

FloatArray = NDArray[np.float64]

#: Analytic unsteady fields are sampled every (still-water time / this) seconds.
LEVELS_PER_CROSSING = 48


@dataclass(frozen=True, eq=False)
class RouteProblem:
    """What `setup` fixes: the field, start/goal (deg; goal lon unwrapped about the start),
    speed (m/s), departure t0 and limit t_max (s since the field's epoch), why t_max is the
    limit ("time_span" / "max_duration"), the great-circle distance (m), the settings."""

    field_: FlowField
    start: tuple[float, float]
    goal: tuple[float, float]
    speed: float
    t0: float
    t_max: float
    limit_reason: str
    distance_m: float
    settings: RouteSettings
    depart: np.datetime64 | None
    warnings: tuple[str, ...] = ()


@dataclass(eq=False)
class RouteGrid:
    """What `grid` builds: the lattice, the window, the field on it, the clearance (m) and
    the obstacle nodes (land, or within the clearance of land)."""

    lattice: Lattice
    window: Window
    currents: WindowCurrents
    clearance_m: float
    obstacle: NDArray[np.bool_]
    land: NDArray[np.bool_]
    warnings: list[str] = field(default_factory=list)
    coast_xyz: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    #: the clearance of the front's obstacles (m): less than clearance_m when the route keeps
    #: the clearance at the land mask's resolution (`routing.coast`)
    front_clearance_m: float | None = None

    @property
    def spacing_m(self) -> float:
        return self.lattice.spacing_m


@dataclass(frozen=True, eq=False)
class FrontOutcome:
    """The front's answer: arrival times (s since epoch, inf never) on the final window, the
    goal's arrival (None if not reached), the stop reason (kernel's) and, when unreachable,
    the route's `unreachable_reason`; the closest approach (m); the kernel's problem (for
    backtracking); steps and window growths."""

    arrival: FloatArray
    goal_time: float | None
    reason: str
    unreachable_reason: str | None
    closest_m: float
    problem: Any
    steps: int
    growths: int
    state: Any = None


@dataclass(frozen=True, eq=False)
class Candidate:
    """A route to verify: vertex times (s since epoch), lat/lon (deg, lon continuous),
    compass headings (rad) of the through-water velocity, held per leg (`hold`) or linear in
    time; its duration (s) and method name."""

    method: str
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    chi: FloatArray
    hold: bool
    duration: float
    note: str = ""


# --------------------------------------------------------------------------------- setup


def _as_field(field_: Any, depth_range: tuple[float, float] | None) -> FlowField:
    if isinstance(field_, FlowField):
        if depth_range is not None:
            raise InvalidParameterError(
                "depth_range", depth_range, "applies when reading files; average the field first"
            )
        return field_
    if isinstance(field_, (str, pathlib.Path)) or (
        isinstance(field_, Sequence) and all(isinstance(p, (str, pathlib.Path)) for p in field_)
    ):
        from glideplan.fields.io import open_field

        return open_field(field_, depth_range=depth_range)
    raise InvalidParameterError("field", type(field_).__name__, "must be a FlowField or file(s)")


def _check_point(fld: FlowField, t: float, point: Any, name: str) -> tuple[float, float]:
    from glideplan.validation import check_finite

    try:
        lat, lon = (check_finite(name, float(point[0])), check_finite(name, float(point[1])))
    except (TypeError, ValueError, IndexError):
        raise InvalidParameterError(name, point, "must be (lat, lon) in degrees") from None
    if abs(lat) > 90.0:
        raise InvalidParameterError(name, point, "latitude must lie in [-90, 90]")
    fld.check_position(lat, lon, name=name)
    if abs(lat) > 85.0:
        raise InvalidParameterError(name, point, "latitude beyond +-85 deg: the router's "
                                    "lat/lon grid does not reach the poles")
    u, v = fld.velocity(t, lat, lon)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise InvalidParameterError(name, (lat, lon), fld.nan_cause(t, lat, lon))
    return lat, lon


def setup(field_: Any, start: Any, goal: Any, speed: float, depart: Any = None,
          depth_range: tuple[float, float] | None = None,
          settings: RouteSettings | None = None) -> RouteProblem:
    """Check the inputs and fix the problem (module docstring). Raises InvalidParameterError."""
    from glideplan.validation import check_physical

    settings = settings or RouteSettings()
    speed = check_physical("speed", speed, "speed")
    fld = _as_field(field_, depth_range)
    if (getattr(fld, "info", None) or {}).get("medium") == "water":  # a current, not a wind
        check_physical("speed", speed, "water_speed")
    if depart is None:
        t0 = fld.time_span[0] if fld.time_span is not None else 0.0
        if fld.time_span is None and fld.time_levels is not None:
            t0 = float(fld.time_levels[0])
        tl = getattr(fld, "times", None)
        if fld.time_span is None and tl is not None and np.size(tl) == 1:
            t0 = float(np.ravel(tl)[0])
    else:
        t0 = float(to_seconds(depart, fld.epoch))
    fld.check_time(t0)
    a = _check_point(fld, t0, start, "from")
    b = _check_point(fld, t0, goal, "to")
    b = (b[0], float(unwrap_lon(b[1], a[1])))
    dist = float(gc_distance(a[0], a[1], b[0], b[1]))
    md = settings.max_duration
    if fld.time_span is not None:
        t_max, reason = fld.time_span[1], "time_span"
        if md is not None and t0 + md < t_max:
            t_max, reason = t0 + md, "max_duration"
    else:
        t_max = t0 + (md if md is not None else max(10.0 * dist / speed, 3600.0))
        reason = "max_duration"
    depart_dt = None if fld.epoch is None else fld.epoch + np.timedelta64(round(t0 * 1e3), "ms")
    return RouteProblem(fld, a, b, float(speed), float(t0), float(t_max), reason, dist,
                        settings, depart_dt, tuple(getattr(fld, "warnings", ())))


# ---------------------------------------------------------------------------------- grid


def spacing_for(problem: RouteProblem) -> float:
    """The routing spacing h (m): the setting, else distance / cells (>= 1 m)."""
    s = problem.settings
    if s.resolution is not None:
        return float(s.resolution)
    return max(problem.distance_m / s.cells, 1.0)


def _free_zones(problem: RouteProblem, rg_land_clear: float, dist_start: float,
                dist_goal: float, h: float) -> list[tuple[float, float, float]]:
    zones = []
    for p, d in ((problem.start, dist_start), (problem.goal, dist_goal)):
        if d < rg_land_clear:
            zones.append((p[0], p[1], rg_land_clear - d + 2.0 * h))
    return zones


def build_obstacles(problem: RouteProblem, window: Window, currents: WindowCurrents,
                    clearance: float, strict: bool = False) -> tuple[
                        NDArray[np.bool_], NDArray[np.bool_], list[str], FloatArray, float]:
    """(obstacle mask, land mask, warnings, coast points (3-D, m), the front's clearance) on
    `window` (module docstring of `routing.window`; `routing.coast.front_obstacles` where the
    route keeps the clearance at the land mask's resolution, unless `strict`)."""
    from glideplan.routing.window import distance_to_land, land_points

    land = currents.land()
    h = window.lattice.spacing_m
    warn: list[str] = []
    zones: list[tuple[float, float, float]] = []
    pts = land_points(problem.field_, window, land, clearance + h)
    if clearance > 0:
        if pts.shape[0]:
            ds = float(distance_to_land(pts, np.array(problem.start[0]),
                                        np.array(problem.start[1]), clearance))
            dg = float(distance_to_land(pts, np.array(problem.goal[0]),
                                        np.array(problem.goal[1]), clearance))
            zones = _free_zones(problem, clearance, ds, dg, h)
            for (name, d) in (("start", ds), ("goal", dg)):
                if d < clearance:
                    warn.append(f"the {name} is {d:.0f} m from land, closer than the land "
                                f"clearance {clearance:.0f} m: the clearance is relaxed "
                                f"around it")
    from glideplan.routing import coast

    lat_ref = 0.5 * (problem.start[0] + problem.goal[0])
    if not zones and pts.shape[0] and coast.applies(problem.field_, clearance, lat_ref,
                                                    window.periodic):
        mask, c_front, more = coast.front_obstacles(problem, window, land, clearance, pts,
                                                    strict)
        return mask | ~window.inside, land, warn + more, pts, c_front
    mask, _ = obstacles(problem.field_, window, land, clearance, zones, pts)
    return mask | ~window.inside, land, warn, pts, clearance


def grid(problem: RouteProblem) -> RouteGrid:
    """The lattice, first window, the field on it and the obstacles (module docstring)."""
    h = spacing_for(problem)
    if problem.distance_m > 0 and problem.distance_m < 4 * h:
        raise InvalidParameterError(
            "resolution", h,
            f"too coarse: start and goal are {problem.distance_m:.0f} m apart (need >= 4 cells)")
    lattice = build_lattice(problem.field_, problem.start, problem.goal, h)
    window = initial_window(lattice, problem.goal, problem.distance_m, problem.settings.margin)
    if window.nodes > problem.settings.max_nodes:
        raise InvalidParameterError(
            "resolution", h, f"gives {window.shape[0]} x {window.shape[1]} nodes (limit "
            f"{problem.settings.max_nodes:g}): choose a coarser one")
    sample_dt = max(problem.distance_m / problem.speed / LEVELS_PER_CROSSING, 1.0)
    currents = WindowCurrents.build(window, problem.field_, problem.t0, sample_dt)
    lat_ref = 0.5 * (problem.start[0] + problem.goal[0])
    clearance = problem.settings.land_clearance_m
    if clearance is None:
        from glideplan.routing.coast import applies

        clearance = land_clearance_default(problem.field_, h, lat_ref)
        exact = land_clearance_default(problem.field_, 0.0, lat_ref)  # the field's own cells
        if exact > 0 and applies(problem.field_, exact, lat_ref, window.periodic):
            clearance = exact  # kept at the mask's resolution: no grid spacing added
    mask, land, warn, pts, c_front = build_obstacles(problem, window, currents, clearance)
    return RouteGrid(lattice, window, currents, float(clearance), mask, land, warn, pts,
                     c_front)


def regrid(problem: RouteProblem, rg: RouteGrid, window: Window) -> RouteGrid:
    """`rg` on a grown window: the field resampled there, the obstacles recomputed."""
    currents = rg.currents.regrown(window)
    strict = rg.front_clearance_m == rg.clearance_m
    mask, land, warn, pts, c_front = build_obstacles(problem, window, currents, rg.clearance_m,
                                                     strict)
    from glideplan.routing.coast import GAP_CLOSED, GAP_WARNING

    old = [w for w in rg.warnings if not w.startswith((GAP_WARNING, GAP_CLOSED))]
    return RouteGrid(rg.lattice, window, currents, rg.clearance_m, mask, land,
                     sorted(set(old) | set(warn)), pts, c_front)


def strict_grid(problem: RouteProblem, rg: RouteGrid) -> RouteGrid:
    """`rg` with the front's obstacles at the full clearance (the way the front found at a
    reduced one is closed at the land mask's resolution)."""
    mask, land, warn, pts, c_front = build_obstacles(problem, rg.window, rg.currents,
                                                     rg.clearance_m, strict=True)
    from glideplan.routing.coast import GAP_CLOSED, GAP_WARNING

    old = [w for w in rg.warnings if not w.startswith((GAP_WARNING, GAP_CLOSED))]
    return RouteGrid(rg.lattice, rg.window, rg.currents, rg.clearance_m, mask, land,
                     sorted(set(old) | set(warn)), pts, c_front)


# --------------------------------------------------------------------------------- front


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


# ----------------------------------------------------------------------------- backtrack


#: A held heading switches to the next leg's this long (s) after the vertex.
SWITCH_S = 1e-3


def _held(method: str, times: FloatArray, lat: FloatArray, lon: FloatArray, chi: FloatArray,
          t0: float) -> Candidate:
    """Leg headings held to each vertex, written as controls linear in time between samples:
    each inner vertex twice, the second SWITCH_S later with the next leg's heading, so the
    published track is one representation (linear between samples) of the held controls.
    The candidate is verified piecewise (`hold`: the integrator restarts at every sample,
    which a switch of a millisecond needs).

    Samples: (t0, h0), (t1, h0), (t1 + s, h1), (t2, h1), ..., (tn, h_{n-1}).
    """
    n = times.size
    h = np.unwrap(np.asarray(chi, dtype=float))[: n - 1]  # leg k's heading
    inner = times[1:-1]
    legs = np.diff(times)
    after = inner + np.minimum(SWITCH_S, 0.25 * np.minimum(legs[:-1], legs[1:]))
    t_out = np.concatenate([[times[0]], np.column_stack([inner, after]).ravel(), [times[-1]]])
    h_out = np.concatenate([[h[0]], np.column_stack([h[:-1], h[1:]]).ravel(), [h[-1]]])
    la_out = np.concatenate([[lat[0]], np.repeat(lat[1:-1], 2), [lat[-1]]])
    lo_out = np.concatenate([[lon[0]], np.repeat(lon[1:-1], 2), [lon[-1]]])
    return Candidate(method, t_out, la_out, lo_out, h_out, True, float(times[-1] - t0))


#: The method of a `backtrack` answer that says: run the front again at the full clearance.
CLOSED = "closed"

#: Up to this many legs the grid route's headings are held leg by leg (the verification
#: restarts its integrator at every vertex); longer routes get one smooth control.
HOLD_MAX_LEGS = 400


def backtrack(problem: RouteProblem, rg: RouteGrid, fo: FrontOutcome) -> Candidate:
    """The grid route: the kernel's characteristic from the goal, held leg by leg (docstring)."""
    from glideplan.fronts import backtrack as kernel_backtrack

    assert fo.goal_time is not None
    tr = kernel_backtrack(fo.problem, fo.arrival, goal=problem.goal, t_goal=fo.goal_time,
                          t0=problem.t0, source=problem.start,
                          start_radius_m=fo.state.start_radius_m)
    lat = np.asarray(tr.lat, dtype=float)
    lon = unwrap_lon(np.asarray(tr.lon, dtype=float), problem.start[1])
    lon = np.degrees(np.unwrap(np.radians(lon)))
    t = np.asarray(tr.t, dtype=float)
    order = np.argsort(t, kind="stable")
    lat, lon, t = lat[order], lon[order], t[order]
    # Pin the ends on the start and the goal.
    if gc_distance(lat[0], lon[0], *problem.start) > 1e-6:
        lat, lon = np.r_[problem.start[0], lat], np.r_[problem.start[1], lon]
    else:
        lat[0], lon[0] = problem.start
    if gc_distance(lat[-1], lon[-1], *problem.goal) > 1e-6:
        lat, lon = np.r_[lat, problem.goal[0]], np.r_[lon, problem.goal[1]]
    else:
        lat[-1], lon[-1] = problem.goal
    lat, lon = _thin(lat, lon, 1.5 * rg.spacing_m)
    rules = clearance_rules(rg)
    snap = out_of_obstacles(rg)
    lat, lon = keep_clearance(lat, lon, rules, snap=snap)

    def current(tt: FloatArray, la: FloatArray, lo: FloatArray) -> FloatArray:
        c = rg.currents.points(float(tt[0]), la, lo)
        near = ~(np.isfinite(c[0]) & np.isfinite(c[1]))
        if near.any():  # within a window cell of the coast: the field's own current
            u, v = problem.field_.velocity(float(tt[0]), np.asarray(la)[near],
                                           np.asarray(lo)[near])
            c[0, near], c[1, near] = u, v
        return c

    times, chi, _ok = crab_controls(current, problem.speed, problem.t0, lat, lon)
    if _near(lat, lon, rules, 2.0 * rg.spacing_m):
        # Next to obstacles: the taut polyline (clearance kept) when it is not slower; round
        # the field's own land nodes the exact one (`routing.coast`), which is also taken
        # when the grid route cuts into the clearance.
        from glideplan.routing.coast import clearance_of, round_coast

        exact = round_coast(problem, rg, fo.arrival)
        if exact is None and rg.front_clearance_m is not None and \
                rg.front_clearance_m < rg.clearance_m:
            # the front's way, found at a reduced clearance, is closed at the full one
            return Candidate(CLOSED, times, lat, lon, chi, True, math.inf)
        la2, lo2 = exact if exact is not None else taut(lat, lon, rules, snap=snap)
        t2, c2, ok2 = crab_controls(current, problem.speed, problem.t0, la2, lo2)
        wet = exact is not None or np.all(np.isfinite(rg.currents.points(problem.t0, la2,
                                                                          lo2)))
        cuts = exact is not None and clearance_of(
            lat, lon, rg.coast_xyz, min(rg.clearance_m, rg.spacing_m) / 4) < \
            rg.clearance_m * (1 - 1e-3)
        if ok2 and wet and (t2[-1] < times[-1] or cuts):
            # the taut polyline: a few long legs with sharp corners at the obstacles. Each
            # leg's heading held until its vertex (piecewise constant) reproduces it; a
            # heading linear in time between the legs' middles would cut every corner
            # (measured: a 670 m miss round an island where the held legs end within metres).
            return _held("grid", t2, la2, lo2, c2, problem.t0)
    if len(times) <= HOLD_MAX_LEGS + 1:
        # few legs: each held to its vertex, as crab_controls timed them (exact in still water)
        return _held("grid", times, lat, lon, chi, problem.t0)
    # Controls: each leg's heading at its middle time, linear in time between (one smooth
    # control the verification integrates in one pass; the ends hold the first/last leg's).
    mid = 0.5 * (times[:-1] + times[1:])
    tc = np.concatenate([[times[0]], mid, [times[-1]]])
    cc = np.unwrap(np.concatenate([[chi[0]], chi[:-1], [chi[-2]]]))
    ta = np.unique(np.concatenate([times, mid]))
    return Candidate("grid", ta, np.interp(ta, times, lat), np.interp(ta, times, lon),
                     np.interp(ta, tc, cc), False, float(times[-1] - problem.t0))


def clearance_rules(rg: RouteGrid) -> list[tuple[Any, float]]:
    """What a route must keep clear of, as (k-d tree of 3-D points, distance m): the coast
    points by the land clearance, and the window's land and off-field nodes (the field's
    NaN stencil and edge) by 1.5 spacings (the chords between vertices 1.5 spacings apart
    then stay clear too)."""
    from scipy.spatial import cKDTree

    from glideplan.routing.window import _coast, _xyz

    rules: list[tuple[Any, float]] = []
    if rg.clearance_m > 0 and rg.coast_xyz.shape[0]:
        rules.append((cKDTree(rg.coast_xyz), rg.clearance_m))
    hard = rg.land | ~rg.window.inside
    if hard.any():
        edge = _coast(hard)
        LA, LO = np.meshgrid(rg.window.lat, rg.window.lon, indexing="ij")
        rules.append((cKDTree(_xyz(LA[edge], LO[edge])), 1.5 * rg.spacing_m))
    return rules


def _near(lat: FloatArray, lon: FloatArray, rules: Sequence[tuple[Any, float]],
          margin: float) -> bool:
    """Whether a vertex lies within a rule's distance + `margin` (m) of its points."""
    from glideplan.routing.window import _xyz

    p = _xyz(lat, lon)
    return any(bool(np.any(tree.query(p, distance_upper_bound=c + margin)[0] < c + margin))
               for tree, c in rules)


def out_of_obstacles(rg: RouteGrid) -> Callable[[FloatArray, FloatArray], tuple[
        FloatArray, FloatArray]] | None:
    """(lat, lon) -> the same points, those whose nearest node is land or off the field moved
    to the nearest node that is neither (a characteristic that meets an obstacle can run
    straight through it); None when there is no such node."""
    from scipy.ndimage import distance_transform_edt

    hard = rg.land | ~rg.window.inside
    if not hard.any():
        return None
    _, (ni, nj) = distance_transform_edt(hard, return_indices=True)
    win = rg.window
    lat_n, lon_n = win.lat, win.lon

    def snap(la: FloatArray, lo: FloatArray) -> tuple[FloatArray, FloatArray]:
        fi, fj = win.frac_index(la, lo)
        ny, nx = win.shape
        i = np.clip(np.rint(fi).astype(int), 0, ny - 1)
        j = np.rint(fj).astype(int)
        j = np.mod(j, nx) if win.periodic else np.clip(j, 0, nx - 1)
        bad = hard[i, j]
        bad[0] = bad[-1] = False
        if not bad.any():
            return la, lo
        la, lo = la.copy(), lo.copy()
        ti, tj = ni[i[bad], j[bad]], nj[i[bad], j[bad]]
        la[bad] = lat_n[ti]
        lo[bad] = unwrap_lon(lon_n[tj], lo[bad])
        return la, lo

    return snap


def keep_clearance(lat: FloatArray, lon: FloatArray, rules: Sequence[tuple[Any, float]],
                   passes: int = 3, snap: Callable[[FloatArray, FloatArray], tuple[
                       FloatArray, FloatArray]] | None = None) -> tuple[FloatArray, FloatArray]:
    """Vertices inside an obstacle moved out (`snap`, `out_of_obstacles`), then those closer
    than a rule's distance (m) to one of its points moved straight away from it to that
    distance (`clearance_rules`; the backtracked characteristic may cut a cell or more into
    the obstacles' margin next to them; the ends stay where they are)."""
    if lat.size < 3:
        return lat, lon
    if snap is not None:
        lat, lon = snap(lat, lon)
    if not rules:
        return lat, lon
    from glideplan.routing.window import _xyz

    la, lo = lat.copy(), lon.copy()
    for _ in range(passes):
        moved = False
        for tree, clearance in rules:
            p = _xyz(la[1:-1], lo[1:-1])
            d, k = tree.query(p)
            close = d < clearance * (1 - 1e-6)
            if not close.any():
                continue
            moved = True
            q = tree.data[k[close]]
            dirn = p[close] - q
            norm = np.linalg.norm(dirn, axis=1, keepdims=True)
            norm[norm == 0] = 1.0
            new = q + clearance * (1 + 1e-6) * dirn / norm
            new *= EARTH_RADIUS_M / np.linalg.norm(new, axis=1, keepdims=True)
            nla = np.degrees(np.arcsin(np.clip(new[:, 2] / EARTH_RADIUS_M, -1, 1)))
            nlo = np.degrees(np.arctan2(new[:, 1], new[:, 0]))
            idx = np.flatnonzero(close) + 1
            la[idx] = nla
            lo[idx] = unwrap_lon(nlo, lo[idx])
        if not moved:
            break
    return la, lo


def taut(lat: FloatArray, lon: FloatArray, rules: Sequence[tuple[Any, float]],
         iterations: int = 200, snap: Callable[[FloatArray, FloatArray], tuple[
             FloatArray, FloatArray]] | None = None) -> tuple[FloatArray, FloatArray]:
    """The polyline pulled taut with the ends fixed, keeping the clearance: each pass moves
    every interior vertex half way to its neighbours' mean, then out of the clearance
    (`keep_clearance`); in still water this converges to the shortest way round (tangent,
    arc of the clearance circle, tangent)."""
    from glideplan.routing.window import _xyz

    p = _xyz(lat, lon)
    la, lo = lat.copy(), lon.copy()
    for _ in range(iterations):
        mid = 0.5 * (p[:-2] + p[2:])
        p[1:-1] = 0.5 * p[1:-1] + 0.5 * mid
        p *= EARTH_RADIUS_M / np.linalg.norm(p, axis=1, keepdims=True)
        la = np.degrees(np.arcsin(np.clip(p[:, 2] / EARTH_RADIUS_M, -1, 1)))
        lo = unwrap_lon(np.degrees(np.arctan2(p[:, 1], p[:, 0])), lo)
        la, lo = keep_clearance(la, lo, rules, passes=1, snap=snap)
        p = _xyz(la, lo)
    la[0], lo[0], la[-1], lo[-1] = lat[0], lon[0], lat[-1], lon[-1]
    return la, lo


def _thin(lat: FloatArray, lon: FloatArray, min_step: float) -> tuple[FloatArray, FloatArray]:
    """Drop vertices closer than `min_step` (m) to the previous kept one (ends kept)."""
    keep = [0]
    for k in range(1, lat.size - 1):
        if gc_distance(lat[keep[-1]], lon[keep[-1]], lat[k], lon[k]) >= min_step:
            keep.append(k)
    keep.append(lat.size - 1)
    if len(keep) >= 2 and keep[-2] != 0 and gc_distance(
            lat[keep[-2]], lon[keep[-2]], lat[-1], lon[-1]) < 0.25 * min_step:
        keep.pop(-2)
    idx = np.array(keep)
    return lat[idx], lon[idx]


# -------------------------------------------------------------------------------- refine


def refine(problem: RouteProblem, rg: RouteGrid, grid_route: Candidate) -> tuple[
    Candidate | None, str
]:
    """Zermelo shooting on the sphere from the grid route (`routing.zermelo`); (None, why)
    when it does not converge, meets land or the obstacles, or leaves the window."""
    from glideplan.routing.zermelo import zermelo_shooting

    k = min(max(1, grid_route.chi.size // 20), grid_route.chi.size - 1)
    chi0 = float(np.arctan2(np.mean(np.sin(grid_route.chi[:k])),
                            np.mean(np.cos(grid_route.chi[:k]))))
    tol = max(1e-2 * rg.spacing_m, 0.01)  # 1 % of a cell, through the grid's current
    shot = zermelo_shooting(rg.currents, problem.speed, problem.t0, problem.start,
                            problem.goal, chi0, grid_route.duration, tol_m=tol)
    if not shot.converged:
        return None, shot.message
    fi, fj = rg.window.frac_index(shot.lat, shot.lon)
    ii = np.clip(np.rint(fi).astype(int), 0, rg.window.shape[0] - 1)
    jj = np.rint(fj).astype(int)
    jj = np.mod(jj, rg.window.shape[1]) if rg.window.periodic else np.clip(
        jj, 0, rg.window.shape[1] - 1)
    if np.any(rg.obstacle[ii, jj]):
        return None, "the shooting's track enters the land clearance"
    if rg.front_clearance_m is not None and rg.front_clearance_m < rg.clearance_m:
        from glideplan.routing.coast import clearance_of  # the front's obstacles are narrower

        step = max(min(rg.clearance_m, rg.spacing_m) / 4, 1.0)
        if clearance_of(shot.lat, shot.lon, rg.coast_xyz, step) < rg.clearance_m * (1 - 1e-3):
            return None, "the shooting's track enters the land clearance"
    return Candidate("zermelo-shooting", shot.t, shot.lat, shot.lon, shot.chi, False,
                     shot.duration), ""


# -------------------------------------------------------------------------------- verify


def verify(problem: RouteProblem, rg: RouteGrid, cand: Candidate) -> FlownRoute:
    """Fly the candidate's controls through the field (NaN stencils at the coast filled with
    the nearest water node's current, counted in `filled`; a point whose nearest node is land
    is on land)."""
    from scipy.ndimage import distance_transform_edt

    land = rg.land
    window = rg.window
    if land.any():
        _, (ni, nj) = distance_transform_edt(land, return_indices=True)
    else:
        ni = nj = None

    def node(lat: float, lon: float) -> tuple[int, int] | None:
        fi, fj = window.frac_index(lat, lon)
        i, j = int(np.rint(fi)), int(np.rint(fj))
        ny, nx = window.shape
        if window.periodic:
            j %= nx
        if not (0 <= i < ny and 0 <= j < nx):
            return None
        return i, j

    field_land = _field_land_cells(problem.field_)

    def is_land(lat: float, lon: float) -> bool:
        if field_land is not None:
            return field_land(lat, lon)
        ij = node(lat, lon)
        return bool(ij is not None and land[ij])

    def fill(t: float, lat: float, lon: float) -> tuple[float, float]:
        ij = node(lat, lon)
        if ij is None:
            return 0.0, 0.0
        i, j = ij
        if ni is not None and nj is not None:
            i, j = int(ni[i, j]), int(nj[i, j])
        u, v = rg.currents.at(t)
        return float(np.nan_to_num(u[i, j])), float(np.nan_to_num(v[i, j]))

    return fly_headings(problem.field_, problem.speed, cand.t, cand.chi, problem.start,
                        problem.goal, hold=cand.hold, fill=fill, is_land=is_land)


def _field_land_cells(fld: FlowField) -> Callable[[float, float], bool] | None:
    """For a gridded field: (lat, lon) -> whether the field node nearest the point is land
    (NaN), i.e. the point lies in a land cell; None for other fields (their NaN is land)."""
    from glideplan.fields.field import GriddedField

    if not isinstance(fld, GriddedField):
        return None
    nan = ~(np.isfinite(fld.u[0]) & np.isfinite(fld.v[0]))
    lat_f, lon_f = fld.lat, fld.lon
    periodic = bool(getattr(fld, "periodic_lon", False))

    def nearest(axis: FloatArray, x: float) -> int:
        k = int(np.clip(np.searchsorted(axis, x), 1, axis.size - 1))
        return k if abs(axis[k] - x) < abs(x - axis[k - 1]) else k - 1

    def is_land(lat: float, lon: float) -> bool:
        lo = float(lon_f[0] + np.mod(lon - lon_f[0], 360.0))
        if periodic and lo > lon_f[-1] + 0.5 * (lon_f[0] + 360.0 - lon_f[-1]):
            j = 0
        else:
            j = nearest(lon_f, lo)
        return bool(nan[nearest(lat_f, lat), j])

    return is_land


def flown_ok(flown: FlownRoute, tolerance: float) -> bool:
    """The acceptance rule: in the water, in the field, within the tolerance."""
    return not (flown.on_land or flown.left_field) and flown.endpoint_error_m <= tolerance


__all__ += ["EARTH_RADIUS_M", "flown_ok", "regrid", "spacing_for"]
