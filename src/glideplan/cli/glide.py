"""`glideplan glide polar|ardusoar|final`: sailplane polars, ArduSoar parameters, final glide."""

from __future__ import annotations

import math
import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli.app import glide_app
from glideplan.errors import InvalidParameterError

MC_TABLE = tuple(0.5 * k for k in range(11))  # 0, 0.5, ..., 5 m/s

MassOpt = Annotated[
    float | None,
    typer.Option("--mass", help="All-up mass without water (kg); default the file's reference."),
]
BallastOpt = Annotated[float, typer.Option("--ballast", help="Water ballast (litres, 1 kg/L).")]
BugsOpt = Annotated[
    float, typer.Option("--bugs", help="Bugs: percent less glide ratio at every speed (0-50).")
]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object.")]


def _read(file: pathlib.Path, flag: str) -> Any:
    """The polar file named by `flag` (`--polar` or the FILE argument), errors naming it."""
    from glideplan.cli.common import check_input_file, file_flag
    from glideplan.sailplane import read_plr

    check_input_file(file, flag)
    with file_flag(flag, file, f"polar file {file}"):
        return read_plr(file)


def _polar(
    file: pathlib.Path, mass: float | None, ballast: float, bugs: float, flag: str = "FILE"
) -> Any:
    from glideplan.cli.common import flag_names
    from glideplan.sailplane import polar_from_file
    from glideplan.validation import check_finite, check_physical

    pf = _read(file, flag)
    for name, value in (("--mass", mass), ("--ballast", ballast), ("--bugs", bugs)):
        if value is not None:
            check_finite(name, value)
    if mass is not None:
        check_physical("--mass", mass, "mass")
    with flag_names(
        mass="--mass",
        mass_kg="--mass",
        ballast="--ballast",
        ballast_l="--ballast",
        bugs="--bugs",
        bugs_pct="--bugs",
    ):
        return polar_from_file(pf, mass_kg=mass, ballast_l=ballast, bugs_pct=bugs)


def _print(data: dict[str, Any]) -> None:
    from glideplan.cli.common import print_json

    print_json(data)


# library parameter -> the flag of `glide final` (library errors name their parameters)
FINAL_FLAGS = {
    "start": "--from",
    "goal": "--to",
    "mc": "--mc",
    "wind": "--wind",
    "safety_height": "--safety-height",
    "arrival_heading": "--arrival-heading",
    "start_heading": "--start-heading",
    "bank_max": "--bank-max",
}


def check_final_inputs(
    start: tuple[float, float, float],
    goal: tuple[float, float, float],
    *,
    mc: float,
    wind: tuple[float, float] | None,
    safety_height: float,
    arrival_heading: float | None,
    start_heading: float | None,
    bank_max: float,
) -> None:
    """Every number of `glide final` against `validation.PHYSICAL_RANGES`, before any work."""
    from glideplan.geodesy import check_latlon
    from glideplan.validation import check_physical

    check_latlon(start[0], start[1], "--from")
    check_latlon(goal[0], goal[1], "--to")
    check_physical("--from altitude", start[2], "altitude")
    check_physical("--to elevation", goal[2], "elevation")
    check_physical("--mc", mc, "mc")
    if wind is not None:
        check_physical("--wind speed", wind[0], "wind_speed")
        check_physical("--wind direction", wind[1], "heading")
    check_physical("--safety-height", safety_height, "height")
    for flag, heading in (("--arrival-heading", arrival_heading),
                          ("--start-heading", start_heading)):
        if heading is not None:
            check_physical(flag, heading, "heading")
    check_physical("--bank-max", bank_max, "bank")


@glide_app.command("polar")
def glide_polar(
    file: Annotated[
        pathlib.Path, typer.Argument(metavar="FILE", help="Polar file (.plr).", show_default=False)
    ],
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    json_out: JsonOpt = False,
) -> None:
    """Quadratic polar of a .plr file: best glide, minimum sink, MacCready table (MC 0-5 m/s)."""
    from glideplan.sailplane import maccready_table

    pf = _read(file, "FILE")
    p = _polar(file, mass, ballast, bugs)
    data = {
        "name": p.name,
        "file": str(file),
        "a": p.a,
        "b": p.b,
        "c": p.c,
        "units": "w = a v^2 + b v + c; w (sink, positive down) and v in m/s",
        "best_glide_ratio": p.best_glide_ratio,
        "best_glide_speed_kmh": p.v_best_glide * 3.6,
        "min_sink_ms": p.w_ms,
        "min_sink_speed_kmh": p.v_ms * 3.6,
        "speed_range_kmh": [p.v_min * 3.6, p.v_max * 3.6],
        "reference_mass_kg": p.reference_mass_kg,
        "mass_kg": p.mass_kg,
        "ballast_l": ballast,
        "max_ballast_l": pf.max_ballast_l,
        "bugs_pct": p.bugs_pct,
        "wing_area_m2": p.wing_area_m2,
        "stated_best_glide_ratio": pf.best_ld,
        "maccready": maccready_table(p, MC_TABLE),
    }
    if json_out:
        _print(data)
        return
    typer.echo(
        f"{p.name}: w = {p.a:.6g} v^2 + {p.b:.6g} v + {p.c:.6g} (m/s) at {p.mass_kg:g} kg\n"
        f"best glide {p.best_glide_ratio:.1f} at {p.v_best_glide * 3.6:.1f} km/h; "
        f"min sink {p.w_ms:.2f} m/s at {p.v_ms * 3.6:.1f} km/h"
    )
    typer.echo(f"{'MC m/s':>7} {'STF km/h':>9} {'L/D':>6} {'XC km/h':>8}")
    for row in data["maccready"]:
        typer.echo(
            f"{row['mc']:7.1f} {row['speed_to_fly_kmh']:9.1f} {row['glide_ratio']:6.1f} "
            f"{row['cross_country_kmh']:8.1f}"
        )


