"""Chapter 6 figures: control set, hodograph, polars, extremal arcs, three examples (6.3-6.13).

Parameters (6.21): n_max = 2, (L/D)max = 30, v_min = 0.75, v_max = 2. The examples are solved
by the direct method (`glideplan.planners.load_factor`) and compared with the dissertation's
qualitative results and with an independent multi-start collocation (costs 0.36138, 0.26256,
0.20926).
"""

from __future__ import annotations

import functools
import math
import pathlib
from typing import Any

import numpy as np

from glideplan.analysis import load_factor as lf
from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import Comparison, FigureReport, reproducible
from glideplan.pose import Pose
from glideplan.vehicles.load_factor_glider import LoadFactorGlider

__all__ = ["EXAMPLES", "draw_solution", "solve_example"]

GLIDER = LoadFactorGlider()  # (6.21)
# goal, dissertation figure, independent cost, turn word, corner reached (section 6.8)
EXAMPLES: dict[str, dict[str, Any]] = {
    "fig6.11": {"goal": (-2.0, 4.0, 7 * math.pi / 4), "cost": 0.36138, "word": "L",
                "corner": False, "s_axis": 8.0},
    "fig6.12": {"goal": (0.0, -0.5, math.pi), "cost": 0.26256, "word": "LRL",
                "corner": False, "s_axis": 5.0},
    "fig6.13": {"goal": (1.1, 2.0, 0.0), "cost": 0.20926, "word": "LR",
                "corner": True, "s_axis": 2.5},
}  # fmt: skip
_CLASS_STYLE = {
    "corner": ("tab:red", "corner"),
    "stall": ("tab:orange", "stall boundary"),
    "locus": ("tab:blue", "extremal locus"),
    "wings_level": ("tab:green", "wings level"),
    "other": ("0.5", "other"),
}


def _draw_control_set(ax, glider: LoadFactorGlider) -> None:
    cs = lf.control_set(glider)
    corridor = cs["corridor"]
    ax.fill(corridor.x, corridor.y, color="0.9", label="manoeuvre corridor")
    for key, style in (
        ("stall", "k-"),
        ("max_load", "k-"),
        ("max_speed", "k-"),
        ("wings_level", "k-"),
        ("best_glide", "k:"),
        ("extremal_locus", "b--"),
    ):
        c = cs[key]
        ax.plot(c.x, c.y, style, lw=1.2, label=c.label if key not in ("max_load",) else None)
    vc, nm = lf.corner(glider)
    vl, nl = lf.locus_stall_intersection(glider)
    ax.plot([vc], [nm], "rs", label=f"corner ({vc:.3f}, {nm:g})")
    ax.plot([vl], [nl], "bo", ms=4, label=f"locus meets stall ({vl:.3f}, {nl:.3f})")
    ax.set_xlabel("speed v")
    ax.set_ylabel("load factor n")


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
    _draw_control_set(ax, g)
    ax.set_xlim(0.5, 2.1)
    ax.set_ylim(0.8, 2.2)
    ax.legend(fontsize=7, loc="upper right")
    ax.set_title("Control set Omega (6.20), parameters (6.21)")
    vl, nl = lf.locus_stall_intersection(g)
    rows = (
        Comparison("p1 = 1/(2 (L/D)max)", f"{g.p1:.5f}", "1/60 (REFERENCE_NOTES 5.4)"),
        Comparison("p2 = 1/v_min^2", f"{g.p2:.4f}", "1.778"),
        Comparison("v_lim, n_lim", f"{vl:.4f}, {nl:.4f}", "(2/(1+p2^2))^(1/4), sqrt(2-v^4)"),
        Comparison("corner (v_c, n_max)", f"{g.corner_speed:.4f}, {g.n_limit:g}",
                   "v_c = sqrt(n_max/p2)"),
        Comparison("smallest turn radius (corner)", f"{g.corner_radius:.4f}", "",
                   "v_c^2 / sqrt(n_max^2 - 1)"),
    )  # fmt: skip
    return FigureReport(files=(save_png(fig, out_dir / "fig6_3.png", crop=True).name,), rows=rows)


