"""Matplotlib drawing of paths and solutions (Matplotlib is imported inside functions)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from glideplan.path import Path
    from glideplan.solution import Solution

__all__ = ["plot_path", "plot_solution", "save_figure"]


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=(6, 6))
    return ax


def plot_path(
    path: Path,
    ax: Any = None,
    *,
    switch_markers: bool = True,
    pose_markers: bool = True,
    n: int = 400,
    **line_kwargs: Any,
) -> Any:
    """Draw a path: the track, switching points (open circles) and boundary poses (filled)."""
    ax = _axes(ax)
    smp = path.sample(n=max(n, 50 * len(path.segments)))
    (line,) = ax.plot(smp.x, smp.y, **({"lw": 1.8} | line_kwargs))
    colour = line.get_color()
    if switch_markers and len(path.segments) > 1:
        pts = np.array([[s.start.x, s.start.y] for s in path.segments[1:]])
        ax.plot(pts[:, 0], pts[:, 1], "o", mfc="none", mec=colour, ms=6)
    if pose_markers:
        for p in (path.start, path.end):
            ax.plot(p.x, p.y, "o", color=colour, ms=6)
            scale = 0.15 * max(1e-9, path.length / max(1, len(path.segments)))
            ax.annotate(
                "",
                xy=(p.x + scale * np.cos(p.heading), p.y + scale * np.sin(p.heading)),
                xytext=(p.x, p.y),
                arrowprops={"arrowstyle": "->", "color": colour},
            )
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    return ax


def plot_solution(solution: Solution, ax: Any = None, *, candidates: bool = False) -> Any:
    """Draw the best path of a solution (and optionally the other feasible candidates)."""
    ax = _axes(ax)
    if candidates:
        for c in solution.candidates[1:]:
            if c.path is not None:
                plot_path(c.path, ax, switch_markers=False, pose_markers=False, lw=0.8, alpha=0.5)
    if solution.path is not None:
        plot_path(
            solution.path, ax, label=f"{solution.family or solution.word} {solution.cost:.4g}"
        )
        ax.legend(loc="best", fontsize=8)
    ax.set_title(f"{solution.planner}: {solution.status.value}")
    return ax


def save_figure(ax_or_fig: Any, filename: str) -> None:
    """Save the figure owning `ax_or_fig` and close it."""
    import matplotlib.pyplot as plt

    fig = ax_or_fig.get_figure() if hasattr(ax_or_fig, "get_figure") else ax_or_fig
    fig.tight_layout()
    fig.savefig(filename, dpi=130)
    plt.close(fig)
