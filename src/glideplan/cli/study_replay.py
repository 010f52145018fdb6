"""`glideplan study replay` (many missions replayed on forecasts through the truth, on Dask or
local processes, resumable) and `glideplan study replay-twin` (writes a twin experiment)."""

from __future__ import annotations

import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import study_app


@study_app.command("replay")
def study_replay_command(
    truth: Annotated[pathlib.Path, typer.Option("--truth", metavar="FILE", show_default=False,
                                                help="The real ocean (NetCDF).")],
    forecasts: Annotated[str, typer.Option("--forecasts", metavar="GLOB", show_default=False,
                                           help="Forecast files (a quoted glob).")],
    missions: Annotated[pathlib.Path, typer.Option(
        "--missions", metavar="CSV", show_default=False,
        help="id,start_lat,start_lon,goal_lat,goal_lon,depart,speed_mps,goal_radius_m,"
        "max_hours")],
    out: Annotated[pathlib.Path, typer.Option("--out", metavar="DIR", show_default=False,
                                              help="Results directory (resumable).")],
    scheduler: Annotated[str | None, typer.Option(
        "--scheduler", metavar="ADDR", show_default=False,
        help="Dask scheduler address (tcp://HOST:8786); default: local processes.")] = None,
    workers: Annotated[int | None, typer.Option(
        "--workers", metavar="N", show_default=False,
        help="Local worker processes (default: one per core).")] = None,
    replan_every: Annotated[float | None, typer.Option(
        "--replan-every", metavar="HOURS", show_default=False,
        help="Also replan this often (h).")] = None,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
) -> None:
    """Replay every mission of missions.csv (replan, plan_once, naive, hindsight) and report
    the success rate of each controller over the missions feasible in hindsight and the
    median duration against hindsight (DIR/summary.json, outcomes.csv, summary.png)."""
    import sys

    from glideplan.cli.common import announce, print_json
    from glideplan.cli.route_replay import open_truth, positive
    from glideplan.errors import InvalidParameterError
    from glideplan.routing.forecasts import open_forecasts
    from glideplan.routing.replay import check_coverage
    from glideplan.studies.replay import mission_of, read_missions, run_replay_study

    if scheduler is not None and workers is not None:
        raise InvalidParameterError("--workers", workers, "give --scheduler or --workers")
    if workers is not None and workers < 1:
        raise InvalidParameterError("--workers", workers, "must be >= 1")
    positive("--replan-every", replan_every, "h")
    rows = read_missions(missions)
    flow = open_truth(truth)
    fcs = open_forecasts(forecasts)
    for row in rows:  # bad missions fail here, in one line, before any work is sent out
        try:
            check_coverage(flow, fcs, mission_of(row, replan_every))
        except InvalidParameterError as exc:
            raise InvalidParameterError(f"--missions {missions} mission {row['id']}: "
                                        f"{exc.name}", exc.value, exc.rule) from None
    files = [p for fc in fcs for p in fc.paths]
    answer, report = run_replay_study(truth, files, missions, out, scheduler=scheduler,
                                      processes=workers, replan_every_h=replan_every,
                                      progress=sys.stderr.isatty())
    answer["run"] = {"ran": report.ran, "skipped": report.skipped,
                     "seconds": round(report.seconds, 2), "out": str(out)}
    if json_out:
        print_json(answer)
    else:
        _print(answer["summary"], report)
    announce(f"wrote {out}/summary.json, outcomes.csv, summary.png", json_out)


def _print(s: dict[str, Any], report: Any) -> None:
    def pct(v: float | None) -> str:
        return "n/a" if v is None else f"{100 * v:.1f} %"

    typer.echo(f"missions: {s['missions']} (ran {report.ran}, resumed {report.skipped}, "
               f"{report.seconds:.1f} s)  feasible in hindsight: {s['feasible']}  with 10 % "
               f"to spare: {s['feasible_10pct_margin']}")
    for c in ("replan", "plan_once", "naive"):
        ratio = s["median_duration_vs_hindsight_by_controller"][c]
        typer.echo(f"{c:>10}: reached {pct(s['success_rate'][c])} of feasible, "
                   f"{pct(s['success_rate_10pct_margin'][c])} with 10 % to spare; median "
                   f"duration / hindsight " + ("n/a" if ratio is None else f"{ratio:.3f}"))


@study_app.command("replay-twin")
def study_replay_twin_command(
    out: Annotated[pathlib.Path, typer.Option("--out", metavar="DIR", show_default=False,
                                              help="Writes truth.nc, forecasts/, missions.csv.")],
    missions: Annotated[int, typer.Option("--missions", help="Random missions to write.")] = 60,
    days: Annotated[float, typer.Option("--days", help="Length of the truth (days).")] = 14.0,
    seed: Annotated[int, typer.Option("--seed", help="Model and missions seed.")] = 1,
    speed: Annotated[float, typer.Option("--speed", help="Missions' vehicle speed (m/s).")] = 0.5,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
) -> None:
    """Write an identical-twin experiment: a QG-model truth, daily forecasts from a perturbed
    truth (5 days of lead) and random missions; prints the forecasts' vector RMS error by lead
    day."""
    import json

    from glideplan.cli.common import print_json
    from glideplan.cli.route_replay import positive
    from glideplan.errors import InvalidParameterError
    from glideplan.fields.twin import TwinConfig, twin_missions, write_twin
    from glideplan.studies.replay import write_missions

    positive("--days", days, "days")
    positive("--speed", speed, "m/s")
    if missions < 1:
        raise InvalidParameterError("--missions", missions, "must be >= 1")
    if days < 9:
        raise InvalidParameterError("--days", days, "must be >= 9 (8-day missions + departures)")
    cfg = TwinConfig(days=days, forecasts=int(days) - 4, seed=seed)
    files = write_twin(out, cfg)
    rows = twin_missions(files, missions, seed=seed, speed=speed,
                         depart_days=(0.0, days - 8.0 - 1.0 / 24))
    write_missions(out / "missions.csv", rows)
    info = {"truth": str(files.truth), "forecasts": [str(p) for p in files.forecasts],
            "missions": str(out / "missions.csv"), "forecast_vector_rms_error": files.skill}
    (out / "skill.json").write_text(json.dumps(info, indent=1) + "\n")
    if json_out:
        print_json(info)
    else:
        typer.echo(f"wrote {files.truth}, {len(files.forecasts)} forecasts, "
                   f"{out / 'missions.csv'} ({missions} missions)")
        typer.echo("forecast vector RMS error by lead: " + ", ".join(
            f"{k.split('_')[1]} d {100 * v:.0f} %" for k, v in files.skill.items()))
