"""Routes on every member of a forecast ensemble: arrival distribution, corridor, a route to fly.

`route_ensemble(members, start, goal, speed, ...)` routes on every member (files or FlowFields)
in parallel on `glideplan.batch.run_batch` (local processes, or Dask with `scheduler=`), then:

- durations T_m (s; inf where the member's route is not solved) and their quantiles P10, P50,
  P90 by linear interpolation between order statistics (numpy's default: at h = (M-1) q,
  T_(floor h) + (h - floor h)(T_(ceil h) - T_(floor h))); a quantile that needs an
  unreachable member is None (not reached);
- p_arrival = #{m : route m solved (within the max duration)} / M;
- the corridor: every member's track and its envelope (`corridor_envelope`);
- the route to fly: each solved member route i is flown in closed loop through every member j
  (`follow_waypoints`: its track as waypoints, steering at the next one at full speed with the
  crab angle for the local current); p_i = #{j : arrives within the max duration} / M; the
  chosen route maximises p_i, ties (equal p_i) broken by the smaller mean arrival over the
  members it reaches, then by the lower member index.

Members must share one grid (latitudes, longitudes, times): members on different grids are
refused, naming the first file that differs (regrid them to a common grid first, e.g. with
`cdo remapbil`). Time-outs: every route and closed-loop flight stops at the departure plus
`settings.max_duration` (default: the field's time span).
"""

from __future__ import annotations

import math
import pathlib
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, GriddedField
from glideplan.results import Outcome
from glideplan.routing.result import RouteResult
from glideplan.routing.settings import RouteSettings
from glideplan.solution import Status

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = [
    "BATCH_CELLS",
    "MEMBER_DIMS",
    "EnsembleResult",
    "RouteTask",
    "check_same_grid",
    "corridor_envelope",
    "ensemble_quantile",
    "expand_members",
    "open_members",
    "route_ensemble",
]

FloatArray = NDArray[np.float64]
QUANTILES = (0.1, 0.5, 0.9)
#: Cells across the start-goal distance for each of many routes (`glideplan route --ensemble`,
#: `--depart-range`) when no resolution is given, against 250 for one route: the front costs
#: ~cells^3, and on the 300 km benchmark member the arrival moves by 0.02 % between 250 and
#: 150 cells, far inside an ensemble's spread.
BATCH_CELLS = 150


def expand_members(pattern: str, flag: str = "--ensemble") -> list[pathlib.Path]:
    """The files matching a glob pattern (sorted; a folder: its .nc and GRIB files); none
    matching -> an error naming `flag`."""
    import glob

    folder = pathlib.Path(pattern).expanduser()
    if folder.is_dir():
        found = sorted(p for p in folder.iterdir() if p.is_file() and p.suffix.lower() in (
            ".nc", ".nc4", ".grib", ".grib2", ".grb", ".grb2"))
        if not found:
            raise InvalidParameterError(flag, pattern, "this folder holds no .nc or GRIB file")
        return found
    paths = sorted(pathlib.Path(p) for p in glob.glob(str(pathlib.Path(pattern).expanduser()))
                   if pathlib.Path(p).is_file())
    if not paths:
        raise InvalidParameterError(flag, pattern, "matches no file (quote the pattern so the "
                                    "shell does not expand it, e.g. 'ENS_DIR/member_*.nc')")
    return paths


def check_same_grid(fields: Sequence[FlowField], names: Sequence[str],
                    flag: str = "members") -> None:
    """Refuse members whose latitudes, longitudes or times differ from the first member's."""
    f0 = fields[0]
    if not isinstance(f0, GriddedField):
        return
    for f, name in zip(fields[1:], names[1:], strict=True):
        what = None
        if not isinstance(f, GriddedField):
            what = "is not a gridded field"
        elif f.lat.shape != f0.lat.shape or not np.allclose(f.lat, f0.lat, atol=1e-9):
            what = f"has latitudes {_axis(f.lat)} against {_axis(f0.lat)}"
        elif f.lon.shape != f0.lon.shape or not np.allclose(f.lon, f0.lon, atol=1e-9):
            what = f"has longitudes {_axis(f.lon)} against {_axis(f0.lon)}"
        elif f.times.shape != f0.times.shape or f.epoch != f0.epoch or not np.allclose(
                f.times, f0.times, atol=1e-3):
            what = f"has {f.times.size} time steps from {f.format_time(float(f.times[0]))} " \
                   f"against {f0.times.size} from {f0.format_time(float(f0.times[0]))}"
        if what is not None:
            raise InvalidParameterError(
                flag, name, f"members must share one grid: this one {what} in {names[0]}; "
                "regrid the members to a common grid (e.g. cdo remapbil)")


