"""Short legs through a gridded field at the cost of the leg: Zermelo shooting in the leg's
own cube of field nodes, verified by integration through the same interpolation.

A coastal survey's legs (1-5 km) are far shorter than a forecast's cells (~9 km at 1/12
deg): across one leg the field is the trilinear interpolation of a few nodes. Building the
router's window, front and backtrack for such a leg costs ~2 s; the time-optimal route is
the Zermelo extremal (Zermelo 1931; the router's own refinement, `routing.zermelo`), found
here directly by shooting:

    d lat/dt = (V cos chi + v) / R,  d lon/dt = (V sin chi + u) / (R cos lat),
    d theta/dt = sin^2 theta v_x + sin theta cos theta (u_x - v_y) - cos^2 theta u_y,

theta = pi/2 - chi the heading counter-clockwise from east, u_x... the current's gradients
(east, north; per metre). Unknowns (chi0, T), started from the drift disk of the current at
the leg's middle (`routing.extract.drift_disk_time`), Newton with dF/dT the ground velocity
at the end and dF/dchi0 by a finite difference.

The current is `GriddedField`'s own linear interpolation (time, lat, lon), evaluated from the
cube of nodes round the leg (`LocalCube`, same formula as SciPy's RegularGridInterpolator
'linear'). Verification: the headings (linear in time between the flight's nodes) are flown
again at four times finer RK4 steps through the cube, the endpoint error measured as the
router measures it; a leg is accepted only if it is within the router's tolerance (one grid
spacing at the router's default resolution), stays inside the cube (which holds no land and
reaches beyond the leg by the land clearance) and the current stays slower than the vehicle.
Otherwise `fast_leg` returns None and the leg goes to `glideplan.routing.route`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.routing.sphere import EARTH_RADIUS_M

__all__ = ["BATCH_MIN_LEGS", "FAST_MAX_DISTANCE_M", "LocalCube", "fast_leg", "steady_legs"]

FloatArray = NDArray[np.float64]

#: Legs up to this long (m) are tried by local shooting first.
FAST_MAX_DISTANCE_M = 20_000.0
#: Missions in a steady field with at least this many legs run on the batch runner.
BATCH_MIN_LEGS = 40
#: Legs per batch task (the field is pickled once per task).
LEGS_PER_TASK = 25
#: Metres per degree of latitude on the router's sphere.
M_PER_DEG = math.radians(1.0) * EARTH_RADIUS_M
#: RK4 steps of the shooting flight (the verification uses four times as many).
STEPS = 48


@dataclass(frozen=True, eq=False)
class LocalCube:
    """A gridded field's nodes round a leg: times (nt,), lat (ny,), lon (nx,) ascending,
    u, v (nt, ny, nx) m/s, no NaN. `at(t, lat, lon)` -> (u, v, u_x, u_y, v_x, v_y)."""

    times: FloatArray
    lat: FloatArray
    lon: FloatArray
    u: FloatArray
    v: FloatArray

    def __post_init__(self) -> None:
        # plain Python lists: one point at a time is faster on floats than on NumPy scalars
        object.__setattr__(self, "_ax", (self.times.tolist(), self.lat.tolist(),
                                         self.lon.tolist()))
        object.__setattr__(self, "_uv", (self.u.tolist(), self.v.tolist()))

    def inside(self, lat: float, lon: float) -> bool:
        _, la, lo = self._ax  # type: ignore[attr-defined]
        return la[0] <= lat <= la[-1] and lo[0] <= lon <= lo[-1]

    def at(self, t: float, lat: float, lon: float) -> tuple[float, ...]:
        """Trilinear (u, v) and their east/north gradients (s^-1) at one point."""
        from bisect import bisect_right

        tt, la, lo = self._ax  # type: ignore[attr-defined]
        i = min(max(bisect_right(la, lat) - 1, 0), len(la) - 2)
        j = min(max(bisect_right(lo, lon) - 1, 0), len(lo) - 2)
        dy, dx = la[i + 1] - la[i], lo[j + 1] - lo[j]
        wy, wx = (lat - la[i]) / dy, (lon - lo[j]) / dx
        if len(tt) == 1:
            k, wt = 0, 0.0
        else:
            k = min(max(bisect_right(tt, t) - 1, 0), len(tt) - 2)
            wt = (t - tt[k]) / (tt[k + 1] - tt[k])
        out = []
        for f in self._uv:  # type: ignore[attr-defined]
            r0, r1 = f[k][i], f[k][i + 1]
            a, b, cc, d = r0[j], r0[j + 1], r1[j], r1[j + 1]
            if wt:
                q0, q1 = f[k + 1][i], f[k + 1][i + 1]
                a += wt * (q0[j] - a)
                b += wt * (q0[j + 1] - b)
                cc += wt * (q1[j] - cc)
                d += wt * (q1[j + 1] - d)
            val = (1 - wy) * ((1 - wx) * a + wx * b) + wy * ((1 - wx) * cc + wx * d)
            gx = ((1 - wy) * (b - a) + wy * (d - cc)) / dx
            gy = ((1 - wx) * (cc - a) + wx * (d - b)) / dy
            out.append((val, gx, gy))
        my = M_PER_DEG
        mx = my * max(math.cos(math.radians(lat)), 1e-9)
        (u, ux, uy), (v, vx, vy) = out
        return u, v, ux / mx, uy / my, vx / mx, vy / my


def cube_for(fld: Any, start: tuple[float, float], goal: tuple[float, float], t0: float,
             t_end: float, reach_m: float) -> LocalCube | None:
    """The nodes of a `GriddedField` covering the leg's box grown by `reach_m` (and one node),
    over the levels bracketing [t0, t_end]; None when it holds land (NaN), wraps the seam or
    leaves the field."""
    from glideplan.fields.field import GriddedField

    if not isinstance(fld, GriddedField) or fld.periodic_lon:
        return None
    dlat = math.degrees(reach_m / EARTH_RADIUS_M)
    dlon = dlat / max(math.cos(math.radians(max(abs(start[0]), abs(goal[0])) + dlat)), 1e-6)
    la0, la1 = min(start[0], goal[0]) - dlat, max(start[0], goal[0]) + dlat
    lo0, lo1 = min(start[1], goal[1]) - dlon, max(start[1], goal[1]) + dlon
    lat, lon = fld.lat, fld.lon
    if la0 < lat[0] or la1 > lat[-1] or lo0 < lon[0] or lo1 > lon[-1]:
        return None
    i0 = max(int(np.searchsorted(lat, la0, side="right")) - 2, 0)
    i1 = min(int(np.searchsorted(lat, la1)) + 2, lat.size)
    j0 = max(int(np.searchsorted(lon, lo0, side="right")) - 2, 0)
    j1 = min(int(np.searchsorted(lon, lo1)) + 2, lon.size)
    tt = fld.times
    if tt.size == 1:
        k0, k1 = 0, 1
    else:
        k0 = max(int(np.searchsorted(tt, t0, side="right")) - 1, 0)
        k1 = min(int(np.searchsorted(tt, t_end)) + 1, tt.size)
    u = np.asarray(fld.u[k0:k1, i0:i1, j0:j1], dtype=float)
    v = np.asarray(fld.v[k0:k1, i0:i1, j0:j1], dtype=float)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        return None
    return LocalCube(np.asarray(tt[k0:k1], dtype=float), lat[i0:i1], lon[j0:j1], u, v)


def _fly(cube: LocalCube, speed: float, t0: float, start: tuple[float, float], chi0: float,
         T: float, steps: int, controls: tuple[FloatArray, FloatArray] | None = None) -> tuple[
             FloatArray, FloatArray, FloatArray, FloatArray, tuple[float, float]] | None:
    """RK4 flight: with `controls` (t, chi) given, those headings linear in time; else the
    Zermelo heading equation from chi0. Returns (t, lat, lon, chi) at the steps and the
    ground velocity (east, north) at the end; None when it leaves the cube."""
    from bisect import bisect_right

    R, V = EARTH_RADIUS_M, speed
    ct_t = [] if controls is None else controls[0].tolist()
    ct_c = [] if controls is None else np.unwrap(controls[1]).tolist()

    def rhs(s: float, z: tuple[float, float, float]) -> tuple[float, float, float] | None:
        la, lo, th = z
        lad, lod = math.degrees(la), math.degrees(lo)
        if not cube.inside(lad, lod):
            return None
        u, v, ux, uy, vx, vy = cube.at(s, lad, lod)
        if controls is not None:
            m = min(max(bisect_right(ct_t, s) - 1, 0), len(ct_t) - 2)
            w = (s - ct_t[m]) / (ct_t[m + 1] - ct_t[m])
            th = 0.5 * math.pi - (ct_c[m] + w * (ct_c[m + 1] - ct_c[m]))
            dth = 0.0
        else:
            st, ct = math.sin(th), math.cos(th)
            dth = st * st * vx + st * ct * (ux - vy) - ct * ct * uy
        return ((V * math.sin(th) + v) / R,
                (V * math.cos(th) + u) / (R * max(math.cos(la), 1e-9)), dth)

    dt = T / steps
    z = (math.radians(start[0]), math.radians(start[1]), 0.5 * math.pi - chi0)
    ts = t0 + dt * np.arange(steps + 1)
    out = np.empty((steps + 1, 3))
    out[0] = z
    for n in range(steps):
        s = float(ts[n])
        k1 = rhs(s, z)
        k2 = None if k1 is None else rhs(s + dt / 2, tuple(a + dt / 2 * b for a, b in zip(
            z, k1, strict=True)))  # type: ignore[arg-type]
        k3 = None if k2 is None else rhs(s + dt / 2, tuple(a + dt / 2 * b for a, b in zip(
            z, k2, strict=True)))  # type: ignore[arg-type]
        k4 = None if k3 is None else rhs(s + dt, tuple(a + dt * b for a, b in zip(
            z, k3, strict=True)))  # type: ignore[arg-type]
        if k1 is None or k2 is None or k3 is None or k4 is None:
            return None
        z = tuple(a + dt / 6 * (b + 2 * c + 2 * d + e) for a, b, c, d, e in zip(
            z, k1, k2, k3, k4, strict=True))  # type: ignore[assignment]
        out[n + 1] = z
    end = rhs(float(ts[-1]), z)
    if end is None:
        return None
    ge = end[1] * R * math.cos(z[0])
    gn = end[0] * R
    chi = np.asarray(0.5 * math.pi - out[:, 2], dtype=float)
    if controls is not None:
        chi = np.asarray(np.interp(ts, controls[0], controls[1]), dtype=float)
    return (np.asarray(ts, dtype=float), np.asarray(np.degrees(out[:, 0]), dtype=float),
            np.asarray(np.degrees(out[:, 1]), dtype=float), chi, (ge, gn))


def _miss(lat: float, lon: float, goal: tuple[float, float]) -> FloatArray:
    """(east, north) m from the goal to (lat, lon), locally."""
    R = EARTH_RADIUS_M
    return np.array([R * math.cos(math.radians(goal[0])) * math.radians(lon - goal[1]),
                     R * math.radians(lat - goal[0])])


def shoot(cube: LocalCube, speed: float, t0: float, start: tuple[float, float],
          goal: tuple[float, float], chi0: float, T: float, tol_m: float,
          iterations: int = 8) -> tuple[float, float] | None:
    """Newton on (chi0, T) until the Zermelo flight ends within tol_m of the goal."""
    for _ in range(iterations):
        f = _fly(cube, speed, t0, start, chi0, T, STEPS)
        if f is None:
            return None
        F = _miss(f[1][-1], f[2][-1], goal)
        if float(np.hypot(*F)) <= tol_m:
            return chi0, T
        d = 1e-6
        g = _fly(cube, speed, t0, start, chi0 + d, T, STEPS)
        if g is None:
            return None
        J = np.column_stack([(_miss(g[1][-1], g[2][-1], goal) - F) / d, np.array(f[4])])
        try:
            step = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            return None
        chi0 += float(np.clip(step[0], -0.5, 0.5))
        T = max(T + float(step[1]), 0.5 * T)
    return None


def _first_guess(cube: LocalCube, speed: float, t0: float, start: tuple[float, float],
                 goal: tuple[float, float], t_max: float) -> tuple[float, float] | None:
    """(chi0, T) of the drift disk of the current at the leg's middle."""
    from glideplan.routing.extract import drift_disk_time
    from glideplan.routing.sphere import gc_bearing, gc_distance

    mid = 0.5 * (start[0] + goal[0]), 0.5 * (start[1] + goal[1])
    inner = cube.times[(cube.times > t0) & (cube.times < t_max)]
    ts = np.concatenate([[t0], inner, [t_max]])
    uv = np.array([cube.at(float(s), *mid)[:2] for s in ts])
    d = float(gc_distance(*start, *goal))
    b = float(gc_bearing(*start, *goal))
    g = np.array([d * math.sin(b), d * math.cos(b)])
    first, _ = drift_disk_time(ts, uv[:, 0], uv[:, 1], g, speed, substeps=8)
    if first is None or first <= t0:
        return None
    T = first - t0
    dx = g - T * np.mean(uv, axis=0)  # the drift over T, roughly
    return math.atan2(dx[0], dx[1]), T


