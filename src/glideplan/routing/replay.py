"""Replay: plan on forecasts, fly the truth, replan -- and the baselines on the same truth.

`replay(truth, forecasts, mission)` flies four controllers through the truth (a `FlowField`
the planner never sees), from the same start at the same departure:

- `replan` (the closed loop): at departure, whenever a newer forecast is issued, every
  `replan_every_s` if given, and when a plan runs out before the goal, `route()` plans from the
  vehicle's position on the newest forecast issued by then (`glideplan.routing.forecasts.
  planning_field`: the last field held past the forecast's end; corrected near the vehicle by
  the current it measured since its last fix, a fix every `fix_every_s`); its headings are
  flown through the truth until the next replan;
- `plan_once`: the departure plan's headings flown without replanning;
- `hindsight`: the route planned on the truth itself (the best possible), flown the same way;
- `naive`: heading straight at the goal all the way (pure pursuit).

How the closed loop steers (`ReplaySettings.feedback`, on by default): with each plan it
computes the time-to-go map tau(x) on the same field (the front run backwards from the goal
from the plan's arrival time, `routing.replay_feedback`) and flies the heading -grad(tau) at
wherever the vehicle is: a feedback law that does not need to regain the plan's path after
the truth pushed it off (measured on the QG twin at 0.3 m/s, see the README). Where the map has
no value it tracks the plan as below. The baselines are flown by tracking.

How a plan is flown (`ReplaySettings.follow`): "track" (default) -- as a glider flies
waypoints, the vehicle steers at the plan's point `lookahead_m` (6 km) beyond its point nearest
the vehicle, with the crab angle for the current it expects (the field the plan was made on:
the forecast corrected by its own measurement; the truth for hindsight; still water for
none); past the plan's end, at the goal. "headings" -- the plan's headings in time, open loop,
then straight at the goal. Open-loop headings diverge from the plan in eddies within hours
(measured on the QG twin: the hindsight plan flown by its headings through the very field it
was planned on missed missions it reaches by tracking), so tracking is the default. When
planning fails the vehicle heads straight at the goal and tries again 3 h later. Motion (the
truth's current c plus the water velocity of compass heading chi):

    dlat/dt = (V cos chi + c_north) / R,   dlon/dt = (V sin chi + c_east) / (R cos lat)

integrated with RK4 in steps of at most `step_s` (restarting at every node of a plan's
controls); the track is kept at every step (<= 15 min apart). The mission ends `solved` when
the vehicle is within `goal_radius_m` of the goal (the crossing interpolated in the step), else
`unreachable` with a reason: `max_duration` (time ran out), `field_extent` (left the truth's
field) or `aground` (the truth's current is NaN: land).
"""

from __future__ import annotations

import math
import time as timer
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.results import Outcome, Reason
from glideplan.routing.forecasts import Forecast, mean_current, newest, planning_field
from glideplan.routing.replay_flyer import _Expected, _Flyer, _lateness
from glideplan.routing.steering import _follow, _naive, _tracker
from glideplan.solution import Status

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["REASONS", "Flight", "Mission", "Plan", "ReplayResult", "ReplaySettings", "replay"]

FloatArray = NDArray[np.float64]
REASONS = ("max_duration", "field_extent", "aground")


@dataclass(frozen=True)
class Mission:
    """start/goal (lat, lon deg), speed (m/s), depart (datetime64), goal_radius_m,
    max_duration_s, replan_every_s (None: at departure and at each new forecast only)."""

    start: tuple[float, float]
    goal: tuple[float, float]
    speed: float
    depart: np.datetime64
    goal_radius_m: float = 2000.0
    max_duration_s: float = 8 * 86400.0
    replan_every_s: float | None = None

    def __post_init__(self) -> None:
        for name in ("speed", "goal_radius_m", "max_duration_s"):
            val = getattr(self, name)
            if not (math.isfinite(val) and val > 0):
                raise InvalidParameterError(name, val, "must be finite and > 0")
        r = self.replan_every_s
        if r is not None and not (math.isfinite(r) and r >= 600.0):
            raise InvalidParameterError("replan_every", r, "must be >= 600 s (10 min)")


