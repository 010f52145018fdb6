"""The front: first-arrival times of a reachable set on a lat/lon grid (level set, narrow band).

The set reachable by time t from a source, with velocities in conv{ a_k n + d_k(x, t) : |n| = 1,
k = 1..K } (a_k >= 0 the normal speeds, d_k = b_k + s_k c(x, t) the drifts), is {phi <= 0} of

    d phi/dt + max_k ( a_k |grad phi| + d_k . grad phi ) = 0         (Lolla et al. 2012, eq. 3
                                                                       for K = 1; Osher-Sethian)

and the first-arrival time T(x) is the time phi(x) first reaches 0. Routes use K = 1 (a = the
vehicle's speed through the water, s = 1, c the current); glide reach uses "time" = altitude
lost and K airspeeds of the polar (a_k = V_k / w_k, b_k = W / w_k). Obstacles: a node not
yet reached cannot be entered after its block time (-inf: land, always blocked).

Discretisation (`glideplan.fronts.kernel`): ENO2 + Godunov/upwind, TVD-RK2, CFL time step,
narrow band of half-width B = 6 h. The start: the exact reachable set of the source at
tau0 = r0 / max a_k for the drift frozen at the source (its gauge function on 1440 directions).
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fronts.grid import LatLonGrid
from glideplan.fronts.stepping import GoalWatch, MayBlock, StepArgs

__all__ = [
    "DriftLevels",
    "FrontProblem",
    "FrontResult",
    "FrontState",
    "propagate",
    "start_state",
]

FloatArray = NDArray[np.float64]

#: Band half-width in grid spacings: phi is clipped to +-B, B = BAND_CELLS x max spacing.
BAND_CELLS = 6.0

#: Active nodes from which a step splits its nodes over numba's threads (NUMBA_NUM_THREADS;
#: the Makefile's tests set 1, since pytest -n 2 already keeps both cores busy).
PARALLEL_MIN_NODES = 30_000


_EDGE_NAMES = ((1, "south"), (2, "north"), (4, "west"), (8, "east"))


@dataclass(eq=False)
class DriftLevels:
    """A drift field c(x, t) on the grid, linear in time between levels (east, north; m/s).

    times: (L,) level times (s, ascending; one level = steady); fn(k) -> (u, v), each (ny, nx),
    at level k (NaN = obstacle). Levels are evaluated lazily and kept (least recently used
    dropped beyond `max_cached`).
    """

    times: FloatArray
    fn: Callable[[int], tuple[Any, Any]]
    max_cached: int = 64
    _cache: dict[int, FloatArray] = field(default_factory=dict)
    evaluations: int = 0

    def __post_init__(self) -> None:
        self.times = np.atleast_1d(np.asarray(self.times, dtype=float))
        if self.times.size < 1 or np.any(np.diff(self.times) <= 0):
            raise InvalidParameterError("drift times", self.times.size, "must be ascending")

    @property
    def steady(self) -> bool:
        return self.times.size == 1

    def level(self, k: int) -> FloatArray:
        """(2, ny*nx) float64, C-contiguous: u and v at level k."""
        if k in self._cache:
            self._cache[k] = self._cache.pop(k)
            return self._cache[k]
        u, v = self.fn(k)
        arr = np.ascontiguousarray(np.stack([np.asarray(u, dtype=float).ravel(),
                                             np.asarray(v, dtype=float).ravel()]))
        self._cache[k] = arr
        self.evaluations += 1
        if len(self._cache) > self.max_cached:
            self._cache.pop(next(iter(self._cache)))
        return arr

    def bracket(self, t: float) -> tuple[int, float]:
        """Level k and weight w with t between levels k and k+1 (held beyond the ends)."""
        lv = self.times
        if lv.size == 1:
            return 0, 0.0
        k = min(max(bisect.bisect_right(lv, t) - 1, 0), lv.size - 2)  # scalar: no NumPy calls
        a, b = float(lv[k]), float(lv[k + 1])
        return k, min(max((t - a) / (b - a), 0.0), 1.0)

    def pair(self, t: float) -> tuple[FloatArray, FloatArray, float]:
        k, w = self.bracket(t)
        lo = self.level(k)
        hi = lo if self.times.size == 1 else self.level(k + 1)
        return lo, hi, w

    def at(self, grid: LatLonGrid, t: float, fi: float, fj: float) -> FloatArray:
        """(u, v) at fractional node (fi, fj), bilinear; NaN stencils give NaN."""
        lo, hi, w = self.pair(t)
        ny, nx = grid.shape
        i = min(max(math.floor(fi), 0), ny - 2)
        wy = min(max(fi - i, 0.0), 1.0)
        if grid.periodic:
            j0 = math.floor(fj)
            wx = fj - j0
            j0 %= nx
            j1 = (j0 + 1) % nx
        else:
            j0 = min(max(math.floor(fj), 0), nx - 2)
            j1 = j0 + 1
            wx = min(max(fj - j0, 0.0), 1.0)
        r0, r1 = i * nx, (i + 1) * nx
        out = [0.0, 0.0]
        for arr, weight in ((lo, 1.0 - w), (hi, w)):
            if weight == 0.0:
                continue
            for c in (0, 1):
                row = arr[c]
                out[c] += weight * ((1 - wy) * ((1 - wx) * row[r0 + j0] + wx * row[r0 + j1])
                                    + wy * ((1 - wx) * row[r1 + j0] + wx * row[r1 + j1]))
        return np.array(out)


@dataclass(frozen=True, eq=False)
class FrontProblem:
    """H(p; x, t) = max_k (a_k |p| + (b_k + s_k c(x, t)) . p) on `grid`, with block times.

    speeds: a (K,) >= 0; drifts: b (K, 2) east/north; drift_scales: s (K,) (default 1 with a
    drift field); drift: the field c (None: none); block_time: (ny, nx) -- a node not yet
    reached cannot be entered at times t > block_time (-inf: always an obstacle; default +inf).
    """

    grid: LatLonGrid
    speeds: FloatArray
    drifts: FloatArray | None = None
    drift_scales: FloatArray | None = None
    drift: DriftLevels | None = None
    block_time: FloatArray | None = None

    def __post_init__(self) -> None:
        a = np.atleast_1d(np.asarray(self.speeds, dtype=float))
        k = a.size
        if k < 1 or not np.all(np.isfinite(a)) or np.any(a < 0) or not np.any(a > 0):
            raise InvalidParameterError("speeds", a, "must be finite, >= 0, one > 0")
        b = np.zeros((k, 2)) if self.drifts is None else np.asarray(self.drifts, dtype=float)
        b = np.ascontiguousarray(b.reshape(k, 2))
        if not np.all(np.isfinite(b)):
            raise InvalidParameterError("drifts", b, "must be finite")
        s = np.ones(k) if self.drift_scales is None else np.atleast_1d(
            np.asarray(self.drift_scales, dtype=float))
        if s.size != k or not np.all(np.isfinite(s)):
            raise InvalidParameterError("drift_scales", s, f"must be {k} finite values")
        shape = self.grid.shape
        tb = np.full(shape, np.inf) if self.block_time is None else np.asarray(
            self.block_time, dtype=float)
        if tb.shape != shape or np.any(np.isnan(tb)):
            raise InvalidParameterError("block_time", tb.shape, f"must be {shape}, not NaN")
        object.__setattr__(self, "speeds", a)
        object.__setattr__(self, "drifts", b)
        object.__setattr__(self, "drift_scales", s)
        object.__setattr__(self, "block_time", np.ascontiguousarray(tb))

    @property
    def block_times(self) -> FloatArray:
        """(ny, nx) block times (s), +inf where none was given."""
        assert self.block_time is not None  # set in __post_init__
        return self.block_time

    @property
    def band(self) -> float:
        return BAND_CELLS * float(max(self.grid.hy, float(np.max(self.grid.hx))))

    def drift_at(self, t: float, fi: float, fj: float) -> FloatArray:
        """(K, 2): the drifts b_k + s_k c at a fractional node (c NaN -> 0)."""
        b = np.array(self.drifts, dtype=float)
        if self.drift is not None:
            c = np.nan_to_num(self.drift.at(self.grid, t, fi, fj))
            b = b + np.outer(np.asarray(self.drift_scales), c)
        return b


@dataclass(frozen=True, eq=False)
class FrontState:
    """Resumable state: phi and arrival (ny, nx), time t (s), active node indices, steps."""

    phi: FloatArray
    arrival: FloatArray
    t: float
    active: NDArray[np.int64]
    steps: int = 0
    source: tuple[float, float] = (0.0, 0.0)
    start_radius_m: float = 0.0

    def embedded(self, shape: tuple[int, int], row0: int, col0: int, band: float) -> FrontState:
        """This state placed at (row0, col0) of a larger grid of `shape` (growing the domain)."""
        ny, nx = self.phi.shape
        phi = np.full(shape, band)
        arr = np.full(shape, np.inf)
        # The band's half-width B follows the grid's largest spacing, which changes as the
        # grid grows: the old plateaus (+-B_old, and tails snapped to them) become +-B, or
        # every node of the old grid would count as inside the new band.
        old = np.array(self.phi, dtype=float)
        b_old = float(np.max(np.abs(old))) if old.size else band
        snap = 0.97 * b_old
        old[old >= snap] = band
        old[old <= -snap] = -band
        phi[row0:row0 + ny, col0:col0 + nx] = old
        arr[row0:row0 + ny, col0:col0 + nx] = self.arrival
        i, j = np.divmod(self.active, nx)
        act = ((i + row0) * shape[1] + (j + col0)).astype(np.int64)
        return replace(self, phi=phi, arrival=arr, active=act)


@dataclass(frozen=True, eq=False)
class FrontResult:
    """arrival (ny, nx) s (inf: never reached); reason "goal", "stalled", "edge" or "t_max";
    goal_time (s) or None; edges the band touched; the final state (to resume)."""

    arrival: FloatArray
    reason: str
    goal_time: float | None
    edges: frozenset[str]
    state: FrontState
    steps: int
    t: float


def _gauge_times(x: FloatArray, y: FloatArray, a: FloatArray, d: FloatArray) -> FloatArray:
    """First arrival at (x, y) from 0 with velocities conv{a_k n + d_k}: sup_n x.n / F(n).

    F(n) = max_k (a_k + d_k . n) is the support function of the velocity set; where F(n) <= 0
    for a direction with x . n > 0 the point is never reached (inf).
    """
    th = np.linspace(0.0, 2 * np.pi, 1440, endpoint=False)
    n = np.stack([np.cos(th), np.sin(th)])  # (2, M)
    f = np.max(a[:, None] + d @ n, axis=0)  # (M,)
    proj = np.outer(x, n[0]) + np.outer(y, n[1])  # (P, M)
    pos = f > 1e-12 * max(float(np.max(a)), 1e-300)
    with np.errstate(divide="ignore", invalid="ignore"):
        tt = np.where(pos[None, :], proj / np.where(pos, f, 1.0)[None, :], -np.inf)
    out = np.max(tt, axis=1)
    bad = np.any((~pos)[None, :] & (proj > 1e-9 * (np.abs(x) + np.abs(y) + 1.0)[:, None]),
                 axis=1)
    out = np.where(bad, np.inf, np.maximum(out, 0.0))
    return out


def start_state(problem: FrontProblem, t0: float, lat0: float, lon0: float,
                radius_m: float | None = None) -> FrontState:
    """The exact reachable set of the source at t0 + tau0 (module docstring) as phi, arrival.

    radius_m: r0 (default 10 grid spacings); tau0 = r0 / max_k a_k. The drift is frozen at its
    source value averaged over [t0, t0 + tau0].
    """
    g = problem.grid
    if not bool(g.contains(lat0, lon0)):
        raise InvalidParameterError("source", (lat0, lon0), "lies outside the front's grid")
    h = g.min_spacing_m
    r0 = 10.0 * max(g.hy, float(np.max(g.hx))) if radius_m is None else float(radius_m)
    if not (math.isfinite(r0) and r0 > 0):
        raise InvalidParameterError("radius_m", radius_m, "must be finite and > 0 (m)")
    a = np.asarray(problem.speeds)
    tau0 = r0 / float(np.max(a))
    fi_a, fj_a = g.frac_index(lat0, lon0)
    fi, fj = float(fi_a), float(fj_a)
    d = 0.5 * (problem.drift_at(t0, fi, fj) + problem.drift_at(t0 + tau0, fi, fj))
    band = problem.band
    ny, nx = g.shape
    reach = r0 + band + float(np.max(np.hypot(d[:, 0], d[:, 1]))) * tau0
    di = math.ceil(reach / g.hy) + 3
    i0, i1 = max(math.floor(fi) - di, 0), min(math.ceil(fi) + di + 1, ny)
    rows = np.arange(i0, i1)
    cmin = float(np.min(g.hx[rows]))
    dj = math.ceil(reach / cmin) + 3
    if g.periodic:
        dj = min(dj, nx // 2)
        cols = np.arange(math.floor(fj) - dj, math.ceil(fj) + dj + 1) % nx
        cols = np.unique(cols)
    else:
        cols = np.arange(max(math.floor(fj) - dj, 0), min(math.ceil(fj) + dj + 1, nx))
    ii, jj = np.meshgrid(rows, cols, indexing="ij")
    dlon = np.mod(g.lon[jj] - lon0 + 180.0, 360.0) - 180.0
    x = g.radius_m * np.cos(np.radians(g.lat[ii])) * np.radians(dlon)
    y = g.radius_m * np.radians(g.lat[ii] - lat0)
    T = _gauge_times(x.ravel(), y.ravel(), a, d).reshape(x.shape)
    dist = np.hypot(x, y)
    fin = np.isfinite(T)
    pos = fin & (T > 0)
    scale = np.full(T.shape, float(np.max(a)))
    scale[pos] = dist[pos] / T[pos]
    local = np.full(T.shape, band)
    local[fin] = (T[fin] - tau0) * scale[fin]
    phi = np.full((ny, nx), band)
    phi[ii, jj] = np.clip(local, -band, band)
    arrival = np.full((ny, nx), np.inf)
    inside = np.isfinite(T) & (T <= tau0)
    arrival[ii[inside], jj[inside]] = t0 + T[inside]
    tb = problem.block_times
    blocked = (np.isinf(arrival) & (t0 + tau0 > tb))
    if problem.drift is not None:
        lo = problem.drift.level(problem.drift.bracket(t0)[0])
        blocked |= ~np.isfinite(lo[0].reshape(ny, nx))
    phi[blocked] = band
    arrival[blocked] = np.inf
    near = np.abs(phi) < band
    near |= np.isfinite(arrival)
    act = np.flatnonzero(_dilate(near, 2, g.periodic)).astype(np.int64)
    del h
    return FrontState(phi, arrival, t0 + tau0, act, 0, (float(lat0), float(lon0)), r0)


def _dilate(mask: NDArray[np.bool_], r: int, periodic: bool) -> NDArray[np.bool_]:
    out = mask.copy()
    _ny, _nx = mask.shape
    for d in range(1, r + 1):
        out[d:, :] |= mask[:-d, :]
        out[:-d, :] |= mask[d:, :]
        if periodic:
            out |= np.roll(mask, d, axis=1) | np.roll(mask, -d, axis=1)
        else:
            out[:, d:] |= mask[:, :-d]
            out[:, :-d] |= mask[:, d:]
    return out


def propagate(
    problem: FrontProblem,
    state: FrontState,
    t_max: float,
    goal: tuple[float, float] | None = None,
    *,
    cfl: float = 0.5,
    stop_on_edge: bool = False,
    edge_margin: int = 3,
    on_step: Callable[[float, int, int], None] | None = None,
) -> FrontResult:
    """Advance the front from `state` until the goal is passed, it stalls, or t_max.

    goal: (lat, lon) to stop at (after a few more steps so the arrival map is complete around
    it); None runs until the front stalls or t_max. stop_on_edge: return with reason "edge"
    as soon as the band comes within `edge_margin` nodes of a non-periodic side (the caller
    grows the grid and resumes with `FrontResult.state.embedded(...)`). A front "stalls"
    when its band is empty, or (steady problems) when it advances less than 1e-6 of a cell
    per step over 40/cfl steps. on_step(t, steps, reached_total) is called every step.
    """
    if not (0.0 < cfl <= 0.9):
        raise InvalidParameterError("cfl", cfl, "must lie in (0, 0.9]")
    g = problem.grid
    ny, nx = g.shape
    phi = np.ascontiguousarray(state.phi, dtype=float).ravel().copy()
    arrival = np.ascontiguousarray(state.arrival, dtype=float).ravel().copy()
    act = np.ascontiguousarray(state.active, dtype=np.int64)
    t = float(state.t)
    steps = state.steps
    args = StepArgs.of(problem)
    drift = problem.drift
    blocks = MayBlock.of(args.tb)
    mark = np.zeros(ny * nx, dtype=np.int64)
    steady = (drift is None or drift.steady) and not np.any(np.isfinite(args.tb)
                                                            & (args.tb > t))
    stall_limit = math.ceil(40.0 / cfl)
    stall = 0
    h_min = g.min_spacing_m
    reached_total = int(np.count_nonzero(np.isfinite(arrival)))
    watch = None if goal is None else GoalWatch.at(g, goal, phi.reshape(ny, nx))
    edges_seen = 0
    reason = "t_max"
    stepper = _Stepper(args, drift, phi, arrival)
    while t < t_max:
        if drift is not None:
            blocks.see(drift, t)
        dt, reached, dmax = stepper.step(act, t, t_max, cfl, blocks.may)
        if dt < 1e-300:
            reason = "stalled"
            break
        t = t + dt
        steps += 1
        reached_total += reached
        act, nband, edges = stepper.next_active(act, mark, edge_margin)
        edges_seen |= edges
        if on_step is not None:
            on_step(t, steps, reached_total)
        if nband == 0:
            reason = "stalled"
            break
        if watch is not None and watch.done(g, phi.reshape(ny, nx), arrival.reshape(ny, nx),
                                            problem.block_times, t, dt, cfl):
            reason = "goal"
            break
        if stop_on_edge and edges and (watch is None or watch.time is None):
            reason = "edge"
            break
        if steady:
            stall = stall + 1 if (reached == 0 and dmax < 1e-6 * h_min) else 0
            if stall > stall_limit:
                reason = "stalled"
                break
    stepper.restore_threads()
    goal_time = None if watch is None else watch.time
    if goal_time is not None and reason == "t_max":
        reason = "goal"
    names = frozenset(name for bit, name in _EDGE_NAMES if edges_seen & bit)
    arr = arrival.reshape(ny, nx)
    new_state = FrontState(phi.reshape(ny, nx), arr, t, act, steps, state.source,
                           state.start_radius_m)
    return FrontResult(arr, reason, goal_time, names, new_state, steps, t)


class _Stepper:
    """One TVD-RK2 step of the kernel over the active nodes, in place on phi and arrival;
    numba's threads set per step (PARALLEL_MIN_NODES) and restored at the end."""

    def __init__(self, args: StepArgs, drift: DriftLevels | None, phi: FloatArray,
                 arrival: FloatArray) -> None:
        import numba

        from glideplan.fronts import kernel  # chooses numba's threading layer (first)

        self.args, self.drift, self.phi, self.arrival = args, drift, phi, arrival
        self.p1 = phi.copy()
        self.dummy = np.zeros((2, 1))
        self.threads = int(numba.get_num_threads())
        self.current = self.threads
        self.stamp = 0
        self.kernel = kernel

    def step(self, act: NDArray[np.int64], t: float, t_max: float, cfl: float,
             may: NDArray[np.uint8]) -> tuple[float, int, float]:
        """Advance from t: (dt, nodes newly reached, max phi change); dt < 1e-300 = stalled."""
        import numba

        from glideplan.compute import checkpoint, kernel_section

        kernel = self.kernel
        x, drift = self.args, self.drift
        has_drift = drift is not None
        if drift is not None:
            lo, hi, w = drift.pair(t)
        else:
            lo = hi = self.dummy
            w = 0.0
        dt_cap = max(t_max - t, 1e-12 * max(abs(t), 1.0))
        use = self.threads if act.size >= PARALLEL_MIN_NODES else 1
        if use != self.current:
            numba.set_num_threads(use)
            self.current = use
        checkpoint()  # a cancelled computation (a superseded explorer request) stops here
        with kernel_section():  # a lock only where the threading layer is not thread-safe
            dt = kernel.rk_stage(self.phi, self.p1, act, t, w, dt_cap, x.band, x.ny, x.nx,
                                 x.periodic, *x.spacings, x.a, x.b, x.s, self.arrival, x.tb,
                                 lo, hi, has_drift, cfl, may)
        if dt < 1e-300:
            return dt, 0, 0.0
        t1 = t + dt
        if drift is not None:
            lo, hi, w1 = drift.pair(t1)
        else:
            w1 = 0.0
        with kernel_section():
            reached, dmax = kernel.stage_two(self.phi, self.p1, act, t, t1, w1, dt, x.band,
                                             x.ny, x.nx, x.periodic, *x.spacings, x.a, x.b,
                                             x.s, self.arrival, x.tb, lo, hi, has_drift, may)
        return dt, reached, dmax

    def next_active(self, act: NDArray[np.int64], mark: NDArray[np.int64],
                    edge_margin: int) -> tuple[NDArray[np.int64], int, int]:
        """The next step's active nodes, the band's size and the edges it touches (bits)."""
        from glideplan.fronts.kernel import next_active

        self.stamp += 1
        x = self.args
        return next_active(self.phi, act, x.band, mark, self.stamp, x.ny, x.nx, x.periodic,
                           edge_margin)

    def restore_threads(self) -> None:
        import numba

        if self.current != self.threads:
            numba.set_num_threads(self.threads)
