"""`glideplan demo`: the main job — every planner on the dissertation's examples, and the
products (route, mission, final glide, glide reach) through the one outcome contract."""

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
    """Plan the dissertation's examples with every planner, then run each product (a route,
    a mission, a final glide, a glide reach); write JSON, figures and a report."""
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
    product_lines, product_table, product_failures = _products(out, plots)
    lines += ["", *product_lines]
    failures += product_failures
    (out / "report.md").write_text("\n".join(lines) + "\n")
    console = Console()
    if not console.is_terminal:  # piped or logged: do not squeeze the table into 80 columns
        console = Console(width=140)
    console.print(table)
    console.print(product_table)
    typer.echo(f"wrote {out / 'report.md'}")
    if failures:
        raise typer.Exit(1)



def _products(out: pathlib.Path, plots: bool) -> tuple[list[str], Any, int]:
    """Run each product (route, mission, final glide, glide reach) through the outcome
    contract: the report's products section, the console table and the number that failed.

    A product fails when its status is not solved, its reference is not met, or it raises
    (the report then shows the exception, and the demo exits 1).
    """
    from rich.table import Table

    from glideplan.demos.products import PRODUCTS, available_products, run_product

    lines = [
        "## Products",
        "",
        "Each through the one outcome contract: `status`, `message`, `to_dict()` (the JSON "
        "written beside the figure) and `plot()`; the reference is what the answer must meet.",
        "",
        "| product | source | status | numbers | reference | check | figure | seconds |",
        "|---|---|---|---|---|---|---|---|",
    ]
    table = Table(title="glideplan demo: the products (one outcome contract)")
    for col in ("product", "status", "numbers", "reference", "check", "time [s]"):
        table.add_column(col, justify="right" if col == "time [s]" else "left")
    cases = available_products()
    failures = 0
    for case in cases:
        try:
            run = run_product(case, out / case.key, plots)
        except Exception as exc:  # shown in the report, and the demo fails
            why = " ".join(f"{type(exc).__name__}: {exc}".split())
            failures += 1
            table.add_row(case.name, "error", why, "", "FAILED", "")
            lines.append(f"| {case.name} | {case.source} | error | {why} | | FAILED | - | |")
            continue
        numbers = "; ".join(f"{k} {v}" for k, v in run.check.numbers)
        figure = f"![{case.key}]({case.key}/{case.key}.png)" if run.figure else "-"
        check = "met" if run.ok else "FAILED"
        failures += not run.ok
        table.add_row(case.name, run.status, numbers, run.check.reference, check,
                      f"{run.seconds:.3f}")
        lines.append(
            f"| {case.name} | {case.source} | {run.status} | {numbers} | {run.check.reference} "
            f"| {check} | {figure} | {run.seconds:.3f} |"
        )
        if run.check.files:
            lines.append(f"| | files: {', '.join(run.check.files)} | | | | | | |")
    missing = [p.name for p in PRODUCTS if p not in cases]
    if missing:
        lines += ["", f"Not run (not available in this build): {', '.join(missing)}."]
    return lines, table, failures
