"""`glideplan reproduce`: regenerate the dissertation figures and tables this package covers."""

from __future__ import annotations

import os
import pathlib
import time
from typing import Annotated

import typer

from glideplan.cli.app import app
from glideplan.cli.common import write_json


def _relative(files: tuple[str, ...], out: pathlib.Path) -> list[str]:
    """File names relative to the output directory, so the index survives being moved."""
    rel = []
    for f in files:
        p = pathlib.Path(f)
        if not p.is_absolute() and (out / p).exists():
            rel.append(str(p))  # already relative to the output directory
        else:  # absolute, or relative to the working directory
            rel.append(os.path.relpath(p.resolve(), out))
    return rel


def _index_markdown(results: list[tuple[object, object, float]], out: pathlib.Path) -> str:
    lines = [
        "# glideplan reproduce",
        "",
        "Each figure or table of A. Wolek, *Optimal Paths in Gliding Flight* (2015) that this",
        "package regenerates, with our numbers next to the dissertation's.",
        "",
    ]
    for spec, report, seconds in results:
        lines += [f"## {spec.id}: {spec.title}", "", f"*Dissertation:* {spec.dissertation}", ""]
        files = _relative(report.files, out)
        if files:
            lines.append("Files: " + ", ".join(f"[{f}]({f})" for f in files))
            lines.append("")
            for f in files:
                if f.endswith(".png"):
                    lines += [f"![{spec.id}]({f})", ""]
        if report.rows:
            lines += ["| quantity | glideplan | dissertation | note |", "|---|---|---|---|"]
            for r in report.rows:
                lines.append(f"| {r.quantity} | {r.ours} | {r.dissertation} | {r.note} |")
            lines.append("")
        if report.notes:
            lines += [report.notes, ""]
        lines += [f"*({seconds:.1f} s)*", ""]
    return "\n".join(lines)


@app.command("reproduce")
def reproduce(
    out: Annotated[pathlib.Path, typer.Option("--out", help="Output directory.")] = pathlib.Path(
        "out/reproduce"
    ),
    only: Annotated[
        str | None, typer.Option("--only", help="Comma-separated ids, e.g. fig3.1,table4.3.")
    ] = None,
    full: Annotated[
        bool, typer.Option("--full", help="Full-size studies instead of the reduced defaults.")
    ] = False,
    list_ids: Annotated[bool, typer.Option("--list", help="List the figure ids and exit.")] = False,
) -> None:
    """Regenerate figures and tables into OUT, with index.md beside the dissertation's numbers."""
    from rich.console import Console

    from glideplan.figures import figure_specs, get_figure, load_all, run_figure

    load_all()
    if list_ids:
        for spec in figure_specs():
            typer.echo(f"{spec.id}\t{spec.title}")
        return
    specs = [get_figure(i) for i in only.split(",") if i.strip()] if only else figure_specs()
    console = Console(stderr=True)
    results = []
    for spec in specs:
        t0 = time.perf_counter()
        with console.status(f"{spec.id}: {spec.title}"):
            report = run_figure(spec, out, full=full)
        results.append((spec, report, time.perf_counter() - t0))
        console.print(f"[green]done[/green] {spec.id} ({time.perf_counter() - t0:.1f} s)")
    (out / "index.md").write_text(_index_markdown(results, out.resolve()))
    write_json(
        {
            spec.id: {
                "title": spec.title,
                "files": _relative(rep.files, out.resolve()),
                "rows": [r.__dict__ for r in rep.rows],
                "seconds": sec,
            }
            for spec, rep, sec in results
        },
        out / "index.json",
    )
    typer.echo(f"wrote {len(results)} figure(s) and {out / 'index.md'}")
