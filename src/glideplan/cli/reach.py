"""`glideplan glide reach|turnback`: glide reach over terrain in wind; the turn-back point."""

from __future__ import annotations

import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import glide_app

PolarOpt = Annotated[
    pathlib.Path | None,
    typer.Option("--polar", metavar="FILE",
                 help="Polar file (.plr); required unless --example.", show_default=False),
]
FromOpt = Annotated[
    tuple[float, float, float] | None,
    typer.Option("--from", metavar="LAT LON ALT_M",
                 help="Glider now: LAT LON (WGS84 degrees) and altitude ALT_M (m MSL); "
                      "required unless --example.",
                 show_default=False),
]
ExampleOpt = Annotated[
    str | None,
    typer.Option("--example", metavar="NAME",
                 help="A built-in scenario instead of files: ridge (synthetic SRTM3 tile, "
                      "fields, start, polar, wind); explicit options override its values.",
                 show_default=False),
]
WriteExampleOpt = Annotated[
    pathlib.Path | None,
    typer.Option("--write-example", metavar="DIR",
                 help="With --example: write its terrain (.hgt), fields (.cup) and polar "
                      "into DIR, print the equivalent command line, and stop.",
                 show_default=False),
]
TerrainOpt = Annotated[
    list[pathlib.Path] | None,
    typer.Option("--terrain", metavar="FILE|DIR",
                 help="Terrain: SRTM .hgt (also zipped .zip or gzipped .hgt.gz), GeoTIFF "
                      "(any CRS: UTM and others are reprojected to lat/lon), a folder of "
                      "them, or a quoted glob; repeat for several (all merged).",
                 show_default=False),
]
WindOpt = Annotated[
    tuple[float, float] | None,
    typer.Option("--wind", metavar="SPEED_MS FROM_DEG",
                 help="Wind SPEED_MS FROM_DEG (compass, where it blows from).",
                 show_default=False),
]
McOpt = Annotated[float | None, typer.Option(
    "--mc", help="MacCready setting (m/s); 0: best glide. Default 0 (the example's with "
    "--example).", show_default=False)]
SafetyOpt = Annotated[float | None, typer.Option(
    "--safety-height",
    help="Sets both --terrain-clearance and --arrival-height (m; the former single option). "
         "Without it they are 150 and 300 (the example's with --example).", show_default=False)]
ClearanceOpt = Annotated[float | None, typer.Option(
    "--terrain-clearance", metavar="M",
    help="Height kept above the terrain en route (m). Default 150 (XCSoar's); "
         "--safety-height sets it too.", show_default=False)]
ArrivalOpt = Annotated[float | None, typer.Option(
    "--arrival-height", metavar="M",
    help="Height above a field on arrival (m). Default 300 (XCSoar's); --safety-height sets "
         "it too.", show_default=False)]
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
    help="Search grid spacing (m). reach: default the terrain's own (passes as the data "
         "has them); coarser max-pools the terrain (narrow passes close). turnback: the "
         "home check's grid (the example's: 700).",
    show_default=False)]
VoidsOpt = Annotated[str | None, typer.Option(
    "--fill-voids", metavar="nearest|linear",
    help="Fill terrain voids (no-data samples) instead of refusing the file.",
    show_default=False)]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object.")]
PlotOpt = Annotated[pathlib.Path | None, typer.Option(
    "--plot", metavar="FILE", help="Draw the figure to FILE (.png, .pdf, .svg).")]

_FLAGS = {
    "start": "--from", "start altitude": "--from altitude", "mc": "--mc",
    "safety_height": "--safety-height", "terrain_clearance": "--terrain-clearance",
    "arrival_height": "--arrival-height", "safety_glide_ratio": "--safety-glide-ratio",
    "resolution": "--resolution", "wind": "--wind", "wind east": "--wind",
    "wind north": "--wind", "wind speed": "--wind SPEED_MS", "wind direction": "--wind FROM_DEG",
    "course": "--course", "home": "--home", "voids": "--fill-voids", "terrain": "--terrain",
    "example": "--example", "directory": "--write-example",
    "landable 'HOME'": "--home",  # turnback's home (`reach.turnback`: Landable("HOME", ...))
}
DEFAULT_MC = 0.0
DEFAULT_SAFETY_M = 300.0


