"""`glideplan design ...`: chapter 7 design analyses (buoyancy engine, valves, trim, glide, LBL).

Inputs at the edge in the units a designer uses (litres, psi, metres, degrees); a full
parameter set comes from `--params FILE.toml` (`glideplan design init FILE.toml` writes one).
"""

from __future__ import annotations

import math
import pathlib
from typing import Annotated, Any

import numpy as np
import typer

from glideplan.cli.app import design_app
from glideplan.cli.common import (
    check_input_file,
    check_output_file,
    file_flag,
    flag_names,
    json_flag,
    print_json,
    print_warnings,
)
from glideplan.errors import InvalidParameterError
from glideplan.validation import check_finite, check_in_range, check_physical, check_positive

ParamsOpt = Annotated[
    pathlib.Path | None,
    typer.Option(
        "--params",
        metavar="FILE",
        help="TOML parameter set (see `glideplan design init`); fields it omits keep the "
        "defaults, listed in a warning.",
    ),
]
MAX_STATIONS = 1001  # `design trim --steps`: a table, not a sweep
MAX_SWATHS = 1000  # `design lbl --swaths`
MAX_PINGS = 1e6  # `design lbl`: swaths x track length / --step-m

JsonOpt = Annotated[bool, json_flag("Print JSON instead of a table.")]


def _params(path: pathlib.Path | None) -> Any:
    """The parameter set of `--params FILE` (or the defaults); warn which fields defaulted."""
    import tomllib

    from glideplan.design import DesignParameters
    from glideplan.design.params import defaulted_fields, loads_parameters, read_parameter_text

    if path is None:
        return DesignParameters()
    check_input_file(path, "--params")
    try:
        with file_flag("--params", path), flag_names(params="--params"):
            text = read_parameter_text(path)
            params = loads_parameters(text, source=str(path))
    except InvalidParameterError as exc:
        raise _toml_error(exc) from None
    missing = defaulted_fields(tomllib.loads(text))
    total = len(defaulted_fields({}))
    if len(missing) == total:
        print_warnings(
            [f"{path} sets no parameters: all {total} are the defaults (see design init)"]
        )
    elif missing:
        sections: dict[str, list[str]] = {}
        for name in missing:
            section, field = name.split(".", 1)
            sections.setdefault(section, []).append(field)
        full = set(sections) - {
            n.split(".", 1)[0] for n in defaulted_fields({}) if n not in missing
        }
        parts = [
            f"[{s}] all" if s in full else f"{s}.{{{', '.join(f)}}}" for s, f in sections.items()
        ]
        print_warnings([f"{path}: defaults used for {len(missing)} of {total}: {'; '.join(parts)}"])
    return params


def _toml_error(exc: InvalidParameterError) -> InvalidParameterError:
    """`is not valid TOML: Expected ']' ... (at line 1, column 6)` ->
    `is not valid TOML (line 1, column 6: Expected ']' ...)`; other errors unchanged."""
    import re

    head = "is not valid TOML: "
    found = re.fullmatch(r"(.*) \(at line (\d+), column (\d+)\)", exc.rule[len(head) :])
    if not exc.rule.startswith(head) or found is None:
        return exc
    what, line, column = found.groups()
    return InvalidParameterError(
        exc.name, exc.value, f"is not valid TOML (line {line}, column {column}: {what})"
    )


def _check_psi(flag: str, psi: float) -> float:
    """A pressure typed in psi against the SI range of `PHYSICAL_RANGES["pressure"]`."""
    from glideplan.units import psi_to_pa

    value = check_finite(flag, psi)
    try:
        check_physical(flag, float(psi_to_pa(value)), "pressure")
    except InvalidParameterError as exc:
        raise InvalidParameterError(flag, psi, f"as {exc.value:.6g} Pa: {exc.rule}") from None
    return value


def _bladder_volume_l(flag: str, litres: float, bladder: Any) -> float:
    """A bladder volume (L) inside [0, bladder.max_volume_m3] of the parameter set."""
    vmax_l = 1e3 * bladder.max_volume_m3
    value = check_finite(flag, litres)
    if not 0.0 <= value <= vmax_l:
        raise InvalidParameterError(
            flag, litres, f"must lie in [0, {vmax_l:g}] L (bladder.max_volume_m3 of the parameters)"
        )
    return value


def _emit(title: str, columns: list[str], rows: list[list[Any]], data: Any, json_out: bool) -> None:
    if json_out:
        print_json(data)
        return
    from rich.console import Console
    from rich.table import Table

    table = Table(title=title)
    for i, col in enumerate(columns):
        table.add_column(col, justify="left" if i == 0 else "right")
    for row in rows:
        table.add_row(*(f"{v:.6g}" if isinstance(v, float) else str(v) for v in row))
    Console().print(table)


