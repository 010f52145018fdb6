"""`glideplan route replay`: plan on forecasts, fly the truth, replan; with the baselines.

Registered as the hidden top-level command `route-replay`; `glideplan.cli.app.main` turns
`route replay ...` into it, so `glideplan route --field ...` stays the one route command.
"""

from __future__ import annotations

import math
import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import app


def check_latlon(name: str, val: tuple[float, float]) -> None:
    """--from/--to: finite, latitude in [-90, 90], longitude in [-180, 360] (as `route`:
    `geodesy.check_latlon`)."""
    from glideplan.geodesy import check_latlon as check

    check(val[0], val[1], name)


def positive(name: str, val: float | None, unit: str) -> None:
    from glideplan.errors import InvalidParameterError

    if val is not None and not (math.isfinite(val) and val > 0):
        raise InvalidParameterError(name, val, f"must be finite and > 0 ({unit})")


def open_truth(path: pathlib.Path) -> Any:
    """The truth field from --truth (errors name the flag)."""
    from glideplan.cli.common import check_input_file, flag_names
    from glideplan.fields import open_field

    check_input_file(path, "--truth")
    with flag_names(field="--truth"):
        return open_field(path)


def _check_inputs(speed: float, from_: tuple[float, float], to: tuple[float, float],
                  goal_radius: float, resolution: float | None, max_duration: float | None,
                  replan_every: float | None, plot: pathlib.Path | None,
                  geojson: pathlib.Path | None) -> pathlib.Path | None:
    """The options' ranges (the rows `route` checks), naming each option; the --plot file."""
    from glideplan.cli.common import check_figure_file
    from glideplan.errors import InvalidParameterError
    from glideplan.validation import check_physical

    check_physical("--speed", speed, "speed")  # the rows `route` checks
    check_latlon("--from", from_)
    check_latlon("--to", to)
    for flag, value in (("--goal-radius", goal_radius), ("--resolution", resolution)):
        if value is not None:
            check_physical(flag, value, "distance")
    positive("--max-duration", max_duration, "h")
    positive("--replan-every", replan_every, "h")
    plot = check_figure_file(plot)
    if geojson is not None and not geojson.parent.is_dir():
        raise InvalidParameterError("--geojson", str(geojson), "its folder does not exist")
    return plot


def _max_duration_s(flow: Any, when: Any, depart: str, max_duration: float | None) -> float:
    """--max-duration in s; by default from --depart to the truth's last time."""
    import numpy as np

    from glideplan.errors import InvalidParameterError

    if max_duration is not None:
        return max_duration * 3600.0
    span = flow.time_span
    if span is None or flow.epoch is None:
        raise InvalidParameterError("--max-duration", None, "give it (the truth is steady)")
    max_s = span[1] - float((when - flow.epoch) / np.timedelta64(1, "s"))
    if max_s <= 0:
        raise InvalidParameterError("--depart", depart, "after the truth's last time")
    return float(max_s)