def _wind(wind: tuple[float, float] | None) -> tuple[float, float]:
    from glideplan.cli.common import flag_names
    from glideplan.units import wind_from_compass

    if wind is None:
        return (0.0, 0.0)
    with flag_names(**_FLAGS):
        return wind_from_compass(float(wind[0]), float(wind[1]))


def _terrain(files: list[pathlib.Path] | None, voids: str | None, required: bool) -> Any:
    from glideplan.cli.common import check_input_file, file_flag, flag_names
    from glideplan.terrain import read_terrain

    if not files:
        if required:
            from glideplan.cli.common import usage_error

            usage_error("--terrain FILE is required (SRTM .hgt or GeoTIFF, or a folder)")
        return None
    import glob

    for f in files:
        if not f.is_dir() and not (glob.has_magic(str(f)) and not f.exists()):
            check_input_file(f, "--terrain")  # folders and patterns: read_terrain checks
    mode = "refuse" if voids is None else voids
    with flag_names(voids="--fill-voids"):
        if len(files) == 1 and files[0].is_file():
            with file_flag("--terrain", files[0]):
                return read_terrain(files, voids=mode)
        try:
            return read_terrain(files, voids=mode)
        except Exception as exc:  # name the flag; the message names the file
            from glideplan.errors import InvalidParameterError

            if isinstance(exc, InvalidParameterError):
                whole = str(exc.name) == str(exc.value)  # a folder or pattern: named once
                raise InvalidParameterError("--terrain" if whole else f"--terrain {exc.name}",
                                            exc.value, exc.rule) from None
            raise


def _polar(file: pathlib.Path, mass: float | None, ballast: float, bugs: float) -> Any:
    from glideplan.cli.glide import _polar as read_polar

    return read_polar(file, mass, ballast, bugs, "--polar")


def _example(name: str | None, write_to: pathlib.Path | None) -> Any:
    """The `--example` scenario (None without one); --write-example needs --example."""
    if name is None:
        if write_to is not None:
            from glideplan.cli.common import usage_error

            usage_error("--write-example DIR needs --example NAME (ridge)")
        return None
    from glideplan.cli.common import flag_names
    from glideplan.reach.examples import example

    with flag_names(**_FLAGS):
        return example(name)


def _or(value: Any, ex: Any, attr: str, default: Any) -> Any:
    """An explicit option wins; else the example's value; else the default."""
    if value is not None:
        return value
    return getattr(ex, attr) if ex is not None else default


def _announce_example(ex: Any, start: tuple[float, float, float], polar: Any,
                      wind: tuple[float, float] | None, mc: float, safety: float,
                      json_out: bool, extra: str = "") -> None:
    """One line naming the example and the values it runs with (overrides included)."""
    from glideplan.cli.common import announce

    w = "still air" if wind is None else f"wind {wind[0]:g} m/s from {wind[1]:g} deg"
    announce(f"example {ex.name}: {ex.description}; start {start[0]:g} N {start[1]:g} E "
             f"{start[2]:g} m; polar {getattr(polar, 'name', '')}; {w}; MC {mc:g} m/s; "
             f"safety height {safety:g} m{extra}", json_out)


def _required(value: Any, flag: str, ex: Any) -> None:
    if value is None and ex is None:
        from glideplan.cli.common import usage_error

        usage_error(f"{flag} is required (or give --example ridge)")


def _write_example(ex: Any, directory: pathlib.Path, command: str, args: list[str],
                   json_out: bool) -> None:
    """Write the example's files into `directory`; print the equivalent command line (the
    example's files and values, with `args`: the options given explicitly)."""
    import shlex

    from glideplan.cli.common import announce, flag_names, print_json
    from glideplan.reach.examples import write_example

    with flag_names(**_FLAGS):
        files = write_example(ex, directory)
    line = shlex.join(["glideplan", "glide", command, *args])
    if json_out:
        print_json({"example": ex.name, "files": [str(f) for f in files], "command": line})
        return
    for f in files:
        announce(f"wrote {f}", json_out)
    typer.echo("the same case from these files:")
    typer.echo(line)