@design_app.command("init")
def init(
    file: Annotated[pathlib.Path, typer.Argument(metavar="FILE", help="TOML file to write.")],
    force: Annotated[bool, typer.Option("--force", help="Overwrite an existing file.")] = False,
) -> None:
    """Write a template parameter set (the VTUG / FX23DV / Seaglider-like defaults)."""
    from glideplan.design import DesignParameters, save_parameters

    if file.is_dir():
        raise InvalidParameterError("FILE", str(file), "is a directory; give a file name")
    if file.exists() and not force:
        raise InvalidParameterError("FILE", str(file), "exists; pass --force to overwrite")
    check_output_file(file, "FILE")
    with file_flag("FILE", file):
        save_parameters(DesignParameters(), file)
    typer.echo(f"wrote {file}")


@design_app.command("tank")
def tank(
    params: ParamsOpt = None,
    pressure_psi: Annotated[
        float | None, typer.Option("--pressure-psi", help="Tank pressure (default: rated).")
    ] = None,
    json_out: JsonOpt = False,
) -> None:
    """Air in the tank by the ideal gas law (7.1) and how deep it can inflate."""
    from glideplan.design import M_AIR_KG_PER_MOL, R_GAS_J_PER_MOL_K
    from glideplan.units import pa_to_psi, psi_to_pa

    p = _params(params)
    t = p.tank
    env = p.environment
    rated_psi = float(pa_to_psi(t.max_pressure_pa))
    p_pa = (
        t.max_pressure_pa
        if pressure_psi is None
        else psi_to_pa(
            check_in_range("--pressure-psi", pressure_psi, 0.0, rated_psi, low_open=True)
        )
    )
    n = float(t.moles(env.temperature_k, p_pa))
    data = {
        "tank": t.name,
        "pressure_pa": float(p_pa),
        "pressure_psi": float(pa_to_psi(p_pa)),
        "internal_volume_m3": t.internal_volume_m3,
        "temperature_k": env.temperature_k,
        "moles": n,
        "air_mass_kg": n * M_AIR_KG_PER_MOL,
        "temperature_for_31_1_mol_k": p_pa * t.internal_volume_m3 / (R_GAS_J_PER_MOL_K * 31.1),
        "max_inflation_depth_m": float(env.depth_at_pressure_m(p_pa)),
    }
    rows = [[k, v] for k, v in data.items()]
    _emit("Tank air (7.1)", ["quantity", "value"], rows, data, json_out)


