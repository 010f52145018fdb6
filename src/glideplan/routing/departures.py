"""The best departure: the route (or the ensemble's routes) for each departure of a range.

`route_departures(fields, start, goal, speed, departures, ...)` routes every (member,
departure) pair in parallel on `glideplan.batch.run_batch` and ranks the departures:

- one field: the best departure has the shortest duration T(t_d) among solved routes; a
  departure whose duration is within GRID_TIME_TOLERANCE (the front's relative discretisation
  error, 5e-3) of the shortest ties with it and the earliest tied departure wins (leaving
  earlier for the same passage time arrives earlier). Earliest arrival is no criterion: in a
  current field an earlier departure never arrives later (the FIFO property of Zermelo's
  problem), so it would always pick the first departure.
- an ensemble: the highest p_arrival, then the shortest P50 (same tolerance; the mean
  duration of the arriving members when fewer than half arrive), then the earliest; only
  the best departure's route to fly is chosen (the closed loop of
  `glideplan.routing.ensemble`), the others carry their statistics.

`departure_times(start, end, step_h)`: start, start + step, ... up to end inclusive.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.results import Outcome
from glideplan.routing.ensemble import EnsembleResult, RouteTask, run_task, summarise
from glideplan.routing.result import RouteResult
from glideplan.routing.route import GRID_TIME_TOLERANCE
from glideplan.routing.settings import RouteSettings
from glideplan.solution import Status

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["DepartureResult", "departure_times", "route_departures"]

#: More departures than this is surely a typo in the step (a year of 15-minute steps).
MAX_DEPARTURES = 10_000


def departure_times(start: np.datetime64, end: np.datetime64, step_h: float,
                    flag: str = "--depart-range") -> np.ndarray:
    """start, start + step, ... <= end (datetime64[ms]); END < START or a step <= 0 refused."""
    if not (math.isfinite(step_h) and step_h > 0):
        raise InvalidParameterError(flag, step_h, "HOURS (the step) must be finite and > 0")
    if end < start:
        raise InvalidParameterError(flag, f"{start} {end}", "END must not be before START")
    step = np.timedelta64(round(step_h * 3.6e6), "ms")
    if step <= np.timedelta64(0, "ms"):
        raise InvalidParameterError(flag, step_h, "HOURS (the step) must be >= 1 ms")
    n = int((end - start) // step) + 1
    if n > MAX_DEPARTURES:
        raise InvalidParameterError(flag, n, f"at most {MAX_DEPARTURES} departures")
    return start.astype("datetime64[ms]") + step * np.arange(n)


def _iso(t: Any) -> Any:
    if isinstance(t, np.datetime64):
        return str(t.astype("datetime64[s]")) + "Z"
    return float(t)


@dataclass(frozen=True, eq=False, kw_only=True)
class DepartureResult(Outcome):
    """Routes (one field) or ensembles (members) per departure, and the best departure."""

    departures: tuple[Any, ...] = ()
    routes: tuple[RouteResult, ...] = ()
    ensembles: tuple[EnsembleResult, ...] = ()
    best: int | None = None

    @property
    def durations_s(self) -> np.ndarray:
        """Per departure: the duration (s; inf unsolved) or, for ensembles, the P50 (s)."""
        if self.ensembles:
            return np.array([math.inf if (p := e.quantile_h(0.5)) is None else p * 3600.0
                             for e in self.ensembles])
        return np.array([r.duration_s if r.ok and r.duration_s is not None else math.inf
                         for r in self.routes])

    def rows(self) -> list[dict[str, Any]]:
        """The table: one row per departure."""
        out = []
        for k, t in enumerate(self.departures):
            if self.ensembles:
                s = self.ensembles[k].summary()
                row = {"depart": _iso(t), "p_arrival": s["p_arrival"], "p10_h": s["p10_h"],
                       "p50_h": s["p50_h"], "p90_h": s["p90_h"], "duration_s": s["duration_s"]}
            else:
                r = self.routes[k]
                d = r.to_dict()
                row = {"depart": _iso(t), "status": r.status.value, "duration_s": r.duration_s,
                       "arrive": d["arrive"]}
            out.append(row)
        return out

    def to_dict(self) -> dict[str, Any]:
        """The best departure's route (or ensemble) JSON, plus `departures` and
        `best_departure`."""
        items: Sequence[Any] = self.ensembles or self.routes
        base = items[self.best if self.best is not None else 0]
        out = {**base.to_dict(), **super().to_dict()}
        out["departures"] = self.rows()
        out["best_departure"] = None if self.best is None else _iso(self.departures[self.best])
        return out

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        from glideplan.results import as_figure
        from glideplan.routing.ensemble_plot import departure_figure

        return as_figure(departure_figure(self, ax=ax, **kwargs))


def _best(keys: Sequence[tuple[float, float]]) -> int | None:
    """Index of the best (-p, T) with T ties within GRID_TIME_TOLERANCE -> the earliest."""
    finite = [k for k in keys if math.isfinite(k[1])]
    if not finite:
        return None
    p_best = min(k[0] for k in finite)
    t_best = min(k[1] for k in finite if k[0] == p_best)
    for i, (p, t) in enumerate(keys):
        if p == p_best and t <= t_best * (1 + GRID_TIME_TOLERANCE) + 1e-9:
            return i
    return None  # pragma: no cover - the minimum is always found


def _typical(e: EnsembleResult) -> float:
    """P50 (s), or the mean duration of the members that arrive when P50 is not reached."""
    q = e.quantile_h(0.5)
    if q is not None:
        return q * 3600.0
    d = e.durations[np.isfinite(e.durations)]
    return float(d.mean()) if d.size else math.inf


def route_departures(
    fields: Sequence[FlowField],
    start: tuple[float, float],
    goal: tuple[float, float],
    speed: float,
    departures: Sequence[Any],
    *,
    ensemble: bool = False,
    settings: RouteSettings | None = None,
    names: Sequence[str] | None = None,
    scheduler: Any = None,
    processes: int | None = None,
    progress: bool = False,
) -> DepartureResult:
    """Route each departure (every member's route when `ensemble`; else fields[0]) in one
    parallel batch and rank them (module docstring)."""
    from glideplan.batch import run_batch

    if len(departures) == 0:
        raise InvalidParameterError("departures", 0, "give at least one departure")
    settings = replace(settings or RouteSettings(), progress=False)
    members = list(fields) if ensemble else list(fields[:1])
    tasks = [RouteTask(f, start, goal, speed, t, settings) for t in departures for f in members]
    results = run_batch(run_task, tasks, scheduler=scheduler, processes=processes,
                        progress=progress, description="departures")
    m = len(members)
    per = [results[k * m:(k + 1) * m] for k in range(len(departures))]
    warnings = sorted({w for r in results for w in r.warnings})
    if not ensemble:
        routes = tuple(p[0] for p in per)
        res = DepartureResult(status=Status.SOLVED, departures=tuple(departures), routes=routes)
        best = _best([(0.0, float(d)) for d in res.durations_s])
    else:
        labels = list(names) if names is not None else [f"member {i}" for i in range(m)]
        ens = [summarise(members, p, labels, speed, goal, settings.max_duration, choose=False)
               for p in per]
        best = _best([(-e.p_arrival, _typical(e)) for e in ens])
        if best is not None:
            ens[best] = summarise(members, per[best], labels, speed, goal,
                                  settings.max_duration, choose=True)
        res = DepartureResult(status=Status.SOLVED, departures=tuple(departures),
                              ensembles=tuple(ens))
    if best is None:
        return replace(res, status=Status.UNREACHABLE, warnings=tuple(warnings),
                       message=f"no departure of {len(departures)} reaches the goal")
    return replace(res, best=best, warnings=tuple(warnings),
                   message=f"best departure {_iso(departures[best])} of {len(departures)}")
