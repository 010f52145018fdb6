"""`glideplan demo`: the main job — every planner on the dissertation's examples."""

from __future__ import annotations

import pathlib
import re
from typing import Annotated

import typer

from glideplan.cli.app import app
from glideplan.cli.common import write_json


def _slug(name: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", name.lower()).strip("-")


@app.command("demo")
def demo(
    out: Annotated[pathlib.Path, typer.Option("--out", help="Output directory.")] = pathlib.Path(
        "out"
    ),
    plots: Annotated[bool, typer.Option("--plots/--no-plots", help="Draw each path.")] = True,
) -> None:
    """Plan the dissertation's examples with every planner; write JSON, figures and a report."""
    from rich.console import Console
    from rich.table import Table

    from glideplan.demos import demo_cases, run_demo_case
    from glideplan.plotting import plot_solution, save_figure

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
            save_figure(plot_solution(sol, candidates=True), str(out / f"{slug}.png"))
        ref = f"{case.reference_cost:.4f} {case.reference_word}" if case.reference_cost else ""
        err = f"{sol.endpoint_error.max:.1e}" if sol.endpoint_error else "-"
        cost = f"{sol.cost:.4f}" if sol.ok else sol.status.value
        failures += not sol.ok
        table.add_row(case.name, sol.planner, sol.word, cost, ref, err, f"{res.seconds:.3f}")
        lines.append(
            f"| {case.name} | {case.source} | {sol.planner} | {sol.word} | {cost} | {ref} "
            f"| {err} | {res.seconds:.3f} |"
        )
    (out / "report.md").write_text("\n".join(lines) + "\n")
    console = Console()
    if not console.is_terminal:  # piped or logged: do not squeeze the table into 80 columns
        console = Console(width=140)
    console.print(table)
    typer.echo(f"wrote {out / 'report.md'}")
    if failures:
        raise typer.Exit(1)