@design_app.command("dives")
def dives(
    volume_l: Annotated[
        list[float] | None,
        typer.Option("--volume-l", metavar="L", help="Bladder displacement, L (repeat)."),
    ] = None,
    depth_m: Annotated[
        list[float] | None,
        typer.Option("--depth-m", metavar="M", help="Dive depth, m (repeat)."),
    ] = None,
    usable: Annotated[
        bool, typer.Option("--usable", help="Leave the air that cannot leave the tank at depth.")
    ] = False,
    params: ParamsOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Air per dive and number of dives N = n_tank / n_cycle on a volume x depth grid (Fig 7.3)."""
    from glideplan.design import moles_per_cycle, number_of_dives
    from glideplan.units import litre_to_m3

    p = _params(params)
    vols = volume_l or [3.0, 5.0]
    depths = depth_m or [50.0, 100.0]
    rows, data = [], []
    for v in vols:
        check_positive("--volume-l", v)
        _bladder_volume_l("--volume-l", v, p.bladder)
    for z in depths:
        check_physical("--depth-m", z, "depth")
    with flag_names(depth_m="--depth-m"):
        for v in vols:
            v_m3 = litre_to_m3(v)
            for z in depths:
                n_dives = float(number_of_dives(p.tank, v_m3, z, p.environment, usable_only=usable))
                n_cycle = float(moles_per_cycle(v_m3, z, p.environment))
                rows.append([f"{v:g} L", f"{z:g} m", n_cycle, n_dives, math.floor(n_dives)])
                data.append(
                    {"volume_l": v, "depth_m": z, "moles_per_cycle": n_cycle, "dives": n_dives}
                )
    cols = ["volume", "depth", "mol/dive", "dives", "full dives"]
    _emit(f"Dives with {p.tank.name}", cols, rows, data, json_out)


@design_app.command("valve")
def valve(
    volume_l: Annotated[float, typer.Option("--volume-l", help="Bladder volume to hold, L.")] = 5.0,
    depth_m: Annotated[float, typer.Option("--depth-m", help="Depth, m (deflator).")] = 100.0,
    tank_psi: Annotated[
        float, typer.Option("--tank-psi", help="Tank pressure, psia (inflator).")
    ] = 500.0,
    drag_coefficient: Annotated[
        float | None, typer.Option("--cd", help="Drag coefficient (default: params hull).")
    ] = None,
    params: ParamsOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Valve C_v to hold a bladder volume at the terminal depth rate (7.6-7.8; Fig 7.8).

    Above the neutral volume the glider rises and the deflator is sized; below it the glider
    sinks and the inflator is sized (choked, and as (7.8) is printed).
    """
    from glideplan.design import (
        air_exchange_rate_mol_s,
        deflator_cv,
        inflator_cv,
        molar_flow_to_scfm,
        terminal_depth_rate_m_s,
    )
    from glideplan.design.valves import ASSUMED_BLADDER_CURVE_NOTE
    from glideplan.units import litre_to_m3, psi_to_pa

    check_physical("--depth-m", depth_m, "depth")
    _check_psi("--tank-psi", tank_psi)
    if drag_coefficient is not None:
        check_physical("--cd", drag_coefficient, "coefficient")
    p = _params(params)
    b, h, env = p.bladder, p.hull, p.environment
    v = litre_to_m3(_bladder_volume_l("--volume-l", volume_l, b))
    cd = h.drag_coefficient if drag_coefficient is None else drag_coefficient
    check_positive("--tank-psi", tank_psi)
    names = {"tank_pressure_pa": "--tank-psi (in Pa)"}
    with flag_names(depth_m="--depth-m", drag_coefficient="--cd", **names):
        zdot = float(terminal_depth_rate_m_s(b.net_weight_n(v, env), h.cross_section_m2, cd, env))
        ndot = float(air_exchange_rate_mol_s(v, zdot, env))
        data: dict[str, Any] = {
            "volume_l": volume_l,
            "drag_coefficient": cd,
            "depth_rate_m_s": zdot,
            "exchange_rate_mol_s": ndot,
            "flow_scfm": float(molar_flow_to_scfm(abs(ndot))),
        }
        if v > b.neutral_volume_m3:
            data |= {
                "valve": "deflator",
                "depth_m": depth_m,
                "cv": float(deflator_cv(b, h, v, depth_m, env, drag_coefficient=cd)),
            }
        elif v < b.neutral_volume_m3:
            data |= {
                "valve": "inflator",
                "tank_psia": tank_psi,
                "cv": float(inflator_cv(b, h, v, psi_to_pa(tank_psi), env, drag_coefficient=cd)),
                "cv_as_printed_7_8": float(
                    inflator_cv(
                        b, h, v, psi_to_pa(tank_psi), env, choked="never", drag_coefficient=cd
                    )
                ),
            }
        else:
            data |= {"valve": "none (neutral: no flow needed)", "cv": 0.0}
        data["note"] = ASSUMED_BLADDER_CURVE_NOTE
    rows = [[k, v] for k, v in data.items() if k != "note"]
    _emit("Valve sizing (7.6-7.8)", ["quantity", "value"], rows, data, json_out)
    if not json_out:
        typer.echo(f"Note: {ASSUMED_BLADDER_CURVE_NOTE}.")


@design_app.command("trim")
def trim(
    bladder_l: Annotated[float, typer.Option("--bladder-l", help="Bladder volume, L.")] = 2.5,
    steps: Annotated[int, typer.Option("--steps", help="Moving-mass stations to list.")] = 5,
    params: ParamsOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Equilibrium pitch over the moving-mass travel, with CG and CB (7.9-7.14)."""
    from glideplan.design import (
        centre_of_buoyancy_m,
        centre_of_gravity_m,
        equilibrium_pitch_rad,
        net_vertical_force_n,
    )
    from glideplan.units import litre_to_m3

    if not 2 <= steps <= MAX_STATIONS:
        raise InvalidParameterError("--steps", steps, f"must lie in [2, {MAX_STATIONS}]")
    p = _params(params)
    lay = p.trim
    v = litre_to_m3(_bladder_volume_l("--bladder-l", bladder_l, p.bladder))
    stations = np.linspace(lay.moving_mass_min_station_m, lay.moving_mass_max_station_m, steps)
    theta = np.degrees(equilibrium_pitch_rad(lay, stations, v, p.environment))
    cgx, cgz = centre_of_gravity_m(lay, stations)
    cbx = float(centre_of_buoyancy_m(lay, v))
    rows = [
        [f"{s:.3f} m", float(cx), float(cgz), cbx, float(t)]
        for s, cx, t in zip(stations, np.atleast_1d(cgx), theta, strict=True)
    ]
    data = {
        "bladder_l": bladder_l,
        "net_vertical_force_n": float(net_vertical_force_n(lay, v, p.environment)),
        "centre_of_buoyancy_x_m": cbx,
        "stations_m": stations,
        "cg_x_m": cgx,
        "cg_z_m": float(cgz),
        "pitch_deg": theta,
    }
    cols = ["moving mass", "CG x (m)", "CG z (m)", "CB x (m)", "pitch (deg)"]
    _emit("Pitch trim (7.10, + nose-up)", cols, rows, data, json_out)


@design_app.command("glide")
def glide(
    volume_l: Annotated[
        list[float] | None,
        typer.Option("--volume-l", metavar="L", help="Net buoyancy |V - V_neutral|, L (repeat)."),
    ] = None,
    params: ParamsOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Top forward speed and dive speed from the parabolic polar (7.15-7.20; Fig 7.17)."""
    from glideplan.design import glide_velocity_m_s, max_forward_speed
    from glideplan.units import litre_to_m3

    p = _params(params)
    env, polar = p.environment, p.glide
    vols = volume_l or [0.5, 1.0, 1.5, 2.0, 2.5]
    rows, data = [], []
    b = p.bladder
    net_max_l = 1e3 * max(b.neutral_volume_m3, b.max_volume_m3 - b.neutral_volume_m3)
    for v in vols:
        check_positive("--volume-l", v)
        if v > net_max_l:
            raise InvalidParameterError(
                "--volume-l",
                v,
                f"must be <= {net_max_l:g} L (the most net buoyancy the bladder gives: "
                "max(neutral, max - neutral volume) of the parameters)",
            )
    for v in vols:
        w = env.specific_weight_n_m3 * litre_to_m3(v)
        u, g = max_forward_speed(polar, w, env)
        _, dive = glide_velocity_m_s(polar, math.pi / 2, w, env)
        rows.append([f"{v:g} L", w, u, math.degrees(g), float(dive)])
        data.append(
            {
                "volume_l": v,
                "net_weight_n": w,
                "max_forward_speed_m_s": u,
                "gamma_at_max_deg": math.degrees(g),
                "vertical_dive_speed_m_s": float(dive),
            }
        )
    cols = ["net buoyancy", "W~ (N)", "u max (m/s)", "gamma (deg)", "dive (m/s)"]
    title = f"{polar.name}: gamma_min = {math.degrees(polar.min_glide_angle_rad):.2f} deg"
    _emit(title, cols, rows, data, json_out)


@design_app.command("lbl")
def lbl(
    seed: Annotated[int, typer.Option("--seed", help="Random seed.")] = 0,
    noise_m: Annotated[
        float | None, typer.Option("--noise-m", help="Range noise std, m (default: params).")
    ] = None,
    success: Annotated[
        float | None, typer.Option("--success", help="Ping success probability.")
    ] = None,
    swaths: Annotated[int, typer.Option("--swaths", help="North-south swaths.")] = 7,
    step_m: Annotated[float, typer.Option("--step-m", help="Distance between pings, m.")] = 5.0,
    params: ParamsOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """Simulate an LBL survey (lawn-mower track) and report position error stats (sec 7.6)."""
    import dataclasses

    from glideplan.design import lawnmower_track, simulate_survey

    if noise_m is not None:
        check_physical("--noise-m", noise_m, "distance")
    check_physical("--step-m", step_m, "distance")
    p = _params(params)
    cfg = p.lbl
    changes: dict[str, float] = {}
    if noise_m is not None:
        changes["range_noise_std_m"] = noise_m
    if success is not None:
        changes["ping_success_probability"] = success
    try:
        cfg = dataclasses.replace(cfg, **changes)
    except InvalidParameterError as exc:
        flag = {"range_noise_std_m": "--noise-m", "ping_success_probability": "--success"}
        raise InvalidParameterError(flag.get(exc.name, exc.name), exc.value, exc.rule) from None
    b = np.asarray(cfg.beacons_m)
    pad = 0.1 * float(np.max(np.ptp(b, axis=0)))
    if not 1 <= swaths <= MAX_SWATHS:
        raise InvalidParameterError("--swaths", swaths, f"must lie in [1, {MAX_SWATHS}]")
    pings = swaths * (float(np.ptp(b[:, 1])) + 2 * pad) / step_m
    if pings > MAX_PINGS:
        raise InvalidParameterError(
            "--step-m", step_m, f"gives about {pings:.3g} pings; at most {MAX_PINGS:g} "
            "(a survey simulation, not a sweep): give a larger step")
    with flag_names(swaths="--swaths", step_m="--step-m"):
        track = lawnmower_track(
            (float(b[:, 0].min() - pad), float(b[:, 0].max() + pad)),
            (float(b[:, 1].min() - pad), float(b[:, 1].max() + pad)),
            swaths,
            step_m,
        )
    stats = simulate_survey(cfg, track, seed).statistics
    data = stats.to_dict() | {"seed": seed, "beacons": len(b), "method": cfg.method}
    rows = [[k, v] for k, v in data.items()]
    _emit("LBL survey (section 7.6)", ["quantity", "value"], rows, data, json_out)
