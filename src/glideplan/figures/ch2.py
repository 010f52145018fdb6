"""Chapter 2 figures: Fig 2.2, the candidate Dubins paths to two endpoints (section 2.7)."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import Comparison, FigureReport, reproducible

# Fig 2.2: endpoints normalised by R0; (a) far away, (b) close enough for a CCC path.
FIG_2_2_CASES = {
    "a": ((-3.0, 2.0, 3 * math.pi / 2), "x1 = (-3, 2, 3pi/2)"),
    "b": ((1.0, 1.0, math.pi), "x1 = (1, 1, pi)"),
}
FIG_2_2_TEXT = {
    "a": "far away: only candidates containing an S segment are feasible",
    "b": "closer: reachable by a turn-turn-turn candidate (e.g. RLR)",
}


@reproducible(
    "fig2.2",
    title="Candidate Dubins paths for a given endpoint",
    dissertation=(
        "Fig 2.2 (section 2.7): the six Dubins candidates LSL LSR RSL RSR LRL RLR to "
        "(a) x1 = (-3, 2, 3pi/2) and (b) x1 = (1, 1, pi), positions in units of R0; in (a) "
        "only S-containing words are drawn as feasible, in (b) a CCC word (RLR) reaches the goal."
    ),
)
def fig2_2(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Draw every feasible candidate for both endpoints and list their lengths."""
    from glideplan import DubinsCar, Pose, plan
    from glideplan.plotting import plot_path

    fig, axes = pyplot().subplots(1, 2, figsize=(11, 5))
    rows = []
    for ax, (key, (goal, name)) in zip(axes, FIG_2_2_CASES.items(), strict=True):
        sol = plan(Pose(), Pose(*goal), DubinsCar()).raise_for_status()
        feasible = [c for c in sol.candidates if c.feasible]
        for cand in feasible:
            best = cand is sol.candidates[0]
            plot_path(
                cand.path,
                ax,
                switch_markers=best,
                pose_markers=best,
                lw=2.2 if best else 1.0,
                alpha=1.0 if best else 0.7,
                label=f"{cand.word} {cand.cost:.3f}" + (" (optimal)" if best else ""),
            )
        ax.legend(fontsize=8, loc="best")
        ax.set_title(f"({key}) {name}")
        ax.grid(alpha=0.3)
        words = " ".join(c.word for c in feasible)
        ccc = [c.word for c in feasible if "S" not in c.word]
        rows.append(
            Comparison(
                f"({key}) feasible candidates",
                f"{len(feasible)}: {words}",
                FIG_2_2_TEXT[key],
                ""
                if key == "b" or not ccc
                else (
                    f"{', '.join(ccc)} is also feasible here (outer circle centres "
                    f"{_centre_distance(goal):.2f} R0 < 4 R0 apart) but longest, with "
                    "outer arcs over pi, so never optimal; the dissertation omits it"
                ),
            )
        )
        rows.append(
            Comparison(
                f"({key}) optimal word, length / R0",
                f"{sol.word} {sol.cost:.4f}",
                "not stated",
                f"endpoint error {sol.endpoint_error.max:.1e}",
            )
        )
    path = save_png(fig, out_dir / "fig2_2_dubins_candidates.png")
    return FigureReport(files=(path.name,), rows=tuple(rows))


def _centre_distance(goal: tuple[float, float, float]) -> float:
    """Distance between the start and goal left turning circles (units of R0)."""
    x, y, h = goal
    return float(np.hypot(x - math.sin(h), y + math.cos(h) - 1.0))