def fast_leg(fld: Any, start: tuple[float, float], goal: tuple[float, float], speed: float,
             depart: Any, resolution: float | None, land_clearance_m: float | None) -> Any:
    """The leg's `RouteResult` by local shooting (module docstring), or None (use the router)."""
    from glideplan.routing import phases
    from glideplan.routing.result import RouteResult
    from glideplan.routing.route import _track
    from glideplan.routing.settings import RouteSettings
    from glideplan.solution import Status

    settings = RouteSettings(resolution=resolution, land_clearance_m=land_clearance_m)
    problem = phases.setup(fld, start, goal, speed, depart, None, settings)
    dist = problem.distance_m
    if not (0 < dist <= FAST_MAX_DISTANCE_M):
        return None
    h = phases.spacing_for(problem)
    tol = settings.endpoint_tolerance_cells * h
    if land_clearance_m is not None:
        clear = land_clearance_m
    else:
        cell = math.radians(float(np.max(np.diff(fld.lat)))) * EARTH_RADIUS_M
        clear = 1.5 * cell + h  # at least the router's default (a cell's diagonal + h)
    reach = 0.5 * dist + clear
    t_cap = min(problem.t_max, problem.t0 + 10.0 * dist / speed)
    cube = cube_for(fld, problem.start, problem.goal, problem.t0, t_cap, reach)
    if cube is None or float(np.max(np.hypot(cube.u, cube.v))) >= 0.9 * speed:
        return None
    guess = _first_guess(cube, speed, problem.t0, problem.start, problem.goal, t_cap)
    if guess is None:
        return None
    sol = shoot(cube, speed, problem.t0, problem.start, problem.goal, *guess,
                tol_m=min(0.01 * tol, 0.5))
    if sol is None or problem.t0 + sol[1] > problem.t_max:
        return None
    f = _fly(cube, speed, problem.t0, problem.start, sol[0], sol[1], STEPS)
    assert f is not None
    ts, la, lo, chi, _ = f
    # the track keeps the clearance from the cube's edge (beyond which land may lie)
    m_lat = math.degrees(0.5 * dist / EARTH_RADIUS_M)
    m_lon = m_lat / max(math.cos(math.radians(float(np.max(np.abs(la))))), 1e-6)
    a, b = problem.start, problem.goal
    if (np.min(la) < min(a[0], b[0]) - m_lat or np.max(la) > max(a[0], b[0]) + m_lat
            or np.min(lo) < min(a[1], b[1]) - m_lon or np.max(lo) > max(a[1], b[1]) + m_lon):
        return None
    # the verification: the headings flown again, four times finer, through the cube
    check = _fly(cube, speed, problem.t0, problem.start, sol[0], sol[1], 4 * STEPS,
                 controls=(ts, chi))
    if check is None:
        return None
    err = float(np.hypot(*_miss(check[1][-1], check[2][-1], problem.goal)))
    if err > tol:
        return None
    cand = phases.Candidate("zermelo-local", ts, la, lo, chi, False, float(sol[1]))
    from glideplan.routing.sphere import gc_distance

    length = float(np.sum(gc_distance(la[:-1], lo[:-1], la[1:], lo[1:])))
    return RouteResult(
        status=Status.SOLVED, message="solved", warnings=problem.warnings,
        start=problem.start, goal=problem.goal, speed=speed, depart=problem.depart,
        depart_s=problem.t0, duration_s=float(sol[1]), distance_m=length,
        track=_track(problem, cand), endpoint_error_m=err, endpoint_tolerance_m=tol,
        straight_line_duration_s=None, grid_duration_s=None, refined_duration_s=float(sol[1]),
        method="zermelo-local", land_clearance_m=float(clear),
        field_info=fld.describe(), stats={"spacing_m": h, "cube_nodes": list(cube.u.shape)})


