"""The explorer's downloads: the solution JSON (as `plan --json`), the path CSV, a PNG figure."""

from __future__ import annotations

import csv
import io
import math
from typing import Any

import numpy as np

__all__ = ["path_csv", "solution_json", "solution_png"]

_CSV_SAMPLES = 400


def solution_json(solution: Any) -> str:
    """`Solution.to_dict()` written by the library's JSON encoder (`glideplan.jsonio`): the
    object `plan --json` prints; without a solution, status `no_path` and why."""
    from glideplan.jsonio import to_json
    from glideplan.solution import Status

    if solution is None:
        return to_json({"status": Status.NO_PATH.value, "message": "no solution"}) + "\n"
    return to_json(solution.to_dict()) + "\n"


def path_csv(solution: Any) -> str:
    """The optimal path sampled at 400 even times plus every switch: t (s), s (m), x, y (m),
    heading_deg, speed (m/s), turn_rate (rad/s) and the cumulative cost of the objective."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    cols = ["t", "s", "x", "y", "heading_deg", "speed", "turn_rate", "cost"]
    writer.writerow(cols)
    path = getattr(solution, "path", None)
    if path is None:
        return out.getvalue()
    edges = np.cumsum([seg.duration for seg in path.segments])
    times = np.unique(np.concatenate([np.linspace(0.0, path.duration, _CSV_SAMPLES), edges]))
    smp = path.sample(times=times, objective=solution.objective)
    cost = smp.cost if smp.cost is not None else np.full_like(smp.t, math.nan)
    rows = np.column_stack(
        [smp.t, smp.s, smp.x, smp.y, np.degrees(smp.heading), smp.speed, smp.turn_rate, cost]
    )
    for row in rows:
        writer.writerow([f"{v:.12g}" for v in row])
    return out.getvalue()


def solution_png(solution: Any) -> bytes:
    """The solution drawn by `glideplan.plotting.plot_solution` (with its candidates), as PNG."""
    from matplotlib.figure import Figure  # no pyplot: thread-safe, no GUI backend

    fig = Figure(figsize=(7, 6))
    ax = fig.add_subplot()
    if solution is not None and solution.path is not None:
        from glideplan.plotting import plot_solution

        plot_solution(solution, ax, candidates=True)
    else:
        ax.text(0.5, 0.5, "no solution", ha="center", va="center", transform=ax.transAxes)
    from glideplan.plotting import save_figure

    buf = io.BytesIO()
    save_figure(fig, buf, crop=False)  # the library's one saver (its dpi and layout)
    return buf.getvalue()