def _hc_minimiser(g: LoadFactorGlider, lam: float, grid: int) -> tuple[float, float]:
    """(v, n) minimising f0 - lam f_psi over Omega (turning left), by dense grid search.

    The grid is laid in the box coordinates (6.53)-(6.54), bank angle phi and speed fraction
    vbar (squared spacing, dense near the stall boundary), so that the stall boundary and the
    corner are grid points.
    """
    vbar, phi = np.meshgrid(np.linspace(0.0, 1.0, grid) ** 2, np.linspace(0, g.max_bank, grid))
    n = 1.0 / np.cos(phi)
    v = np.sqrt(n / g.p2) * (1.0 - vbar) + g.v_max * vbar
    h = g.sink_per_length(v, n) - lam * np.sqrt(np.maximum(n**2 - 1, 0)) / v**2
    i = np.unravel_index(np.argmin(h), h.shape)
    return float(v[i]), float(n[i])


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
    v, n = _hc_minimiser(g, lam, 600)
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
        Comparison("lowest sink (wings level, v = 1)", f"{2 * g.p1:.5f}", "2 p1 = 0.0333"),
        Comparison("largest turn rate (corner)", f"{1 / g.corner_radius:.4f}", "about 1.5 (axis)"),
        Comparison("grid minimum of f0 minus locus image", f"{gap:.2e}", ">= 0",
                   "the locus is the southern boundary"),
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
    mins = np.array([_hc_minimiser(g, lam, grid) for lam in lams])
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 4))
    _draw_control_set(a1, g)
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
        Comparison("max |n_grid - n(6.36)| on the locus", f"{err_n:.1e}", "0",
                   f"grid {grid}^2 (step {1 / grid:.0e})"),
        Comparison("max |v_grid - v(6.37)| on the locus", f"{err_v:.1e}", "0"),
        Comparison("stall binds at |eta_psi|/(2 eta0 p1)", f"{lam_stall_p:.4f}",
                   "sqrt((p2^2-1)/(p2^2+1))",
                   f"grid minimisers on the stall boundary beyond: {bool(np.all(on_stall[8:]))}"),
        Comparison("corner reached by |eta_psi|/(2 eta0 p1)", f"<= {corner_from:.2f}",
                   f"{lam_corner:.4f}", "(6.47) at n = n_max; the minimiser then stays there"),
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
    area_ratio = hull.volume
    rows = (
        Comparison("hull area", f"{area_ratio:.4f}", "", "nonconvex: hull adds area in the north"),
    )
    return FigureReport(files=(save_png(fig, out_dir / "fig6_6.png", crop=True).name,), rows=rows)


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
    rows = (
        Comparison("argmin_v f0 at n = 1.5", f"{n15.x[i]:.3f}",
                   f"sqrt(1.5) = {math.sqrt(1.5):.3f}"),
        Comparison("best glide f0 at n = 1", f"{2 * g.p1:.4f}", "1/(L/D)max = 0.0333"),
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
        Comparison("best turn rate, at v_c",
                   f"{1 / g.corner_radius:.4f} at v = {g.corner_speed:.4f}",
                   "corner speed v_c", "y axis of Fig 6.8 reaches 1.5"),
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
    for p3 in (1.02, 1.1, 1.5, 3.0):
        s, v, s1 = lf.locus_speed_history(g, p3)
        vn = lf.locus_speed_history_numeric(g, p3, s)
        ax.plot(s, v, label=f"p3 = {p3:g}")
        rows.append(
            Comparison(f"s1 (6.44), p3 = {p3:g}", f"{s1:.4f}",
                       f"numerical (6.41): max |dv| {np.max(np.abs(v - vn)):.1e}")
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
            Comparison(f"p3 = {p3:g}: corner reached", str(r["corner"]),
                       "yes" if p3 == 10.0 else "no", f"max n = {np.max(r['n']):.4f}")
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


def draw_solution(solution, filename: str | pathlib.Path, title: str = "") -> None:
    """Fig 6.11-style panels: (a) v and n vs s, (b) path, (c) (v, n) over Omega by arc class."""
    plt = pyplot()
    glider = solution.vehicle
    ctr = solution.extras["controls"]
    s, v, n = (np.asarray(ctr[k]) for k in ("s", "v", "n"))
    labels = np.asarray(ctr["label"])
    fig = plt.figure(figsize=(12, 4))
    a1 = fig.add_subplot(1, 3, 1)
    a1.plot(s, v, "b-", label="speed v")
    a1.plot(s, n, "r-", label="load factor n")
    a1.set_xlabel("arc length s")
    a1.legend(fontsize=7)
    a1.set_title("(a) controls")
    a2 = fig.add_subplot(1, 3, 2)
    smp = solution.path.sample(400)
    a2.plot(smp.x, smp.y, "k-")
    st, gl = solution.start, solution.goal
    for p, c in ((st, "g"), (gl, "r")):
        a2.quiver(p.x, p.y, math.cos(p.heading), math.sin(p.heading), color=c, scale=12)
    a2.set_aspect("equal")
    a2.set_title("(b) path")
    a3 = fig.add_subplot(1, 3, 3)
    _draw_control_set(a3, glider)
    for cls, (color, name) in _CLASS_STYLE.items():
        m = labels == cls
        if np.any(m):
            a3.plot(v[m], n[m], "o", color=color, ms=3, label=name)
    a3.set_xlim(0.5, 2.1)
    a3.set_ylim(0.8, 2.2)
    a3.legend(fontsize=6, loc="upper right")
    a3.set_title("(c) controls over Omega")
    if title:
        fig.suptitle(title)
    save_png(fig, filename, crop=True)


def _example(fig_id: str, out_dir: pathlib.Path) -> FigureReport:
    ex = EXAMPLES[fig_id]
    sol = solve_example(ex["goal"])
    name = f"{fig_id.replace('.', '_')}.png"
    if not sol.ok:
        return FigureReport(notes=f"the direct method failed: {sol.message}")
    draw_solution(sol, out_dir / name, f"{fig_id}: x1 = {tuple(round(c, 4) for c in ex['goal'])}")
    arcs = sol.extras["arcs"]
    fr = arcs["fractions"]
    err = sol.endpoint_error
    rows = (
        Comparison("altitude loss (cost)", f"{sol.cost:.5f}", f"{ex['cost']:.5f} (independent)",
                   f"difference {sol.cost - ex['cost']:+.1e}"),
        Comparison("turn word", arcs["turn_word"], "-".join(ex["word"])),
        Comparison("corner reached", str(arcs["reaches_corner"]), str(ex["corner"]),
                   f"{100 * fr['corner']:.0f}% of s at the corner"),
        Comparison("arc length s1", f"{sol.path.length:.3f}",
                   f"s axis of the figure ticks to {ex['s_axis']:g}"),
        Comparison("share on locus / stall / corner", f"{fr['locus']:.2f} / {fr['stall']:.2f} / "
                   f"{fr['corner']:.2f}", "locus and stall boundary (section 6.8)"),
        Comparison("endpoint error (integration)", f"{err.max:.1e}", "", "plan() verification"),
        Comparison("mesh costs", ", ".join(f"{c:.6f}" for c in sol.stats["mesh_costs"]), "",
                   "mesh sizes " + ", ".join(str(m) for m in sol.stats["mesh_sizes"])),
    )  # fmt: skip
    return FigureReport(files=(name,), rows=rows, data={"cost": sol.cost})


@reproducible(
    "fig6.11",
    title="Locally optimal solution for x1 = (-2, 4, 7 pi/4)",
    dissertation="Fig 6.11: one long left turn on the extremal locus and stall boundary, wings "
    "level only at an isolated point; independent cost 0.36138",
)
def fig6_11(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example("fig6.11", out_dir)


@reproducible(
    "fig6.12",
    title="Locally optimal solution for x1 = (0, -0.5, pi)",
    dissertation="Fig 6.12: L-R-L; the speed along the locus mirrors about (1, 1); independent "
    "cost 0.26256",
)
def fig6_12(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example("fig6.12", out_dir)


@reproducible(
    "fig6.13",
    title="Locally optimal solution for x1 = (1.1, 2, 0)",
    dissertation="Fig 6.13: L-R, the only example that reaches the corner; independent cost "
    "0.20926 with 84% of the path at the corner",
)
def fig6_13(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example("fig6.13", out_dir)
