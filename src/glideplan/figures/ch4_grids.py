"""Chapter 4 goal grids (Figs 4.9-4.11): optimal paths to a grid of endpoints, R = 1, r = 0.3."""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import (
    FigureReport,
    Printed,
    compare,
    reproducible_each,
    yes_no,
)
from glideplan.pose import Pose
from glideplan.studies.min_time_table import example_car

PI = math.pi


_GRID_TEXT = {
    "fig4.9": (0.0, "psi1 = 0: e.g. x1 = (2, 2, 0) and (2, -2, 0) are Dubins (BSB) paths"),
    "fig4.10": (2 * PI / 3, "psi1 = 2pi/3: most optimal paths use cornering turns"),
    "fig4.11": (PI, "psi1 = pi: x1 = (-2, 0, pi) has two optimal paths (mirror images)"),
}


def _grid_figure(fid: str, out_dir: pathlib.Path, full: bool) -> FigureReport:
    from glideplan.planners.min_time.grid import time_optimal_grid

    plt = pyplot()
    heading, text = _GRID_TEXT[fid]
    car = example_car()
    n = 61 if full else 25
    xs = np.linspace(-3.0, 3.0, n)
    grid = time_optimal_grid(car, xs, xs, heading)
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.6))
    _family_panel(plt, axes[0], grid, xs, heading, full)
    _paths_panel(axes[1], car, heading)
    ax = axes[2]
    im = ax.imshow(grid.ratio, origin="lower", extent=(-3, 3, -3, 3), cmap="viridis")
    fig.colorbar(im, ax=ax, label="Dubins time at v_max / optimal time")
    ax.set_xlabel("x1 (m)")
    ax.set_ylabel("y1 (m)")
    ax.set_title("ratio Dubins(v_max) / optimal")
    f = save_png(fig, out_dir / f"{fid.replace('.', '_')}_grid.png")
    rows = _grid_rows(grid, n, heading) + _example_rows(fid, car)
    return FigureReport(files=(f.name,), rows=tuple(rows), notes=text)


def _family_panel(plt: Any, ax: Any, grid: Any, xs: np.ndarray, heading: float,
                  full: bool) -> None:
    """The optimal family at each grid goal, one colour per family."""
    fams = sorted({f for f in grid.family.ravel() if f})
    code = np.vectorize(lambda f: fams.index(f) if f else -1)(grid.family)
    cmap = plt.get_cmap("tab20", max(len(fams), 1))
    gx, gy = np.meshgrid(xs, xs)
    for i, fam in enumerate(fams):
        m = code == i
        ax.scatter(gx[m], gy[m], s=8 if full else 22, color=cmap(i), marker="s", label=fam)
    ax.set_aspect("equal")
    ax.set_xlabel("x1 (m, R = 1)")
    ax.set_ylabel("y1 (m)")
    ax.set_title(f"optimal family, psi1 = {heading:.3f} rad")
    ax.legend(fontsize=7, ncol=5, loc="upper center", bbox_to_anchor=(0.5, -0.1))


def _paths_panel(ax: Any, car: Any, heading: float) -> None:
    """The optimal paths to a 7 x 7 subset of the goals."""
    from glideplan.planning import plan
    from glideplan.plotting import plot_path

    sub = np.linspace(-3.0, 3.0, 7)
    for y in sub:
        for x in sub:
            if abs(x) < 1e-12 and abs(y) < 1e-12 and abs(heading) < 1e-12:
                continue
            s = plan(Pose(), Pose(x, y, heading), car)
            if s.path is not None:
                plot_path(s.path, ax, switch_markers=False, pose_markers=False, lw=0.8)
                ax.plot(x, y, "k.", ms=3)
    ax.set_aspect("equal", adjustable="box")
    ax.set_xlim(-4, 4)
    ax.set_ylim(-4, 4)
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title("optimal paths to a 7 x 7 subset")


def _grid_rows(grid: Any, n: int, heading: float) -> list[Any]:
    """Points solved, the Dubins/optimal ratio (>= 1: a lower bound) and, for psi1 = 0 or
    pi, the symmetry t(x, y) = t(x, -y)."""
    ratio = grid.ratio[np.isfinite(grid.ratio)]
    rows = [
        compare("grid points solved", int(np.isfinite(grid.time).sum()), unit="",
                note=f"{n} x {n} on [-3, 3]^2"),
        compare("Dubins/optimal time ratio: mean", float(ratio.mean())),
        compare("Dubins/optimal time ratio: smallest", float(ratio.min()), reference=1.0,
                reference_source="lower bound: the Dubins path at v_max is a candidate",
                note=f"{int(np.sum(ratio < 1 - 1e-9))} points below 1"),
    ]  # fmt: skip
    if abs(math.sin(heading)) < 1e-12:
        mirror = np.isclose(grid.time, grid.time[::-1, :], rtol=1e-9, atol=1e-12)
        rows.append(
            compare(
                "points where t(x, y) = t(x, -y)",
                100.0 * float(np.mean(mirror)),
                unit="%",
                reference=100.0,
                reference_source="the problem is symmetric about the x axis for psi1 = 0, pi",
            )
        )
    return rows


def _example_rows(fid: str, car: Any) -> list[Any]:
    """The section's named examples: Fig 4.9's two Dubins goals, Fig 4.11's mirror image."""
    from glideplan.planners.min_time.grid import best_time
    from glideplan.planning import plan

    rows = []
    if fid == "fig4.9":
        for g in ((2.0, 2.0, 0.0), (2.0, -2.0, 0.0)):
            t, fam, word = best_time(car, *g)
            group = "Dubins" if set(fam) <= {"B", "S"} or fam == "CCC" else fam
            rows.append(
                compare(
                    f"family of the optimal path to {g}",
                    group,
                    Printed("Dubins", "section 4.9, Fig 4.9", word=True),
                    note=f"{fam} {word}, {t:.4f} s",
                )
            )
    if fid == "fig4.11":
        a = plan(Pose(), Pose(-2.0, 0.0, PI), car)
        b = a.path.reflected() if a.path is not None else None
        equal = b is not None and a.cost is not None and abs(b.duration - a.cost) <= 1e-9
        rows.append(
            compare(
                "x1 = (-2, 0, pi): the mirror image of the optimal path has equal time",
                yes_no(equal),
                Printed("yes", "section 4.9, Fig 4.11", word=True),
                note=f"{a.family} {a.word} {a.cost:.6f} s; mirror "
                f"{b.word if b else '-'} {b.duration if b else math.nan:.6f} s",
            )
        )
    return rows


reproducible_each(
    {
        "fig4.9": (
            "Optimal paths over a grid of goals, psi1 = 0",
            "Fig 4.9: lowest-cost paths to a grid of endpoints on [-3, 3]^2 with psi1 = 0; "
            "some are Dubins paths, e.g. x1 = (2, 2, 0) and (2, -2, 0).",
        ),
        "fig4.10": (
            "Optimal paths over a grid of goals, psi1 = 2pi/3",
            "Fig 4.10: lowest-cost paths to a grid of endpoints on [-3, 3]^2 with "
            "psi1 = 2pi/3; most involve cornering turns.",
        ),
        "fig4.11": (
            "Optimal paths over a grid of goals, psi1 = pi",
            "Fig 4.11: lowest-cost paths to a grid of endpoints on [-3, 3]^2 with psi1 = pi; "
            "the path to x1 = (-2, 0, pi) and its mirror image have equal cost.",
        ),
    },
    _grid_figure,
)