@dataclass(frozen=True)
class ReplaySettings:
    """step_s: integration step (s, <= 900); fix_every_s: the vehicle's fixes (s); bias_length_m
    / bias_time_s: reach of the measured-current correction (0 length: none); resolution:
    the planner's grid spacing (m; None: distance / cells, at least 2 km); cells; follow:
    "track" (steer at the plan's point `lookahead_m` ahead of the nearest, with the crab angle
    for the current the vehicle expects: the plan's field, corrected by its measurement) or
    "headings" (the plan's headings in time, open loop); switch_margin: a new plan replaces
    the one being flown only when it is faster, on the new forecast, than the rest of the old
    path by this fraction (0: always); crab_fixes: the crab angle's current is corrected at
    each fix by the current the vehicle measured since the previous one (as at planning);
    late_replan_s: the closed loop also replans (on the newest forecast, with the new
    measurement) at a fix where the vehicle is this far behind its plan's schedule (None:
    never). Both off by default: on the QG twin (0.3 m/s) they gained on one mission set
    (90.7 -> 94.4 % of feasible) and lost on another (82.4 -> 76.5 %). feedback: the closed
    loop steers by each plan's time-to-go map (module docstring) where it has a value."""

    step_s: float = 600.0
    fix_every_s: float = 3 * 3600.0
    bias_length_m: float = 20e3
    bias_time_s: float = 12 * 3600.0
    resolution: float | None = None
    cells: int = 60
    follow: str = "track"
    lookahead_m: float = 6000.0
    switch_margin: float = 0.03
    crab_fixes: bool = False
    late_replan_s: float | None = None
    feedback: bool = True

    def __post_init__(self) -> None:
        if self.follow not in ("track", "headings"):
            raise InvalidParameterError("follow", self.follow, "must be 'track' or 'headings'")


@dataclass(frozen=True, eq=False)
class Plan:
    """One plan: made at time_s (s after departure) on the forecast issued at `issued`; its
    status, planned duration (s) and track (t s after departure, lat, lon, compass chi rad)."""

    time_s: float
    issued: str
    status: str
    planned_duration_s: float | None
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    chi: FloatArray

    def to_dict(self) -> dict[str, Any]:
        return {"time_s": self.time_s, "forecast_reference_time": self.issued,
                "status": self.status, "planned_duration_s": self.planned_duration_s}


@dataclass(frozen=True, eq=False)
class Flight:
    """A controller's outcome: status, reason, duration (s), track (t s after departure)."""

    status: str
    duration_s: float | None
    reason: str | None
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    plans: tuple[Plan, ...] = ()

    def summary(self) -> dict[str, Any]:
        return {"status": self.status, "duration_s": self.duration_s,
                "unreachable_reason": self.reason}