def _flag_args(polar: pathlib.Path, start: tuple[float, float, float],
               terrain: list[pathlib.Path], wind: tuple[float, float] | None, mc: float,
               safety: float, ratio: float | None, mass: float | None, ballast: float,
               bugs: float, resolution: float | None, voids: str | None) -> list[str]:
    """The shared options as command-line words."""
    out = ["--polar", str(polar), "--from", *(repr(float(v)) for v in start)]
    for f in terrain:
        out += ["--terrain", str(f)]
    if wind is not None:
        out += ["--wind", repr(float(wind[0])), repr(float(wind[1]))]
    out += ["--mc", repr(float(mc)), "--safety-height", repr(float(safety))]
    for flag, value in (("--safety-glide-ratio", ratio), ("--mass", mass),
                        ("--resolution", resolution)):
        if value is not None:
            out += [flag, repr(float(value))]
    if ballast:
        out += ["--ballast", repr(float(ballast))]
    if bugs:
        out += ["--bugs", repr(float(bugs))]
    if voids is not None:
        out += ["--fill-voids", voids]
    return out


def _example_files(ex: Any, directory: pathlib.Path) -> tuple[pathlib.Path, ...]:
    """Where `write_example` puts the tile, the fields and the polar."""
    return (directory / ex.tile_name, directory / "fields.cup", directory / ex.polar_file.name)


def _shared(ex: Any, start: Any, wind: Any, mc: float | None, safety_height: float | None,
            resolution: float | None) -> tuple[float, float, float | None, Any, Any]:
    """The options both commands take, the example's values where not given: MC (m/s),
    safety height (m), resolution (m), start (lat, lon, alt) and wind (speed, FROM deg),
    checked against `validation.PHYSICAL_RANGES` before any work (the rows `glide_reach`,
    `turnback` and `glide final` check)."""
    from glideplan.units import wind_from_compass
    from glideplan.validation import check_physical

    out = (
        check_physical("--mc", float(_or(mc, ex, "mc", DEFAULT_MC)), "mc"),
        check_physical("--safety-height",
                       float(_or(safety_height, ex, "safety_height", DEFAULT_SAFETY_M)), "height"),
        _or(resolution, ex, "resolution_m", None),
        _or(start, ex, "start", None),
        wind if wind is not None or ex is None else (ex.wind_speed_ms, ex.wind_from_deg),
    )
    if out[3] is not None:
        check_physical("--from altitude", out[3][2], "altitude")
    if out[4] is not None:
        wind_from_compass(out[4][0], out[4][1], param="--wind")
    return out


@glide_app.command("reach")
def glide_reach_cmd(
    polar_file: PolarOpt = None,
    start: FromOpt = None,
    terrain: TerrainOpt = None,
    landables: Annotated[pathlib.Path | None, typer.Option(
        "--landables", metavar="FILE.cup",
        help="Landables: SeeYou .cup (styles 2-5 are landable).", show_default=False)] = None,
    wind: WindOpt = None,
    mc: McOpt = None,
    safety_height: SafetyOpt = None,
    terrain_clearance: ClearanceOpt = None,
    arrival_height: ArrivalOpt = None,
    safety_glide_ratio: RatioOpt = None,
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    resolution: ResolutionOpt = None,
    fill_voids: VoidsOpt = None,
    example_name: ExampleOpt = None,
    write_example_dir: WriteExampleOpt = None,
    json_out: JsonOpt = False,
    geojson: Annotated[pathlib.Path | None, typer.Option(
        "--geojson", metavar="FILE", help="Write the footprint and landables as GeoJSON.",
        show_default=False)] = None,
    kml: Annotated[pathlib.Path | None, typer.Option(
        "--kml", metavar="FILE", help="Write the footprint and landables as KML.",
        show_default=False)] = None,
    plot: PlotOpt = None,
) -> None:
    """Where can I still glide to? Footprint over terrain in wind, each landable verified.

    Try it without files: glideplan glide reach --example ridge
    """
    from glideplan.cli.common import check_figure_file, check_output_file, flag_names
    from glideplan.cli.emit import emit
    from glideplan.reach import glide_reach

    ex = _example(example_name, write_example_dir)
    _required(polar_file, "--polar FILE", ex)
    _required(start, "--from LAT LON ALT_M", ex)
    if ex is None and not terrain:
        _terrain(terrain, fill_voids, required=True)  # the usage error
    plot = check_figure_file(plot)
    check_output_file(geojson, "--geojson")
    check_output_file(kml, "--kml")
    mc_v, safety_v, _, start_v, wind_in = _shared(ex, start, wind, mc, safety_height, resolution)
    if write_example_dir is not None:
        tile, cup, plr = _example_files(ex, write_example_dir)
        args = _flag_args(polar_file or plr, start_v, list(terrain or [tile]), wind_in, mc_v,
                          safety_v, safety_glide_ratio, mass, ballast, bugs, resolution,
                          fill_voids) + _height_args(terrain_clearance, arrival_height)
        args += ["--landables", str(landables or cup)]
        _write_example(ex, write_example_dir, "reach", args, json_out)
        return
    p = _polar(polar_file or ex.polar_file, mass, ballast, bugs)
    t = _terrain(terrain, fill_voids, required=True) if terrain else ex.terrain
    lands, notes = _landables(landables, t, () if ex is None else ex.landables)
    w = _wind(wind_in)
    if ex is not None:
        _announce_example(ex, start_v, p, wind_in, mc_v, safety_v, json_out)
    # --safety-height (or the example's) sets both heights unless the new flags are given;
    # the example's 700 m grid is not used: the search runs at the terrain's own spacing
    one_height = safety_height if safety_height is not None or ex is None else safety_v
    with flag_names(**_FLAGS):
        result = glide_reach(t, (start_v[0], start_v[1], start_v[2]), p, landables=lands,
                             mc=mc_v, wind=w, safety_height=one_height,
                             terrain_clearance=terrain_clearance, arrival_height=arrival_height,
                             safety_glide_ratio=safety_glide_ratio, resolution_m=resolution,
                             progress=True)
    if notes:  # into the result's warnings (JSON too)
        import dataclasses

        result = dataclasses.replace(result, warnings=(*(f"--landables {n}" for n in notes),
                                                       *result.warnings))
    exports = _write_reach_files(result, geojson, kml)
    emit(result, json=json_out, plot=plot, exports=exports or None, summary=_reach_summary,
         what="reach")


