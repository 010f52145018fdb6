"""`glideplan mission plan`: a route file in, an optimal multi-leg mission and vehicle files out."""

from __future__ import annotations

import pathlib
from dataclasses import replace
from typing import TYPE_CHECKING, Annotated, Any

import typer

from glideplan.cli.app import mission_app
from glideplan.cli.common import (
    check_figure_file,
    check_output_dir,
    check_writable,
    file_flag,
    flag_names,
    phase_progress,
    print_warnings,
)
from glideplan.errors import InvalidParameterError

if TYPE_CHECKING:
    from glideplan.missions.field_mission import FieldMission
    from glideplan.missions.plan import MissionPlan


# the long phases of `plan_mission`, as the progress bar names them
PHASES = {
    "headings": "choosing the headings (DP over the legs)",
    "refine": "refining the headings",
    "legs": "planning and verifying the legs",
}
# Slocum goto files are numbered goto_l00.ma .. goto_l99.ma
SLOCUM_LAST_FILE = 99


def check_mission_inputs(
    *,
    speed: float,
    radius: float,
    wind: tuple[float, float] | None,
    headings: int | None,
    acceptance_radius: float,
    max_deviation: float | None,
    altitude: float,
    depth_range: tuple[float, float] | None,
) -> None:
    """Every number of `mission plan` against `validation.PHYSICAL_RANGES`, before any work."""
    from glideplan.validation import check_physical

    check_physical("--speed", speed, "speed")
    check_physical("--radius", radius, "turn_radius")
    if wind is not None:
        check_physical("--wind speed", wind[0], "wind_speed")
        check_physical("--wind direction", wind[1], "heading")
    if headings is not None and not 4 <= headings <= 3600:
        raise InvalidParameterError("--headings", headings, "must be an integer in [4, 3600]")
    check_physical("--acceptance-radius", acceptance_radius, "distance")
    if max_deviation is not None:
        check_physical("--max-deviation", max_deviation, "distance")
    check_physical("--altitude", altitude, "altitude")
    if depth_range is not None:
        for z in depth_range:
            check_physical("--depth-range", z, "depth")


