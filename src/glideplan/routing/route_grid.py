"""The grid phase of `route()`: the lattice and first window (`routing.window`), the field
on it, the land clearance and the obstacle nodes (`RouteGrid`); regridding when the window
grows (`glideplan.routing.phases`)."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.routing.problem import FloatArray, RouteGrid, RouteProblem
from glideplan.routing.window import (
    Window,
    WindowCurrents,
    build_lattice,
    initial_window,
    land_clearance_default,
    obstacles,
)

#: Analytic unsteady fields are sampled every (still-water time / this) seconds.
LEVELS_PER_CROSSING = 48


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
