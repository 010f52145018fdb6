"""Chapter 6 figures: control set, hodograph, polars, extremal arcs, three examples (6.3-6.13).

Parameters (6.21): n_max = 2, (L/D)max = 30, v_min = 0.75, v_max = 2. The three examples
(Figs 6.11-6.13) are in `ch6_examples.py`; this module holds the analysis figures, the cached
example solve and the drawing they share.
"""

from __future__ import annotations

import functools
import math
import pathlib
from typing import Any

import numpy as np

from glideplan.analysis import load_factor as lf
from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import FigureReport, Printed, compare, reproducible, yes_no
from glideplan.pose import Pose
from glideplan.solution_figures import draw_control_set
from glideplan.studies.load_factor_hodograph import hc_minimiser
from glideplan.vehicles.load_factor_glider import LoadFactorGlider

__all__ = ["GLIDER", "draw_solution", "solution_figure", "solve_example"]

GLIDER = LoadFactorGlider()  # (6.21)
S67 = "section 6.7"


# ----- 6.3 to 6.10: analysis --------------------------------------------------------------
@reproducible(
    "fig6.3",
    title="Control set, manoeuvre corridor, extremal locus, stall boundary and corner",
    dissertation="Fig 6.3: Omega for (6.21) on 0.5 <= v <= 2, 0.8 <= n <= 2.2; extremal "
    "locus v^4 + n^2 = 2 (6.35) meets the stall boundary at v_lim = (2/(1+p2^2))^(1/4)",
)
def fig6_3(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    fig, ax = plt.subplots(figsize=(6, 4.5))
    draw_control_set(ax, g)
    ax.set_xlim(0.5, 2.1)
    ax.set_ylim(0.8, 2.2)
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title("Control set Omega (6.20), parameters (6.21)")
    vl, nl = lf.locus_stall_intersection(g)
    v_lim = (2.0 / (1.0 + g.p2**2)) ** 0.25
    rows = (
        compare("n_max", g.n_limit, Printed("2", "(6.21)")),
        compare("v_min", math.sqrt(1.0 / g.p2), Printed("0.75", "(6.21)")),
        compare("p1 = 1/(2 (L/D)max)", g.p1, reference=1 / 60,
                reference_source="REFERENCE_NOTES 5.4: (L/D)max = 30 -> 1/60"),
        compare("p2 = 1/v_min^2", g.p2, reference=1.778,
                reference_source="REFERENCE_NOTES 5.4 (3 decimals)"),
        compare("v_lim: the extremal locus meets the stall boundary", vl, reference=v_lim,
                reference_source="closed form (2/(1+p2^2))^(1/4): (6.35) with n = p2 v^2"),
        compare("n_lim", nl, reference=math.sqrt(2 - v_lim**4),
                reference_source="closed form sqrt(2 - v_lim^4) (6.35)"),
        compare("corner speed v_c", g.corner_speed, reference=math.sqrt(g.n_limit / g.p2),
                reference_source="closed form sqrt(n_max/p2)"),
        compare("smallest turn radius (corner)", g.corner_radius,
                reference=g.corner_speed**2 / math.sqrt(g.n_limit**2 - 1),
                reference_source="closed form v_c^2 / sqrt(n_max^2 - 1)"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_3.png", crop=True).name,), rows=rows)


@reproducible(
    "fig6.4",
    title="Hodograph: attainable (turn rate, sink rate) per unit length",
    dissertation="Fig 6.4: image of Omega under (f_psi, f0), f_psi in [-2, 2], f0 in [0, 0.12]; "
    "its southern boundary is the image of the extremal locus; a separating plane tangent "
    "at the stall boundary",
)
def fig6_4(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    hod = lf.hodograph(g, 200 if full else 120)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    pts = hod["points"]
    ax.plot(pts[:, 0], pts[:, 1], ".", color="0.85", ms=1)
    styles = {"extremal_locus": "b--", "stall": "k-", "max_load": "k-", "max_speed": "k-",
              "wings_level": "k-"}  # fmt: skip
    for name, c in hod["curves"].items():
        for sgn in (1, -1):
            ax.plot(sgn * c.x, c.y, styles.get(name, "k-"), lw=1.2,
                    label=c.label if sgn == 1 else None)  # fmt: skip
    # a separating plane tangent at a stall-boundary point: |eta_psi| / (2 eta0 p1) = 2,
    # between the stall (0.72) and corner (4.56) thresholds of fig6.5
    lam = 2.0 * g.p1 * 2.0
    v, n = hc_minimiser(g, lam, 600)
    k0 = math.sqrt(n**2 - 1) / v**2
    f0 = float(g.sink_per_length(v, n))
    xs = np.linspace(-2, 2, 10)
    ax.plot(xs, f0 + lam * (xs - k0), "r:", label="separating plane")
    ax.plot([k0], [f0], "ro")
    ax.set_xlim(-2.1, 2.1)
    ax.set_ylim(0, 0.12)
    ax.set_xlabel("turn rate per unit length f_psi")
    ax.set_ylabel("sink per unit length f0")
    ax.legend(fontsize=7, loc="upper center")
    # southern boundary = image of the locus: check against the grid minimum of f0
    loc = hod["curves"]["extremal_locus"]
    grid_min = []
    for kk in loc.x[5:-5:10]:
        sel = np.abs(pts[:, 0] - kk) < 0.01
        grid_min.append(pts[sel, 1].min() if np.any(sel) else np.nan)
    ref = np.interp(loc.x[5:-5:10], loc.x, loc.y)
    gap = float(np.nanmin(np.asarray(grid_min) - ref))
    rows = (
        compare("lowest sink per unit length (hodograph grid)", float(pts[:, 1].min()),
                reference=1 / 30, reference_source="1/(L/D)max with (L/D)max = 30 (6.21)"),
        compare("largest turn rate per unit length (hodograph grid)", float(pts[:, 0].max()),
                reference=1 / g.corner_radius,
                reference_source="the corner: sqrt(n_max^2-1)/v_c^2"),
        compare("grid minimum of f0 minus the locus image", gap, reference=0.0,
                reference_source="section 6.5: the extremal locus is the southern boundary",
                note="the locus is the southern boundary where this is >= 0 (up to the grid "
                "step)"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_4.png", crop=True).name,), rows=rows)


@reproducible(
    "fig6.5",
    title="Extremal controls along the hodograph boundary for increasing |eta_psi|",
    dissertation="Fig 6.5: as |eta_psi| grows the minimiser of Hc moves from wings level along "
    "the extremal locus and the stall boundary to the corner, where it stays",
)
def fig6_5(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    grid = 900 if full else 500
    # adjoint ratio lam' = |eta_psi| / (2 eta0 p1); Hc / eta0 = f0 - lam f_psi, lam = 2 p1 lam'
    lam_stall_p = math.sqrt((g.p2**2 - 1) / (g.p2**2 + 1))
    lamp = np.concatenate(
        [np.linspace(0.0, lam_stall_p, 8), np.linspace(0.75, 3.0, 10), [4.0, 4.5, 4.6, 6.0, 10.0]]
    )
    lams = 2 * g.p1 * lamp
    mins = np.array([hc_minimiser(g, lam, grid) for lam in lams])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    draw_control_set(a1, g)
    a1.plot(mins[:, 0], mins[:, 1], "ro-", ms=3, label="minimiser of Hc")
    a1.set_xlim(0.5, 2.1)
    a1.set_ylim(0.8, 2.2)
    a1.legend(fontsize=6)
    k = np.sqrt(np.maximum(mins[:, 1] ** 2 - 1, 0)) / mins[:, 0] ** 2
    f0 = g.sink_per_length(mins[:, 0], mins[:, 1])
    hod = lf.hodograph(g, 100)
    a2.plot(hod["points"][:, 0], hod["points"][:, 1], ".", color="0.85", ms=1)
    for kk, ff, lam in zip(k, f0, lams, strict=True):
        xs = np.array([kk - 0.4, kk + 0.4])
        a2.plot(xs, ff + lam * (xs - kk), "r:", lw=0.8)
    a2.plot(k, f0, "ro", ms=3)
    a2.set_xlim(-0.2, 2.0)
    a2.set_ylim(0, 0.12)
    a2.set_xlabel("f_psi")
    a2.set_ylabel("f0")
    # on the locus the minimiser is n = sqrt(1 + lam'^2), v = (1 - lam'^2)^(1/4) (6.36, 6.37)
    # with lam' = eta_psi / (2 eta0 p1) = lam / (2 p1)
    sel = (lamp > 0) & (lamp < 0.99 * lam_stall_p)
    lp = lamp[sel]
    err_n = float(np.max(np.abs(mins[sel, 1] - np.sqrt(1 + lp**2))))
    err_v = float(np.max(np.abs(mins[sel, 0] - (1 - lp**2) ** 0.25)))
    at_corner = np.isclose(mins[:, 1], g.n_limit, atol=5e-3)
    corner_from = float(lamp[np.argmax(at_corner)]) if np.any(at_corner) else math.inf
    lam_corner = 0.5 * (1 / g.p2**2 + 1) * g.n_limit**2 * math.sqrt(g.n_limit**2 - 1)
    on_stall = np.abs(mins[:, 1] - g.p2 * mins[:, 0] ** 2) < 0.02
    rows = (
        compare("max |n_grid - n(6.36)| on the locus", err_n, reference=0.0,
                reference_source="closed form (6.36)", note=f"grid {grid}^2 (step {1 / grid:.0e})"),
        compare("max |v_grid - v(6.37)| on the locus", err_v, reference=0.0,
                reference_source="closed form (6.37)"),
        compare("grid minimisers on the stall boundary past the stall threshold",
                yes_no(bool(np.all(on_stall[8:]))), reference="yes",
                reference_source="section 6.7: beyond sqrt((p2^2-1)/(p2^2+1)) the stall binds"),
        compare("first adjoint ratio of the grid at the corner", corner_from,
                reference=lam_corner, reference_source="(6.47) at n = n_max",
                note="adjoint ratios searched above 3: "
                + ", ".join(f"{x:g}" for x in lamp[lamp > 3])
                + "; ours is the first of them at the corner"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_5.png", crop=True).name,), rows=rows)


@reproducible(
    "fig6.6",
    title="Relaxed problem: convex hull of the hodograph",
    dissertation="Fig 6.6: the hodograph is nonconvex; the relaxed problem's hodograph is its "
    "convex hull, whose southern boundary keeps the original extremal controls",
)
def fig6_6(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    from scipy.spatial import ConvexHull

    plt = pyplot()
    g = GLIDER
    pts = lf.hodograph(g, 160 if full else 100)["points"]
    hull = ConvexHull(pts)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(pts[:, 0], pts[:, 1], ".", color="0.8", ms=1, label="hodograph")
    cyc = np.append(hull.vertices, hull.vertices[0])
    ax.plot(pts[cyc, 0], pts[cyc, 1], "r-", label="convex hull (relaxed)")
    ax.set_xlabel("f_psi")
    ax.set_ylabel("f0")
    ax.legend(fontsize=7)
    inside = _hull_fraction_filled(pts, hull)
    rows = (
        compare("area of the convex hull (relaxed hodograph)", float(hull.volume)),
        compare("share of the hull covered by the hodograph", inside, unit="%",
                note="below 100%: the hodograph is nonconvex (section 6.6)"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_6.png", crop=True).name,), rows=rows)


def _hull_fraction_filled(pts: np.ndarray, hull: Any, bins: int = 80) -> float:
    """Percentage of the hull's grid cells (bins x bins over its box) holding a hodograph point
    among the cells whose centre lies inside the hull."""
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    xs = lo[0] + (np.arange(bins) + 0.5) * (hi[0] - lo[0]) / bins
    ys = lo[1] + (np.arange(bins) + 0.5) * (hi[1] - lo[1]) / bins
    cx, cy = np.meshgrid(xs, ys, indexing="ij")
    centres = np.column_stack([cx.ravel(), cy.ravel()])
    eq = hull.equations
    in_hull = np.all(centres @ eq[:, :2].T + eq[:, 2] <= 1e-12, axis=1).reshape(bins, bins)
    ij = np.clip(((pts - lo) / (hi - lo) * bins).astype(int), 0, bins - 1)
    filled = np.zeros((bins, bins), dtype=bool)
    filled[ij[:, 0], ij[:, 1]] = True
    return 100.0 * float(np.sum(filled & in_hull)) / float(np.sum(in_hull))


@reproducible(
    "fig6.7",
    title="Turn polar: sink per unit length vs speed for constant load factors",
    dissertation="Fig 6.7: f0 on 0.5 <= v <= 2, 0.03 <= f0 <= 0.09; minimum over v for fixed n "
    "on the locus n = v^2",
)
def fig6_7(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    fig, ax = plt.subplots(figsize=(6, 4))
    curves = lf.turn_polar(g)
    for name, c in curves.items():
        ax.plot(c.x, c.y, "k:" if name == "best_glide" else "-", label=c.label)
    ax.set_xlim(0.5, 2.05)
    ax.set_ylim(0.03, 0.09)
    ax.set_xlabel("speed v")
    ax.set_ylabel("sink per unit length z' = f0")
    ax.legend(fontsize=7)
    n15 = curves["n=1.5"]
    i = int(np.argmin(n15.y))
    n1 = curves["n=1"] if "n=1" in curves else None
    rows = (
        compare("argmin over v of f0 at n = 1.5", float(n15.x[i]), reference=math.sqrt(1.5),
                reference_source="the extremal locus n = v^2 (section 6.7)",
                note=f"curve sampled every {float(np.mean(np.diff(n15.x))):.3f}"),
        compare("best glide f0 at n = 1", float(np.min(n1.y)) if n1 is not None else 2 * g.p1,
                reference=1 / 30, reference_source="1/(L/D)max with (L/D)max = 30 (6.21)"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_7.png", crop=True).name,), rows=rows)


@reproducible(
    "fig6.8",
    title="Doghouse plot: turn rate per unit length vs speed",
    dissertation="Fig 6.8: constant load-factor lines and the stall boundary on 0.5 <= v <= 2, "
    "0 <= psi' <= 1.5; best turn rate at the corner speed v_c",
)
def fig6_8(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    fig, ax = plt.subplots(figsize=(6, 4))
    for name, c in lf.doghouse(g).items():
        ax.plot(c.x, c.y, "k-" if name == "stall" else "-", label=c.label)
    ax.plot([g.corner_speed], [1 / g.corner_radius], "rs", label="corner")
    ax.set_xlim(0.5, 2.05)
    ax.set_ylim(0, 1.6)
    ax.set_xlabel("speed v")
    ax.set_ylabel("turn rate per unit length psi'")
    ax.legend(fontsize=7)
    rows = (
        compare("best turn rate per unit length (the corner)", 1 / g.corner_radius,
                note=f"at v = v_c = {g.corner_speed:.4f}; the y axis of Fig 6.8 ends at 1.5"),
    )  # fmt: skip
    notes = (
        "The extracted text calls Fig 6.8 sink rate versus speed; its axis range (0 to 1.5) "
        "and the discussion of the best turn rate at the corner speed fit the turn rate per "
        "unit length, which is what is drawn."
    )
    return FigureReport(
        files=(save_png(fig, out_dir / "fig6_8.png", crop=True).name,), rows=rows, notes=notes
    )


@reproducible(
    "fig6.9",
    title="Speed along the extremal locus for several p3",
    dissertation="Fig 6.9: v(s) from v_lim to 1 (0 <= s <= 2), (6.41) integrated numerically; "
    "arc length s1 (6.44) grows without bound as p3 -> 1",
)
def fig6_9(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    fig, ax = plt.subplots(figsize=(6, 4))
    rows = []
    s1s = []
    for p3 in (1.02, 1.1, 1.5, 3.0):
        s, v, s1 = lf.locus_speed_history(g, p3)
        vn = lf.locus_speed_history_numeric(g, p3, s)
        ax.plot(s, v, label=f"p3 = {p3:g}")
        s1s.append(s1)
        rows.append(compare(f"p3 = {p3:g}: arc length s1 (6.44)", s1))
        rows.append(
            compare(f"p3 = {p3:g}: max |v(6.44) - v from integrating (6.41)|",
                    float(np.max(np.abs(v - vn))), reference=0.0,
                    reference_source="numerical integration of (6.41) (analysis.load_factor)")
        )  # fmt: skip
    rows.append(
        compare("s1 grows as p3 decreases towards 1", yes_no(bool(np.all(np.diff(s1s) < 0))),
                Printed("yes", f"{S67}: s1 -> infinity as p3 -> 1", word=True),
                note="s1 = " + ", ".join(f"{x:.3f}" for x in s1s))
    )  # fmt: skip
    ax.set_xlim(0, 2)
    ax.set_xlabel("arc length s")
    ax.set_ylabel("speed v")
    ax.legend(fontsize=7)
    return FigureReport(
        files=(save_png(fig, out_dir / "fig6_9.png", crop=True).name,), rows=tuple(rows)
    )


@reproducible(
    "fig6.10",
    title="Load factor along the stall boundary for several p3",
    dissertation="Fig 6.10: n(s) from n_lim, (6.49)-(6.50); only p3 = 10 reaches the corner; "
    "for small p3, n returns to n_lim",
)
def fig6_10(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    fig, ax = plt.subplots(figsize=(6, 4))
    rows = []
    for p3 in (1.0, 2.0, 4.0, 10.0):
        r = lf.stall_load_factor_history(g, p3)
        ax.plot(r["s"], r["n"], label=f"p3 = {p3:g}")
        rows.append(
            compare(f"p3 = {p3:g}: the corner is reached", yes_no(bool(r["corner"])),
                    Printed("yes" if p3 == 10.0 else "no",
                            f"{S67}: in Figure 6.10 only p3 = 10 reaches the corner", word=True),
                    note=f"max n = {np.max(r['n']):.4f}, n_max = {g.n_limit:g}")
        )  # fmt: skip
    ax.axhline(g.n_limit, color="k", ls=":", lw=0.8)
    ax.set_xlim(0, 3)
    ax.set_xlabel("arc length s")
    ax.set_ylabel("load factor n")
    ax.legend(fontsize=7)
    return FigureReport(
        files=(save_png(fig, out_dir / "fig6_10.png", crop=True).name,), rows=tuple(rows)
    )


# ----- 6.11 to 6.13: the three examples ----------------------------------------------------
@functools.lru_cache(maxsize=8)
def solve_example(goal: tuple[float, float, float], scheme: str = "hermite-simpson"):
    """`plan()` for one chapter 6 example with the (6.21) glider (cached)."""
    from glideplan.planning import plan

    return plan(Pose(), Pose(*goal), GLIDER, "altitude", "direct", scheme=scheme)


def solution_figure(solution: Any, title: str = "") -> Any:
    """Figs. 6.11-6.13's panels: `glideplan.solution_figures.load_factor_figure`."""
    from glideplan.solution_figures import load_factor_figure

    return load_factor_figure(solution, title)


def draw_solution(solution: Any, filename: str | pathlib.Path, title: str = "") -> None:
    """Fig 6.11-style panels (`solution_figure`) written to `filename` (PNG)."""
    from glideplan.solution_figures import draw_load_factor

    draw_load_factor(solution, filename, title)
