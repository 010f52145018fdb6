"""`glideplan plan wind`: time-optimal paths in a known steady uniform wind or current."""

from __future__ import annotations

import math
import pathlib
from typing import Annotated

import typer

from glideplan.cli.app import plan_app
from glideplan.cli.common import (
    check_figure_file,
    emit_solution,
    flag_names,
    parse_pose,
    solving,
)


@plan_app.command("wind")
def plan_wind_command(
    goal: Annotated[
        tuple[float, float, float],
        typer.Option(
            "--goal",
            metavar="X Y HEADING_DEG",
            help="Goal pose over ground X Y HEADING_DEG (m, m, degrees).",
            show_default=False,
        ),
    ],
    speed: Annotated[float, typer.Option("--speed", help="Air- (water-) relative speed v (m/s).")],
    radius: Annotated[
        float, typer.Option("--radius", help="Minimum turn radius R0 in the air frame (m).")
    ],
    wind: Annotated[
        tuple[float, float],
        typer.Option(
            "--wind",
            metavar="SPEED DIRECTION_DEG",
            help="Wind SPEED (m/s) and DIRECTION_DEG it blows towards (counter-clockwise from +x).",
            show_default=False,
        ),
    ],
    start: Annotated[
        tuple[float, float, float],
        typer.Option(
            "--start", metavar="X Y HEADING_DEG", help="Start pose X Y HEADING_DEG (m, m, degrees)."
        ),
    ] = (0.0, 0.0, 0.0),
    eps: Annotated[
        float,
        typer.Option(
            "--eps",
            help="Bound on an extra unknown disturbance, eps = delta_max / v: plan with "
            "R0 (1 + eps)^2 in the air frame (Corollary A.2; needs w + eps v < v).",
        ),
    ] = 0.0,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    plot: Annotated[
        pathlib.Path | None,
        typer.Option("--plot", metavar="FILE", help="Draw the ground path to FILE."),
    ] = None,
) -> None:
    """Time-optimal convected Dubins path in a steady wind (dissertation 3.2, appendix A).

    The cost is the flight time (s); the path is trochoidal arcs and straights over ground.
    """
    from glideplan.errors import InvalidParameterError
    from glideplan.planning import plan
    from glideplan.validation import check_finite, check_in_range, check_nonnegative, check_positive
    from glideplan.vehicles import DubinsCarInWind

    plot = check_figure_file(plot)
    speed = check_positive("--speed", speed)
    w = check_nonnegative("--wind SPEED", wind[0])
    direction = math.radians(check_finite("--wind DIRECTION_DEG", wind[1]))
    eps = check_in_range("--eps", eps, 0.0, 1.0, high_open=True)
    if w + eps * speed >= speed:
        raise InvalidParameterError(
            "--wind", w, f"wind speed + eps * speed must be < speed ({w:g} + {eps:g} * {speed:g})"
        )
    start_pose, goal_pose = parse_pose(start, "--start"), parse_pose(goal, "--goal")
    names = {"turn_radius": "--radius", "speed": "--speed", "speed/turn_radius": "--speed/--radius"}
    with flag_names(**names, wind_speed="--wind", start="--start", goal="--goal"):
        vehicle = DubinsCarInWind(speed, radius, w, direction)
        solution = solving(
            "planning (wind)",
            lambda: plan(start_pose, goal_pose, vehicle, disturbance_ratio=eps),
        )
    emit_solution(solution, json_out, plot, plot_candidates=False)
