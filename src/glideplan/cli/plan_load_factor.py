"""`glideplan plan load-factor`: minimum altitude loss with speed and load-factor controls."""

from __future__ import annotations

import pathlib
from typing import Annotated

import typer

from glideplan.cli.app import plan_app
from glideplan.cli.common import (
    announce,
    check_figure_file,
    emit_solution,
    flag_names,
    parse_pose,
    print_warnings,
    solving,
    time_limit_option,
)


@plan_app.command("load-factor")
def plan_load_factor_command(
    goal: Annotated[
        tuple[float, float, float],
        typer.Option(
            "--goal",
            metavar="X Y HEADING_DEG",
            help="Goal pose X Y HEADING_DEG (nondimensional lengths V^2/g, degrees).",
            show_default=False,
        ),
    ],
    start: Annotated[
        tuple[float, float, float],
        typer.Option("--start", metavar="X Y HEADING_DEG", help="Start pose X Y HEADING_DEG."),
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
    time_limit: Annotated[
        float | None,
        typer.Option(
            "--time-limit",
            metavar="SECONDS",
            help="Stop the direct solver after SECONDS and report what it has (direct only).",
            show_default=False,
        ),
    ] = None,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
    plot: Annotated[
        pathlib.Path | None,
        typer.Option(
            "--plot", metavar="FILE", help="Draw controls, path and control set (Fig 6.11 style)."
        ),
    ] = None,
) -> None:
    """Minimum altitude loss, speed and load-factor controls, by the direct method (6.8).

    Defaults are the dissertation's example (6.21). `cost` is the nondimensional altitude
    loss; the JSON adds the control history (`controls`: s, v, n, bank_deg, label) and the
    arc classification (`arcs`: extremal locus, stall boundary, corner, wings level).
    """
    from glideplan.planning import plan
    from glideplan.vehicles.load_factor_glider import LoadFactorGlider

    plot = check_figure_file(plot)
    start_pose = parse_pose(start, "--start")
    goal_pose = parse_pose(goal, "--goal")
    names = {
        "l_over_d_max": "--l-over-d",
        "v_min": "--v-min",
        "v_max": "--v-max",
        "n_max": "--n-max",
        "scheme": "--scheme",
        "max_starts": "--max-starts",
        "max_iterations": "--max-iterations",
    }
    with flag_names(**names, start="--start", goal="--goal"):
        glider = LoadFactorGlider(l_over_d_max=l_over_d, v_min=v_min, v_max=v_max, n_max=n_max)
        options = time_limit_option(glider, "altitude", "direct", time_limit)
        solution = solving(
            "planning (load-factor, direct method)",
            lambda: plan(
                start_pose,
                goal_pose,
                glider,
                "altitude",
                "direct",
                scheme=scheme,
                max_starts=max_starts,
                max_iterations=max_iterations,
                **options,
            ),
        )
    if plot is not None and solution.ok:
        if "controls" in solution.extras:
            from glideplan.figures.ch6 import draw_solution

            draw_solution(solution, plot)
        else:  # no control history (start = goal): the path figure
            from glideplan.plotting import plot_solution, save_figure

            save_figure(plot_solution(solution), str(plot))
        announce(f"wrote {plot}", json_out)
    elif plot is not None:
        print_warnings([f"no path to draw: {plot} not written"])
    emit_solution(solution, json_out, None)