@dataclass(frozen=True, eq=False, kw_only=True)
class ReplayResult(Outcome):
    """The replay (closed loop) and its baselines (module docstring): an `Outcome` whose status
    and reason are the closed loop's flight's (SOLVED, or UNREACHABLE with reason
    max_duration / field_extent / aground)."""

    mission: Mission
    flight: Flight
    baselines: dict[str, Flight]
    stats: dict[str, Any] = field(default_factory=dict)
    #: where the truth and forecasts came from (JSON "truth", "forecasts"; set by the CLI)
    sources: dict[str, Any] = field(default_factory=dict)

    def plot(self, ax: Any = None, truth: FlowField | None = None, **kwargs: Any) -> Figure:
        """The flown track, its plans and the baselines (`replay_plot.replay_figure`), over
        the truth's current when `truth` (a FlowField) is given."""
        from glideplan.results import as_figure
        from glideplan.routing.replay_plot import replay_figure

        return as_figure(replay_figure(self, truth, ax=ax))

    def regret_s(self) -> float | None:
        """Replay duration minus hindsight duration (s), when both arrived."""
        h = self.baselines["hindsight"].duration_s
        d = self.flight.duration_s
        return None if h is None or d is None else d - h

    def to_dict(self) -> dict[str, Any]:
        """The JSON of `glideplan route replay --json`."""
        f = self.flight
        dep = self.mission.depart
        arrival = None if f.duration_s is None else str(
            (dep + np.timedelta64(round(f.duration_s), "s")).astype("datetime64[s]")) + "Z"
        return {
            **super().to_dict(),
            "unreachable_reason": f.reason, "duration_s": f.duration_s,
            "depart": str(dep.astype("datetime64[s]")) + "Z", "arrival_time": arrival,
            "track": {"time_s": f.t.tolist(), "lat": f.lat.tolist(),
                      "lon": (((f.lon + 180.0) % 360.0) - 180.0).tolist()},
            "replans": [p.to_dict() for p in f.plans],
            "baselines": {k: b.summary() for k, b in self.baselines.items()},
            "regret_s": self.regret_s(),
            "stats": dict(self.stats), **self.sources,
        }


# ------------------------------------------------------------------------------ planning


def _plan(fld: FlowField, pos: tuple[float, float], goal: tuple[float, float], speed: float,
          t: float, horizon: float, t0: float, issued: str, settings: ReplaySettings) -> Plan:
    """route() from pos at t on `fld` (never the truth unless it is the hindsight plan)."""
    from glideplan.routing import route
    from glideplan.routing.sphere import gc_distance

    dist = float(gc_distance(*pos, *goal))
    res = settings.resolution or max(2000.0, dist / settings.cells)
    empty = np.zeros(0)
    try:
        r = route(fld, pos, goal, speed, depart=t, resolution=res, refine=False,
                  max_duration=max(horizon - t, 3600.0), progress=False)
    except InvalidParameterError:
        return Plan(float(t - t0), issued, "failed", None, empty, empty, empty, empty)
    if r.status.value == "unreachable" or not r.track.size:
        return Plan(float(t - t0), issued, r.status.value, None, empty, empty, empty, empty)
    chi = math.pi / 2 - np.asarray(r.track.heading, dtype=float)
    times = np.asarray(r.track.t, dtype=float)
    # a route not verified in a current stronger than the vehicle carries no duration
    # (finer_grid): its held legs' own time is its track's end
    dur = float(times[-1] if r.duration_s is None else r.duration_s)
    if r.status.value != "solved":  # its legs' times are not flown ones: the front's
        times, dur = _front_schedule(r, times, dur)
    return Plan(float(t - t0), issued, r.status.value, dur, times + t - t0,
                r.lat.copy(), r.lon.copy(), chi)


def _front_schedule(r: Any, times: FloatArray, dur: float) -> tuple[FloatArray, float]:
    """A route whose controls did not verify keeps its path (the front's characteristic) but
    takes the front's schedule: the arrival map T(lat, lon) interpolated (bilinear) at its
    vertices, made non-decreasing, ending at the front's arrival (grid_duration_s). Its legs'
    own times (each leg held with its crab angle) are wrong where a leg heads into a current
    faster than the vehicle (measured on the QG twin: 2,160 h for a 111 h front)."""
    fm, T = r.front, r.grid_duration_s
    if fm is None or T is None or not math.isfinite(T) or r.lat.size < 2:
        return times, dur
    from scipy.interpolate import RegularGridInterpolator

    arr = np.where(np.isfinite(fm.arrival), fm.arrival, np.nan)
    interp = RegularGridInterpolator((fm.lat, fm.lon), arr, bounds_error=False)
    sched = interp(np.column_stack([r.lat, r.lon]))
    if not np.all(np.isfinite(sched)):
        return times, dur
    sched = np.clip(np.maximum.accumulate(sched - sched[0]), 0.0, T)
    sched[-1] = T
    return sched, float(T)