def _axis(a: FloatArray) -> str:
    return f"{a.size} from {float(a[0]):g} to {float(a[-1]):g}"


#: Dimensions that number the members of an ensemble in one file (CF, ECMWF, GEFS, others).
MEMBER_DIMS = ("realization", "number", "ens", "member", "ensemble", "ensemble_member")


def _split_members(path: pathlib.Path, depth_range: tuple[float, float] | None
                   ) -> tuple[list[FlowField], list[str]]:
    """A file's members: one per index of its member dimension (MEMBER_DIMS), or itself."""
    from glideplan.fields.io import _find_components, _open_one, from_xarray

    ds = _open_one(path)
    dims = set(ds[_find_components(ds)[0]].dims)
    dim = next((d for d in MEMBER_DIMS if d in dims and ds.sizes[d] > 1), None)
    if dim is None:
        return [from_xarray(ds, depth_range=depth_range, source=str(path))], [str(path)]
    vals = ds[dim].values if dim in ds.coords else np.arange(ds.sizes[dim])
    names = [f"{path}[{dim}={v}]" for v in vals]
    return [from_xarray(ds.isel({dim: i}), depth_range=depth_range, source=name)
            for i, name in enumerate(names)], names


def open_members(paths: Sequence[str | pathlib.Path], depth_range: tuple[float, float] | None
                 = None, flag: str = "members") -> tuple[list[FlowField], list[str]]:
    """Read every member (one per file, or one per index of a file's member dimension:
    CF `realization`, ECMWF `number`, GEFS `ens`, ...) and check they share one grid:
    (fields, their names)."""
    fields: list[FlowField] = []
    names: list[str] = []
    for p in paths:
        f, n = _split_members(pathlib.Path(p), depth_range)
        fields += f
        names += n
    check_same_grid(fields, names, flag)
    return fields, names


@dataclass(frozen=True)
class RouteTask:
    """One route for the batch runner: a field (or file), start, goal, speed, departure."""

    field_: Any
    start: tuple[float, float]
    goal: tuple[float, float]
    speed: float
    depart: Any
    settings: RouteSettings
    depth_range: tuple[float, float] | None = None


def run_task(task: RouteTask) -> RouteResult:
    """Route one task (module-level: picklable for processes and Dask); the front map is
    dropped to keep the transfer small."""
    from glideplan.routing.route import route

    res = route(task.field_, task.start, task.goal, task.speed, depart=task.depart,
                depth_range=task.depth_range, settings=task.settings)
    return replace(res, front=None)


def ensemble_quantile(durations: Sequence[float] | FloatArray, q: float) -> float | None:
    """The q-quantile of durations (inf = not arriving) by linear interpolation between order
    statistics (numpy's 'linear'); None when it needs a member that does not arrive."""
    d = np.sort(np.asarray(durations, dtype=float))
    if d.size == 0:
        return None
    h = (d.size - 1) * q
    lo, hi = math.floor(h), math.ceil(h)
    if not (math.isfinite(d[lo]) and math.isfinite(d[hi])):
        return None
    return float(d[lo] + (h - lo) * (d[hi] - d[lo]))


def corridor_envelope(tracks: Sequence[tuple[FloatArray, FloatArray]],
                      start: tuple[float, float], goal: tuple[float, float],
                      bins: int = 60) -> tuple[FloatArray, FloatArray]:
    """The corridor's outline (closed polygon lat, lon deg): in the plane about the start with x
    along the start-goal direction, the smallest and largest cross-track y of all tracks in
    each of `bins` slices of x (tracks resampled to 1/4 slice), left edge out, right edge back."""
    from glideplan.geodesy import LocalProjection

    proj = LocalProjection(*start)
    gx, gy = proj.to_local(np.array([goal[0]]), np.array([goal[1]]))
    ang = math.atan2(float(gy[0]), float(gx[0]))
    ca, sa = math.cos(ang), math.sin(ang)
    xs, ys = [], []
    for la, lo in tracks:
        x, y = proj.to_local(np.asarray(la, float), np.asarray(lo, float))
        s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
        n = max(int(4 * bins * s[-1] / max(float(np.hypot(gx[0], gy[0])), 1.0)), 2) + 1
        ss = np.linspace(0.0, s[-1], n)
        xi, yi = np.interp(ss, s, x), np.interp(ss, s, y)
        xs.append(ca * xi + sa * yi)
        ys.append(-sa * xi + ca * yi)
    ax, ay = np.concatenate(xs), np.concatenate(ys)
    edges = np.linspace(float(ax.min()), float(ax.max()), bins + 1)
    idx = np.clip(np.searchsorted(edges, ax, side="right") - 1, 0, bins - 1)
    lo_y, hi_y = np.full(bins, np.inf), np.full(bins, -np.inf)
    np.minimum.at(lo_y, idx, ay)
    np.maximum.at(hi_y, idx, ay)
    used = np.isfinite(lo_y)
    mid = 0.5 * (edges[:-1] + edges[1:])[used]
    mid[0], mid[-1] = float(ax.min()), float(ax.max())
    px = np.concatenate([mid, mid[::-1], mid[:1]])
    py = np.concatenate([hi_y[used], lo_y[used][::-1], hi_y[used][:1]])
    lat, lon = proj.to_geographic(ca * px - sa * py, sa * px + ca * py)
    return np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)


