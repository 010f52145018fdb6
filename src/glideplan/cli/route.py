"""`glideplan route`: the time-optimal route through a current/wind forecast."""

from __future__ import annotations

import math
import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import app

_EXAMPLES = ("double-gyre",)
_RUN_ARGS = ("from_", "to", "speed", "field", "example", "depart", "depth_range", "resolution",
             "land_clearance", "max_duration", "radius", "json_out", "plot", "geojson", "kml",
             "ensemble", "depart_range", "scheduler", "workers")


def parse_depart(text: str | None) -> Any:
    """`--depart`: ISO 8601 (UTC if no offset; 'Z' accepted) -> numpy.datetime64[ms] in UTC,
    or None (`glideplan.fields.parse_utc`, which the explorer calls too)."""
    from glideplan.fields.field import parse_utc

    return parse_utc(text, "--depart")


def check_route_inputs(*, speed: float, from_: tuple[float, float], to: tuple[float, float],
                       resolution: float | None, radius: float | None,
                       land_clearance: float | None, max_duration: float | None) -> None:
    """Every number of `route` against `validation.PHYSICAL_RANGES` (the rows the library's
    `route()`, `RouteSettings` and `follow_route` check), before any file is read."""
    from glideplan.errors import InvalidParameterError
    from glideplan.geodesy import check_latlon
    from glideplan.validation import check_finite, check_physical

    check_physical("--speed", speed, "speed")
    for name, val in (("--from", from_), ("--to", to)):
        check_latlon(val[0], val[1], name)
    for flag, value, kind in (("--resolution", resolution, "distance"),
                              ("--radius", radius, "turn_radius"),
                              ("--land-clearance", land_clearance, "clearance")):
        if value is not None:
            check_physical(flag, value, kind)
    if max_duration is not None:  # hours at this edge, seconds in the table
        hours = check_finite("--max-duration", max_duration)
        try:
            check_physical("--max-duration", hours * 3600.0, "duration")
        except InvalidParameterError as exc:
            raise InvalidParameterError("--max-duration", max_duration,
                                        f"as {exc.value:.6g} s: {exc.rule}") from None


def check_depth_range(depth_range: tuple[float, float] | None) -> tuple[float, float] | None:
    """`--depth-range Z0 Z1`: metres, positive down, 0 <= Z0 < Z1 (None passes)."""
    from glideplan.errors import InvalidParameterError

    if depth_range is not None and not (
        all(math.isfinite(z) and z >= 0 for z in depth_range) and depth_range[0] < depth_range[1]
    ):
        raise InvalidParameterError("--depth-range", depth_range, "needs 0 <= Z0 < Z1 (m, down)")
    return depth_range


def check_depart(flow: Any, when: Any) -> Any:
    """`--depart` (datetime64 from `parse_depart`, or None) checked against the field's time
    span: outside it, an error naming `--depart` and the bound."""
    from glideplan.errors import InvalidParameterError
    from glideplan.fields.field import to_seconds

    if when is None:
        return None
    try:
        flow.check_time(to_seconds(when, flow.epoch))
    except InvalidParameterError as exc:
        raise InvalidParameterError("--depart", str(when)[:19] + "Z", exc.rule) from None
    return when