def _fly_plan(fl: _Flyer, plan: Plan, t_stop: float, s: ReplaySettings,
              expected: FlowField | None = None, late_s: float | None = None,
              ttg: Any = None) -> bool:
    """Fly the plan until t_stop: its track (crabbing for the `expected` current, corrected
    at each fix by the current the vehicle measured) or its headings (then at the goal);
    without a plan, at the goal. With `late_s`, stop early (True) at the first fix where the
    vehicle is more than `late_s` behind the plan's schedule (`_lateness`)."""
    if not plan.t.size:
        return fl.fly(t_stop, _naive(fl.m.goal))
    if s.follow != "track":
        return fl.fly(t_stop, _follow(plan, fl.t0, fl.m.goal), plan.t + fl.t0)
    cur = None if expected is None else _Expected(expected, s)
    steer = _tracker(plan, fl.m.goal, fl.m.speed, cur, s.lookahead_m)
    if ttg is not None:
        steer = _by_time_to_go(ttg, steer)
    if cur is None or not s.crab_fixes:
        return fl.fly(t_stop, steer)
    fix = s.fix_every_s
    while True:  # a fix every `fix` s after departure: the crab's current is corrected there
        t = fl.t[-1]
        if t > fl.t0 + 60.0:
            cur.update(fl)
            if late_s is not None and _lateness(plan, fl) > late_s:
                return True
        seg = min(t_stop, fl.t0 + (math.floor((t - fl.t0) / fix + 1e-9) + 1) * fix)
        if not fl.fly(seg, steer) or seg >= t_stop - 1e-9:
            return fl.status is None and fl.t[-1] < fl.t_end - 1e-9


def _by_time_to_go(ttg: Any, track: Callable[[float, float, float], float]) -> Callable[
        [float, float, float], float]:
    """Steer along -grad(time-to-go) where the map has a value, else by `track`."""

    def heading(t: float, lat: float, lon: float) -> float:
        h = ttg.heading(lat, lon)
        return track(t, lat, lon) if h is None else h

    return heading


def _events(forecasts: list[Forecast], epoch: np.datetime64, t0: float, t_end: float,
            every: float | None) -> list[float]:
    """Replan times after departure: each newer forecast's issue, every `every` seconds."""
    ev = {float((fc.issued - epoch) / np.timedelta64(1, "s")) for fc in forecasts}
    if every:
        ev |= set(np.arange(t0 + every, t_end, every).tolist())
    return sorted(e for e in ev if t0 < e < t_end)


