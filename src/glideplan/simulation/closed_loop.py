"""Closed-loop path following of the disturbed car (3.2)/(A.4), thousands of vehicles at once.

Dissertation §3.4; REFERENCE_NOTES §1. Each vehicle flies at constant air-relative speed v
with heading psi and turn rate |u| <= u_max, pushed by a disturbance velocity delta(t):

    x' = v cos psi + delta_x,  y' = v sin psi + delta_y,  psi' = u.

Breivik-Fossen lookahead guidance (`glideplan.simulation.guidance`) turns the path and the
measured position and ground velocity into a course command chi_d; a saturated bang-bang
controller tracks it, u = u_max sat((chi_d - chi) / phi_b) with chi the measured course
(pure bang-bang u = u_max sign(chi_d - chi) when phi_b = 0), plus, by default, the path's
own turn rate at the path point, kappa_p varpi', as a feedforward, the sum saturated at
+-u_max. The feedforward removes the boundary layer's steady course lag on arcs; where a path
needs the full u_max (R_plan = R0) it leaves no authority for the feedback, which is exactly
the effect the feasible radius R0' addresses. Each step holds u and delta constant and moves
the vehicle exactly (circular arc plus drift); dt = 0.05 s is converged to within 3% in the
mean final error (tests/simulation/test_following.py::test_time_step_converged;
benchmarks/validate_time_step.py against dt = 0.0125 s and 0.00625 s).

The final cross-track error (REFERENCE_NOTES §1.5) is the distance from the path's end to the
point where the vehicle crosses the finish line — the line through the end orthogonal to
the final tangent — going forwards, interpolated between steps. The detector is armed only
once the path point has reached the path's last segment; a vehicle that has not crossed by
the time-out t_max = timeout_factor (L + 2 pi R0) / (v - delta_max), or whose path point has
run 2 R0 past the path's end (it passed the finish line without crossing it forwards while
armed), is a failure.

The disturbance is either a stream stepped once per step (`DisturbanceStream`: steady wind,
Dryden gusts; vehicles share rows of one realisation) or a `PositionalStream` evaluated at
each flying vehicle's position and the step's start time (a current or wind field,
`disturbances.FieldDisturbance`); a vehicle whose disturbance is undefined there (NaN: off
the field, on land) stops as a failure, flagged in `FollowResult.stopped`.
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.pose import TWO_PI
from glideplan.simulation.disturbances import DisturbanceStream, PositionalStream
from glideplan.simulation.guidance import PathArrays
from glideplan.simulation.step import _guidance, _move, _turn_rate
from glideplan.validation import check_in_range, check_nonnegative, check_positive

__all__ = ["FollowResult", "FollowerSettings", "finish_line_error", "follow_paths"]


@dataclass(frozen=True)
class FollowerSettings:
    """Vehicle, guidance and simulation parameters (SI units).

    speed: v (m/s); max_turn_rate: u_max (rad/s); lookahead: Delta (m), None for R0 = v/u_max;
    gamma: along-track gain (1/s); boundary_layer: phi_b (rad), 0 for pure bang-bang;
    dt: time step (s); timeout_factor: see the module docstring; feedforward: add the path's
    turn rate to the feedback. The defaults are the dissertation's vehicle (v = 20 m/s,
    u_max = 0.3 rad/s) and gains chosen, as in the dissertation (which does not report its
    own), heuristically for reasonable tracking across wind strengths and radii.
    """

    speed: float = 20.0
    max_turn_rate: float = 0.3
    lookahead: float | None = None
    gamma: float = 1.0
    boundary_layer: float = 0.2
    dt: float = 0.05
    timeout_factor: float = 2.0
    feedforward: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", check_positive("speed", self.speed))
        object.__setattr__(self, "max_turn_rate", check_positive("umax", self.max_turn_rate))
        if self.lookahead is not None:
            object.__setattr__(self, "lookahead", check_positive("lookahead", self.lookahead))
        object.__setattr__(self, "gamma", check_nonnegative("gamma", self.gamma))
        object.__setattr__(
            self, "boundary_layer", check_nonnegative("boundary_layer", self.boundary_layer)
        )
        object.__setattr__(self, "dt", check_positive("dt", self.dt))
        object.__setattr__(
            self, "timeout_factor", check_positive("timeout_factor", self.timeout_factor)
        )

    @property
    def min_radius(self) -> float:
        """R0 = v / u_max (m)."""
        return self.speed / self.max_turn_rate

    @property
    def lookahead_distance(self) -> float:
        """Delta (m)."""
        return self.lookahead if self.lookahead is not None else self.min_radius


@dataclass(frozen=True, eq=False)
class FollowResult:
    """Per vehicle: final cross-track error (m; NaN for failures), whether it crossed the
    finish line, and the crossing (or time-out) time (s). When recorded: `tracks` (steps, N, 2)
    positions (m) and `cross_track` (steps - 1, N) the cross-track error e (m, + left of the
    path) the guidance saw at the start of each step (NaN once a vehicle has finished).
    `stopped` (N,): the disturbance was undefined (NaN) where the vehicle was (positional
    disturbances only; None otherwise)."""

    error: np.ndarray
    crossed: np.ndarray
    time: np.ndarray
    tracks: np.ndarray | None = field(default=None)
    cross_track: np.ndarray | None = field(default=None)
    stopped: np.ndarray | None = field(default=None)

    @property
    def failures(self) -> int:
        return int(np.count_nonzero(~self.crossed))


def _crossing(x0, y0, x1, y1, a0, a1, xf, yf):
    """Crossing of the finish line between two samples whose signed distances to it are
    a0 < 0 <= a1: the step fraction and the distance from the path's end (xf, yf)."""
    frac = a0 / (a0 - a1)
    return frac, np.hypot(x0 + frac * (x1 - x0) - xf, y0 + frac * (y1 - y0) - yf)


