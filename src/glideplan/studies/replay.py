"""The replay study: many missions through `glideplan.routing.replay`, on the batch runner.

Each mission (a row of missions.csv: id,start_lat,start_lon,goal_lat,goal_lon,depart,
speed_mps,goal_radius_m,max_hours) is one work unit: the worker opens the truth and the
forecasts (once per process), replays the mission and returns each controller's outcome.
Units run on `glideplan.batch.run_batch` (a Dask cluster with a scheduler address, local
processes otherwise) and are stored as they finish in DIR/results.sqlite (a `ResultsStore`:
a restart runs only the missing missions).

The summary: `feasible` counts the missions whose hindsight route (planned on the truth,
flown through it) reached the goal; `success_rate[c]` the share of those that controller c
reached; `success_rate_10pct_margin[c]` the same over the missions feasible with 10 % of the
time limit to spare (hindsight duration <= 0.9 max_hours); `median_duration_vs_hindsight` the
median of replan duration / hindsight duration over the missions both reached.
"""

from __future__ import annotations

import csv
import io
import json
import math
import pathlib
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.studies.runner import RunReport, run_units
from glideplan.studies.store import ResultsStore

__all__ = ["COLUMNS", "CONTROLLERS", "ReplayStudy", "read_missions", "run_replay_study",
           "summarise", "write_missions"]

COLUMNS = ("id", "start_lat", "start_lon", "goal_lat", "goal_lon", "depart", "speed_mps",
           "goal_radius_m", "max_hours")
CONTROLLERS = ("replan", "plan_once", "naive", "hindsight")
STORE_NAME = "results.sqlite"
_STORE_COLUMNS = (("unit", "INTEGER"), ("id", "TEXT"), ("controller", "TEXT"),
                  ("status", "TEXT"), ("duration_s", "REAL"), ("reason", "TEXT"),
                  ("replans", "INTEGER"))
_KEY = ("unit", "controller")


def read_missions(path: str | pathlib.Path) -> list[dict[str, Any]]:
    """The missions of a CSV file (module docstring); errors name the file and the column."""
    p = pathlib.Path(path)
    if not p.is_file():
        raise InvalidParameterError("--missions", str(p), "no such file")
    try:  # utf-8-sig: a byte-order mark (a spreadsheet's "CSV UTF-8") is not a column name
        text = p.read_text(encoding="utf-8-sig")
    except UnicodeDecodeError:
        raise InvalidParameterError("--missions", str(p), "not a UTF-8 text CSV file") from None
    if "\x00" in text:
        raise InvalidParameterError("--missions", str(p), "not a UTF-8 text CSV file (got binary)")
    with io.StringIO(text, newline="") as fh:
        reader = csv.DictReader(fh)
        names = [n.strip() for n in (reader.fieldnames or [])]
        missing = [c for c in COLUMNS if c not in names]
        if missing:
            raise InvalidParameterError(
                "--missions", str(p), f"missing column(s) {', '.join(missing)}: the header "
                f"must name {','.join(COLUMNS)}")
        rows = []
        for k, raw in enumerate(reader, start=2):
            row = {key.strip(): (val or "").strip() for key, val in raw.items() if key}
            try:
                m = {"id": row["id"], "depart": row["depart"]}
                for c in COLUMNS[1:]:
                    if c != "depart":
                        val = float(row[c])
                        m[c] = val
                        if not math.isfinite(val):
                            raise ValueError(c)
                np.datetime64(row["depart"].rstrip("Z"), "s")
            except (ValueError, TypeError) as exc:
                raise InvalidParameterError("--missions", f"{p} line {k}",
                                            f"unreadable value ({exc}): numbers and ISO 8601 "
                                            "depart expected") from None
            rows.append(m)
    if not rows:
        raise InvalidParameterError("--missions", str(p), "has no missions")
    ids = [m["id"] for m in rows]
    if len(set(ids)) != len(ids):
        raise InvalidParameterError("--missions", str(p), "ids must be unique")
    return rows


def write_missions(path: str | pathlib.Path, missions: list[dict[str, Any]]) -> pathlib.Path:
    """Write missions (dicts with the COLUMNS) as CSV (read back by `read_missions`)."""
    p = pathlib.Path(path)
    with p.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=list(COLUMNS))
        w.writeheader()
        for m in missions:
            w.writerow({c: m[c] for c in COLUMNS})
    return p


@dataclass(frozen=True)
class ReplayStudy:
    """One mission's work unit: the files, the mission row, the replay settings (a dict)."""

    truth: str
    forecasts: tuple[str, ...]
    mission: dict[str, Any]
    settings: dict[str, Any]
    replan_every_h: float | None = None


_CACHE: dict[Any, Any] = {}


def _inputs(truth: str, forecasts: tuple[str, ...]) -> tuple[Any, Any]:
    """The truth and forecasts, opened once per worker process."""
    from glideplan.fields import open_field
    from glideplan.routing.forecasts import open_forecasts

    key = (truth, forecasts)
    if key not in _CACHE:
        _CACHE.clear()
        _CACHE[key] = (open_field(truth), open_forecasts(list(forecasts)))
    return _CACHE[key]


def mission_of(row: dict[str, Any], replan_every_h: float | None = None) -> Any:
    from glideplan.routing.replay import Mission

    return Mission((row["start_lat"], row["start_lon"]), (row["goal_lat"], row["goal_lon"]),
                   row["speed_mps"], np.datetime64(str(row["depart"]).rstrip("Z"), "s"),
                   row["goal_radius_m"], row["max_hours"] * 3600.0,
                   None if replan_every_h is None else replan_every_h * 3600.0)


