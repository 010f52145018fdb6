"""Chapter 2 figures: Fig 2.2, the candidate Dubins paths to two endpoints (section 2.7)."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import FigureReport, Printed, compare, reproducible, yes_no

# Fig 2.2: endpoints normalised by R0; (a) far away, (b) close enough for a CCC path.
FIG_2_2_CASES = {
    "a": ((-3.0, 2.0, 3 * math.pi / 2), "x1 = (-3, 2, 3pi/2)"),
    "b": ((1.0, 1.0, math.pi), "x1 = (1, 1, pi)"),
}
# What section 2.7 prints about Fig 2.2: in (a) "only the candidates containing an S segment
# are feasible" (no CCC word), in (b) the goal "can be reached by a turn-turn-turn (e.g. RLR)".
PRINTED_CCC = {
    "a": Printed("none", "section 2.7, Fig 2.2(a)", word=True),
    "b": Printed("yes", "section 2.7, Fig 2.2(b)", word=True),
}
# Hand derivations of the optimal lengths (units of R0), independent of the planner:
# (a) LSL: quarter turns and a straight: sqrt(5) + 3 pi / 2; (b) RLR: 3 pi - 2 acos(-1/4).
HAND_LENGTH = {
    "a": ("LSL", math.sqrt(5.0) + 1.5 * math.pi),
    "b": ("RLR", 3.0 * math.pi - 2.0 * math.acos(-0.25)),
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
            assert cand.path is not None
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
        ax.set_xlabel("x / R0")
        ax.set_ylabel("y / R0")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(alpha=0.3)
        ccc = [c for c in feasible if "S" not in c.word]
        ccc_words = ", ".join(c.word for c in ccc) or "none"
        ours = ccc_words if key == "a" else yes_no(bool(ccc))
        centre = _centre_distance(goal)
        note = ""
        if key == "a" and ccc:
            longest = max(feasible, key=lambda c: c.cost)
            note = (
                f"{ccc_words} is feasible too: the outer turning circles' centres are "
                f"{centre:.2f} R0 < 4 R0 apart; at {ccc[0].cost:.3f} R0 it is "
                + ("the longest candidate" if longest in ccc else f"longer than {sol.word}")
                + " and the figure draws only words with an S"
            )
        rows.append(
            compare(
                f"({key}) {name}: a CCC candidate is feasible" + (" (which)" if key == "a" else ""),
                ours,
                PRINTED_CCC[key],
                note=note,
            )
        )
        rows.append(
            compare(
                f"({key}) feasible candidates",
                " ".join(c.word for c in feasible),
                note=f"{len(feasible)} of 6",
            )
        )
        hand_word, hand_length = HAND_LENGTH[key]
        assert sol.endpoint_error is not None and sol.cost is not None
        rows.append(compare(f"({key}) optimal word", sol.word, reference=hand_word,
                            reference_source="hand derivation"))  # fmt: skip
        rows.append(
            compare(
                f"({key}) optimal length",
                sol.cost,
                unit="R0",
                reference=hand_length,
                reference_source=(
                    "hand derivation: sqrt(5) + 3 pi/2" if key == "a" else
                    "hand derivation: 3 pi - 2 acos(-1/4)"
                ),
                note=f"|ours - reference| = {abs(sol.cost - hand_length):.1e}; endpoint error "
                f"{sol.endpoint_error.max:.1e}",
            )
        )  # fmt: skip
    path = save_png(fig, out_dir / "fig2_2_dubins_candidates.png")
    return FigureReport(files=(path.name,), rows=tuple(rows))


def _centre_distance(goal: tuple[float, float, float]) -> float:
    """Distance between the start and goal left turning circles (units of R0)."""
    x, y, h = goal
    return float(np.hypot(x - math.sin(h), y + math.cos(h) - 1.0))
