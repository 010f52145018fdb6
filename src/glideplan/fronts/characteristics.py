"""Backtracking: the optimal path from the arrival-time map T, along the characteristics.

On an optimal path the through-water (through-air) velocity points along the front's outward
normal n = grad T / |grad T| with the mode k* that maximises the front speed in that direction
(Lolla et al. 2012, eq. 6, for K = 1):

    v = a_k* n + d_k*(x, t),   k* = argmax_k (a_k + d_k . n),

so the path solves dx/dt = v backwards from the goal at T(goal). On the sphere

    d lat/dt = v_north / R,    d lon/dt = v_east / (R cos lat)        (radians),

integrated with Heun's method (RK2) at time steps of half a cell. grad T (physical, m^-1
per s) uses central differences, one-sided next to unreached nodes. The last piece joins the
start disk to the source with the velocity that reaches it (a straight crab).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.fronts.grid import LatLonGrid
from glideplan.fronts.solver import FrontProblem

__all__ = ["Characteristic", "arrival_gradient_at", "backtrack"]

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class Characteristic:
    """A backtracked path: t (s), lat, lon (deg, unwrapped: continuous across 180), heading
    (rad CCW from east, of the through-water/air velocity), mode k per sample, complete (it
    reached the source)."""

    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    heading: FloatArray
    mode: NDArray[np.intp]
    complete: bool


def _node_grad(T: FloatArray, grid: LatLonGrid, i: int, j: int) -> tuple[float, float] | None:
    ny, nx = T.shape
    c = T[i, j]
    if not math.isfinite(c):
        return None
    out = []
    for axis in (1, 0):
        if axis == 1:
            h = float(grid.hx[i])
            if grid.periodic:
                m, p = T[i, (j - 1) % nx], T[i, (j + 1) % nx]
            else:
                m = T[i, j - 1] if j > 0 else math.inf
                p = T[i, j + 1] if j < nx - 1 else math.inf
        else:
            h = grid.hy
            m = T[i - 1, j] if i > 0 else math.inf
            p = T[i + 1, j] if i < ny - 1 else math.inf
        fm, fp = math.isfinite(m), math.isfinite(p)
        if fm and fp:
            out.append((p - m) / (2 * h))
        elif fp:
            out.append((p - c) / h)
        elif fm:
            out.append((c - m) / h)
        else:
            out.append(0.0)
    return out[0], out[1]


def arrival_gradient_at(T: FloatArray, grid: LatLonGrid, fi: float, fj: float) -> FloatArray:
    """grad T (east, north; s/m) at a fractional node, bilinear over the reached corners."""
    ny, nx = T.shape
    i = int(np.clip(math.floor(fi), 0, ny - 2))
    wy = float(np.clip(fi - i, 0.0, 1.0))
    if grid.periodic:
        j0 = math.floor(fj)
        wx = fj - j0
        cols = (j0 % nx, (j0 + 1) % nx)
    else:
        j0 = int(np.clip(math.floor(fj), 0, nx - 2))
        wx = float(np.clip(fj - j0, 0.0, 1.0))
        cols = (j0, j0 + 1)
    acc = np.zeros(2)
    wsum = 0.0
    for di, wi in ((0, 1 - wy), (1, wy)):
        for dj, wj in ((0, 1 - wx), (1, wx)):
            gr = _node_grad(T, grid, i + di, cols[dj])
            if gr is None or wi * wj == 0.0:
                continue
            acc += wi * wj * np.array(gr)
            wsum += wi * wj
    if wsum == 0.0:
        return np.full(2, np.nan)
    return acc / wsum


def _velocity(problem: FrontProblem, T: FloatArray, t: float, lat: float, lon: float,
              fallback: FloatArray) -> tuple[FloatArray, float, int]:
    g = problem.grid
    fi, fj = g.frac_index(lat, lon)
    grad = arrival_gradient_at(T, g, float(fi), float(fj))
    norm = float(np.hypot(grad[0], grad[1]))
    n = grad / norm if (math.isfinite(norm) and norm > 0) else fallback
    d = problem.drift_at(t, float(fi), float(fj))
    a = np.asarray(problem.speeds)
    k = int(np.argmax(a + d @ n))
    return a[k] * n + d[k], math.atan2(n[1], n[0]), k


def _dist_to_source(R: float, source: tuple[float, float], la: float, lo: float) -> float:
    """Local-plane distance (m) from the source to (la, lo) (mid-latitude cosine)."""
    lat0, lon0 = source
    x = R * math.cos(math.radians(0.5 * (la + lat0))) * math.radians(lo - lon0)
    y = R * math.radians(la - lat0)
    return math.hypot(x, y)


def _outward(source: tuple[float, float], la: float, lo: float) -> FloatArray:
    """Unit vector from the source towards (la, lo) (east, north; east if they coincide)."""
    lat0, lon0 = source
    x = math.cos(math.radians(la)) * math.radians(lo - lon0)
    y = math.radians(la - lat0)
    nrm = math.hypot(x, y)
    return np.array([x / nrm, y / nrm]) if nrm > 0 else np.array([1.0, 0.0])


def _max_drift(problem: FrontProblem, t_goal: float) -> tuple[float, float]:
    """(max |b_k|, max |s_k| max |c| at t_goal's level) (m/s): bound the step's ground speed."""
    bmax = float(np.max(np.hypot(problem.drifts[:, 0], problem.drifts[:, 1])))  # type: ignore[index]
    cmax = 0.0
    if problem.drift is not None:
        lv = problem.drift.level(problem.drift.bracket(t_goal)[0])
        cmax = float(np.nanmax(np.hypot(lv[0], lv[1]))) if np.any(np.isfinite(lv[0])) else 0.0
        cmax *= float(np.max(np.abs(problem.drift_scales)))  # type: ignore[arg-type]
    return bmax, cmax


def _join_source(problem: FrontProblem, t0: float, source: tuple[float, float],
                 arrays: tuple[NDArray[Any], ...]) -> tuple[NDArray[Any], ...]:
    """Prepend the source: straight from it to the first point at ground velocity gv, with the
    mode whose speed best matches the water velocity gv - d it needs."""
    t_arr, la_arr, lo_arr, h_arr, k_arr = arrays
    g = problem.grid
    R = g.radius_m
    lat0, lon0 = source
    dur = t_arr[0] - t0
    x = R * math.cos(math.radians(0.5 * (la_arr[0] + lat0))) * math.radians(lo_arr[0] - lon0)
    y = R * math.radians(la_arr[0] - lat0)
    gv = np.array([x, y]) / dur
    fi, fj = g.frac_index(lat0, lon0)
    d = problem.drift_at(t0, float(fi), float(fj))
    wv = gv[None, :] - d
    k = int(np.argmin(np.abs(np.hypot(wv[:, 0], wv[:, 1]) - np.asarray(problem.speeds))))
    h0 = math.atan2(wv[k, 1], wv[k, 0])
    return (np.concatenate([[t0], t_arr]), np.concatenate([[lat0], la_arr]),
            np.concatenate([[lon0], lo_arr]), np.concatenate([[h0], h_arr]),
            np.concatenate([[k], k_arr]))


def backtrack(
    problem: FrontProblem,
    arrival: FloatArray,
    goal: tuple[float, float],
    t_goal: float,
    t0: float,
    source: tuple[float, float],
    start_radius_m: float,
    step_cells: float = 0.5,
) -> Characteristic:
    """Integrate the characteristic backwards from `goal` at t_goal to the source (docstring)."""
    g = problem.grid
    R = g.radius_m
    a = np.asarray(problem.speeds)
    lon0 = source[1]
    lat, lon = float(goal[0]), float(goal[1])
    lon = lon0 + ((lon - lon0 + 180.0) % 360.0) - 180.0  # unwrapped about the source
    t = float(t_goal)
    ts, las, los, hs, ks = [t], [lat], [lon], [], []
    bmax, cmax = _max_drift(problem, t_goal)
    vmax = float(np.max(a)) + bmax + cmax
    complete = False
    max_steps = 200000
    for _ in range(max_steps):
        if _dist_to_source(R, source, lat, lon) <= start_radius_m or t <= t0:
            complete = True
            break
        coslat = max(math.cos(math.radians(lat)), 1e-6)
        h_loc = min(g.hy, R * coslat * math.radians(g.dlon_deg))
        ds = min(step_cells * h_loc / vmax, t - t0)
        v1, hd, k = _velocity(problem, arrival, t, lat, lon, _outward(source, lat, lon))
        hs.append(hd)
        ks.append(k)
        la1 = lat - ds * math.degrees(v1[1] / R)
        lo1 = lon - ds * math.degrees(v1[0] / (R * coslat))
        v2, _, _ = _velocity(problem, arrival, t - ds, la1, lo1, _outward(source, la1, lo1))
        coslat2 = max(math.cos(math.radians(0.5 * (lat + la1))), 1e-6)
        lat = lat - 0.5 * ds * math.degrees((v1[1] + v2[1]) / R)
        lon = lon - 0.5 * ds * math.degrees((v1[0] + v2[0]) / (R * coslat2))
        t -= ds
        ts.append(t)
        las.append(lat)
        los.append(lon)
    while len(hs) < len(ts):
        hs.append(hs[-1] if hs else 0.0)
        ks.append(ks[-1] if ks else 0)
    arrays: tuple[NDArray[Any], ...] = (
        np.array(ts[::-1]), np.array(las[::-1]), np.array(los[::-1]), np.array(hs[::-1]),
        np.array(ks[::-1], dtype=np.intp))
    if complete and arrays[0][0] > t0 and _dist_to_source(R, source, arrays[1][0],
                                                          arrays[2][0]) > 0.0:
        arrays = _join_source(problem, t0, source, arrays)
    t_arr, la_arr, lo_arr, h_arr, k_arr = arrays
    return Characteristic(t_arr, la_arr, lo_arr, np.unwrap(h_arr), k_arr, complete)
