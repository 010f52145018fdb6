"""Per-planner solution figures, beside the path plotting (`glideplan.plotting`).

Panels that show what a planner's `Solution` holds beyond its path: the chapter 5 glider's
candidates with the control history (`min_altitude_figure`, Figs. 5.5-5.7) and the chapter 6
glider's controls over the control set Omega (`load_factor_figure`, Figs. 6.11-6.13). Written
with `draw_min_altitude` / `draw_load_factor` (`plotting.save_figure`). The CLI's `--plot`
and `glideplan reproduce` (`figures.ch5`, `figures.ch6`) both draw them. Matplotlib is
imported inside the functions.
"""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.plotting import describe_vehicle, mark_pose, pose_text, save_figure
from glideplan.solution import Solution
from glideplan.units import ms_to_kmh
from glideplan.vehicles.load_factor_glider import LoadFactorGlider
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = [
    "CLASS_STYLE",
    "draw_control_set",
    "draw_load_factor",
    "draw_min_altitude",
    "load_factor_figure",
    "min_altitude_figure",
]

CLASS_STYLE = {
    "corner": ("tab:red", "corner"),
    "stall": ("tab:orange", "stall boundary"),
    "locus": ("tab:blue", "extremal locus"),
    "wings_level": ("tab:green", "wings level"),
    "other": ("0.5", "other"),
}



def draw_control_set(ax: Any, glider: LoadFactorGlider) -> None:
    """The load-factor glider's control set Omega on (v, n) axes (Fig 6.3's curves)."""
    from glideplan.analysis import load_factor as lf

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


def min_altitude_figure(solution: Solution, *, max_candidates: int = 6, title: str = "") -> Any:
    """Chapter 5's solution figure (Figs. 5.5-5.7; returned, not saved): left the candidate
    paths in units of R_stf with the Dubins path at v_stf (dashed), start and goal with their
    headings and the legend below the axes; right the optimal control history (turn rate and speed
    against time, limits dashed); the title states the problem (after `title`, e.g. the
    figure's name) and the answer."""
    import matplotlib.pyplot as plt

    glider = solution.vehicle
    assert isinstance(glider, QuadraticPolarGlider)
    unit = glider.radius_stf
    fig = plt.figure(figsize=(12.5, 6.4), layout="constrained")
    grid = fig.add_gridspec(2, 2, width_ratios=(1.15, 1.0))
    ref = _candidates_panel(fig.add_subplot(grid[:, 0]), solution, glider, max_candidates)
    if solution.path is not None:
        _control_panels(fig, grid, solution.path, glider)
    problem = (
        f"Minimum altitude loss, {describe_vehicle(glider)}\n"
        f"start {pose_text(solution.start, 'R_stf', unit)} -> "
        f"goal {pose_text(solution.goal, 'R_stf', unit)}"
    )
    if solution.ok:
        answer = (
            f"optimal word {solution.word or '-'}, family {solution.family or '-'}, "
            f"altitude loss {solution.cost:.4g} m"
        )
        if ref is not None and ref.path is not None:
            answer += f" (Dubins path at v_stf: {ref.cost:.4g} m)"
    else:
        answer = f"status {solution.status.value}: {solution.message}"
    text = f"{problem}\n{answer}"
    fig.suptitle(f"{title}\n{text}" if title else text, fontsize=10, x=0.01, ha="left")
    return fig


