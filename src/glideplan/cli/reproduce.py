"""`glideplan reproduce`: regenerate the dissertation figures and tables this package covers.

Writes the files of each figure, `DIR/index.json` and `DIR/index.md` (rendered from the same
rows). index.json is `{"figures": {ID: {"title", "files", "status", "rows": [ROW, ...]}}}`,
ROW as `glideplan.figures.Comparison.to_dict()`. Exit 1 (one line naming them) when a
figure's computation failed; the other figures are still written.
"""

from __future__ import annotations

import os
import pathlib
import sys
import time
from collections import Counter
from dataclasses import dataclass
from typing import TYPE_CHECKING, Annotated, Any

import typer

from glideplan.cli.app import app
from glideplan.cli.common import flag_names
from glideplan.errors import InvalidParameterError

if TYPE_CHECKING:
    from glideplan.figures.registry import FigureReport, FigureSpec

COMPUTED = "computed"


@dataclass(frozen=True)
class FigureResult:
    """One figure's outcome: its report (None if it failed), status and time (s)."""

    spec: FigureSpec
    report: FigureReport | None
    status: str
    seconds: float


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


def _cell(value: object) -> str:
    if value is None:
        return "-"
    if isinstance(value, float):
        return f"{value:.6g}"
    return str(value).replace("|", "\\|")  # a literal bar inside a Markdown table cell


def index_json(results: list[FigureResult], out: pathlib.Path) -> dict[str, Any]:
    """The `index.json` document."""
    figures = {}
    for r in results:
        rep = r.report
        figures[r.spec.id] = {
            "title": r.spec.title,
            "files": _relative(rep.files, out) if rep else [],
            "status": r.status,
            "rows": [row.to_dict() for row in rep.rows] if rep else [],
        }
    return {"figures": figures}


def index_markdown(document: dict[str, Any], results: list[FigureResult]) -> str:
    """`index.md`, rendered from the rows of `index_json`."""
    counts = Counter(row["verdict"] for fig in document["figures"].values() for row in fig["rows"])
    lines = [
        "# glideplan reproduce",
        "",
        "Each figure or table of A. Wolek, *Optimal Paths in Gliding Flight* (2015) that this",
        "package regenerates, with our numbers beside the values printed in the dissertation.",
        "Verdicts are computed: numbers agree iff |ours - dissertation| <= tolerance (half a",
        "unit of the last printed digit unless stated), words iff equal; 'not printed' when",
        "the dissertation gives no value (an independent reference may still be shown).",
        "",
        f"Rows: {sum(counts.values())}; agrees {counts['agrees']}, differs "
        f"{counts['differs']}, not printed {counts['not printed']}.",
        "",
    ]
    for r in results:
        fig = document["figures"][r.spec.id]
        lines += [f"## {r.spec.id}: {r.spec.title}", "", f"*Dissertation:* {r.spec.dissertation}"]
        lines += ["", f"*Status:* {fig['status']} ({r.seconds:.1f} s)", ""]
        if fig["files"]:
            lines += ["Files: " + ", ".join(f"[{f}]({f})" for f in fig["files"]), ""]
            lines += [f"![{r.spec.id}]({f})\n" for f in fig["files"] if f.endswith(".png")]
        if fig["rows"]:
            lines += [
                "| quantity | unit | ours | dissertation | source | reference | reference "
                "source | tolerance | verdict | note |",
                "|---|---|---|---|---|---|---|---|---|---|",
            ]
            for row in fig["rows"]:
                cells = (
                    row["quantity"],
                    row["unit"],
                    row["ours"],
                    row["dissertation"],
                    row["dissertation_source"],
                    row["reference"],
                    row["reference_source"],
                    row["tolerance"],
                    f"**{row['verdict']}**" if row["verdict"] == "differs" else row["verdict"],
                    row["note"],
                )
                lines.append("| " + " | ".join(_cell(c) for c in cells) + " |")
            lines.append("")
        if r.report is not None and r.report.notes:
            lines += [r.report.notes, ""]
    return "\n".join(lines)


