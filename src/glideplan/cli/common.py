"""Helpers shared by the command modules: pose parsing, solution output, figures."""

from __future__ import annotations

import json
import math
import pathlib
from typing import Any

import numpy as np
import typer

from glideplan.errors import InvalidParameterError, PlanningError
from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.validation import check_finite

__all__ = ["emit_solution", "json_default", "parse_pose", "print_json", "write_json"]


def parse_pose(values: list[float] | tuple[float, ...] | None, name: str) -> Pose:
    """X Y HEADING_DEG from the command line to a `Pose` (heading in radians)."""
    if values is None:
        return Pose(0.0, 0.0, 0.0)
    if len(values) != 3:
        raise InvalidParameterError(name, values, "needs three numbers: X Y HEADING_DEG")
    x, y, h = (check_finite(f"{name} {c}", v) for c, v in zip("xyh", values, strict=True))
    return Pose(x, y, math.radians(h))


def json_default(obj: Any) -> Any:
    """Make NumPy scalars and arrays JSON-serialisable (non-finite floats become null)."""
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, np.generic):
        return obj.item()
    if hasattr(obj, "to_dict"):
        return obj.to_dict()
    if hasattr(obj, "value"):
        return obj.value
    raise TypeError(f"cannot serialise {type(obj).__name__}")


def _clean(obj: Any) -> Any:
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_clean(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return _clean(obj.tolist())
    if isinstance(obj, np.generic):
        return _clean(obj.item())
    return obj


def to_json(data: Any) -> str:
    return json.dumps(_clean(data), default=json_default, indent=2)


def print_json(data: Any) -> None:
    typer.echo(to_json(data))


def write_json(data: Any, filename: pathlib.Path | str) -> None:
    pathlib.Path(filename).write_text(to_json(data) + "\n")


def emit_solution(
    solution: Solution,
    json_out: bool,
    plot_file: pathlib.Path | None,
    *,
    extra: dict[str, Any] | None = None,
    plot_candidates: bool = False,
) -> None:
    """Print the solution (JSON or a table), draw it if asked, and fail when not solved."""
    data = solution.to_dict() | (extra or {})
    if json_out:
        print_json(data)
    else:
        from rich.console import Console
        from rich.table import Table

        table = Table(title=f"{solution.planner} ({solution.objective})")
        table.add_column("quantity")
        table.add_column("value", justify="right")
        table.add_row("status", solution.status.value)
        if solution.ok:
            err = solution.endpoint_error
            table.add_row("cost", f"{solution.cost:.6g}")
            table.add_row("word", solution.word)
            table.add_row("family", solution.family)
            table.add_row("length", f"{data['length']:.6g}")
            table.add_row("duration", f"{data['duration']:.6g}")
            table.add_row("endpoint error", f"{err.max:.2e}" if err else "n/a")
            table.add_row("candidates", str(len(solution.candidates)))
        Console().print(table)
    if plot_file is not None and solution.path is not None:
        from glideplan.plotting import plot_solution, save_figure

        save_figure(plot_solution(solution, candidates=plot_candidates), str(plot_file))
    if not solution.ok:
        raise PlanningError(f"{solution.planner}: {solution.status.value}: {solution.message}")