@app.command("route-replay", hidden=True)
def route_replay_command(
    truth: Annotated[pathlib.Path, typer.Option("--truth", metavar="FILE", show_default=False,
                                                help="The real ocean (NetCDF): flown, never "
                                                "planned on.")],
    forecasts: Annotated[str, typer.Option("--forecasts", metavar="GLOB", show_default=False,
                                           help="Forecast files (a quoted glob).")],
    from_: Annotated[tuple[float, float], typer.Option(
        "--from", metavar="LAT LON", help="Start LAT LON (deg).", show_default=False)],
    to: Annotated[tuple[float, float], typer.Option(
        "--to", metavar="LAT LON", help="Goal LAT LON (deg).", show_default=False)],
    speed: Annotated[float, typer.Option("--speed", help="Speed through the water V (m/s).")],
    depart: Annotated[str, typer.Option("--depart", metavar="TIME", show_default=False,
                                        help="Departure, ISO 8601 (UTC).")],
    goal_radius: Annotated[float, typer.Option(
        "--goal-radius", metavar="METRES", help="Arrived within this distance (m).")] = 2000.0,
    max_duration: Annotated[float | None, typer.Option(
        "--max-duration", metavar="HOURS", show_default=False,
        help="Give up after this long (h; default: to the truth's end).")] = None,
    replan_every: Annotated[float | None, typer.Option(
        "--replan-every", metavar="HOURS", show_default=False,
        help="Also replan this often (h; default: at each new forecast).")] = None,
    resolution: Annotated[float | None, typer.Option(
        "--resolution", metavar="METRES", show_default=False,
        help="Planner grid spacing (m; default: distance / 60, at least 2 km).")] = None,
    follow: Annotated[str, typer.Option(
        "--follow", metavar="HOW", help="track: the replanning loop steers by each plan's "
        "time-to-go map (-grad tau, feedback), along the plan's track with the crab angle for "
        "the expected current where the map has none (the baselines: by the track); "
        "headings: its headings in time, open loop.")
    ] = "track",
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    plot: Annotated[pathlib.Path | None, typer.Option(
        "--plot", metavar="FILE", help="Draw the replay to FILE (.png/.pdf/.svg).")] = None,
    geojson: Annotated[pathlib.Path | None, typer.Option(
        "--geojson", metavar="FILE", help="Write the flown track and the plans.")] = None,
) -> None:
    """Replay a mission (`glideplan route replay`): plan on the newest forecast, fly the plan
    through the truth, replan at each new forecast (and every --replan-every h); with the
    baselines naive, plan_once and hindsight. Exit 0 reached, 1 not reached, 2 bad input."""
    from glideplan.cli.route import parse_depart
    from glideplan.errors import InvalidParameterError
    from glideplan.routing.forecasts import open_forecasts
    from glideplan.routing.replay import Mission, ReplaySettings, replay

    plot = _check_inputs(speed, from_, to, goal_radius, resolution, max_duration, replan_every,
                         plot, geojson)
    when = parse_depart(depart)
    flow = open_truth(truth)
    fcs = open_forecasts(forecasts)
    max_s = _max_duration_s(flow, when, depart, max_duration)
    mission = Mission(from_, to, speed, when, goal_radius, max_s,
                      None if replan_every is None else replan_every * 3600.0)
    if follow not in ("track", "headings"):
        raise InvalidParameterError("--follow", follow, "must be track or headings")
    res = replay(flow, fcs, mission, ReplaySettings(resolution=resolution, follow=follow))
    from dataclasses import replace

    from glideplan.cli.emit import emit

    res = replace(res, sources={"truth": str(truth),
                                "forecasts": [p for fc in fcs for p in fc.paths]})
    exports: dict[str, pathlib.Path] = {}
    if geojson is not None:
        from glideplan.routing.replay_plot import write_replay_geojson

        write_replay_geojson(res, geojson)
        exports["geojson"] = geojson
    emit(res, json=json_out, plot=plot, exports=exports or None,
         summary=lambda r: _print_summary(r.to_dict()), plot_kw={"truth": flow},
         what="route replay")


def _print_summary(out: dict[str, Any]) -> None:
    def hours(s: float | None) -> str:
        return "n/a" if s is None else f"{s / 3600.0:.2f} h"

    typer.echo(f"status: {out['status']}" + (
        f" ({out['unreachable_reason']})" if out["unreachable_reason"] else ""))
    typer.echo(f"depart: {out['depart']}  arrive: {out['arrival_time']}  duration: "
               f"{hours(out['duration_s'])}  replans: {len(out['replans'])}")
    for name, b in out["baselines"].items():
        why = f" ({b['unreachable_reason']})" if b["unreachable_reason"] else ""
        typer.echo(f"{name:>10}: {b['status']}{why}  {hours(b['duration_s'])}")
    if out["regret_s"] is not None:
        typer.echo(f"regret against hindsight: {hours(out['regret_s'])}")
