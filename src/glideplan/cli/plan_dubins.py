"""`glideplan plan dubins`: shortest Dubins paths with an optional feasible turn radius."""

from __future__ import annotations

import pathlib
from typing import Annotated

import typer

from glideplan.cli import common
from glideplan.cli.app import plan_app


@plan_app.command("dubins")
def plan_dubins_command(
    goal: Annotated[
        common.PoseValues, common.goal_option("Goal pose X Y HEADING_DEG (m, m, degrees).")
    ],
    radius: Annotated[float, typer.Option("--radius", help="Minimum turn radius R0 (m).")],
    start: Annotated[
        common.PoseValues, common.start_option("Start pose X Y HEADING_DEG (m, m, degrees).")
    ] = (0.0, 0.0, 0.0),
    speed: Annotated[float, typer.Option("--speed", help="Constant speed v (m/s).")] = 1.0,
    eps: Annotated[
        float,
        typer.Option(
            "--eps",
            help="Disturbance ratio eps = delta_max / v in [0, 1): plan with R0 (1 + eps)^2.",
        ),
    ] = 0.0,
    time_objective: Annotated[
        bool, typer.Option("--time", help="Minimise time (length / speed) instead of length.")
    ] = False,
    json_out: Annotated[bool, common.json_flag()] = False,
    plot: Annotated[
        pathlib.Path | None, common.plot_option("Draw the path (and candidates) to FILE.")
    ] = None,
) -> None:
    """Shortest Dubins path (dissertation 2.7) with the feasible radius of eq. 3.3 (--eps)."""
    from glideplan.planning import plan
    from glideplan.vehicles import DubinsCar

    plot = common.check_figure_file(plot)
    start_pose, goal_pose = common.parse_start_goal(start, goal)
    names = {"turn_radius": "--radius", "speed": "--speed", "speed/turn_radius": "--speed/--radius"}
    with common.flag_names(**names, disturbance_ratio="--eps", start="--start", goal="--goal"):
        vehicle = DubinsCar(speed=speed, turn_radius=radius)
        solution = common.solving(
            "planning (dubins)",
            lambda: plan(
                start_pose,
                goal_pose,
                vehicle,
                "time" if time_objective else "length",
                disturbance_ratio=eps,
            ),
        )
    common.emit_solution(solution, json_out, plot, plot_candidates=True)