def _closed_loop(truth: FlowField, forecasts: list[Forecast], m: Mission, t0: float,
                 t_end: float, s: ReplaySettings, warnings: list[str]) -> tuple[
                     Flight, Plan, FlowField]:
    """The replanning controller (module docstring); also returns its departure plan."""
    epoch = truth.epoch
    assert epoch is not None
    fl = _Flyer(truth, m, t0, t_end, s.step_s)
    events = _events(forecasts, epoch, t0, t_end, m.replan_every_s)
    plans: list[Plan] = []
    t = t0
    while True:
        now = epoch + np.timedelta64(round(t), "s")
        fc = newest(forecasts, now)
        assert fc is not None
        pos = (fl.lat[-1], fl.lon[-1])
        meas = fl.measured_current(s.fix_every_s) if s.bias_length_m > 0 else None
        bias = (0.0, 0.0)
        horizon = t + 1.5 * (t_end - t) + 86400.0
        fld, warn = planning_field(fc, epoch, t, horizon)
        if not plans:
            first_field = fld
        if meas is not None:
            fu, fv = mean_current(fld, meas[2], meas[3], meas[4])
            bias = (meas[0] - fu, meas[1] - fv)
            fld, warn = planning_field(fc, epoch, t, horizon, bias, pos, t, s.bias_length_m,
                                       s.bias_time_s)
        warnings.extend(w for w in warn if w not in warnings)
        # planned up to the field's horizon, past the time limit: a late plan is still the
        # fastest way there (an "unreachable" answer would leave only heading at the goal)
        plan = _plan(fld, pos, m.goal, m.speed, t, horizon - 3600.0, t0,
                     str(fc.issued) + "Z", s)
        if plans and s.switch_margin > 0:
            plan = _keep_or_switch(plans[-1], plan, fld, pos, m, t, t0, s.switch_margin)
        plans.append(plan)
        nxt = next((e for e in events if e > t + 1.0), t_end)
        if not plan.t.size:  # no plan: head at the goal, try again in 3 h
            nxt = min(nxt, t + 3 * 3600.0)
        if plan.planned_duration_s is not None and plan.t.size:
            plan_end = t + plan.planned_duration_s
            if plan_end < nxt - 1.0 and fl.goal_distance(*pos) > 4 * m.goal_radius_m:
                nxt = max(plan_end, t + 3600.0)  # the plan ran out before the goal: replan
        ttg = _feedback_map(fld, plan, pos, m, t, s) if s.feedback else None
        if not _fly_plan(fl, plan, nxt, s, fld, s.late_replan_s, ttg):
            break
        t = fl.t[-1]
    return fl.flight(tuple(plans)), plans[0], first_field


def _feedback_map(fld: FlowField, plan: Plan, pos: tuple[float, float], m: Mission, t: float,
                  s: ReplaySettings) -> Any:
    """The time-to-go map (`replay_feedback.time_to_go`) for arriving when the plan does."""
    from glideplan.routing.replay_feedback import time_to_go
    from glideplan.routing.sphere import gc_distance

    if plan.planned_duration_s is None or not plan.t.size:
        return None
    dist = float(gc_distance(*pos, *m.goal))
    res = s.resolution or max(2000.0, dist / s.cells)
    return time_to_go(fld, m.goal, pos, m.speed, t + plan.planned_duration_s, t, res)


def _open_loop(truth: FlowField, m: Mission, t0: float, t_end: float, s: ReplaySettings,
               plan: Plan | None, expected: FlowField | None = None) -> Flight:
    """A plan flown without replanning, then at the goal (plan None: naive all the way)."""
    fl = _Flyer(truth, m, t0, t_end, s.step_s)
    if plan is None:
        fl.fly(t_end, _naive(m.goal))
    else:
        _fly_plan(fl, plan, t_end, s, expected)
    return fl.flight(() if plan is None else (plan,))


def _keep_or_switch(old: Plan, new: Plan, fld: FlowField, pos: tuple[float, float],
                    m: Mission, t: float, t0: float, margin: float) -> Plan:
    """The new plan, unless the rest of the old path (from its vertex nearest the vehicle on),
    timed on the new forecast with the crab angle, is within `margin` of it: then the old
    path, re-timed ("kept"). A pilot does not change course for a forecast's noise: switching
    between two near-equal paths round an eddy loses time at each switch."""
    from glideplan.routing.sphere import crab_controls, gc_distance

    if not old.lat.size:
        return new
    d = gc_distance(pos[0], pos[1], old.lat, old.lon)
    k = int(np.argmin(d))
    lat = np.r_[pos[0], old.lat[k + 1:]]
    lon = np.r_[pos[1], old.lon[k + 1:]]
    if lat.size < 2 or float(gc_distance(lat[-1], lon[-1], *m.goal)) > 2 * m.goal_radius_m:
        return new
    try:
        times, chi, ok = crab_controls(fld, m.speed, t, lat, lon)
    except InvalidParameterError:
        return new
    t_old = float(times[-1] - t)
    if not ok or (new.planned_duration_s is not None and new.t.size
                  and new.planned_duration_s < (1 - margin) * t_old):
        return new
    return Plan(new.time_s, new.issued, "kept", t_old, times - t0, lat, lon, chi)


