"""`glideplan plan wind`: time-optimal paths in a known steady uniform wind or current."""

from __future__ import annotations

import math
import pathlib
from typing import Annotated

import typer

from glideplan.cli import common
from glideplan.cli.app import plan_app


@plan_app.command("wind")
def plan_wind_command(
    goal: Annotated[
        common.PoseValues,
        common.goal_option("Goal pose over ground X Y HEADING_DEG (m, m, degrees)."),
    ],
    speed: Annotated[float, typer.Option("--speed", help="Air- (water-) relative speed v (m/s).")],
    radius: Annotated[
        float, typer.Option("--radius", help="Minimum turn radius R0 in the air frame (m).")
    ],
    wind: Annotated[
        tuple[float, float],
        typer.Option(
            "--wind",
            metavar="SPEED FROM_DEG",
            help="Wind SPEED (m/s) and the compass direction FROM_DEG it blows FROM (degrees "
            "clockwise from +y, north), as every --wind; e.g. 0.3 270 blows towards +x.",
            show_default=False,
        ),
    ],
    start: Annotated[
        common.PoseValues, common.start_option("Start pose X Y HEADING_DEG (m, m, degrees).")
    ] = (0.0, 0.0, 0.0),
    eps: Annotated[
        float,
        typer.Option(
            "--eps",
            help="Bound on an extra unknown disturbance, eps = delta_max / v: plan with "
            "R0 (1 + eps)^2 in the air frame (Corollary A.2; needs w + eps v < v).",
        ),
    ] = 0.0,
    json_out: Annotated[bool, common.json_flag()] = False,
    plot: Annotated[
        pathlib.Path | None, common.plot_option("Draw the ground path to FILE.")
    ] = None,
) -> None:
    """Time-optimal convected Dubins path in a steady wind (dissertation 3.2, appendix A).

    The cost is the flight time (s); the path is trochoidal arcs and straights over ground.
    """
    from glideplan.errors import InvalidParameterError
    from glideplan.planning import plan
    from glideplan.units import wind_from_compass
    from glideplan.validation import check_in_range, check_physical
    from glideplan.vehicles import DubinsCarInWind

    plot = common.check_figure_file(plot)
    speed = check_physical("--speed", speed, "speed")
    check_physical("--radius", radius, "turn_radius")
    vector = wind_from_compass(wind[0], wind[1], param="--wind")  # the compass edge
    w = math.hypot(*vector)
    eps = check_in_range("--eps", eps, 0.0, 1.0, high_open=True)
    if w + eps * speed >= speed:
        raise InvalidParameterError(
            "--wind", w, f"wind speed + eps * speed must be < speed ({w:g} + {eps:g} * {speed:g})"
        )
    start_pose, goal_pose = common.parse_start_goal(start, goal)
    names = {"turn_radius": "--radius", "speed": "--speed", "speed/turn_radius": "--speed/--radius"}
    with common.flag_names(**names, wind="--wind", start="--start", goal="--goal"):
        vehicle = DubinsCarInWind(speed, radius, wind=vector)
        solution = common.solving(
            "planning (wind)",
            lambda: plan(start_pose, goal_pose, vehicle, disturbance_ratio=eps),
        )
    common.emit_solution(solution, json_out, plot, plot_candidates=False)
