"""`glideplan plan min-altitude`: minimum altitude loss with a quadratic glide polar (ch. 5)."""

from __future__ import annotations

import pathlib
from typing import TYPE_CHECKING, Annotated

import typer

from glideplan.cli import common
from glideplan.cli.app import plan_app
from glideplan.errors import InvalidParameterError

if TYPE_CHECKING:
    from glideplan.solution import Solution
    from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

VEHICLES = ("dg1001m",)
METHODS = ("synthesis", "direct")


# plan_min_altitude_command's options (module level keeps the command itself short)
_PlanMinAltitudeGoal = Annotated[
    common.PoseValues,
    common.goal_option(
        "Goal pose X Y HEADING_DEG (m, or units of R_stf with --normalized; degrees)."
    ),
]
_PlanMinAltitudeStart = Annotated[
    common.PoseValues, common.start_option("Start pose X Y HEADING_DEG (same units as --goal).")
]
_PlanMinAltitudeVehicle = Annotated[
    str | None,
    typer.Option(
        "--vehicle",
        help="Preset glider: dg1001m (section 5.9). The default when --polar is not given.",
    ),
]
_PlanMinAltitudePolar = Annotated[
    tuple[float, float, float] | None,
    typer.Option(
        "--polar",
        metavar="A B C",
        help="Sink-rate polar w = A v^2 + B v + C in SI: A (s/m), B (-), C (m/s); "
        "needs --v-stall, --v-max and --u-max.",
        show_default=False,
    ),
]
_PlanMinAltitudeVStall = Annotated[
    float | None, typer.Option("--v-stall", help="Stall speed (m/s), with --polar.")
]
_PlanMinAltitudeVMax = Annotated[
    float | None, typer.Option("--v-max", help="Maximum speed (m/s), with --polar.")
]
_PlanMinAltitudeUMax = Annotated[
    float | None, typer.Option("--u-max", help="Maximum turn rate (rad/s), with --polar.")
]
_PlanMinAltitudeNormalized = Annotated[
    bool,
    typer.Option(
        "--normalized", help="Read X and Y of --goal/--start in units of R_stf = v_stf/u_max."
    ),
]
_PlanMinAltitudeMethod = Annotated[
    str, typer.Option("--method", help="synthesis (default) or direct (collocation + IPOPT).")
]
_PlanMinAltitudeJsonOut = Annotated[
    bool,
    typer.Option(
        "--json",
        help="Print one JSON object (cost = altitude loss in m; dubins_cost; profile).",
    ),
]
_PlanMinAltitudePlot = Annotated[
    pathlib.Path | None,
    common.plot_option("Draw the candidates and the control history to FILE."),
]


@plan_app.command("min-altitude")
def plan_min_altitude_command(
    goal: _PlanMinAltitudeGoal,
    start: _PlanMinAltitudeStart = (0.0, 0.0, 0.0),
    vehicle: _PlanMinAltitudeVehicle = None,
    polar: _PlanMinAltitudePolar = None,
    v_stall: _PlanMinAltitudeVStall = None,
    v_max: _PlanMinAltitudeVMax = None,
    u_max: _PlanMinAltitudeUMax = None,
    normalized: _PlanMinAltitudeNormalized = False,
    method: _PlanMinAltitudeMethod = "synthesis",
    time_limit: Annotated[float | None, common.time_limit_flag()] = None,
    json_out: _PlanMinAltitudeJsonOut = False,
    plot: _PlanMinAltitudePlot = None,
) -> None:
    """Minimum-altitude-loss path of a glider with a quadratic polar (dissertation ch. 5).

    The JSON adds `dubins_cost` (altitude loss of the Dubins path flown at v_stf with radius
    R_stf, m), `improvement` (m), `length_unit` (R_stf, m) and `profile` (time, arc length,
    pose, speed, turn rate and cumulative altitude loss along the path).
    """
    from glideplan.planning import plan
    from glideplan.pose import Pose

    if method not in METHODS:
        raise InvalidParameterError("--method", method, f"must be one of {', '.join(METHODS)}")
    plot = common.check_figure_file(plot)
    with common.flag_names(**_POLAR_FLAGS):
        glider = _glider(vehicle, polar, v_stall, v_max, u_max)
    start_pose, goal_pose = common.parse_start_goal(start, goal)
    if normalized:
        k = glider.radius_stf
        start_pose = Pose(start_pose.x * k, start_pose.y * k, start_pose.heading)
        goal_pose = Pose(goal_pose.x * k, goal_pose.y * k, goal_pose.heading)
    with common.flag_names(start="--start", goal="--goal"):
        options = common.time_limit_option(glider, "altitude", method, time_limit)
        solution = common.solving(
            f"planning (min-altitude, {method})",
            lambda: plan(start_pose, goal_pose, glider, "altitude", method, **options),
        )
    extra = _extras(solution, glider)

    def draw() -> None:
        assert plot is not None
        from glideplan.solution_figures import draw_min_altitude

        draw_min_altitude(solution, plot)

    drawable = solution.ok and solution.path is not None
    try:  # the table first, then `wrote FILE` (or why nothing was drawn), as every command
        common.emit_solution(solution, json_out, None, extra=extra)
    finally:
        common.write_figure(plot, json_out, draw if drawable else None)


#: The glider's parameter names -> the options the user gave (errors name the option).
_POLAR_FLAGS = {
    "a": "--polar A",
    "b": "--polar B",
    "c": "--polar C",
    "v_stall": "--v-stall",
    "v_max": "--v-max",
    "u_max": "--u-max",
    "v_stall/u_max": "--v-stall/--u-max",
    "v_max/u_max": "--v-max/--u-max",
}


def _extras(solution: Solution, glider: QuadraticPolarGlider) -> dict[str, object]:
    """What the JSON adds: the length unit R_stf (m); when solved, the flight profile and the
    improvement (m) on the Dubins path flown at v_stf."""
    from glideplan.planners.min_altitude import flight_profile

    extra: dict[str, object] = {"length_unit": glider.radius_stf}
    if solution.ok and solution.path is not None:
        extra["profile"] = flight_profile(solution.path)
        ref = solution.extras.get("dubins_cost")
        if isinstance(ref, float):
            extra["improvement"] = ref - solution.cost
    return extra


def _glider(
    vehicle: str | None,
    polar: tuple[float, float, float] | None,
    v_stall: float | None,
    v_max: float | None,
    u_max: float | None,
):
    from glideplan.vehicles import QuadraticPolarGlider, dg1001m

    if polar is None:
        extras = {"--v-stall": v_stall, "--v-max": v_max, "--u-max": u_max}
        given = [k for k, v in extras.items() if v is not None]
        if given:
            raise InvalidParameterError(given[0], extras[given[0]], "is only used with --polar")
        name = (vehicle or "dg1001m").lower()
        if name not in VEHICLES:
            raise InvalidParameterError(
                "--vehicle", vehicle, f"must be one of {', '.join(VEHICLES)}"
            )
        return dg1001m()
    if vehicle is not None:
        raise InvalidParameterError(
            "--vehicle", vehicle, "give either --vehicle or --polar, not both"
        )
    if v_stall is None or v_max is None or u_max is None:
        needed = {"--v-stall": v_stall, "--v-max": v_max, "--u-max": u_max}
        missing = [name for name, value in needed.items() if value is None]
        raise InvalidParameterError(missing[0], None, "is needed with --polar")
    a, b, c = polar
    return QuadraticPolarGlider(a, b, c, v_stall, v_max, u_max)