@dataclass(frozen=True, eq=False, kw_only=True)
class EnsembleResult(Outcome):
    """The ensemble's answer (module docstring): member routes, statistics, the chosen route."""

    members: tuple[str, ...] = ()
    routes: tuple[RouteResult, ...] = ()
    max_duration_s: float | None = None
    chosen: int | None = None
    follow_duration_s: FloatArray = field(default_factory=lambda: np.zeros((0, 0)))
    envelope: tuple[FloatArray, FloatArray] | None = None

    @property
    def durations(self) -> FloatArray:
        """Per member: the route's duration (s), inf where it is not solved."""
        return np.array([r.duration_s if r.ok and r.duration_s is not None else math.inf
                         for r in self.routes])

    @property
    def p_arrival(self) -> float:
        return float(np.mean(np.isfinite(self.durations))) if self.routes else 0.0

    def quantile_h(self, q: float) -> float | None:
        v = ensemble_quantile(self.durations, q)
        return None if v is None else v / 3600.0

    @property
    def chosen_p_arrival(self) -> float | None:
        if self.chosen is None:
            return None
        return float(np.mean(np.isfinite(self.follow_duration_s[self.chosen])))

    def summary(self) -> dict[str, Any]:
        """The `ensemble` object of the JSON."""
        out: dict[str, Any] = {
            "members": len(self.routes),
            "files": list(self.members),
            "duration_s": [None if not math.isfinite(d) else float(d) for d in self.durations],
            "status": [r.status.value for r in self.routes],
            "p_arrival": self.p_arrival,
            "p10_h": self.quantile_h(0.1), "p50_h": self.quantile_h(0.5),
            "p90_h": self.quantile_h(0.9),
            "max_duration_h": None if self.max_duration_s is None else
            self.max_duration_s / 3600.0,
        }
        out["chosen"] = None if self.chosen is None else {
            "member": self.chosen, "file": self.members[self.chosen],
            "p_arrival": self.chosen_p_arrival,
            "closed_loop_duration_s": [None if not math.isfinite(d) else float(d)
                                       for d in self.follow_duration_s[self.chosen]],
            "how": "each solved member route flown in closed loop (its track as waypoints, "
                   "steering at the next at full speed with the crab angle) through every "
                   "member; the one arriving in the most members, ties by the smaller mean "
                   "arrival"}
        return out

    @property
    def chosen_route(self) -> RouteResult | None:
        return None if self.chosen is None else self.routes[self.chosen]

    def to_dict(self) -> dict[str, Any]:
        """The chosen route's JSON (the first member's if none) plus `ensemble`."""
        base = self.chosen_route or (self.routes[0] if self.routes else None)
        out: dict[str, Any] = {**(base.to_dict() if base is not None else {}),
                               **super().to_dict()}
        out["ensemble"] = self.summary()
        return out

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        from glideplan.results import as_figure
        from glideplan.routing.ensemble_plot import ensemble_figure

        return as_figure(ensemble_figure(self, ax=ax, **kwargs))


def _member_limit(fields: Sequence[FlowField], routes: Sequence[RouteResult], speed: float,
                  max_duration: float | None) -> float:
    """The closed loop's end (s since the epoch): departure + max duration, within every
    member's time span; steady members without a limit: route()'s default, 10 still-water
    times (at least an hour)."""
    from glideplan.routing.sphere import gc_distance

    t0 = routes[0].depart_s
    ends = [f.time_span[1] for f in fields if f.time_span is not None]
    end = min(ends) if ends else math.inf
    if max_duration is not None:
        end = min(end, t0 + max_duration)
    if not math.isfinite(end):
        s, g = routes[0].start, routes[0].goal
        end = t0 + max(10.0 * float(gc_distance(s[0], s[1], g[0], g[1])) / speed, 3600.0)
    return end