def _count_kinds(specs: list[FigureSpec]) -> str:
    """'1 figure and 2 tables', '3 figures', '0 figures' for these ids (fig... / table...)."""
    tables = sum(s.id.startswith("table") for s in specs)
    figures = len(specs) - tables
    parts = [
        f"{n} {kind}{'' if n == 1 else 's'}"
        for n, kind in ((figures, "figure"), (tables, "table"))
        if n
    ]
    return " and ".join(parts) or "0 figures"


def _selected(only: str | None) -> list[FigureSpec]:
    from glideplan.figures import figure_specs, get_figure

    specs = figure_specs()
    if only is None:
        return specs
    ids = [i.strip() for i in only.split(",") if i.strip()]
    if not ids:
        known = ", ".join(s.id for s in specs)
        raise InvalidParameterError("--only", only, f"is an empty list of ids (known: {known})")
    chosen = []
    for i in ids:
        with flag_names(only="--only", id="--only", figure="--only"):
            spec = get_figure(i)  # unknown ids: InvalidParameterError listing the known ones
        if spec not in chosen:
            chosen.append(spec)
    return chosen


def run_figures(
    specs: list[FigureSpec], out: pathlib.Path, *, full: bool = False, quiet: bool = False
) -> list[FigureResult]:
    """Run each figure; a figure that raises is recorded as failed, the others still run."""
    from rich.console import Console

    from glideplan.figures import run_figure

    console = Console(stderr=True, quiet=quiet)
    results = []
    for spec in specs:
        t0 = time.perf_counter()
        report: FigureReport | None
        with console.status(f"{spec.id}: {spec.title}"):
            try:
                report = run_figure(spec, out, full=full)
                status = COMPUTED
            except Exception as exc:  # a failed figure is reported, not hidden
                report = None
                status = f"failed: {type(exc).__name__}: {' '.join(str(exc).split())}"
        seconds = time.perf_counter() - t0
        results.append(FigureResult(spec, report, status, seconds))
        mark = "[green]done[/green]" if report else "[red]FAILED[/red]"
        console.print(f"{mark} {spec.id} ({seconds:.1f} s)")
    return results


@app.command("reproduce")
def reproduce(
    out: Annotated[
        pathlib.Path, typer.Option("--out", metavar="DIR", help="Output directory.")
    ] = pathlib.Path("out/reproduce"),
    only: Annotated[
        str | None,
        typer.Option(
            "--only", metavar="IDS", help="Comma-separated ids, e.g. fig3.1,table4.3 (see --list)."
        ),
    ] = None,
    full: Annotated[
        bool, typer.Option("--full", help="Full-size studies instead of the reduced defaults.")
    ] = False,
    list_ids: Annotated[bool, typer.Option("--list", help="List the figure ids and exit.")] = False,
) -> None:
    """Regenerate the dissertation's figures and tables into OUT, with index.json and index.md.

    The indexes put our numbers beside the dissertation's (computed verdicts). Exit 1 if a
    figure or table failed."""
    from glideplan.cli.common import check_output_dir, write_json
    from glideplan.figures import figure_specs, load_all

    load_all()
    if list_ids:
        for spec in figure_specs():
            typer.echo(f"{spec.id}\t{spec.title}")
        return
    specs = _selected(only)
    check_output_dir(out, "--out")
    out.mkdir(parents=True, exist_ok=True)
    results = run_figures(specs, out, full=full)
    document = index_json(results, out.resolve())
    write_json(document, out / "index.json")
    (out / "index.md").write_text(index_markdown(document, results))
    counts = Counter(row["verdict"] for fig in document["figures"].values() for row in fig["rows"])
    failed = [r for r in results if r.report is None]
    typer.echo(
        f"wrote {_count_kinds([r.spec for r in results if r.report is not None])}"
        + (f" of {_count_kinds([r.spec for r in results])}" if failed else "")
        + f" to {out}: {sum(counts.values())} rows, {counts['agrees']} agree, "
        f"{counts['differs']} differ, {counts['not printed']} not printed"
    )
    if failed:
        names = "; ".join(f"{r.spec.id} ({r.status.removeprefix('failed: ')})" for r in failed)
        print(f"glideplan: error: {len(failed)} figure(s) failed: {names}", file=sys.stderr)
        raise typer.Exit(1)