# route_command's options (module level keeps the command itself short)
_RouteFrom = Annotated[
    tuple[float, float],
    typer.Option("--from", metavar="LAT LON", help="Start LAT LON (degrees, WGS84).",
                 show_default=False),
]
_RouteTo = Annotated[
    tuple[float, float],
    typer.Option("--to", metavar="LAT LON", help="Goal LAT LON (degrees, WGS84).",
                 show_default=False),
]
_RouteSpeed = Annotated[
    float, typer.Option("--speed", help="Speed through the water (air), V (m/s).")
]
_RouteField = Annotated[
    list[pathlib.Path] | None,
    typer.Option("--field", metavar="FILE",
                 help="NetCDF or GRIB file (repeat to merge files).",
                 show_default=False),
]
_RouteExample = Annotated[
    str | None,
    typer.Option("--example", metavar="NAME",
                 help="A built-in field instead of files: double-gyre.",
                 show_default=False),
]
_RouteDepart = Annotated[
    str | None,
    typer.Option("--depart", metavar="TIME",
                 help="Departure time, ISO 8601 (default: the field's first).",
                 show_default=False),
]
_RouteDepthRange = Annotated[
    tuple[float, float] | None,
    typer.Option("--depth-range", metavar="Z0 Z1",
                 help="Average currents over depths Z0 Z1 (m, down).",
                 show_default=False),
]
_RouteResolution = Annotated[
    float | None,
    typer.Option("--resolution", help="Grid spacing (m; default: the distance over ~250).",
                 show_default=False),
]
_RouteLandClearance = Annotated[
    float | None,
    typer.Option("--land-clearance", metavar="METRES",
                 help="Keep this far from the field's land nodes (m; default: one field "
                 "cell's diagonal with a gridded field, kept at the land mask's resolution; "
                 "else one grid spacing).",
                 show_default=False),
]
_RouteMaxDuration = Annotated[
    float | None,
    typer.Option("--max-duration", metavar="HOURS",
                 help="Give up after this long (h; default: the field's time span, or 10 "
                 "still-water times for a steady field).", show_default=False),
]
_RouteRadius = Annotated[
    float | None,
    typer.Option("--radius", help="Turn radius R0 (m): build the flyable path (Dubins "
                 "pieces of R0' for the route's largest current) and follow it in closed loop "
                 "through the field; also the trochoid pieces (the known-current planner "
                 "with each piece's mean current, R0' for the residual).",
                 show_default=False),
]
_RoutePlot = Annotated[
    pathlib.Path | None,
    typer.Option("--plot", metavar="FILE", help="Draw the route to FILE (.png/.pdf/.svg)."),
]
_RouteGeojson = Annotated[
    pathlib.Path | None,
    typer.Option("--geojson", metavar="FILE",
                 help="Write the route as GeoJSON (split at 180 deg, RFC 7946; the line's "
                 "coordTimes and a Point per vertex carry UTC times)."),
]
_RouteKml = Annotated[
    pathlib.Path | None,
    typer.Option("--kml", metavar="FILE", help="Write the route as KML (each vertex a "
                 "Placemark with its UTC TimeStamp)."),
]
_RouteGpx = Annotated[
    pathlib.Path | None,
    typer.Option("--gpx", metavar="FILE",
                 help="Write the route as a GPX track (each point with its UTC time)."),
]
_RouteCsv = Annotated[
    pathlib.Path | None,
    typer.Option("--csv", metavar="FILE",
                 help="Write the route's vertices as CSV: time_utc,t_s,lat,lon,heading_deg."),
]
_RouteEnsemble = Annotated[
    str | None,
    typer.Option("--ensemble", metavar="GLOB",
                 help="Route on every member file matching GLOB (quoted, e.g. "
                 "'ENS/member_*.nc'; or a folder, or one file with a member dimension; "
                 "one grid): arrival P10/P50/P90, p_arrival within "
                 "--max-duration, the corridor, and the member route that arrives most "
                 "often flown in closed loop through every member.", show_default=False),
]
_RouteDepartRange = Annotated[
    tuple[str, str, float] | None,
    typer.Option("--depart-range", metavar="START END HOURS",
                 help="Route every departure from START to END (ISO 8601) each HOURS: "
                 "duration against departure, the best departure (with --ensemble: per "
                 "departure the ensemble's statistics).", show_default=False),
]
_RouteScheduler = Annotated[
    str | None,
    typer.Option("--scheduler", metavar="ADDRESS",
                 help="Dask scheduler (tcp://HOST:8786) for --ensemble/--depart-range "
                 "(default: local processes).", show_default=False),
]
_RouteWorkers = Annotated[
    int | None,
    typer.Option("--workers", metavar="N",
                 help="Local processes for --ensemble/--depart-range (default: one per "
                 "core).", show_default=False),
]