def choose_route(fields: Sequence[FlowField], routes: Sequence[RouteResult], speed: float,
                 goal: tuple[float, float], t_end: float) -> tuple[int | None, FloatArray]:
    """Fly every solved member route through every member (module docstring): the chosen
    member index (None if no route arrives anywhere) and the (M, M) arrival durations (s,
    inf where route i does not arrive through member j)."""
    from glideplan.routing.follow_waypoints import follow_waypoints

    m = len(routes)
    out = np.full((m, m), np.inf)
    if all(r.ok and r.distance_m <= 1e-6 for r in routes):  # start = goal: nothing to fly
        return 0, np.zeros((m, m))
    solved = [i for i, r in enumerate(routes) if r.ok and r.track.size >= 2]
    if not solved:
        return None, out
    pairs = [(i, j) for i in solved for j in range(m)]
    radius = min(float(routes[i].endpoint_tolerance_m or 0.0) for i in solved)
    radius = radius if radius > 0 else 1000.0
    res = follow_waypoints(fields, [j for _, j in pairs],
                           [(routes[i].lat, routes[i].lon) for i, _ in pairs], speed, goal,
                           routes[solved[0]].depart_s, t_end, radius)
    for (i, j), ok, d in zip(pairs, res.arrived, res.duration_s, strict=True):
        out[i, j] = d if ok else math.inf
    score = [(-float(np.mean(np.isfinite(out[i]))), _mean_finite(out[i]), i) for i in solved]
    best = min(score)
    return (best[2] if best[0] < 0 else None), out


def _mean_finite(a: FloatArray) -> float:
    f = a[np.isfinite(a)]
    return float(f.mean()) if f.size else math.inf


def route_ensemble(
    members: Sequence[Any],
    start: tuple[float, float],
    goal: tuple[float, float],
    speed: float,
    depart: Any = None,
    *,
    settings: RouteSettings | None = None,
    names: Sequence[str] | None = None,
    scheduler: Any = None,
    processes: int | None = None,
    progress: bool = False,
    choose: bool = True,
) -> EnsembleResult:
    """Route on every member (FlowFields on one grid, or files read with `open_members`) and
    summarise (module docstring). Raises InvalidParameterError for bad input."""
    if len(members) == 0:
        raise InvalidParameterError("members", 0, "give at least one ensemble member")
    settings = settings or RouteSettings()
    if all(isinstance(m, FlowField) for m in members):
        fields = list(members)
        labels = list(names) if names is not None else [f"member {i}" for i in range(len(fields))]
        check_same_grid(fields, labels)
    else:
        fields, labels = open_members(members)
    from glideplan.batch import run_batch

    tasks = [RouteTask(f, start, goal, speed, depart, replace(settings, progress=False))
             for f in fields]
    routes = run_batch(run_task, tasks, scheduler=scheduler, processes=processes,
                       progress=progress, description="ensemble members")
    return summarise(fields, routes, labels, speed, goal, settings.max_duration, choose)


def summarise(fields: Sequence[FlowField], routes: Sequence[RouteResult], labels: Sequence[str],
              speed: float, goal: tuple[float, float], max_duration: float | None,
              choose: bool = True) -> EnsembleResult:
    """The EnsembleResult of member routes already computed (statistics, corridor, choice)."""
    warnings = sorted({w for r in routes for w in r.warnings})
    chosen, follow = None, np.full((len(routes), len(routes)), np.inf)
    if choose:
        t_end = _member_limit(fields, routes, speed, max_duration)
        chosen, follow = choose_route(fields, routes, speed, goal, t_end)
    tracks = [(r.lat, r.lon) for r in routes if r.track.size >= 2]
    envelope = corridor_envelope(tracks, routes[0].start, routes[0].goal) if tracks else None
    n_ok = sum(r.ok for r in routes)
    if chosen is not None:
        status, msg = Status.SOLVED, (
            f"{n_ok} of {len(routes)} members reach the goal; the route of member {chosen} "
            f"arrives in {int(np.sum(np.isfinite(follow[chosen])))} of them flown in closed loop")
    elif n_ok and not choose:
        status, msg = Status.SOLVED, f"{n_ok} of {len(routes)} members reach the goal"
    else:
        status = Status.UNREACHABLE
        msg = f"no member's route reaches the goal ({len(routes)} members)" if not n_ok else \
            "no member's route arrives when flown through the members"
    return EnsembleResult(status=status, message=msg, warnings=tuple(warnings),
                          members=tuple(labels), routes=tuple(routes),
                          max_duration_s=max_duration, chosen=chosen, follow_duration_s=follow,
                          envelope=envelope)