def _height_args(terrain_clearance: float | None, arrival_height: float | None) -> list[str]:
    """The two heights as flags of the written example's command line (when given)."""
    args: list[str] = []
    for flag, value in (("--terrain-clearance", terrain_clearance),
                        ("--arrival-height", arrival_height)):
        if value is not None:
            args += [flag, repr(float(value))]
    return args


def _landables(path: pathlib.Path | None, terrain: Any, default: Any) -> tuple[Any, list[str]]:
    """The --landables .cup file read (elevations from the terrain), else `default`; the
    reader's notes (a warning printed for waypoints that are not landable)."""
    from glideplan.cli.common import check_input_file, file_flag, print_warnings

    notes: list[str] = []  # the .cup reader's (elevations taken from the terrain)
    if path is None:
        return default, notes
    check_input_file(path, "--landables")
    from glideplan.reach.landables import read_cup_landables

    with file_flag("--landables", path):
        lands, skipped = read_cup_landables(path, terrain, notes)
    if skipped:
        print_warnings([f"--landables: {skipped} waypoint(s) are not landable (SeeYou "
                        "style not 2-5) and were skipped"])
    return lands, notes


def _write_reach_files(result: Any, geojson: pathlib.Path | None,
                       kml: pathlib.Path | None) -> dict[str, pathlib.Path]:
    """The footprint and landables as GeoJSON (--geojson) and KML (--kml); the files written."""
    from glideplan.cli.common import file_flag

    exports: dict[str, pathlib.Path] = {}
    for path, flag, write in ((geojson, "--geojson", result.write_geojson),
                              (kml, "--kml", result.write_kml)):
        if path is not None:
            with file_flag(flag, path):
                write(path)
            exports[flag[2:]] = path
    return exports


def _reach_summary(result: Any) -> None:
    typer.echo(result.message)
    _table(result)


