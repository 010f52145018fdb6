"""Chapter 3 figures: Dubins partitions (Fig 3.1) and the tradespace ratio T (Fig 3.2)."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import FigureReport, Printed, compare, reproducible

HEADINGS = {"a": (0.0, "0"), "b": (2 * math.pi / 3, "2pi/3"), "c": (math.pi, "pi")}

# Region labels printed in Fig 3.1 (one per connected region; "RSR/LSL" written as a tie).
FIG_3_1_REGIONS = {
    "a": ["LSR", "RLR/LRL", "RLR/LRL", "RSR/LSL", "RSL"],
    "b": ["LRL", "RLR", "RSL", "LSR", "RSL", "LSL", "RSR", "LSR"],
    "c": ["LSL", "RLR", "LRL", "RSR", "LSR", "RSL", "LSR", "RSL"],
}

# REFERENCE_NOTES 4.4 spot values of T at eps = 0.25 (derived there, two decimals; the
# dissertation prints no value of T): an independent reference, not a printed value.
T_SPOTS = [
    ((3.0, 3.0, 2 * math.pi / 3), 1.07),
    ((1.0, 2.0, 0.0), 1.42),
    ((0.5, 0.5, math.pi), 1.62),
    ((-2.0, 0.0, math.pi), 1.71),
    ((6.0, 0.0, 0.0), 1.00),
]


def _canonical(labels: list[str]) -> list[str]:
    return sorted("/".join(sorted(label.split("/"))) for label in labels)


@reproducible(
    "fig3.1",
    title="Dubins partitions of the plane by optimal word",
    dissertation=(
        "Fig 3.1 (section 3.3): partitions P_psi for final headings 0, 2pi/3, pi over "
        "[-6, 6]^2 (units of R0), regions labelled (a) LSR, RLR/LRL x2, RSR/LSL, RSL; "
        "(b) LRL, RLR, RSL x2, LSR x2, LSL, RSR; (c) LSL, RLR, LRL, RSR, LSR x2, RSL x2."
    ),
)
def fig3_1(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """The three partitions; regions found compared with the labels printed in Fig 3.1."""
    from glideplan.studies.map_plots import plot_partition
    from glideplan.studies.maps import partition_map, partition_regions

    n = 601 if full else 241
    fig, axes = pyplot().subplots(1, 3, figsize=(16, 5.4))
    rows = []
    for ax, (key, (psi1, name)) in zip(axes, HEADINGS.items(), strict=True):
        pmap = partition_map(psi1, extent=6.0, n=n, progress=False)
        plot_partition(pmap, ax)
        ours = _canonical([r.label for r in partition_regions(pmap)])
        theirs = _canonical(FIG_3_1_REGIONS[key])
        missing = sorted(set(theirs) - set(ours))
        extra = sorted(set(ours) - set(theirs))
        rows.append(
            compare(
                f"({key}) psi1 = {name}: labelled regions",
                ", ".join(ours),
                Printed(", ".join(theirs), f"Fig 3.1({key}) region labels", word=True),
                note=""
                if ours == theirs
                else f"{len(ours)} regions found, {len(theirs)} printed; printed only: "
                f"{', '.join(missing) or '-'}; found only: {', '.join(extra) or '-'}",
            )
        )
    path = save_png(fig, out_dir / "fig3_1_partitions.png")
    return FigureReport(
        files=(path.name,),
        rows=tuple(rows),
        notes=(
            f"{n} x {n} grid; near-ties (relative difference < 1e-9) are labelled A/B. "
            "Thin tie lines on region boundaries are not counted as regions."
        ),
    )


@reproducible(
    "fig3.2",
    title="Tradespace ratio T = d_feasible / d_optimal, eps = 0.25",
    dissertation=(
        "Fig 3.2 (section 3.3): contours of T(x1, y1, psi1, 0.25) for psi1 = 0, 2pi/3, pi over "
        "[-6, 6]^2, colour truncated at 5, contours every 0.2; T is small far from the origin "
        "and rises sharply within about 4 R0 of it."
    ),
)
def fig3_2(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """The three tradespace maps plus spot values and the near/far behaviour the text states."""
    from glideplan.studies.map_plots import plot_tradespace
    from glideplan.studies.maps import tradespace_map, tradespace_ratio

    n = 601 if full else 241
    fig, axes = pyplot().subplots(1, 3, figsize=(17, 5))
    rows = []
    for ax, (key, (psi1, name)) in zip(axes, HEADINGS.items(), strict=True):
        tmap = tradespace_map(psi1, 0.25, extent=6.0, n=n, progress=False)
        plot_tradespace(tmap, ax)
        gx, gy = np.meshgrid(tmap.x, tmap.y)
        r = np.hypot(gx, gy)
        ok = np.isfinite(tmap.ratio)
        near = np.nanmax(np.where(ok & (r <= 4.0), tmap.ratio, np.nan))
        far = np.nanmedian(np.where(ok & (r >= 5.5), tmap.ratio, np.nan))
        rows.append(
            compare(f"({key}) psi1 = {name}: largest T within 4 R0", float(near),
                    note="section 3.3: T rises sharply within about 4 R0 (no value printed)")
        )  # fmt: skip
        rows.append(
            compare(f"({key}) psi1 = {name}: median T beyond 5.5 R0", float(far),
                    note="section 3.3: small far from the origin (no value printed)")
        )  # fmt: skip
    for (x, y, psi1), ref in T_SPOTS:
        ours = float(tradespace_ratio(x, y, psi1, 0.25))
        rows.append(
            compare(
                f"T({x:g}, {y:g}, {psi1:.4f}, 0.25)",
                ours,
                reference=ref,
                reference_source="REFERENCE_NOTES 4.4 (derived, 2 decimals)",
                note=f"ours - reference = {ours - ref:+.4f}",
            )
        )
    path = save_png(fig, out_dir / "fig3_2_tradespace.png")
    return FigureReport(files=(path.name,), rows=tuple(rows), notes=f"{n} x {n} grid.")
