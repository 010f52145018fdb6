"""`glideplan plan load-factor`: minimum altitude loss with speed and load-factor controls."""

from __future__ import annotations

import pathlib
from typing import TYPE_CHECKING, Annotated, Any

import typer

from glideplan.cli import common
from glideplan.cli.app import plan_app

if TYPE_CHECKING:
    from glideplan.pose import Pose
    from glideplan.solution import Solution
    from glideplan.vehicles.load_factor_glider import LoadFactorGlider


@plan_app.command("load-factor")
def plan_load_factor_command(
    goal: Annotated[
        common.PoseValues,
        common.goal_option("Goal pose X Y HEADING_DEG (nondimensional lengths V^2/g, degrees)."),
    ],
    start: Annotated[
        common.PoseValues, common.start_option("Start pose X Y HEADING_DEG.")
    ] = (0.0, 0.0, 0.0),
    l_over_d: Annotated[
        float, typer.Option("--l-over-d", help="Maximum lift-to-drag ratio (L/D)max.")
    ] = 30.0,
    v_min: Annotated[
        float, typer.Option("--v-min", help="Wings-level stall speed (units of V_md).")
    ] = 0.75,
    v_max: Annotated[float, typer.Option("--v-max", help="Maximum speed (units of V_md).")] = 2.0,
    n_max: Annotated[float, typer.Option("--n-max", help="Maximum load factor (> 1).")] = 2.0,
    scheme: Annotated[
        str, typer.Option("--scheme", help="Collocation: hermite-simpson or radau.")
    ] = "hermite-simpson",
    max_starts: Annotated[
        int, typer.Option("--max-starts", help="Initial guesses solved (cheapest first).")
    ] = 4,
    max_iterations: Annotated[
        int, typer.Option("--max-iterations", help="IPOPT iteration limit per solve.")
    ] = 1000,
    time_limit: Annotated[float | None, common.time_limit_flag()] = None,
    method: Annotated[
        str,
        typer.Option(
            "--method",
            help="direct (collocation, the default) or synthesis (extremals from tables of "
            "the canonical orbits; the direct method answers where it finds none).",
        ),
    ] = "direct",
    json_out: Annotated[bool, common.json_flag()] = False,
    plot: Annotated[
        pathlib.Path | None,
        common.plot_option("Draw controls, path and control set (Fig 6.11 style)."),
    ] = None,
) -> None:
    """Minimum altitude loss, speed and load-factor controls (6.8): direct method or synthesis.

    Defaults are the dissertation's example (6.21). `cost` is the nondimensional altitude
    loss; the JSON adds the control history (`controls`: s, v, n, bank_deg, label) and the
    arc classification (`arcs`: extremal locus, stall boundary, corner, wings level).
    """
    from glideplan.vehicles.load_factor_glider import LoadFactorGlider

    plot = common.check_figure_file(plot)
    start_pose, goal_pose = common.parse_start_goal(start, goal)
    names = {
        "l_over_d_max": "--l-over-d",
        "v_min": "--v-min",
        "v_max": "--v-max",
        "n_max": "--n-max",
        "scheme": "--scheme",
        "max_starts": "--max-starts",
        "max_iterations": "--max-iterations",
    }
    with common.flag_names(**names, start="--start", goal="--goal"):
        glider = LoadFactorGlider(l_over_d_max=l_over_d, v_min=v_min, v_max=v_max, n_max=n_max)
        solution = _solve(start_pose, goal_pose, glider, method, time_limit,
                          {"scheme": scheme, "max_starts": max_starts,
                           "max_iterations": max_iterations})

    def draw() -> None:
        assert plot is not None
        if "controls" in solution.extras:
            from glideplan.solution_figures import draw_load_factor

            draw_load_factor(solution, plot)
        else:  # no control history (start = goal): the path figure
            from glideplan.plotting import plot_solution, save_figure

            save_figure(plot_solution(solution), str(plot))

    try:  # the table first, then `wrote FILE` (or why nothing was drawn), as every command
        common.emit_solution(solution, json_out, None)
    finally:
        common.write_figure(plot, json_out, draw if solution.ok else None)


def _solve(start_pose: Pose, goal_pose: Pose, glider: LoadFactorGlider, method: str,
           time_limit: float | None, direct: dict[str, Any]) -> Solution:
    """`plan` by the synthesis or the direct method (its `direct` options and time limit)."""
    from glideplan.errors import InvalidParameterError
    from glideplan.planning import plan

    if method == "synthesis":
        return common.solving(
            "planning (load-factor, synthesis)",
            lambda: plan(start_pose, goal_pose, glider, "altitude", "synthesis"),
        )
    if method != "direct":
        raise InvalidParameterError("--method", method, "must be direct or synthesis")
    options = common.time_limit_option(glider, "altitude", "direct", time_limit)
    return common.solving(
        "planning (load-factor, direct method)",
        lambda: plan(start_pose, goal_pose, glider, "altitude", "direct", **direct, **options),
    )
