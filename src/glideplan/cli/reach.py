"""`glideplan glide reach|turnback`: glide reach over terrain in wind; the turn-back point."""

from __future__ import annotations

import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import glide_app
from glideplan.errors import PlanningError

PolarOpt = Annotated[
    pathlib.Path,
    typer.Option("--polar", metavar="FILE", help="Polar file (.plr).", show_default=False),
]
FromOpt = Annotated[
    tuple[float, float, float],
    typer.Option("--from", metavar="LAT LON ALT_M",
                 help="Glider now: LAT LON (WGS84 degrees) and altitude ALT_M (m MSL).",
                 show_default=False),
]
TerrainOpt = Annotated[
    list[pathlib.Path] | None,
    typer.Option("--terrain", metavar="FILE",
                 help="Terrain: SRTM .hgt or GeoTIFF (repeat for several tiles; merged).",
                 show_default=False),
]
WindOpt = Annotated[
    tuple[float, float] | None,
    typer.Option("--wind", metavar="SPEED_MS FROM_DEG",
                 help="Wind SPEED_MS FROM_DEG (compass, where it blows from).",
                 show_default=False),
]
McOpt = Annotated[float, typer.Option("--mc", help="MacCready setting (m/s); 0: best glide.")]
SafetyOpt = Annotated[float, typer.Option(
    "--safety-height", help="Height kept above the terrain all along and above the field (m).")]
RatioOpt = Annotated[float | None, typer.Option(
    "--safety-glide-ratio", help="Cap the still-air glide ratio at R (min(polar L/D, R)).",
    show_default=False)]
MassOpt = Annotated[float | None, typer.Option(
    "--mass", help="All-up mass without water (kg); default the file's reference.")]
BallastOpt = Annotated[float, typer.Option("--ballast", help="Water ballast (litres, 1 kg/L).")]
BugsOpt = Annotated[float, typer.Option(
    "--bugs", help="Bugs: percent less glide ratio at every speed (0-50).")]
ResolutionOpt = Annotated[float | None, typer.Option(
    "--resolution", metavar="M",
    help="Front grid spacing (m); default chosen for speed (terrain max-pooled per cell).",
    show_default=False)]
VoidsOpt = Annotated[str | None, typer.Option(
    "--fill-voids", metavar="nearest|linear",
    help="Fill terrain voids (no-data samples) instead of refusing the file.",
    show_default=False)]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object.")]
PlotOpt = Annotated[pathlib.Path | None, typer.Option(
    "--plot", metavar="FILE", help="Draw the figure to FILE (.png, .pdf, .svg).")]

_FLAGS = {
    "start": "--from", "start altitude": "--from ALT_M", "mc": "--mc",
    "safety_height": "--safety-height", "safety_glide_ratio": "--safety-glide-ratio",
    "resolution": "--resolution", "wind": "--wind", "wind east": "--wind",
    "wind north": "--wind", "wind speed": "--wind SPEED_MS", "wind direction": "--wind FROM_DEG",
    "course": "--course", "home": "--home", "voids": "--fill-voids", "terrain": "--terrain",
}


def _wind(wind: tuple[float, float] | None) -> tuple[float, float]:
    from glideplan.cli.common import flag_names
    from glideplan.geodesy import wind_from_to_vector

    if wind is None:
        return (0.0, 0.0)
    with flag_names(**_FLAGS):
        return wind_from_to_vector(float(wind[0]), float(wind[1]))


def _terrain(files: list[pathlib.Path] | None, voids: str | None, required: bool) -> Any:
    from glideplan.cli.common import check_input_file, file_flag, flag_names
    from glideplan.terrain import read_terrain

    if not files:
        if required:
            from glideplan.cli.common import usage_error

            usage_error("--terrain FILE is required (SRTM .hgt or GeoTIFF)")
        return None
    for f in files:
        check_input_file(f, "--terrain")
    mode = "refuse" if voids is None else voids
    with flag_names(voids="--fill-voids"):
        if len(files) == 1:
            with file_flag("--terrain", files[0]):
                return read_terrain(files, voids=mode)
        try:
            return read_terrain(files, voids=mode)
        except Exception as exc:  # name the flag; the message names the file
            from glideplan.errors import InvalidParameterError

            if isinstance(exc, InvalidParameterError):
                raise InvalidParameterError(f"--terrain {exc.name}", exc.value,
                                            exc.rule) from None
            raise


def _polar(file: pathlib.Path, mass: float | None, ballast: float, bugs: float) -> Any:
    from glideplan.cli.glide import _polar as read_polar

    return read_polar(file, mass, ballast, bugs, "--polar")


