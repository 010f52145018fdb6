"""`glideplan demo`: the main job — every planner on the dissertation's examples."""

from __future__ import annotations

import pathlib
import re
from typing import Annotated, Any

import typer

from glideplan.cli.app import app
from glideplan.cli.common import check_output_dir, file_flag, write_json


def _slug(name: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


@app.command("demo")
def demo(
    out: Annotated[
        pathlib.Path, typer.Option("--out", metavar="DIR", help="Output directory.")
    ] = pathlib.Path(
        "out"
    ),
    plots: Annotated[bool, typer.Option("--plots/--no-plots", help="Draw each path.")] = True,
) -> None:
    """Plan the dissertation's examples with every planner; write JSON, figures and a report."""
    from rich.console import Console
    from rich.table import Table

    from glideplan.demos import demo_cases, run_demo_case
    from glideplan.plotting import plot_solution, save_figure

    check_output_dir(out, "--out")
    with file_flag("--out", out):
        out.mkdir(parents=True, exist_ok=True)
    table = Table(title="glideplan demo: the dissertation's examples")
    for col in ("example", "planner", "word", "cost", "reference", "endpoint err", "time [s]"):
        table.add_column(col, justify="right" if col not in ("example", "planner") else "left")
    lines = [
        "# glideplan demo report",
        "",
        "| example | source | planner | word | cost | reference | endpoint error | seconds |",
        "|---|---|---|---|---|---|---|---|",
    ]
    failures = 0
    for case in demo_cases():
        res = run_demo_case(case)
        sol = res.solution
        slug = _slug(case.name)
        write_json(sol.to_dict() | res.extra, out / f"{slug}.json")
        if plots and sol.path is not None:
            ax = plot_solution(sol, candidates=True, heading=f"{case.name} ({case.source})")
            save_figure(ax, str(out / f"{slug}.png"))
        ref = f"{case.reference_cost:.4f} {case.reference_word}" if case.reference_cost else ""
        err = f"{sol.endpoint_error.max:.1e}" if sol.endpoint_error else "-"
        cost = f"{sol.cost:.4f}" if sol.ok else sol.status.value
        failures += not sol.ok
        table.add_row(case.name, sol.planner, sol.word, cost, ref, err, f"{res.seconds:.3f}")
        lines.append(
            f"| {case.name} | {case.source} | {sol.planner} | {sol.word} | {cost} | {ref} "
            f"| {err} | {res.seconds:.3f} |"
        )
    row = _mission_example(out / "mission", plots)
    failures += not row["ok"]
    table.add_row(row["name"], row["planner"], row["word"], row["cost"], row["reference"],
                  row["error"], row["seconds"])
    lines.append(
        f"| {row['name']} | {row['source']} | {row['planner']} | {row['word']} | {row['cost']} "
        f"| {row['reference']} | {row['error']} | {row['seconds']} |"
    )
    lines += ["", f"Mission files (Slocum, Seaglider, QGC, GIS): {', '.join(row['files'])}"]
    (out / "report.md").write_text("\n".join(lines) + "\n")
    console = Console()
    if not console.is_terminal:  # piped or logged: do not squeeze the table into 80 columns
        console = Console(width=140)
    console.print(table)
    typer.echo(f"wrote {out / 'report.md'}")
    if failures:
        raise typer.Exit(1)


def _mission_example(out: pathlib.Path, plots: bool) -> dict[str, Any]:
    """Plan the shipped GPX survey route for a glider and export every vehicle/GIS file.

    The reference column is the best of the two heuristics (point at the next waypoint,
    bisector headings) with the same legs: the optimised headings must not be longer.
    """
    import time

    import numpy as np

    from glideplan.formats import ExportOptions, export_mission, parse_formats, read_route
    from glideplan.missions import (
        StillAirCost,
        bisector_headings,
        headings_cost,
        plan_mission,
        point_at_next_headings,
    )

    t0 = time.perf_counter()
    route_file = pathlib.Path(__file__).parents[1] / "missions" / "data" / "buzzards_bay.gpx"
    route = read_route(route_file)
    mission = plan_mission(route, speed=0.3, radius=300.0)
    files, legs = export_mission(mission, out, parse_formats(None),
                                 ExportOptions(acceptance_radius=100.0, name="buzzards_bay"))
    if plots:
        from glideplan.missions.plot import plot_mission
        from glideplan.plotting import save_figure

        save_figure(plot_mission(mission, legs), str(out / "mission.png"))
        files["plot"] = str(out / "mission.png")
    cost = StillAirCost(route.points, 300.0)
    best = min(headings_cost(cost, f(route.points, route.headings))[0]
               for f in (point_at_next_headings, bisector_headings))
    data = mission.to_dict() | {"files": files, "heuristic_best_m": best}
    write_json(data, out / "mission.json")
    errors = [leg.solution.endpoint_error.max for leg in mission.legs
              if leg.solution.endpoint_error is not None]
    paths = [p for v in files.values() for p in ([v] if isinstance(v, str) else v)]
    return {
        "name": "mission: GPX lawn-mower survey, 8 waypoints",
        "source": "missions/data/buzzards_bay.gpx; heading heuristics",
        "planner": "mission (dubins DP)",
        "word": " ".join(leg.solution.word for leg in mission.legs),
        "cost": f"{mission.total_length_m:.1f}",
        "reference": f"{best:.1f} heuristic",
        "error": f"{max(errors):.1e}" if errors else "-",
        "seconds": f"{time.perf_counter() - t0:.3f}",
        "ok": bool(mission.ok and mission.total_length_m <= best * (1 + 1e-9)
                   and np.isfinite(mission.total_length_m)),
        "files": [pathlib.Path(p).name for p in paths],
    }