def route_one(fld: Any, a: tuple[float, float], b: tuple[float, float], speed: float,
              depart: Any, resolution: float | None, land_clearance_m: float | None) -> Any:
    """One leg: local shooting when it applies, else `glideplan.routing.route`."""
    from glideplan.routing import RouteSettings, route

    res = fast_leg(fld, a, b, speed, depart, resolution, land_clearance_m)
    if res is None:
        res = route(fld, a, b, speed, depart=depart,
                    settings=RouteSettings(resolution=resolution,
                                           land_clearance_m=land_clearance_m))
    return res


def _chunk_task(item: tuple[Any, list[tuple[tuple[float, float], tuple[float, float]]], float,
                            float | None, float | None]) -> list[Any]:
    fld, pairs, speed, resolution, clearance = item
    return [route_one(fld, a, b, speed, None, resolution, clearance) for a, b in pairs]


def steady_legs(route: Any, fld: Any, speed: float, resolution: float | None,
                land_clearance_m: float | None, progress: bool) -> list[Any]:
    """Every leg of `route` through a steady field on the batch runner (`glideplan.batch`,
    local processes), LEGS_PER_TASK legs per task; the `RouteResult`s in leg order, each
    departing at the field's time (`missions.field_mission` chains them)."""
    from glideplan.batch import run_batch

    pairs = [((float(route.lat[i]), float(route.lon[i])),
              (float(route.lat[i + 1]), float(route.lon[i + 1]))) for i in range(route.n - 1)]
    items = [(fld, pairs[k:k + LEGS_PER_TASK], speed, resolution, land_clearance_m)
             for k in range(0, len(pairs), LEGS_PER_TASK)]
    out = run_batch(_chunk_task, items, progress=progress,
                    description=f"legs ({LEGS_PER_TASK} per task)")
    return [r for chunk in out for r in chunk]