def replay_unit(unit: ReplayStudy) -> dict[str, Any]:
    """Replay one mission: each controller's status, duration, reason (and the replans)."""
    from glideplan.routing.replay import ReplaySettings, replay

    truth, fcs = _inputs(unit.truth, unit.forecasts)
    res = replay(truth, fcs, mission_of(unit.mission, unit.replan_every_h),
                 ReplaySettings(**unit.settings))
    out = {"replan": {**res.flight.summary(), "replans": len(res.flight.plans)}}
    for name, b in res.baselines.items():
        out[name] = {**b.summary(), "replans": len(b.plans)}
    return out


def summarise(store: ResultsStore, missions: list[dict[str, Any]]) -> dict[str, Any]:
    """The per-mission table and the summary (module docstring)."""
    rows = store.query("SELECT unit, controller, status, duration_s, reason, replans "
                       "FROM results ORDER BY unit")
    by: dict[int, dict[str, Any]] = {}
    for unit, ctrl, status, dur, reason, replans in rows:
        by.setdefault(unit, {})[ctrl] = {"status": status, "duration_s": dur,
                                         "unreachable_reason": reason, "replans": replans}
    table = []
    for i in sorted(by):
        r = by[i]
        table.append({"id": missions[i]["id"], "status": r["replan"]["status"],
                      "duration_s": r["replan"]["duration_s"],
                      "unreachable_reason": r["replan"]["unreachable_reason"],
                      "replans": r["replan"]["replans"],
                      "max_hours": missions[i]["max_hours"],
                      "baselines": {c: {k: v for k, v in r[c].items() if k != "replans"}
                                    for c in CONTROLLERS[1:]}})
    feas = [m for m in table if m["baselines"]["hindsight"]["status"] == "solved"]
    margin = [m for m in feas if m["baselines"]["hindsight"]["duration_s"]
              <= 0.9 * m["max_hours"] * 3600.0]

    def status_of(m: dict[str, Any], c: str) -> str:
        return str(m["status"] if c == "replan" else m["baselines"][c]["status"])

    def rate(group: list[dict[str, Any]], c: str) -> float | None:
        return None if not group else sum(status_of(m, c) == "solved" for m in group) / len(group)

    def ratio(c: str) -> float | None:
        vals = [(m["duration_s"] if c == "replan" else m["baselines"][c]["duration_s"])
                / m["baselines"]["hindsight"]["duration_s"] for m in feas if status_of(m, c)
                == "solved"]
        return float(np.median(vals)) if vals else None

    summary = {"missions": len(table), "feasible": len(feas),
               "feasible_10pct_margin": len(margin),
               "success_rate": {c: rate(feas, c) for c in CONTROLLERS[:3]},
               "success_rate_10pct_margin": {c: rate(margin, c) for c in CONTROLLERS[:3]},
               "median_duration_vs_hindsight": ratio("replan"),
               "median_duration_vs_hindsight_by_controller": {c: ratio(c)
                                                              for c in CONTROLLERS[:3]}}
    return {"missions": table, "summary": summary}


def _csv(path: pathlib.Path, table: list[dict[str, Any]]) -> None:
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(["id", "max_hours", *[f"{c}_{k}" for c in CONTROLLERS
                                         for k in ("status", "hours")], "replans"])
        for m in table:
            cells: list[Any] = [m["id"], m["max_hours"]]
            for c in CONTROLLERS:
                b = m if c == "replan" else m["baselines"][c]
                d = b["duration_s"]
                cells += [b["status"], "" if d is None else f"{d / 3600:.3f}"]
            w.writerow([*cells, m["replans"]])


def run_replay_study(truth: str | pathlib.Path, forecasts: list[str], missions_csv: str |
                     pathlib.Path, out_dir: str | pathlib.Path, *, scheduler: str | None = None,
                     processes: int | None = None, replan_every_h: float | None = None,
                     settings: dict[str, Any] | None = None, progress: bool = True) -> tuple[
                         dict[str, Any], RunReport]:
    """Run (or resume) the study into `out_dir`: results.sqlite, outcomes.csv,
    summary.json and summary.png; returns (the JSON answer, the run report)."""
    missions = read_missions(missions_csv)
    directory = pathlib.Path(out_dir)
    if directory.exists() and not directory.is_dir():
        raise InvalidParameterError("--out", str(directory), "must be a directory")
    directory.mkdir(parents=True, exist_ok=True)
    fc = tuple(str(pathlib.Path(p).resolve()) for p in forecasts)
    tr = str(pathlib.Path(truth).resolve())
    sett = dict(settings or {})
    units = [ReplayStudy(tr, fc, m, sett, replan_every_h) for m in missions]
    config = {"truth": tr, "forecasts": list(fc), "missions": missions, "settings": sett,
              "replan_every_h": replan_every_h}
    with ResultsStore(directory / STORE_NAME, config, kind="replay", columns=_STORE_COLUMNS,
                      key=_KEY) as store:

        def rows_of(i: int, out: dict[str, Any]) -> list[tuple[Any, ...]]:
            return [(i, missions[i]["id"], c, out[c]["status"], out[c]["duration_s"],
                     out[c]["unreachable_reason"], out[c]["replans"]) for c in CONTROLLERS]

        report = run_units(replay_unit, units, store, rows_of, scheduler=scheduler,
                           processes=processes, progress=progress, label="replay study",
                           unit_name="missions", wave=None if scheduler else
                           2 * (processes or 2))
        answer = summarise(store, missions)
    (directory / "summary.json").write_text(json.dumps(answer, indent=1) + "\n")
    _csv(directory / "outcomes.csv", answer["missions"])
    from glideplan.studies.replay_plot import plot_study

    plot_study(answer, directory / "summary.png")
    return answer, report