@app.command("route")
def route_command(
    from_: _RouteFrom,
    to: _RouteTo,
    speed: _RouteSpeed,
    field: _RouteField = None,
    example: _RouteExample = None,
    depart: _RouteDepart = None,
    depth_range: _RouteDepthRange = None,
    resolution: _RouteResolution = None,
    land_clearance: _RouteLandClearance = None,
    max_duration: _RouteMaxDuration = None,
    radius: _RouteRadius = None,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    plot: _RoutePlot = None,
    geojson: _RouteGeojson = None,
    kml: _RouteKml = None,
    gpx: _RouteGpx = None,
    csv: _RouteCsv = None,
    ensemble: _RouteEnsemble = None,
    depart_range: _RouteDepartRange = None,
    scheduler: _RouteScheduler = None,
    workers: _RouteWorkers = None,
) -> None:
    """Time-optimal route through a current or wind field, on the sphere (front propagation
    on a lat/lon grid that grows with the front, refined, verified through the field).

    Exit 0 solved, 1 unreachable (`unreachable_reason` in --json: front_stopped,
    field_extent, time_span, max_duration, window_limit, outside_drift_cone, polar_limit,
    missing_data) or
    not_verified (the flown controls miss the goal by more than endpoint_tolerance_m,
    one grid spacing), 2 bad input, 3 internal error.
    """
    from glideplan.cli.common import (
        check_figure_file,
        flag_names,
        usage_error,
    )

    check_route_inputs(speed=speed, from_=from_, to=to, resolution=resolution, radius=radius,
                       land_clearance=land_clearance, max_duration=max_duration)
    check_depth_range(depth_range)
    plot = check_figure_file(plot)
    exports = _export_files(geojson=geojson, kml=kml, gpx=gpx, csv=csv)
    if (ensemble is not None or depart_range is not None) and (gpx or csv):
        usage_error("--gpx and --csv write one route: not with --ensemble or --depart-range")
    if ensemble is not None or depart_range is not None:
        from glideplan.cli.route_ensemble import run

        return run(**{k: v for k, v in locals().items() if k in _RUN_ARGS})
    if scheduler is not None or workers is not None:
        usage_error("--scheduler and --workers need --ensemble or --depart-range")
    if field is None and example is None:
        usage_error("give --field FILE or --example NAME (double-gyre)")
    if field is not None and example is not None:
        usage_error("give --field FILE or --example NAME, not both")
    when = parse_depart(depart)

    flow, source = _open_flow(field, example, depth_range)
    check_depart(flow, when)

    import sys
    from dataclasses import replace

    from glideplan.cli.common import solving
    from glideplan.cli.emit import emit
    from glideplan.routing import RouteSettings, route

    names = _ROUTE_FLAGS
    with flag_names(**names):
        settings = RouteSettings(
            resolution=resolution, land_clearance_m=land_clearance,
            max_duration=None if max_duration is None else max_duration * 3600.0,
            progress=sys.stderr.isatty())
        # Progress: the front draws its own bar on a terminal (after ~2 s).
        result = route(flow, from_, to, speed, depart=when, settings=settings)
    result = replace(result, field_info={**source, **result.field_info})
    if radius is not None and result.ok:
        from glideplan.routing.glider import with_flyable_path

        with flag_names(**names):
            result = solving("following the flyable path",
                             lambda: with_flyable_path(result, flow, speed, radius))
    if exports and result.track.size:
        from glideplan.formats.route_export import route_export_warnings

        result = replace(result, warnings=(*result.warnings, *route_export_warnings(result)))
    written = _write_exports(result, exports)
    emit(result, json=json_out, plot=plot, exports=written or None,
         summary=lambda r: _print_summary(r.to_dict()),
         plot_kw={"flow": flow, "speed": speed, "start": from_, "goal": to},
         save_kw={"tight": False}, what="route")


#: The library's parameter names -> the options the user gave (errors name the option).
_ROUTE_FLAGS = {"from": "--from", "to": "--to", "speed": "--speed", "resolution": "--resolution",
                "field": "--field", "depth_range": "--depth-range", "radius": "--radius",
                "land_clearance_m": "--land-clearance", "max_duration": "--max-duration"}


