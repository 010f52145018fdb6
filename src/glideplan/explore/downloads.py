"""The explorer's downloads: the solution JSON (as `plan --json`), the path CSV, a PNG figure."""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Mapping
from typing import Any

import numpy as np

__all__ = ["DownloadFiles", "download_button", "path_csv", "solution_json", "solution_png"]


def download_button(callback: Callable[[], Any], filename: str, label: str) -> Any:
    """A download button that builds the file `filename` on click (not embedded in the page)."""
    import panel as pn

    return pn.widgets.FileDownload(
        callback=callback, filename=filename, label=label, color="primary", width=92, embed=False
    )


_CSV_SAMPLES = 400


def _message(errors: Mapping[str, str] | None) -> str:
    """The page's messages as one line ('; '-joined, each as shown under its input)."""
    return "; ".join(v for v in (errors or {}).values() if v)


def solution_json(solution: Any, errors: Mapping[str, str] | None = None) -> str:
    """`Solution.to_dict()` written by the library's JSON encoder (`glideplan.jsonio`): the
    object `plan --json` prints; without a solution (refused input), no status
    (`results.no_outcome_dict`) and why: "message" (the page's messages, one line) and
    "errors" (by input name; "" for the page's own)."""
    from glideplan.jsonio import to_json
    from glideplan.results import no_outcome_dict

    if solution is None:
        return to_json(no_outcome_dict(_message(errors) or "no solution", errors or {})) + "\n"
    return to_json(solution.to_dict()) + "\n"


def path_csv(solution: Any, errors: Mapping[str, str] | None = None) -> str:
    """The optimal path sampled at 400 even times plus every switch: t (s), s (m), x, y (m),
    heading_deg, speed (m/s), turn_rate (rad/s) and the cumulative cost of the objective.

    Without a path: one column `error` with the page's message (a CSV reader reads it)."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    if getattr(solution, "path", None) is None:
        writer.writerow(["error"])
        writer.writerow([_message(errors) or "no solution"])
        return out.getvalue()
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


def solution_png(solution: Any, errors: Mapping[str, str] | None = None) -> bytes:
    """The solution drawn by `glideplan.plotting.plot_solution` (with its candidates), as PNG;
    without one, the page's message."""
    from matplotlib.figure import Figure  # no pyplot: thread-safe, no GUI backend

    fig = Figure(figsize=(7, 6))
    ax = fig.add_subplot()
    if solution is not None and solution.path is not None:
        from glideplan.plotting import plot_solution

        plot_solution(solution, ax, candidates=True)
    else:
        import textwrap

        text = "no solution\n" + textwrap.fill(_message(errors), 60)
        ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, wrap=True)
        ax.set_axis_off()
    from glideplan.plotting import save_figure

    buf = io.BytesIO()
    save_figure(fig, buf, crop=False)  # the library's one saver (its dpi and layout)
    return buf.getvalue()


class DownloadFiles:
    """The download buttons' files of a page showing `view` (a `solve.View`, or None): the
    solution JSON (as `plan --json`), the path CSV and the figure PNG, each carrying the
    shown state's messages when there is no solution."""

    view: Any

    def _problem(self) -> tuple[Any, dict[str, str]]:
        """The shown solution and the messages of the shown state (for the downloads)."""
        if self.view is None:
            return None, {"": "no answer yet"}
        errors = dict(self.view.errors)
        if self.view.solution is None and not errors:
            errors[""] = self.view.status or "no solution"
        return self.view.solution, errors

    def _json_file(self) -> io.StringIO:
        solution, errors = self._problem()
        return io.StringIO(solution_json(solution, errors))

    def _csv_file(self) -> io.StringIO:
        solution, errors = self._problem()
        return io.StringIO(path_csv(solution, errors))

    def _png_file(self) -> io.BytesIO:
        solution, errors = self._problem()
        return io.BytesIO(solution_png(solution, errors))
