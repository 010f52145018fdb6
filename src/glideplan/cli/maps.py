"""`glideplan map partition|tradespace`: Dubins partition and tradespace maps (Figs 3.1, 3.2)."""

from __future__ import annotations

import csv
import math
import pathlib
from typing import Annotated, Any

import numpy as np
import typer

from glideplan.cli.app import map_app
from glideplan.cli.common import check_figure_file, flag_names
from glideplan.errors import InvalidParameterError

HeadingOpt = Annotated[
    float, typer.Option("--heading", help="Final heading psi1 (degrees).", show_default=False)
]
ExtentOpt = Annotated[
    float, typer.Option("--extent", help="Half-width L of the grid [-L, L]^2 (units of R0).")
]
GridOpt = Annotated[int, typer.Option("--n", help="Grid points per axis (n x n goals).")]
OutOpt = Annotated[
    pathlib.Path | None,
    typer.Option("--out", metavar="FILE", help="Figure file (PNG, PDF, SVG)."),
]
DataOpt = Annotated[
    pathlib.Path | None,
    typer.Option("--data", metavar="FILE", help="Grid data file (.csv or .npz)."),
]
SchedulerOpt = Annotated[
    str | None,
    typer.Option("--scheduler", help="Dask scheduler address (default: local processes)."),
]
ProcessesOpt = Annotated[
    int | None, typer.Option("--processes", help="Local worker processes (1: in-process).")
]


_FLAGS = {"n": "--n", "extent": "--extent", "eps": "--eps", "disturbance_ratio": "--eps"}


def _check_data_file(path: pathlib.Path | None) -> None:
    if path is not None and path.suffix.lower() not in (".csv", ".npz"):
        raise InvalidParameterError("--data", str(path), "must end in .csv or .npz")
    if path is not None and not (path.parent if str(path.parent) else pathlib.Path(".")).is_dir():
        raise InvalidParameterError("--data", str(path), "its directory does not exist")


def _batch_options(scheduler: str | None, processes: int | None) -> dict[str, Any]:
    opts: dict[str, Any] = {"progress": True, "description": "map"}
    if scheduler is not None:
        opts["scheduler"] = scheduler
    if processes is not None:
        if processes < 1:
            raise InvalidParameterError("--processes", processes, "must be >= 1")
        opts["processes"] = processes
    return opts


def _write_data(path: pathlib.Path, columns: dict[str, np.ndarray], meta: dict[str, Any]) -> None:
    if path.suffix.lower() == ".npz":
        arrays: dict[str, Any] = {**columns, **{k: np.asarray(v) for k, v in meta.items()}}
        np.savez_compressed(path, **arrays)
        return
    names = list(columns)
    with path.open("w", newline="") as fh:
        fh.write("".join(f"# {k} = {v}\n" for k, v in meta.items()))
        writer = csv.writer(fh)
        writer.writerow(names)
        for row in zip(*(columns[k].tolist() for k in names), strict=True):
            writer.writerow(
                [f"{v:.12g}" if isinstance(v, float) and math.isfinite(v) else v for v in row]
            )


def _save_plot(ax: Any, path: pathlib.Path) -> None:
    from glideplan.plotting import save_figure

    save_figure(ax, str(path))


@map_app.command("partition")
def partition_command(
    heading: HeadingOpt,
    eps: Annotated[
        float, typer.Option("--eps", help="Plan with R0 (1 + eps)^2 (eps in [0, 1)).")
    ] = 0.0,
    extent: ExtentOpt = 6.0,
    n: GridOpt = 121,
    out: OutOpt = None,
    data: DataOpt = None,
    scheduler: SchedulerOpt = None,
    processes: ProcessesOpt = None,
) -> None:
    """Partition of the plane by optimal Dubins word for final heading psi1 (Fig 3.1)."""
    _run_map("partition", heading, eps, extent, n, out, data, scheduler, processes)


@map_app.command("tradespace")
def tradespace_command(
    heading: HeadingOpt,
    eps: Annotated[float, typer.Option("--eps", help="Disturbance ratio eps in [0, 1).")] = 0.25,
    extent: ExtentOpt = 6.0,
    n: GridOpt = 121,
    out: OutOpt = None,
    data: DataOpt = None,
    scheduler: SchedulerOpt = None,
    processes: ProcessesOpt = None,
) -> None:
    """Ratio T = d_feasible / d_optimal of path lengths with R0 (1 + eps)^2 and R0 (Fig 3.2)."""
    _run_map("tradespace", heading, eps, extent, n, out, data, scheduler, processes)


def _run_map(
    kind: str,
    heading: float,
    eps: float,
    extent: float,
    n: int,
    out: pathlib.Path | None,
    data: pathlib.Path | None,
    scheduler: str | None,
    processes: int | None,
) -> None:
    """Check the options, compute the `kind` map (partition, tradespace), print and write it."""
    from rich.console import Console

    from glideplan.studies.maps import partition_map, tradespace_map

    _check_data_file(data)
    check_figure_file(out, "--out")
    psi1 = math.radians(_finite("--heading", heading))
    with flag_names(**_FLAGS):
        batch = _batch_options(scheduler, processes)
        if kind == "partition":
            grid_map: Any = partition_map(psi1, extent, n, eps, **batch)
        else:
            grid_map = tradespace_map(psi1, eps, extent, n, **batch)
    grid = f"heading {heading:g} deg, eps {eps:g}, {n}x{n} grid"
    if kind == "partition":
        table = _partition_table(grid_map, f"Dubins partition, {grid}")
    else:
        table = _tradespace_table(grid_map, f"Tradespace T, {grid}")
    Console().print(table)
    meta = {"map": kind, "heading_rad": psi1, "eps": eps, "extent": extent, "n": n}
    _write_outputs(grid_map, meta, data, out, f"plot_{kind}")


def _partition_table(pmap: Any, title: str) -> Any:
    """The share of the grid each optimal word holds (a Rich table)."""
    from rich.table import Table

    table = Table(title=title)
    table.add_column("optimal word(s)")
    table.add_column("share of grid", justify="right")
    for label, frac in sorted(pmap.fractions().items(), key=lambda kv: -kv[1]):
        table.add_row(label, f"{100 * frac:.2f} %")
    return table


def _tradespace_table(tmap: Any, title: str) -> Any:
    """Minimum, median and maximum of the ratio T and the shares above 2 and 5 (a Rich table)."""
    from rich.table import Table

    ratio = tmap.ratio[np.isfinite(tmap.ratio)]
    table = Table(title=title)
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_row("min T", f"{ratio.min():.4f}")
    table.add_row("median T", f"{np.median(ratio):.4f}")
    table.add_row("max T", f"{ratio.max():.4f}")
    table.add_row("share with T > 2", f"{100 * np.mean(ratio > 2):.2f} %")
    table.add_row("share with T > 5 (truncated)", f"{100 * np.mean(ratio > 5):.2f} %")
    return table


def _write_outputs(
    grid_map: Any,
    meta: dict[str, Any],
    data: pathlib.Path | None,
    out: pathlib.Path | None,
    plotter: str,
) -> None:
    """Write the grid (CSV/NPZ) and the figure drawn by `map_plots.<plotter>` when asked."""
    if data is not None:
        _write_data(data, grid_map.columns(), meta)
        typer.echo(f"wrote {data}")
    if out is not None:
        from glideplan.studies import map_plots

        _save_plot(getattr(map_plots, plotter)(grid_map), out)
        typer.echo(f"wrote {out}")


def _finite(name: str, value: float) -> float:
    from glideplan.validation import check_finite

    return check_finite(name, value)