def finish_line_error(
    previous: np.ndarray, current: np.ndarray, end: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Final cross-track error of moves from `previous` to `current` positions (N, 2) against
    the finish lines of path ends `end` (N, 3) (REFERENCE_NOTES §1.5).

    Returns (crossed, error): whether each move crosses its line forwards (from behind to on
    or beyond it) and the distance from the end to the crossing point (NaN when not crossed).
    """
    p0, p1, e = (np.asarray(a, dtype=float) for a in (previous, current, end))
    c, s = np.cos(e[:, 2]), np.sin(e[:, 2])
    a0 = (p0[:, 0] - e[:, 0]) * c + (p0[:, 1] - e[:, 1]) * s
    a1 = (p1[:, 0] - e[:, 0]) * c + (p1[:, 1] - e[:, 1]) * s
    crossed = (a0 < 0.0) & (a1 >= 0.0)
    error = np.full(p0.shape[0], np.nan)
    if crossed.any():
        m = crossed
        error[m] = _crossing(
            p0[m, 0], p0[m, 1], p1[m, 0], p1[m, 1], a0[m], a1[m], e[m, 0], e[m, 1]
        )[1]
    return crossed, error


@dataclass(frozen=True, eq=False)
class _SegmentTable:
    """Every segment of every path (flattened, N x K rows) in the form the path point needs.

    On a segment starting at arc length `s0` with heading `h0` and curvature `kappa`, at
    d = varpi - s0 the tangent angle is chi = h0 + kappa d and the point is
    (ax + d bx + cc sin chi, ay + d by - cc cos chi): (ax, ay) the centre and cc = 1/kappa on
    arcs, (ax, ay) the start and (bx, by) the direction on straights (cc = 0) — two
    transcendental functions per vehicle and step.
    """

    s0: np.ndarray
    h0: np.ndarray
    kappa: np.ndarray
    ax: np.ndarray
    bx: np.ndarray
    ay: np.ndarray
    by: np.ndarray
    cc: np.ndarray

    @classmethod
    def of(cls, paths: PathArrays) -> _SegmentTable:
        arc = paths.kappa != 0.0
        inv_k = np.divide(1.0, paths.kappa, out=np.zeros_like(paths.kappa), where=arc)
        ch0, sh0 = np.cos(paths.h0), np.sin(paths.h0)
        columns = (
            paths.s0,
            paths.h0,
            paths.kappa,
            np.where(arc, paths.x0 - inv_k * sh0, paths.x0),
            np.where(arc, 0.0, ch0),
            np.where(arc, paths.y0 + inv_k * ch0, paths.y0),
            np.where(arc, 0.0, sh0),
            inv_k,
        )
        return cls(*(np.ascontiguousarray(c).reshape(-1) for c in columns))


@dataclass(frozen=True, eq=False)
class _PathPoint:
    """The path point of each vehicle: position (m), unit tangent (cos, sin), the curvature of
    its segment (1/m) and how far it lies beyond the path's ends along the end tangent (m)."""

    x: np.ndarray
    y: np.ndarray
    cos: np.ndarray
    sin: np.ndarray
    kappa: np.ndarray
    beyond: np.ndarray


@dataclass(eq=False)
class _Fleet:
    """The vehicles still flying, one entry each (compacted as they finish).

    ids: index into the results; x, y (m) and (cos psi, sin psi); varpi: path parameter (m);
    a_prev: signed distance to the finish line at the last step (m); the finish line's point
    (xf, yf) and normal (cf, sf); tmax: time-out (s); row: disturbance row; the path's length,
    arming arc length, segment break points (arc lengths) and first row in the table.
    """

    ids: np.ndarray
    x: np.ndarray
    y: np.ndarray
    cp: np.ndarray
    sp: np.ndarray
    varpi: np.ndarray
    a_prev: np.ndarray
    xf: np.ndarray
    yf: np.ndarray
    cf: np.ndarray
    sf: np.ndarray
    tmax: np.ndarray
    row: np.ndarray
    length: np.ndarray
    arm: np.ndarray
    s_breaks: np.ndarray
    base: np.ndarray
    seg: np.ndarray

    @classmethod
    def start(cls, paths: PathArrays, t_max: np.ndarray, rows: np.ndarray) -> _Fleet:
        n, kk = paths.kappa.shape
        x, y = paths.x0[:, 0].copy(), paths.y0[:, 0].copy()
        xf, yf = paths.end[:, 0].copy(), paths.end[:, 1].copy()
        cf, sf = np.cos(paths.end[:, 2]), np.sin(paths.end[:, 2])
        return cls(
            ids=np.arange(n),
            x=x,
            y=y,
            cp=np.cos(paths.h0[:, 0]),
            sp=np.sin(paths.h0[:, 0]),
            varpi=np.zeros(n),
            a_prev=(x - xf) * cf + (y - yf) * sf,
            xf=xf,
            yf=yf,
            cf=cf,
            sf=sf,
            tmax=t_max.copy(),
            row=rows.copy(),
            length=paths.length.copy(),
            arm=paths.arm.copy(),
            s_breaks=paths.s0[:, 1:].copy(),
            base=np.arange(n) * kk,
            seg=np.zeros(n, dtype=np.intp),
        )

    def keep(self, mask: np.ndarray) -> None:
        """Drop the vehicles where `mask` is False."""
        for f in fields(self):
            setattr(self, f.name, getattr(self, f.name)[mask])

    def path_point(self, table: _SegmentTable) -> _PathPoint:
        """The path point at each vehicle's varpi (guidance.PathArrays.point_curvature)."""
        if self.s_breaks.shape[1] <= _SCAN_BREAKS:
            seg = self.base.copy()
            for j in range(self.s_breaks.shape[1]):
                seg += self.varpi >= self.s_breaks[:, j]
        else:
            seg = self.base + self._walk_segments()
        wc = np.clip(self.varpi, 0.0, self.length)
        dd = wc - table.s0[seg]
        chi = table.h0[seg] + table.kappa[seg] * dd
        c, s = np.cos(chi), np.sin(chi)
        beyond = self.varpi - wc  # beyond either end: along the end tangent
        cc = table.cc[seg]
        xp = table.ax[seg] + dd * table.bx[seg] + cc * s + beyond * c
        yp = table.ay[seg] + dd * table.by[seg] - cc * c + beyond * s
        return _PathPoint(xp, yp, c, s, table.kappa[seg], beyond)


    def _walk_segments(self) -> np.ndarray:
        """Segment index within each path, walked from the last step's (long paths): the
        number of break points <= varpi, as the scan over every break point gives, since the
        break points are sorted."""
        j, w, br = self.seg, self.varpi, self.s_breaks
        nb = br.shape[1]
        r = np.arange(j.size)
        while True:
            up = j < nb
            up[up] = w[up] >= br[r[up], j[up]]
            if not up.any():
                break
            j = j + up
        while True:
            down = j > 0
            down[down] = w[down] < br[r[down], j[down] - 1]
            if not down.any():
                break
            j = j - down
        self.seg = j
        return j


#: paths with at most this many break points scan them all each step; longer ones walk
_SCAN_BREAKS = 8


def follow_paths(
    paths: PathArrays,
    disturbance: DisturbanceStream | PositionalStream,
    *,
    rows: np.ndarray | None = None,
    settings: FollowerSettings | None = None,
    disturbance_bound: float = 0.0,
    record: bool = False,
) -> FollowResult:
    """Fly every path of `paths` from its start pose under guidance (module docstring).

    disturbance: a stream giving (rows, 2) velocities (m/s) per step, or a positional stream
    evaluated at the vehicles' positions (module docstring); `rows` (N,) maps each
    vehicle to a row (default: vehicle i uses row i), so several vehicles can share one
    realisation. disturbance_bound: delta_max (m/s) for the time-out. record: keep every
    vehicle's positions and cross-track errors (memory grows with N x steps).

    Each step: the path point, the guidance's course error, the turn rate, the exact motion,
    then the finish-line check (crossings interpolated within the step), the time-out and the
    lost check; finished vehicles are dropped from the fleet in batches.
    """
    cfg = settings or FollowerSettings()
    n = paths.count
    v, dt = cfg.speed, cfg.dt
    dmax = check_in_range("disturbance_bound", disturbance_bound, 0.0, v, high_open=True)
    row_of = np.arange(n) if rows is None else np.asarray(rows, dtype=np.intp)
    if row_of.shape != (n,) or (n and (row_of.min() < 0 or row_of.max() >= disturbance.rows)):
        raise InvalidParameterError("rows", row_of.shape, "need one valid row per path")
    lost_margin = 2.0 * cfg.min_radius
    tally = _Tally.empty(n, isinstance(disturbance, PositionalStream))
    t_max = cfg.timeout_factor * (paths.length + TWO_PI * cfg.min_radius) / (v - dmax)
    table = _SegmentTable.of(paths)
    fleet = _Fleet.start(paths, t_max, row_of)
    t = 0.0
    step = 0
    rec = _Recorder.start(fleet) if record else None
    live = np.ones(n, dtype=bool)
    while live.any():
        drift, undefined = _drift(disturbance, t, fleet, live)
        point = fleet.path_point(table)
        err, rate, cross = _guidance(fleet, point, v * fleet.cp + drift[:, 0],
                                     v * fleet.sp + drift[:, 1], cfg)
        if rec is not None:
            rec.cross_track(fleet, live, cross, n)
        x_new, y_new = _move(fleet, _turn_rate(err, rate, point, cfg), drift, cfg)
        step += 1
        if step % 1024 == 0:  # keep (cos psi, sin psi) on the unit circle
            norm = np.hypot(fleet.cp, fleet.sp)
            fleet.cp, fleet.sp = fleet.cp / norm, fleet.sp / norm
        fleet.varpi = fleet.varpi + rate * dt
        t = step * dt
        a = (x_new - fleet.xf) * fleet.cf + (y_new - fleet.yf) * fleet.sf
        hit = live & (fleet.varpi >= fleet.arm) & (fleet.a_prev < 0.0) & (a >= 0.0)
        if undefined is not None:
            hit &= ~undefined
        if hit.any():
            tally.crossing(fleet, hit, x_new, y_new, a, t, dt)
        fleet.x, fleet.y, fleet.a_prev = x_new, y_new, a
        if rec is not None:
            rec.positions(fleet, live)
        # lost: the path point is far past the end, so the vehicle went beyond the finish
        # line without crossing it forwards while armed (it will not come back)
        done = live & (hit | (t >= fleet.tmax) | (fleet.varpi > fleet.length + lost_margin))
        if tally.stopped is not None and undefined is not None and undefined.any():
            tally.stopped[fleet.ids[undefined]] = True
            done |= undefined
        if done.any():
            live = _retire(fleet, tally, live, done, hit, t)
    return FollowResult(error=tally.error, crossed=tally.crossed, time=tally.t_end,
                        tracks=None if rec is None else rec.tracks(),
                        cross_track=None if rec is None else rec.cross_tracks(n),
                        stopped=tally.stopped)


@dataclass(eq=False)
class _Tally:
    """Per-vehicle answers filled as the fleet flies: finish-line error (m), crossed, end
    time (s), and (positional streams) stopped where the disturbance is undefined."""

    error: np.ndarray
    crossed: np.ndarray
    t_end: np.ndarray
    stopped: np.ndarray | None

    @classmethod
    def empty(cls, n: int, positional: bool) -> _Tally:
        """Nothing crossed yet."""
        return cls(np.full(n, np.nan), np.zeros(n, dtype=bool), np.zeros(n),
                   np.zeros(n, dtype=bool) if positional else None)

    def crossing(self, fleet: _Fleet, hit: np.ndarray, x_new: np.ndarray, y_new: np.ndarray,
                 a: np.ndarray, t: float, dt: float) -> None:
        """Record the vehicles `hit` that crossed the finish line in the last step
        (crossing interpolated within the step)."""
        frac, err_h = _crossing(fleet.x[hit], fleet.y[hit], x_new[hit], y_new[hit],
                                fleet.a_prev[hit], a[hit], fleet.xf[hit], fleet.yf[hit])
        k = fleet.ids[hit]
        self.error[k] = err_h
        self.crossed[k] = True
        self.t_end[k] = t - dt + frac * dt


def _drift(disturbance: DisturbanceStream | PositionalStream, t: float, fleet: _Fleet,
           live: np.ndarray) -> tuple[np.ndarray, np.ndarray | None]:
    """The disturbance (m/s) on each vehicle this step; for a positional stream also the
    live vehicles where it is undefined (their drift set to 0)."""
    if isinstance(disturbance, PositionalStream):
        drift = disturbance.at(t, fleet.x, fleet.y, fleet.row)
        bad = ~np.isfinite(drift).all(axis=1)
        drift[bad] = 0.0
        return drift, live & bad
    return disturbance.next()[fleet.row], None


def _retire(fleet: _Fleet, tally: _Tally, live: np.ndarray, done: np.ndarray,
            hit: np.ndarray, t: float) -> np.ndarray:
    """Mark `done` vehicles finished at `t` (crossers keep their interpolated time); drop
    them from the fleet in batches; the new live mask."""
    tally.t_end[fleet.ids[done & ~hit]] = t
    live = live & ~done
    n_live = int(np.count_nonzero(live))
    # finished vehicles ride along (masked) until compacting pays off
    if n_live < 0.9 * live.size or n_live < 256:
        fleet.keep(live)
        live = np.ones(n_live, dtype=bool)
    return live


@dataclass(eq=False)
class _Recorder:
    """Every vehicle's positions and cross-track errors per step (`record=True`)."""

    full: np.ndarray
    track_list: list[np.ndarray] = field(default_factory=list)
    cross_list: list[np.ndarray] = field(default_factory=list)

    @classmethod
    def start(cls, fleet: _Fleet) -> _Recorder:
        """The start positions recorded."""
        full = np.stack([fleet.x, fleet.y], axis=-1)
        return cls(full, [full.copy()])

    def cross_track(self, fleet: _Fleet, live: np.ndarray, cross: np.ndarray, n: int) -> None:
        """Record this step's cross-track errors (NaN for finished vehicles)."""
        row = np.full(n, np.nan)
        row[fleet.ids[live]] = cross[live]
        self.cross_list.append(row)

    def positions(self, fleet: _Fleet, live: np.ndarray) -> None:
        """Record the live vehicles' new positions (finished ones stay where they ended)."""
        self.full[fleet.ids[live], 0], self.full[fleet.ids[live], 1] = (fleet.x[live],
                                                                        fleet.y[live])
        self.track_list.append(self.full.copy())

    def tracks(self) -> np.ndarray:
        """(steps + 1, N, 2) positions (m)."""
        return np.stack(self.track_list)

    def cross_tracks(self, n: int) -> np.ndarray:
        """(steps, N) cross-track errors (m)."""
        return np.stack(self.cross_list) if self.cross_list else np.empty((0, n))
