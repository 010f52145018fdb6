"""The backtrack phase of `route()`: the kernel's characteristic backwards from the goal,
then the headings that hold its polyline leg by leg (`sphere.crab_controls`) -- the "grid"
route (`Candidate`) -- kept clear of land (`glideplan.routing.phases`)."""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import Any

import numpy as np

from glideplan.routing.problem import Candidate, FloatArray, FrontOutcome, RouteGrid, RouteProblem
from glideplan.routing.sphere import EARTH_RADIUS_M, crab_controls, gc_distance, unwrap_lon

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
