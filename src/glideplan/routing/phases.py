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
  grid route; kept by `route()` only if it verifies and is not slower. `straight_line`: the
  great circle held with a crab angle, which `route()` takes when the route found is over
  0.5 % slower and the line verifies.
- `verify`: the controls flown through the field itself (`sphere.fly_headings`).

Where they live: `setup` and the values the phases hand on in `routing.problem`, `grid` in
`routing.route_grid`, `front` in `routing.growing_front`, `backtrack` (and keeping a track
clear of land) in `routing.backtrack`; `refine` and `verify` here. Every phase is imported
from here (`phases.setup`, ...).
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np

from glideplan.fields.field import FlowField
from glideplan.routing.backtrack import (  # noqa: F401 (the phases, one import away)
    CLOSED,
    HOLD_MAX_LEGS,
    SWITCH_S,
    _held,
    backtrack,
    clearance_rules,
    keep_clearance,
    out_of_obstacles,
    taut,
)
from glideplan.routing.growing_front import (  # noqa: F401
    _Progress,
    front,
    kernel_problem,
    level_times,
)
from glideplan.routing.problem import (
    Candidate,
    FloatArray,
    FrontOutcome,
    RouteGrid,
    RouteProblem,
    setup,
)
from glideplan.routing.route_grid import (  # noqa: F401
    LEVELS_PER_CROSSING,
    build_obstacles,
    grid,
    regrid,
    spacing_for,
    strict_grid,
)
from glideplan.routing.sphere import EARTH_RADIUS_M, FlownRoute, fly_headings

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
    "straight_line",
    "verify",
]



# -------------------------------------------------------------------------------- refine


def refine(problem: RouteProblem, rg: RouteGrid, grid_route: Candidate,
           front_duration: float | None = None) -> tuple[Candidate | None, str]:
    """Zermelo shooting on the sphere from the grid route (`routing.zermelo`); (None, why)
    when it does not converge, meets land or the obstacles, or leaves the window.

    The shooting starts from the grid route's first heading and duration, or from the
    front's arrival `front_duration` (s) when the route's held legs take over 1.5 times as
    long: in a current faster than the vehicle they can drift for weeks (3019 h for an M2
    tide the front crosses in 33.9 h), and a shot that long leaves the window."""
    from glideplan.routing.zermelo import zermelo_shooting

    k = min(max(1, grid_route.chi.size // 20), grid_route.chi.size - 1)
    chi0 = float(np.arctan2(np.mean(np.sin(grid_route.chi[:k])),
                            np.mean(np.cos(grid_route.chi[:k]))))
    tol = max(1e-2 * rg.spacing_m, 0.01)  # 1 % of a cell, through the grid's current
    T0 = grid_route.duration
    if front_duration is not None and T0 > 1.5 * front_duration:
        T0 = front_duration
    shot = zermelo_shooting(rg.currents, problem.speed, problem.t0, problem.start,
                            problem.goal, chi0, T0, tol_m=tol)
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


def straight_line(problem: RouteProblem, rg: RouteGrid, tolerance: float,
                  T: float) -> tuple[Candidate, FlownRoute] | None:
    """The straight line with crab angle (`sphere.straight_line_track`, searched to 3 T, at
    least 1 h) as a candidate and its flight through the field, when it verifies within
    `tolerance` (m) and keeps the land clearance; None otherwise."""
    from glideplan.routing.coast import track_clearance
    from glideplan.routing.sphere import straight_line_track

    got = straight_line_track(problem.field_, problem.speed, problem.t0, problem.start,
                              problem.goal, problem.t0 + max(3 * T, 3600.0))
    if got is None:
        return None
    duration, t, lat, lon, chi = got
    line = Candidate("straight-crab", t, lat, lon, chi, False, duration)
    flown = verify(problem, rg, line)
    near = track_clearance(problem, rg, lat, lon)
    clear = near is None or not math.isfinite(near) or near >= rg.clearance_m * (1 - 1e-3)
    return (line, flown) if flown_ok(flown, tolerance) and clear else None


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