@glide_app.command("ardusoar")
def glide_ardusoar(
    file: Annotated[
        pathlib.Path, typer.Argument(metavar="FILE", help="Polar file (.plr).", show_default=False)
    ],
    out: Annotated[
        pathlib.Path,
        typer.Option(
            "--out",
            metavar="FILE",
            help="Parameter file to write (NAME value lines).",
            show_default=False,
        ),
    ],
    wing_area: Annotated[
        float | None, typer.Option("--wing-area", help="Wing area S (m^2); default the file's.")
    ] = None,
    json_out: JsonOpt = False,
) -> None:
    """Fit ArduPilot's SOAR_POLAR_CD0/B/K to the polar (least squares) and write a .parm file."""
    from glideplan.cli.common import announce, check_output_file, file_flag, flag_names
    from glideplan.sailplane import fit_ardusoar, write_parm
    from glideplan.validation import check_physical

    check_output_file(out, "--out")
    if wing_area is not None:
        check_physical("--wing-area", wing_area, "area")
    p = _polar(file, None, 0.0, 0.0)
    with flag_names(**{"wing area": "--wing-area"}):
        fit = fit_ardusoar(p, wing_area)
    with file_flag("--out", out):
        write_parm(
            fit,
            out,
            comment=f"ArduSoar polar for {p.name} at {p.mass_kg:g} kg, fitted by glideplan "
            f"(worst sink error {fit.max_sink_error:.3f} m/s over "
            f"{fit.speed_range[0] * 3.6:.0f}-{fit.speed_range[1] * 3.6:.0f} km/h)",
        )
    data = {
        **fit.params(),
        "max_sink_error_ms": fit.max_sink_error,
        "rms_sink_error_ms": fit.rms_sink_error,
        "speed_range_kmh": [fit.speed_range[0] * 3.6, fit.speed_range[1] * 3.6],
        "mass_kg": p.mass_kg,
        "wing_area_m2": wing_area if wing_area is not None else p.wing_area_m2,
        "out": str(out),
    }
    if json_out:
        _print(data)
    else:
        for name, value in fit.params().items():
            typer.echo(f"{name} {value:.6g}")
        typer.echo(f"worst sink error {fit.max_sink_error:.3f} m/s")
    announce(f"wrote {out}", json_out)


# glide_final's options (module level keeps the command itself short)
_GlideFinalPolarFile = Annotated[
    pathlib.Path,
    typer.Option("--polar", metavar="FILE", help="Polar file (.plr).", show_default=False),
]
_GlideFinalStart = Annotated[
    tuple[float, float, float],
    typer.Option(
        "--from",
        metavar="LAT LON ALT_M",
        help="Start LAT LON ALT_M (WGS84 degrees, metres).",
        show_default=False,
    ),
]
_GlideFinalGoal = Annotated[
    tuple[float, float, float],
    typer.Option(
        "--to",
        metavar="LAT LON ELEV_M",
        help="Goal LAT LON ELEV_M (WGS84 degrees, metres).",
        show_default=False,
    ),
]
_GlideFinalWind = Annotated[
    tuple[float, float] | None,
    typer.Option(
        "--wind",
        metavar="SPEED_MS FROM_DEG",
        help="Wind SPEED_MS FROM_DEG (compass, where it blows from).",
        show_default=False,
    ),
]
_GlideFinalSafetyHeight = Annotated[
    float, typer.Option("--safety-height", help="Arrival height above the goal (m).")
]
_GlideFinalArrivalHeading = Annotated[
    float | None,
    typer.Option("--arrival-heading", help="Heading at the goal (compass degrees)."),
]
_GlideFinalStartHeading = Annotated[
    float | None,
    typer.Option("--start-heading", help="Heading now (compass degrees); default free."),
]
_GlideFinalBankMax = Annotated[
    float, typer.Option("--bank-max", help="Bank limit in turns (degrees).")
]
_GlideFinalPlot = Annotated[
    pathlib.Path | None,
    typer.Option(
        "--plot", metavar="FILE", help="Draw the ground track and altitude profile to FILE."
    ),
]
_GlideFinalCup = Annotated[
    pathlib.Path | None,
    typer.Option("--cup", metavar="FILE", help="Also write a SeeYou .cup task."),
]
_GlideFinalTsk = Annotated[
    pathlib.Path | None,
    typer.Option("--tsk", metavar="FILE", help="Also write an XCSoar .tsk task."),
]


