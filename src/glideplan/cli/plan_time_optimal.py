"""`glideplan plan time-optimal`: minimum-time paths with variable speed (chapter 4)."""

from __future__ import annotations

import pathlib
from typing import Annotated, Any

import typer

from glideplan.cli import common
from glideplan.cli.app import plan_app

__all__ = ["control_history", "plan_time_optimal_command"]


def control_history(path: Any) -> dict[str, list[float]]:
    """Speed (m/s) and turn rate (rad/s) against time (s), exact for piecewise-constant controls.

    Arcs and straights give two samples each (their constant controls at both ends, so a
    switch appears as two samples at the same time); sampled segments give their nodes.
    """
    t_out: list[float] = []
    v_out: list[float] = []
    u_out: list[float] = []
    t0 = 0.0
    for seg in path.segments:
        if hasattr(seg, "t"):
            ts = seg.t
        else:
            ts = [0.0, seg.duration]
        v, u = seg.controls(ts)
        t_out += [t0 + float(t) for t in ts]
        v_out += [float(x) for x in v]
        u_out += [float(x) for x in u]
        t0 += seg.duration
    return {"t": t_out, "speed": v_out, "turn_rate": u_out}


@plan_app.command("time-optimal")
def plan_time_optimal_command(
    goal: Annotated[
        common.PoseValues, common.goal_option("Goal pose X Y HEADING_DEG (m, m, degrees).")
    ],
    v_min: Annotated[
        float, typer.Option("--v-min", help="Minimum speed v_min > 0 (m/s).", show_default=False)
    ],
    v_max: Annotated[
        float,
        typer.Option("--v-max", help="Maximum speed v_max >= v_min (m/s).", show_default=False),
    ],
    u_max: Annotated[
        float,
        typer.Option("--u-max", help="Maximum turn rate u_max > 0 (rad/s).", show_default=False),
    ],
    start: Annotated[
        common.PoseValues, common.start_option("Start pose X Y HEADING_DEG (m, m, degrees).")
    ] = (0.0, 0.0, 0.0),
    method: Annotated[
        str,
        typer.Option(
            "--method",
            help="synthesis (the 72 candidate types of eq. 4.26) or direct (collocation).",
        ),
    ] = "synthesis",
    time_limit: Annotated[float | None, common.time_limit_flag()] = None,
    json_out: Annotated[bool, common.json_flag()] = False,
    plot: Annotated[
        pathlib.Path | None,
        common.plot_option("Draw the path with its switching points to FILE (PNG)."),
    ] = None,
) -> None:
    """Minimum-time path with speed between v_min and v_max, |turn rate| <= u_max (chapter 4).

    Bang turns fly at v_max on radius R = v_max/u_max, cornering turns at v_min on
    r = v_min/u_max; the dissertation's example is --v-min 0.3 --v-max 1 --u-max 1.
    The cost is the time (s).
    """
    from glideplan.errors import InvalidParameterError
    from glideplan.planning import plan
    from glideplan.vehicles.variable_speed_car import VariableSpeedCar

    if method not in ("synthesis", "direct"):
        raise InvalidParameterError("--method", method, "must be synthesis or direct")
    plot = common.check_figure_file(plot)
    start_pose, goal_pose = common.parse_start_goal(start, goal)
    names = {
        "v_min": "--v-min",
        "v_max": "--v-max",
        "u_max": "--u-max",
        "v_max/u_max": "--v-max/--u-max",
        "v_min/u_max": "--v-min/--u-max",
    }
    with common.flag_names(**names, start="--start", goal="--goal"):
        vehicle = VariableSpeedCar(v_min=v_min, v_max=v_max, u_max=u_max)
        options = common.time_limit_option(vehicle, "time", method, time_limit)
        solution = common.solving(
            f"planning (time-optimal, {method})",
            lambda: plan(start_pose, goal_pose, vehicle, "time", method, **options),
        )
    extra: dict[str, Any] = {
        "bang_radius": vehicle.bang_radius,
        "corner_radius": vehicle.corner_radius,
    }
    if solution.path is not None:
        extra["controls"] = control_history(solution.path)
    common.emit_solution(solution, json_out, plot, extra=extra)