def _export_files(**files: pathlib.Path | None) -> dict[str, pathlib.Path]:
    """The export files given (format -> path), each in a folder that exists."""
    from glideplan.errors import InvalidParameterError

    exports = {fmt: p for fmt, p in files.items() if p is not None}
    for fmt, out_file in exports.items():
        if out_file.parent and not out_file.parent.is_dir():
            raise InvalidParameterError(f"--{fmt}", str(out_file), "its folder does not exist")
    return exports


def _open_flow(field: list[pathlib.Path] | None, example: str | None,
               depth_range: tuple[float, float] | None) -> tuple[Any, dict[str, Any]]:
    """The field of `--field FILE...` or `--example NAME`, and where it came from (JSON)."""
    from glideplan.cli.common import check_input_file, flag_names
    from glideplan.errors import InvalidParameterError
    from glideplan.fields import double_gyre, open_field

    if example is not None:
        if example not in _EXAMPLES:
            raise InvalidParameterError("--example", example, f"must be one of {_EXAMPLES}")
        if depth_range is not None:
            raise InvalidParameterError("--depth-range", depth_range, "needs --field files")
        return double_gyre(), {"file": None, "example": example}
    assert field is not None
    for path in field:
        check_input_file(path, "--field")
    with flag_names(field="--field", depth_range="--depth-range"):
        flow = open_field(field, depth_range=depth_range)
    return flow, {"file": [str(p) for p in field]}


def _write_exports(result: Any, exports: dict[str, pathlib.Path]) -> dict[str, pathlib.Path]:
    """The route's track as GeoJSON / KML / GPX / CSV with each vertex's time (when it has a
    track): {format: path} written (`glideplan.formats.route_export`)."""
    if not exports or not result.track.size:
        return {}
    from glideplan.formats.route_export import export_route

    return {fmt: pathlib.Path(p) for fmt, p in export_route(result, exports).items()}


def _print_summary(out: dict[str, Any]) -> None:
    def hours(s: float | None) -> str:
        return "n/a" if s is None else f"{s / 3600.0:.2f} h"

    typer.echo(f"status: {out['status']}")
    if out["status"] == "solved":
        typer.echo(f"depart: {out['depart']}  arrive: {out['arrive']}")
        typer.echo(f"duration: {hours(out['duration_s'])}  distance: "
                   f"{out['distance_m'] / 1000:.2f} km  method: {out['method']}")
        typer.echo(f"straight line with crab angle: {hours(out['straight_line_duration_s'])}")
        typer.echo(f"land clearance: {out['land_clearance_m']:.0f} m")
        typer.echo(f"endpoint error (controls flown through the field): "
                   f"{out['endpoint_error_m']:.2f} m (tolerance "
                   f"{out['endpoint_tolerance_m']:.0f} m)")
        if "glider" in out:
            g = out["glider"]
            if g["status"] == "solved":
                typer.echo(f"glider path: R0' = {g['feasible_radius_m']:.1f} m, {g['legs']} legs,"
                           f" max cross-track error {g['max_cross_track_m']:.2f} m, miss "
                           f"{g['final_distance_m']:.2f} m")
            else:
                typer.echo(f"glider path: {g['status']}: {g['message']}")
            tc = g.get("trochoid")
            if tc is not None and tc["status"] == "solved":
                typer.echo(f"trochoid pieces (mean current per piece): R0' = "
                           f"{tc['feasible_radius_m']:.1f} m for the residual eps' = "
                           f"{tc['residual_ratio']:.3f}, {hours(tc['duration_s'])}, open-loop "
                           f"miss through the field {tc['field_endpoint_error_m']:.1f} m")
    elif out["status"] == "not_verified":
        err = out["endpoint_error_m"]
        typer.echo("endpoint error (controls flown through the field): " + (
            "n/a" if err is None or not math.isfinite(err) else f"{err:.2f} m") + f", tolerance "
            f"{out['endpoint_tolerance_m']:.2f} m")
    else:
        typer.echo(f"unreachable ({out['unreachable_reason']}): best reachable distance to "
                   f"the goal {out['best_distance_m']:.0f} m")