def check_export_options(formats: tuple[str, ...], options: Any, waypoints: int) -> None:
    """Refuse, before planning, export options that cannot work for a route of `waypoints`.

    Slocum: the straight-leg list keeps every mission waypoint, so it has at least
    `waypoints` points and needs at least ceil((n - 1) / (max - 1)) goto files numbered from
    `--goto-number`; past goto_l99.ma the export would fail after the whole plan.
    """
    if "slocum" not in formats:
        return
    per_file = options.max_goto_waypoints - 1
    files = max(1, -(-(waypoints - 1) // per_file))
    last = options.goto_number + files - 1
    if last > SLOCUM_LAST_FILE:
        room = SLOCUM_LAST_FILE - options.goto_number + 1
        need = -(-(waypoints - 1) // room) + 1
        raise InvalidParameterError(
            "--goto-number",
            options.goto_number,
            f"{waypoints} waypoints need at least {files} Slocum goto files of "
            f"{options.max_goto_waypoints} waypoints, numbered {options.goto_number}..{last} "
            f"(beyond {SLOCUM_LAST_FILE}): give --max-goto-waypoints {need} or more, a lower "
            "--goto-number, or leave slocum out of --formats",
        )


# mission_plan's options (module level keeps the command itself short)
_MissionPlanRoute = Annotated[pathlib.Path, typer.Argument(
    metavar="ROUTE",
    help="Route file: .csv (name,lat,lon[,heading_deg] or name,x,y[,heading_deg]), .gpx, "
         ".kml or .geojson.", show_default=False)]
_MissionPlanSpeed = Annotated[float, typer.Option(
    "--speed", help="Speed through the air/water (m/s).", show_default=False)]
_MissionPlanRadius = Annotated[float, typer.Option(
    "--radius", help="Minimum turn radius R0 (m). With --field: each routed leg becomes the "
                     "flyable path of Dubins pieces of radius R0' = R0 (1 + eps)^2, eps = "
                     "the leg's largest current / speed (as `glideplan route --radius`), "
                     "joined with a continuous course at the waypoints, followed in closed "
                     "loop through the field; the track and the vehicle files carry it.",
    show_default=False)]
_MissionPlanObjective = Annotated[str | None, typer.Option(
    "--objective", help="length or time (default: length; time with --wind).")]
_MissionPlanWind = Annotated[tuple[float, float] | None, typer.Option(
    "--wind", metavar="SPEED DIR_DEG",
    help="Steady wind/current: speed (m/s) and the compass direction it blows FROM (deg).",
    show_default=False)]
_MissionPlanField = Annotated[pathlib.Path | None, typer.Option(
    "--field", metavar="FILE",
    help="Current/wind field file (NetCDF or GRIB, as `glideplan route`): each "
                    "leg is routed through it (time-optimal, headings free), departing "
                    "when the previous leg arrives.", show_default=False)]
_MissionPlanDepart = Annotated[str | None, typer.Option(
    "--depart", metavar="TIME",
    help="Departure from the first waypoint, ISO 8601 (UTC if no offset): the "
                     "waypoints' ETAs in the JSON and files as UTC times. With --field: "
                     "default the field's first time; must lie in its time span.",
    show_default=False)]
_MissionPlanDepthRange = Annotated[tuple[float, float] | None, typer.Option(
    "--depth-range", metavar="Z0 Z1",
    help="With --field: average the currents over depths Z0..Z1 (m, positive down; "
         "trapezoidal over the file's levels), as `glideplan route`.",
    show_default=False)]
_MissionPlanHeadings = Annotated[int | None, typer.Option(
    "--headings", help="Candidate headings per free waypoint K (default 360; 36 in wind).",
    show_default=False)]
_MissionPlanExport = Annotated[pathlib.Path | None, typer.Option(
    "--export", metavar="DIR", help="Directory to write the mission files into.",
    show_default=False)]
_MissionPlanFormats = Annotated[str | None, typer.Option(
    "--formats", metavar="LIST",
    help="Comma-separated: geojson,kml,gpx,csv,qgc-wpl,qgc-plan,slocum,"
                      "seaglider (default: all).", show_default=False)]
_MissionPlanAcceptanceRadius = Annotated[float, typer.Option(
    "--acceptance-radius", help="Waypoint acceptance radius in the vehicle files (m).")
]
_MissionPlanMaxDeviation = Annotated[float | None, typer.Option(
    "--max-deviation", help="Largest distance of the straight legs from the planned track "
                            "(m; default half the acceptance radius).",
    show_default=False)]
_MissionPlanAltitude = Annotated[float, typer.Option(
    "--altitude", help="QGC waypoint altitude above home (m).")]
_MissionPlanGotoNumber = Annotated[int, typer.Option(
    "--goto-number", help="Slocum goto file number NN (goto_lNN.ma).")]
_MissionPlanMaxGotoWaypoints = Annotated[int, typer.Option(
    "--max-goto-waypoints", help="Most waypoints per Slocum goto file (split beyond).")]
_MissionPlanPlot = Annotated[pathlib.Path | None, typer.Option(
    "--plot", metavar="FILE", help="Draw the mission into FILE (.png, .pdf, .svg).",
    show_default=False)
]


@mission_app.command("plan")
def mission_plan(
    route: _MissionPlanRoute,
    speed: _MissionPlanSpeed,
    radius: _MissionPlanRadius,
    objective: _MissionPlanObjective = None,
    wind: _MissionPlanWind = None,
    field: _MissionPlanField = None,
    depart: _MissionPlanDepart = None,
    depth_range: _MissionPlanDepthRange = None,
    headings: _MissionPlanHeadings = None,
    export: _MissionPlanExport = None,
    formats: _MissionPlanFormats = None,
    acceptance_radius: _MissionPlanAcceptanceRadius = 100.0,
    max_deviation: _MissionPlanMaxDeviation = None,
    altitude: _MissionPlanAltitude = 50.0,
    goto_number: _MissionPlanGotoNumber = 10,
    max_goto_waypoints: _MissionPlanMaxGotoWaypoints = 8,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    plot: _MissionPlanPlot = None,
) -> None:
    """Plan a multi-leg mission through ROUTE's waypoints, choosing the free headings optimally.

    Each leg is the optimal Dubins (or, with --wind, convected-Dubins minimum-time) path,
    verified by integration. With --export the mission is written for GIS tools and vehicles.
    """
    from glideplan.cli.emit import emit
    from glideplan.cli.route import check_depth_range, parse_depart
    from glideplan.formats import ExportOptions, parse_formats, read_route
    from glideplan.formats.export import skipped_formats, skipped_warning
    from glideplan.missions import plan_mission
    from glideplan.units import wind_from_compass

    plot = check_figure_file(plot)
    if plot is not None:
        check_writable(plot, "--plot")
    if export is not None:
        check_output_dir(export, "--export")
        check_writable(export, "--export")
    if field is None and depth_range is not None:
        raise InvalidParameterError("--depth-range", depth_range, "applies with --field only")
    check_depth_range(depth_range)
    when = parse_depart(depart)
    _check_plan_options(field, wind, objective, speed, radius, headings, acceptance_radius,
                        max_deviation, altitude, depth_range)
    obj = objective or ("time" if wind is not None else "length")
    with flag_names(**{"acceptance-radius": "--acceptance-radius", "altitude": "--altitude",
                       "max-deviation": "--max-deviation", "goto-number": "--goto-number",
                       "max-goto-waypoints": "--max-goto-waypoints"}):
        options = ExportOptions(acceptance_radius=acceptance_radius,
                                max_deviation=max_deviation, altitude=altitude,
                                goto_number=goto_number, max_goto_waypoints=max_goto_waypoints,
                                name=route.stem or "mission")
    with file_flag("ROUTE", route):
        # legs through a field are routed on the sphere: no one-plane size limit then
        r = read_route(route, check_extent=field is None)
    if formats is not None and export is None:
        raise InvalidParameterError("--formats", formats, "needs --export DIR")
    mission: MissionPlan | FieldMission
    with flag_names(formats="--formats", headings="--headings", objective="--objective",
                    field="--field", wind="--wind", speed="--speed", radius="--radius"):
        fmts = parse_formats(formats, r.geographic) if export is not None else ()
        skipped = skipped_formats(formats, r.geographic) if export is not None else ()
        check_export_options(fmts, options, r.n)
        if field is not None:
            mission = _plan_in_field(r, field, speed, radius, when, depth_range)
        else:
            # the compass --wind (speed, FROM deg) becomes the library's (east, north) vector
            vector = None if wind is None else wind_from_compass(wind[0], wind[1], param="--wind")
            with phase_progress(PHASES) as progress:
                mission = plan_mission(r, speed=speed, radius=radius, objective=obj,
                                       wind=vector, headings=headings,
                                       progress=progress)
    if when is not None and field is None:  # the ETAs as UTC times
        mission = replace(mission, depart=when)
    if skipped:
        mission = replace(mission, warnings=(*mission.warnings, skipped_warning(skipped)))
    files: dict[str, Any] = {}
    if mission.ok:  # a failed mission has no track to export or draw
        mission, files = _export(mission, export, fmts, options)
    elif plot is not None:
        print_warnings([f"no track to draw: {plot} not written"])
        plot = None
    # the plan's JSON is the library's (`to_dict`); emit adds only the files written
    emit(mission, json=json_out, plot=plot, exports=files, summary=_print_summary,
         what="mission")


def _check_plan_options(field: Any, wind: tuple[float, float] | None, objective: str | None,
                        speed: float, radius: float, headings: int | None,
                        acceptance_radius: float, max_deviation: float | None,
                        altitude: float, depth_range: Any) -> None:
    """The options that go together (--field with neither --wind nor a length objective) and
    the physical ranges, naming the options."""
    if field is not None and wind is not None:
        raise InvalidParameterError("--wind", wind, "give either --wind or --field, not both")
    if field is not None and objective not in (None, "time"):
        raise InvalidParameterError("--objective", objective, "with --field only time")
    check_mission_inputs(speed=speed, radius=radius, wind=wind, headings=headings,
                         acceptance_radius=acceptance_radius, max_deviation=max_deviation,
                         altitude=altitude, depth_range=depth_range)
    if wind is not None and wind[0] >= speed:
        raise InvalidParameterError(
            "--wind", wind[0], f"speed must be below the vehicle's speed {speed:g} m/s")


def _export(mission: Any, export: pathlib.Path | None, fmts: Any, options: Any) -> tuple[
        Any, dict[str, Any]]:
    """The mission with its straight legs (written in `fmts` under --export when given); the
    files written."""
    from glideplan.formats import export_mission
    from glideplan.missions import straight_leg_list

    files: dict[str, Any] = {}
    with flag_names(**{"max-deviation": "--max-deviation", "goto-number": "--goto-number",
                       "max-goto-waypoints": "--max-goto-waypoints"}):
        if export is not None:
            files, legs = export_mission(mission, export, fmts, options)
        else:
            legs = straight_leg_list(mission, options.deviation)
    return replace(mission, straight_legs=legs), files


def _plan_in_field(r: Any, path: pathlib.Path, speed: float, radius: float, when: Any,
                   depth_range: tuple[float, float] | None) -> FieldMission:
    from glideplan.cli.common import check_input_file, solving
    from glideplan.cli.route import check_depart
    from glideplan.fields import open_field
    from glideplan.missions.field_mission import plan_mission_in_field

    if not r.geographic:
        raise InvalidParameterError("--field", str(path), "needs a geographic route (lat/lon)")
    check_input_file(path, "--field")
    with flag_names(field="--field", depth_range="--depth-range"):
        flow = open_field(path, depth_range=depth_range)
    check_depart(flow, when)
    # its warnings (the field's, the routes', headings not enforced) are printed by the caller
    if r.n > 2:  # a bar that counts the legs, with an ETA (terminals only)
        import sys

        return plan_mission_in_field(r, flow, speed=speed, depart=when, radius=radius,
                                     progress=sys.stderr.isatty())
    return solving("routing the legs", lambda: plan_mission_in_field(
        r, flow, speed=speed, depart=when, radius=radius))


def _print_summary(mission: Any) -> None:
    r, legs = mission.route, mission.straight_legs
    if not mission.ok:
        typer.echo(f"mission {r.source}: {mission.status.value}: {mission.message}")
        return
    through = " (through the field)" if hasattr(mission, "field_info") else ""
    typer.echo(f"mission {r.source}: {r.n} waypoints, {len(mission.legs)} legs, objective "
               f"{mission.objective}{through}")
    for i, leg in enumerate(mission.legs):
        typer.echo(f"  leg {i + 1:3d} {r.names[leg.start]:>10s} -> {r.names[leg.end]:<10s} "
                   f"{leg.word:4s} {leg.length_m:10.1f} m {leg.duration_s:10.1f} s")
    fly = mission.stats.get("flyable")
    if fly:
        typer.echo(f"flyable path: R0' = {min(fly['feasible_radius_m']):.1f}.."
                   f"{max(fly['feasible_radius_m']):.1f} m, {fly['path_length_m']:.1f} m, "
                   f"closed-loop max cross-track error {fly['max_cross_track_m']:.2f} m")
    hd = ", ".join(f"{r.names[i]} {h:.1f}" for i, h in enumerate(mission.headings_deg))
    typer.echo(f"headings (compass deg): {hd}")
    err = mission.stats.get("max_endpoint_error")
    typer.echo(f"total: {mission.total_length_m:.1f} m, {mission.total_duration_s:.1f} s; "
               f"largest endpoint error {'-' if err is None else f'{err:.1e}'} m")
    if r.projection is not None:
        typer.echo(f"projection: aeqd about {r.names[0]}, scale distortion "
                   f"{r.distortion:.1e}")
    typer.echo(f"straight legs: {len(legs.names)} waypoints within {legs.max_deviation_m:.1f} m "
               f"of the track (limit {legs.tolerance_m:g} m)")