@glide_app.command("reach")
def glide_reach_cmd(
    polar_file: PolarOpt,
    start: FromOpt,
    terrain: TerrainOpt = None,
    landables: Annotated[pathlib.Path | None, typer.Option(
        "--landables", metavar="FILE.cup",
        help="Landables: SeeYou .cup (styles 2-5 are landable).", show_default=False)] = None,
    wind: WindOpt = None,
    mc: McOpt = 0.0,
    safety_height: SafetyOpt = 300.0,
    safety_glide_ratio: RatioOpt = None,
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    resolution: ResolutionOpt = None,
    fill_voids: VoidsOpt = None,
    json_out: JsonOpt = False,
    geojson: Annotated[pathlib.Path | None, typer.Option(
        "--geojson", metavar="FILE", help="Write the footprint and landables as GeoJSON.",
        show_default=False)] = None,
    kml: Annotated[pathlib.Path | None, typer.Option(
        "--kml", metavar="FILE", help="Write the footprint and landables as KML.",
        show_default=False)] = None,
    plot: PlotOpt = None,
) -> None:
    """Where can I still glide to? Footprint over terrain in wind, each landable verified."""
    from glideplan.cli.common import (
        announce,
        check_figure_file,
        check_input_file,
        check_output_file,
        file_flag,
        flag_names,
        print_json,
        print_warnings,
    )
    from glideplan.reach import glide_reach

    plot = check_figure_file(plot)
    check_output_file(geojson, "--geojson")
    check_output_file(kml, "--kml")
    p = _polar(polar_file, mass, ballast, bugs)
    t = _terrain(terrain, fill_voids, required=True)
    lands: Any = ()
    if landables is not None:
        check_input_file(landables, "--landables")
        from glideplan.reach.landables import read_cup_landables

        with file_flag("--landables", landables):
            lands, skipped = read_cup_landables(landables)
        if skipped:
            print_warnings([f"--landables: {skipped} waypoint(s) are not landable (SeeYou "
                            "style not 2-5) and were skipped"])
    w = _wind(wind)
    with flag_names(**_FLAGS):
        result = glide_reach(t, (start[0], start[1], start[2]), p, landables=lands, mc=mc, wind=w,
                             safety_height=safety_height,
                             safety_glide_ratio=safety_glide_ratio, resolution_m=resolution)
    if json_out:
        print_json(result.to_dict())
    else:
        typer.echo(result.message)
        typer.echo(f"{'landable':<20} {'reach':>5} {'arrival m':>9} {'margin m':>8} "
                   f"{'dist km':>8} detour")
        for pt in result.points:
            arr = "-" if pt.arrival_altitude_m is None else f"{pt.arrival_altitude_m:.0f}"
            mar = "-" if pt.arrival_margin_m is None else f"{pt.arrival_margin_m:+.0f}"
            dist = "-" if pt.distance_m is None else f"{pt.distance_m / 1000:.1f}"
            typer.echo(f"{pt.landable.name[:20]:<20} {'yes' if pt.reachable else 'no':>5} "
                       f"{arr:>9} {mar:>8} {dist:>8} {'yes' if pt.detour else 'no'}")
    print_warnings(result.warnings)
    for path, flag, write in ((geojson, "--geojson", result.write_geojson),
                              (kml, "--kml", result.write_kml)):
        if path is not None:
            with file_flag(flag, path):
                write(path)
            announce(f"wrote {path}", json_out)
    if plot is not None:
        from glideplan.plotting import save_figure

        save_figure(result.plot(), str(plot))
        announce(f"wrote {plot}", json_out)


@glide_app.command("turnback")
def glide_turnback_cmd(
    polar_file: PolarOpt,
    start: FromOpt,
    course: Annotated[float, typer.Option(
        "--course", metavar="DEG", help="Outbound course (compass degrees).",
        show_default=False)],
    home: Annotated[tuple[float, float, float], typer.Option(
        "--home", metavar="LAT LON ELEV_M", help="Home field: LAT LON and elevation (m).",
        show_default=False)],
    terrain: TerrainOpt = None,
    wind: WindOpt = None,
    mc: McOpt = 0.0,
    safety_height: SafetyOpt = 300.0,
    safety_glide_ratio: RatioOpt = None,
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    resolution: ResolutionOpt = None,
    fill_voids: VoidsOpt = None,
    json_out: JsonOpt = False,
    plot: PlotOpt = None,
) -> None:
    """When must I turn back? Distance out along --course from which home is still reachable."""
    from glideplan.cli.common import (
        announce,
        check_figure_file,
        flag_names,
        print_json,
        print_warnings,
    )
    from glideplan.reach import turnback

    plot = check_figure_file(plot)
    p = _polar(polar_file, mass, ballast, bugs)
    t = _terrain(terrain, fill_voids, required=False)
    w = _wind(wind)
    with flag_names(**_FLAGS):
        result = turnback((start[0], start[1], start[2]), course, (home[0], home[1], home[2]),
                          p, terrain=t, mc=mc, wind=w, safety_height=safety_height,
                          safety_glide_ratio=safety_glide_ratio, resolution_m=resolution)
    if json_out:
        print_json(result.to_dict())
    else:
        typer.echo(f"{result.status.value}: {result.message}")
    print_warnings(result.warnings)
    if plot is not None:
        from glideplan.plotting import save_figure

        save_figure(result.plot(), str(plot))
        announce(f"wrote {plot}", json_out)
    if not result.ok:
        raise PlanningError(f"turnback: {result.status.value}: {result.message}")