def _table(result: Any) -> None:
    """The landables, one line each: reachable, arrival, margin, distance, detour, and for a
    field out of reach how much altitude is missing (or that its terrain is missing)."""
    typer.echo(f"{'landable':<20} {'reach':>5} {'arrival m':>9} {'margin m':>8} "
               f"{'dist km':>8} {'detour':>6}  short by")
    for pt in result.points:
        arr = "-" if pt.arrival_altitude_m is None else f"{pt.arrival_altitude_m:.0f}"
        mar = "-" if pt.arrival_margin_m is None else f"{pt.arrival_margin_m:+.0f}"
        dist = "-" if pt.distance_m is None else f"{pt.distance_m / 1000:.1f}"
        short = ("no terrain" if pt.terrain_missing else "-" if pt.short_by_m is None
                 else f"{pt.short_by_m:.0f} m")
        typer.echo(f"{pt.landable.name[:20]:<20} {'yes' if pt.reachable else 'no':>5} "
                   f"{arr:>9} {mar:>8} {dist:>8} {'yes' if pt.detour else 'no':>6}  {short}")


@glide_app.command("turnback")
def glide_turnback_cmd(
    polar_file: PolarOpt = None,
    start: FromOpt = None,
    course: Annotated[float | None, typer.Option(
        "--course", metavar="DEG", help="Outbound course (compass degrees); required unless "
        "--example.", show_default=False)] = None,
    home: Annotated[tuple[float, float, float] | None, typer.Option(
        "--home", metavar="LAT LON ELEV_M", help="Home field: LAT LON and elevation (m); "
        "required unless --example.", show_default=False)] = None,
    terrain: TerrainOpt = None,
    wind: WindOpt = None,
    mc: McOpt = None,
    safety_height: SafetyOpt = None,
    terrain_clearance: ClearanceOpt = None,
    arrival_height: ArrivalOpt = None,
    safety_glide_ratio: RatioOpt = None,
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    resolution: ResolutionOpt = None,
    fill_voids: VoidsOpt = None,
    example_name: ExampleOpt = None,
    write_example_dir: WriteExampleOpt = None,
    json_out: JsonOpt = False,
    plot: PlotOpt = None,
) -> None:
    """When must I turn back? Distance out along --course from which home is still reachable.

    Try it without files: glideplan glide turnback --example ridge
    """
    from glideplan.cli.common import check_figure_file, flag_names
    from glideplan.cli.emit import emit
    from glideplan.reach import turnback

    ex = _example(example_name, write_example_dir)
    _required(polar_file, "--polar FILE", ex)
    _required(start, "--from LAT LON ALT_M", ex)
    _required(course, "--course DEG", ex)
    _required(home, "--home LAT LON ELEV_M", ex)
    plot = check_figure_file(plot)
    mc_v, safety_v, _, start_v, wind_in = _shared(
        ex, start, wind, mc, safety_height, resolution)
    course_v = float(_or(course, ex, "course_deg", None))
    from glideplan.validation import check_physical

    course_v = check_physical("--course", course_v, "heading")
    home_v = home if home is not None else (ex.home.lat, ex.home.lon, ex.home.elevation_m)
    if write_example_dir is not None:
        tile, _, plr = _example_files(ex, write_example_dir)
        args = _flag_args(polar_file or plr, start_v, list(terrain or [tile]), wind_in, mc_v,
                          safety_v, safety_glide_ratio, mass, ballast, bugs, resolution,
                          fill_voids) + _height_args(terrain_clearance, arrival_height)
        args += ["--course", repr(course_v), "--home", *(repr(float(v)) for v in home_v)]
        _write_example(ex, write_example_dir, "turnback", args, json_out)
        return
    p = _polar(polar_file or ex.polar_file, mass, ballast, bugs)
    if terrain:
        t = _terrain(terrain, fill_voids, required=False)
    else:
        t = None if ex is None else ex.terrain
    w = _wind(wind_in)
    if ex is not None:
        home_name = ex.home.name if home is None else "--home"
        _announce_example(ex, start_v, p, wind_in, mc_v, safety_v, json_out,
                          f"; home {home_name}, course {course_v:g} deg")
    # --safety-height (or the example's) sets both heights unless the new flags are given
    one_height = safety_height if safety_height is not None or ex is None else safety_v
    with flag_names(**_FLAGS):
        result = turnback((start_v[0], start_v[1], start_v[2]), course_v,
                          ex.home if home is None else (home_v[0], home_v[1], home_v[2]), p,
                          terrain=t, mc=mc_v, wind=w,
                          safety_height=one_height, safety_glide_ratio=safety_glide_ratio,
                          resolution_m=resolution,  # the example's 700 m grid: not used
                          terrain_clearance=terrain_clearance, arrival_height=arrival_height)
    emit(result, json=json_out, plot=plot, what="turnback")