@glide_app.command("final")
def glide_final(
    polar_file: _GlideFinalPolarFile,
    start: _GlideFinalStart,
    goal: _GlideFinalGoal,
    mass: MassOpt = None,
    ballast: BallastOpt = 0.0,
    bugs: BugsOpt = 0.0,
    mc: Annotated[float, typer.Option("--mc", help="MacCready setting (m/s).")] = 0.0,
    wind: _GlideFinalWind = None,
    safety_height: _GlideFinalSafetyHeight = 300.0,
    arrival_heading: _GlideFinalArrivalHeading = None,
    start_heading: _GlideFinalStartHeading = None,
    bank_max: _GlideFinalBankMax = 45.0,
    json_out: JsonOpt = False,
    plot: _GlideFinalPlot = None,
    cup: _GlideFinalCup = None,
    tsk: _GlideFinalTsk = None,
) -> None:
    """Altitude needed to reach a goal: straight final glide, or to an arrival heading."""
    from glideplan.cli.common import check_figure_file, check_output_file, flag_names
    from glideplan.cli.emit import emit
    from glideplan.sailplane.request import final_glide
    from glideplan.units import wind_from_compass

    plot = check_figure_file(plot)
    check_output_file(cup, "--cup")
    check_output_file(tsk, "--tsk")
    check_final_inputs(
        start,
        goal,
        mc=mc,
        wind=wind,
        safety_height=safety_height,
        arrival_heading=arrival_heading,
        start_heading=start_heading,
        bank_max=bank_max,
    )
    p = _polar(polar_file, mass, ballast, bugs, "--polar")
    if start_heading is not None and arrival_heading is None:
        raise InvalidParameterError(
            "--start-heading", start_heading, "is only used with --arrival-heading"
        )
    with flag_names(**FINAL_FLAGS):
        # the library's wind is the (east, north) vector: the compass stays at this edge
        result = final_glide(
            p,
            start,
            goal,
            mc=mc,
            wind=None if wind is None else wind_from_compass(*wind),
            safety_height=safety_height,
            arrival_heading=arrival_heading,
            start_heading=start_heading,
            bank_max=bank_max,
        )
    exports = _write_task(cup, tsk, start, goal, p.name)
    emit(result, json=json_out, plot=plot, exports=exports or None, summary=_final_summary,
         what="final glide")


def _write_task(cup: pathlib.Path | None, tsk: pathlib.Path | None,
                start: tuple[float, float, float], goal: tuple[float, float, float],
                polar_name: str) -> dict[str, pathlib.Path]:
    """The start-goal task as SeeYou .cup (--cup) and XCSoar .tsk (--tsk); the files written."""
    from glideplan.cli.common import file_flag

    exports: dict[str, pathlib.Path] = {}
    if cup is not None or tsk is not None:
        from glideplan.sailplane import TaskPoint, write_cup_task, write_tsk_task

        # The start is airborne: ground elevation unknown, the altitude in the description.
        a = TaskPoint("START", start[0], start[1], None, f"glider at {start[2]:g} m")
        b = TaskPoint("GOAL", goal[0], goal[1], goal[2])
        for path, flag in ((cup, "--cup"), (tsk, "--tsk")):
            if path is None:
                continue
            with file_flag(flag, path):
                if flag == "--cup":
                    write_cup_task(path, a, b, description=f"final glide {polar_name}")
                else:
                    write_tsk_task(path, a, b)
            exports[flag[2:]] = path
    return exports


def _final_summary(result: Any) -> None:
    """The human summary of `glide final` (one line)."""
    data = result.to_dict()
    if data["status"] == "unreachable":
        typer.echo(
            f"unreachable: distance {data['distance_m'] / 1000:.2f} km on bearing "
            f"{data['bearing_deg']:.0f}°, wind {data['wind']['speed_ms']:g} m/s from "
            f"{data['wind']['from_deg']:g}°: no altitude is enough"
        )
        return
    typer.echo(
        f"{data['status']}: distance {data['distance_m'] / 1000:.2f} km, loss "
        f"{_fmt(data['altitude_loss_m'])} m, required {_fmt(data['altitude_required_m'])} m, "
        f"margin {_fmt(data['arrival_margin_m'])} m, glide ratio needed "
        f"{_fmt(data['glide_ratio_required'], 1)}, speed to fly "
        f"{_fmt(data['speed_to_fly_kmh'])} km/h"
        + (f", path {data['word']}" if "word" in data else "")
    )


def _fmt(value: Any, digits: int = 0) -> str:
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "-"
    return f"{value:.{digits}f}"