def check_coverage(truth: FlowField, forecasts: list[Forecast], m: Mission) -> tuple[float,
                                                                                   float]:
    """(t0, t_end) in the truth's clock; InvalidParameterError when the truth does not cover
    the mission or no forecast is issued by the departure."""
    if truth.epoch is None:
        raise InvalidParameterError("--truth", "no time axis", "the truth needs dates")
    t0 = float((m.depart - truth.epoch) / np.timedelta64(1, "s"))
    t_end = t0 + m.max_duration_s
    span = truth.time_span
    if span is not None and (t0 < span[0] - 1e-6 or t_end > span[1] + 1e-6):
        raise InvalidParameterError(
            "--truth", f"{truth.format_time(span[0])}..{truth.format_time(span[1])}",
            f"does not cover the mission {truth.format_time(t0)}..{truth.format_time(t_end)}: "
            "give a longer truth, a later --depart or a shorter --max-duration")
    truth.check_position(*m.start, name="--from")
    truth.check_position(*m.goal, name="--to")
    for fc in forecasts:  # a forecast of another sea: named, before any plan asks it
        for name, where in (("--from", m.start), ("--to", m.goal)):
            try:
                fc.field.check_position(*where, name=name)
            except InvalidParameterError as exc:
                raise InvalidParameterError(
                    "--forecasts", ", ".join(fc.paths),
                    f"does not cover {exc.name}={exc.value}: {exc.rule}") from None
    if newest(forecasts, m.depart) is None:
        first = str(forecasts[0].issued) + "Z" if forecasts else "none"
        raise InvalidParameterError(
            "--forecasts", ", ".join(forecasts[0].paths) if forecasts else "",
            f"no forecast is issued at or before the departure {str(m.depart)[:19]}Z (the "
            f"first is issued {first}): depart later or add an earlier forecast")
    return t0, t_end


def replay(truth: FlowField, forecasts: list[Forecast], mission: Mission,
           settings: ReplaySettings | None = None) -> ReplayResult:
    """Fly the replanning controller and the baselines through the truth (module docstring)."""
    from glideplan.fields.scalar import scalar_gridded

    s = settings or ReplaySettings()
    truth = scalar_gridded(truth)
    t0, t_end = check_coverage(truth, forecasts, mission)
    clock = timer.perf_counter()
    warnings: list[str] = []
    flight, first, first_field = _closed_loop(truth, forecasts, mission, t0, t_end, s, warnings)
    t_replay = timer.perf_counter() - clock
    once = _open_loop(truth, mission, t0, t_end, s, first if first.t.size else None,
                      first_field)
    naive = _open_loop(truth, mission, t0, t_end, s, None)
    hind_plan = _plan(truth, mission.start, mission.goal, mission.speed, t0, t_end, t0,
                      "truth", s)
    hindsight = _open_loop(truth, mission, t0, t_end, s, hind_plan if hind_plan.t.size else None,
                           truth)
    if warnings:
        warnings = [f"{len(warnings)} of the {len(flight.plans)} plans ran past their "
                    "forecast's last time step: planned on with its last field held "
                    "(persistence keeps its eddies where it put them; the next forecast "
                    "replaces it); first: " + warnings[0]]
    stats = {"replay_s": round(t_replay, 3), "total_s": round(timer.perf_counter() - clock, 3),
             "replans": len(flight.plans)}
    return ReplayResult(status=Status(flight.status),
                        reason=None if flight.reason is None else Reason(flight.reason),
                        mission=mission, flight=flight,
                        baselines={"naive": naive, "plan_once": once, "hindsight": hindsight},
                        warnings=tuple(warnings), stats=stats)