def _candidates_panel(ax: Any, solution: Solution, glider: QuadraticPolarGlider,
                      max_candidates: int) -> Any:
    """The candidate paths in units of R_stf (the optimal black), the Dubins path at v_stf
    (grey, dashed), start and goal; return that Dubins reference (or None)."""
    from glideplan.planners.min_altitude import dubins_reference

    unit = glider.radius_stf
    feasible = [c for c in solution.candidates if c.path is not None]
    styles = ("--", "-.", ":", (0, (5, 1, 1, 1)))
    for k, cand in enumerate(feasible[:max_candidates]):
        assert cand.path is not None
        smp = cand.path.sample(n=400)
        best = k == 0
        name = "optimal" if best else "candidate"
        ax.plot(
            smp.x / unit,
            smp.y / unit,
            color="black" if best else f"C{k - 1}",
            ls="-" if best else styles[(k - 1) % len(styles)],
            lw=2.4 if best else 1.1,
            alpha=1.0 if best else 0.8,
            zorder=3 if best else 2,
            label=f"{name} {cand.family} {cand.word}, {cand.cost:.2f} m",
        )
    ref = dubins_reference(solution.start, solution.goal, glider)
    if ref is not None and ref.path is not None:
        smp = ref.path.sample(n=400)
        ax.plot(
            smp.x / unit,
            smp.y / unit,
            color="0.45",
            ls=(0, (2, 2)),
            lw=1.2,
            label=f"Dubins {ref.word} at v_stf, {ref.cost:.2f} m",
        )
    if solution.path is not None:
        opt = solution.path.sample(n=200)
        span = max(float(np.ptp(opt.x)), float(np.ptp(opt.y))) / unit
    else:
        span = math.hypot(solution.goal.x - solution.start.x, solution.goal.y - solution.start.y)
        span /= unit
    arrow = max(0.3, 0.1 * span)
    mark_pose(ax, solution.start, arrow, colour="tab:green", marker="o",
              label="start (heading)", scale=unit)
    mark_pose(ax, solution.goal, arrow, colour="tab:red", marker="s",
              label="goal (heading)", scale=unit)
    ax.set_aspect("equal", adjustable="datalim")
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.set_xlabel(f"x / R_stf  (R_stf = {unit:.4g} m)")
    ax.set_ylabel("y / R_stf")
    ax.set_title("candidate paths, altitude loss in m", fontsize=10)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.1), ncol=2,
              borderaxespad=0.0)
    return ref


def _control_panels(fig: Any, grid: Any, path: Any, glider: QuadraticPolarGlider) -> None:
    """The optimal control history: turn rate (limits +-u_max) above speed (v_stall, v_stf)."""
    smp = path.sample(n=600)
    ax_u = fig.add_subplot(grid[0, 1])
    ax_u.plot(smp.t, smp.turn_rate, "b-")
    for lim in (-glider.u_max, glider.u_max):
        ax_u.axhline(lim, color="k", ls="--", lw=0.8)
    for lim, name, va in ((glider.u_max, "u_max", "top"), (-glider.u_max, "-u_max", "bottom")):
        ax_u.text(0.99, lim, f"{name} ", transform=ax_u.get_yaxis_transform(), ha="right",
                  va=va, fontsize=7)
    ax_u.set_ylabel("turn rate u (rad/s)")
    ax_u.set_title("optimal control history", fontsize=10)
    ax_u.grid(True, lw=0.4, alpha=0.5)
    ax_u.tick_params(labelbottom=False)
    ax_v = fig.add_subplot(grid[1, 1], sharex=ax_u)
    ax_v.plot(smp.t, ms_to_kmh(smp.speed), "b-")
    for v, name in ((glider.v_stall, "v_stall"), (glider.v_stf, "v_stf")):
        ax_v.axhline(ms_to_kmh(v), color="k", ls="--", lw=0.8)
        ax_v.text(0.99, ms_to_kmh(v), f"{name} ", transform=ax_v.get_yaxis_transform(),
                  ha="right", va="bottom" if name == "v_stall" else "top", fontsize=7)
    ax_v.set_xlabel("time t (s)")
    ax_v.set_ylabel("speed v (km/h)")
    ax_v.grid(True, lw=0.4, alpha=0.5)


def draw_min_altitude(
    solution: Solution, filename: pathlib.Path | str, *, max_candidates: int = 6, title: str = ""
) -> None:
    """Write `min_altitude_figure(solution)` to `filename`."""
    fig = min_altitude_figure(solution, max_candidates=max_candidates, title=title)
    save_figure(fig, filename, crop=True, tight=False)


def load_factor_figure(solution: Solution, title: str = "") -> Any:
    """Chapter 6's solution figure (Figs. 6.11-6.13; returned, not saved): (a) v and n
    against s, (b) the path with start and goal headings, (c) (v, n) over Omega coloured by
    arc class; lengths in l_ref = V_ref^2 / g, speeds in V_ref; legends below the panels; the
    title states the problem (after `title`, e.g. the figure's name) and the answer."""
    import matplotlib.pyplot as plt

    glider = solution.vehicle
    ctr = solution.extras["controls"]
    s, v, n = (np.asarray(ctr[k]) for k in ("s", "v", "n"))
    labels = np.asarray(ctr["label"])
    fig = plt.figure(figsize=(13.5, 5.6), layout="constrained")
    def below(ax: Any) -> dict[str, Any]:
        """Legend placement 40 pt under the panel's bottom edge (clear of its tick labels
        and axis label) whatever height the equal aspect leaves the panel."""
        from matplotlib.transforms import ScaledTranslation

        shift = ScaledTranslation(0.0, -40.0 / 72.0, fig.dpi_scale_trans)
        return {"loc": "upper center", "bbox_to_anchor": (0.5, 0.0), "borderaxespad": 0.0,
                "bbox_transform": ax.transAxes + shift}

    a1 = fig.add_subplot(1, 3, 1)
    a1.plot(s, v, "b-", label="speed v / V_ref")
    a1.plot(s, n, "r-", label="load factor n")
    a1.set_xlabel("arc length s / l_ref")
    a1.set_ylabel("v / V_ref, n")
    a1.grid(True, lw=0.4, alpha=0.5)
    a1.legend(fontsize=8, ncol=2, **below(a1))
    a1.set_title("(a) controls", fontsize=10)
    a2 = fig.add_subplot(1, 3, 2)
    assert solution.path is not None
    smp = solution.path.sample(400)
    a2.plot(smp.x, smp.y, "k-", lw=2.0,
            label=f"optimal {solution.word or '-'} ({solution.family or '-'}), "
                  f"{solution.cost:.5g} l_ref")
    span = float(max(np.ptp(smp.x), np.ptp(smp.y), 1e-9))
    mark_pose(a2, solution.start, 0.1 * span, colour="tab:green", marker="o",
              label="start (heading)")
    mark_pose(a2, solution.goal, 0.1 * span, colour="tab:red", marker="s",
              label="goal (heading)")
    a2.margins(0.08)
    a2.set_aspect("equal", adjustable="box")
    a2.set_xlabel("x / l_ref")
    a2.set_ylabel("y / l_ref")
    a2.grid(True, lw=0.4, alpha=0.5)
    a2.legend(fontsize=8, ncol=1, **below(a2))
    a2.set_title("(b) path", fontsize=10)
    a3 = fig.add_subplot(1, 3, 3)
    assert isinstance(glider, LoadFactorGlider)
    draw_control_set(a3, glider)
    for cls, (color, name) in CLASS_STYLE.items():
        m = labels == cls
        if np.any(m):
            a3.plot(v[m], n[m], "o", color=color, ms=3, label=f"path: {name}")
    a3.set_xlim(0.5, 2.1)
    a3.set_ylim(0.8, 2.2)
    a3.set_xlabel("speed v / V_ref")
    a3.legend(fontsize=7, ncol=2, **below(a3))
    a3.set_title("(c) controls over Omega", fontsize=10)
    problem = (
        f"Minimum altitude loss, {describe_vehicle(glider)}; lengths in l_ref = V_ref^2 / g\n"
        f"start {pose_text(solution.start, 'l_ref')} -> goal {pose_text(solution.goal, 'l_ref')}"
        f"\noptimal word {solution.word or '-'}, family {solution.family or '-'}, "
        f"altitude loss {solution.cost:.5g} l_ref, path length {solution.path.length:.4g} l_ref"
    )
    fig.suptitle(f"{title}\n{problem}" if title else problem, fontsize=10, x=0.01, ha="left")
    return fig


def draw_load_factor(solution: Solution, filename: str | pathlib.Path, title: str = "") -> None:
    """Write `load_factor_figure(solution)` to `filename`."""
    save_figure(load_factor_figure(solution, title), filename, crop=True, tight=False)
