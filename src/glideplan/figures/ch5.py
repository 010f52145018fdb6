"""Chapter 5 figures: the glide polar, Table 5.2 and the three DG-1001M examples (5.9).

Goals are in units of R_stf (the turn radius at the speed to fly, 139.5 m). Each example is
planned by the synthesis (`glideplan.planners.min_altitude`), checked against the direct
method, and compared with the Dubins path flown at v_stf, as in Figs. 5.5-5.7.
"""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import Comparison, FigureReport, reproducible
from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.units import ms_to_kmh
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider, dg1001m

__all__ = ["EXAMPLES", "GLIDER", "dissertation_family_bbb", "draw_solution", "plan_example"]

GLIDER = dg1001m()
# goal (units of R_stf), dissertation's best type and orientation, its improvement over the
# Dubins path at v_stf (m, %), and our independent direct-method altitude loss (m)
EXAMPLES: dict[str, dict[str, Any]] = {
    "fig5.5": {"goal": (0.0, 1.0, 2 * math.pi / 3), "word": "BBB RLR", "gain": 2.4,
               "percent": 11.0, "direct": 19.4289},
    "fig5.6": {"goal": (-3.0, 4.0, 0.0), "word": "BSB LSR", "gain": 1.8, "percent": 6.5,
               "direct": 25.8483,
               "note": "Our gain is 1.75 m (6.3%), 0.05 m less than the dissertation's. The "
               "best path is an unsaturated BSB (untouched by the extension) that the direct "
               "method confirms to 1e-5 m; rounding the polar (v_ms = 91.1 instead of 91.0 "
               "km/h, R_stf = 139 m) moves the gain by less than 0.03 m. We attribute the "
               "difference to the dissertation's own numerics (1.75 m rounded up to 1.8 m "
               "gives its 6.5% of 27.6 m)."},
    "fig5.7": {"goal": (0.0, 2.0, 7 * math.pi / 4), "word": "BSB LSL", "gain": 1.7,
               "percent": 7.8, "direct": 20.1252},
}  # fmt: skip


def example_goal(figure_id: str, glider: QuadraticPolarGlider = GLIDER) -> Pose:
    """The example's goal in metres (the dissertation gives it in units of R_stf)."""
    x, y, h = EXAMPLES[figure_id]["goal"]
    return Pose(x * glider.radius_stf, y * glider.radius_stf, h)


def plan_example(figure_id: str, method: str = "synthesis") -> Solution:
    """Plan one of the three examples of section 5.9 for the DG-1001M."""
    from glideplan.planning import plan

    return plan(Pose(), example_goal(figure_id), GLIDER, "altitude", method).raise_for_status()


# ----- drawing ------------------------------------------------------------------------------


def draw_solution(
    solution: Solution, filename: pathlib.Path | str, *, max_candidates: int = 6
) -> None:
    """Candidate paths with their costs, the Dubins path at v_stf (dashed) and the optimal
    control history (turn rate and speed vs time, limits dashed), as in Figs. 5.5-5.7."""
    from glideplan.planners.min_altitude import dubins_reference

    plt = pyplot()
    glider = solution.vehicle
    assert isinstance(glider, QuadraticPolarGlider)
    unit = glider.radius_stf
    fig = plt.figure(figsize=(11.5, 5.2))
    grid = fig.add_gridspec(2, 2, width_ratios=(1.15, 1.0))
    ax = fig.add_subplot(grid[:, 0])
    feasible = [c for c in solution.candidates if c.path is not None]
    for k, cand in enumerate(feasible[:max_candidates]):
        assert cand.path is not None
        smp = cand.path.sample(n=400)
        best = k == 0
        ax.plot(
            smp.x / unit,
            smp.y / unit,
            lw=2.2 if best else 1.0,
            alpha=1.0 if best else 0.75,
            label=f"{cand.family} {cand.word} [{cand.cost:.2f}]",
        )
    ref = dubins_reference(solution.start, solution.goal, glider)
    if ref is not None and ref.path is not None:
        smp = ref.path.sample(n=400)
        ax.plot(
            smp.x / unit,
            smp.y / unit,
            "k--",
            lw=1.0,
            label=f"Dubins {ref.word} at v_stf [{ref.cost:.2f}]",
        )
    for pose in (solution.start, solution.goal):
        ax.annotate(
            "",
            xy=(
                pose.x / unit + 0.35 * math.cos(pose.heading),
                pose.y / unit + 0.35 * math.sin(pose.heading),
            ),
            xytext=(pose.x / unit, pose.y / unit),
            arrowprops={"arrowstyle": "->", "lw": 1.5},
        )
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x / R_stf")
    ax.set_ylabel("y / R_stf")
    ax.set_title("candidate paths [altitude loss, m]")
    ax.legend(fontsize=7, loc="best")
    if solution.path is not None:
        smp = solution.path.sample(n=600)
        ax_u = fig.add_subplot(grid[0, 1])
        ax_u.plot(smp.t, smp.turn_rate, "b-")
        for lim in (-glider.u_max, glider.u_max):
            ax_u.axhline(lim, color="k", ls="--", lw=0.8)
        ax_u.set_ylabel("turn rate (rad/s)")
        ax_u.set_title("optimal control history")
        ax_v = fig.add_subplot(grid[1, 1], sharex=ax_u)
        ax_v.plot(smp.t, ms_to_kmh(smp.speed), "b-")
        for v, name in ((glider.v_stall, "v_stall"), (glider.v_stf, "v_stf")):
            ax_v.axhline(ms_to_kmh(v), color="k", ls="--", lw=0.8)
            ax_v.text(smp.t[-1], ms_to_kmh(v), f" {name}", va="center", fontsize=7)
        ax_v.set_xlabel("time (s)")
        ax_v.set_ylabel("speed (km/h)")
    save_png(fig, filename)


# ----- Fig 5.1 and Table 5.2 -----------------------------------------------------------------


@reproducible(
    "fig5.1",
    title="A glide polar with the stall speed, minimum-sink speed and speed to fly",
    dissertation="Fig 5.1 (section 5.2): a typical glide polar w(v) with v_stall, v_ms, v_stf "
    "(tangent through the origin) and v_max marked",
)
def fig5_1(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    plt = pyplot()
    g = GLIDER
    v = np.linspace(g.v_stall, g.v_max, 300)
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    ax.plot(ms_to_kmh(v), g.sink_rate(v, 0.0), "b-", label="w(v) (5.26)")
    vt = np.linspace(0.0, g.v_stf * 1.25, 2)
    ax.plot(ms_to_kmh(vt), vt * g.w_stf / g.v_stf, "k:", lw=1, label="tangent through origin")
    for speed, name, offset in (
        (g.v_stall, "v_stall", (-22, -30)),
        (g.v_ms, "v_ms", (0, -30)),
        (g.v_stf, "v_stf", (22, -30)),
        (g.v_max, "v_max", (-30, 8)),
    ):
        w = float(g.sink_rate(speed, 0.0))
        ax.plot(ms_to_kmh(speed), w, "ko")
        ax.annotate(
            f"{name}\n{ms_to_kmh(speed):.1f} km/h",
            (ms_to_kmh(speed), w),
            textcoords="offset points",
            xytext=offset,
            ha="center",
            fontsize=8,
        )
    ax.set_xlim(0, ms_to_kmh(g.v_max) * 1.05)
    ax.set_ylim(0, 1.1 * float(g.sink_rate(g.v_max, 0.0)))
    ax.invert_yaxis()  # the polar is drawn downwards, as sink
    ax.set_xlabel("speed v (km/h)")
    ax.set_ylabel("sink rate w (m/s)")
    ax.set_title("DG-1001M quadratic glide polar")
    ax.legend(fontsize=8, loc="lower left")
    save_png(fig, out_dir / "fig5_1.png")
    slope = float(2 * g.a * g.v_stf + g.b)
    rows = (
        Comparison(
            "tangent check dw/dv(v_stf) = w/v",
            f"{slope:.5f} = {g.w_stf / g.v_stf:.5f}",
            "speed to fly: tangent through the origin",
            "definition (5.2.3)",
        ),
        Comparison(
            "v_ms > (v_stall + v_stf)/2",
            f"{g.v_ms:.3f} > {0.5 * (g.v_stall + g.v_stf):.3f} m/s",
            "holds (Assumption 5.2.4)",
        ),
    )
    return FigureReport(
        files=("fig5_1.png",),
        rows=rows,
        notes="v_max = 160 km/h is our choice (chapter 5 gives none); it never "
        "binds on an extremal.",
    )


@reproducible(
    "table5.2",
    title="Speeds and sink rates of the quadratic DG-1001M polar",
    dissertation="Table 5.2 (section 5.9): approx. stall 75.6 km/h / 0.63 m/s, minimum sink "
    "91.1 km/h / 0.58 m/s, speed to fly 105.2 km/h / 0.62 m/s; R_stf about 139 m",
)
def table5_2(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    g = GLIDER
    data = [
        ("stall speed", g.v_stall, g.w_stall, "75.6 km/h / 0.63 m/s"),
        ("minimum sink", g.v_ms, g.w_ms, "91.1 km/h / 0.58 m/s"),
        ("speed to fly", g.v_stf, g.w_stf, "105.2 km/h / 0.62 m/s"),
    ]
    lines = ["condition,speed_kmh,speed_ms,sink_ms,radius_m"]
    rows = []
    for name, v, w, ref in data:
        lines.append(f"{name},{ms_to_kmh(v):.2f},{v:.4f},{w:.4f},{v / g.u_max:.2f}")
        note = ""
        if name == "minimum sink":
            note = "-b/2a of the printed coefficients is 91.02 km/h; 91.1 rounds differently"
        rows.append(Comparison(name, f"{ms_to_kmh(v):.1f} km/h / {w:.3f} m/s", ref, note))
    rows.append(Comparison("R_stf", f"{g.radius_stf:.1f} m", "about 139 m"))
    rows.append(Comparison("R_stall", f"{g.radius_stall:.1f} m", "about 100 m"))
    (out_dir / "table5_2.csv").write_text("\n".join(lines) + "\n")
    return FigureReport(files=("table5_2.csv",), rows=tuple(rows))


# ----- Figs 5.5-5.7 --------------------------------------------------------------------------


def dissertation_family_bbb(solution: Solution) -> float | None:
    """Best BBB path of the dissertation's family for the solution's goal: unclipped speed
    (lambda <= v_ms - v_stall, Lemma 5.7.6), the middle arc symmetric about theta but its
    angle free (no H = 0), by SLSQP from the best BBB candidate (C.22). Altitude loss (m)."""
    from scipy.optimize import minimize

    from glideplan.planners.min_altitude import Kernel

    g = solution.vehicle
    assert isinstance(g, QuadraticPolarGlider)
    bbb = [c for c in solution.candidates if c.family == "BBB" and c.path is not None]
    if not bbb:
        return None
    angles = np.abs(np.array(bbb[0].info["angles"], dtype=float))
    mirror = bbb[0].info["angles"][0] < 0  # solve the first-turn-L mirror image
    local = solution.goal.relative_to(solution.start)
    gx, gy, gh = (
        local.x,
        (-local.y if mirror else local.y),
        (-local.heading if mirror else local.heading),
    )
    kern, u, lam_max = Kernel.of(g), g.u_max, g.v_ms - g.v_stall

    def evaluate(p: np.ndarray) -> tuple[complex, float]:
        a1, beta, a3, lam = p
        phi = np.array([beta / 2, beta / 2 - a1, -beta / 2, -beta / 2 + a3])
        P, W, _ = kern.primitives(phi, lam)
        z = np.exp(1j * (a1 - beta / 2)) * ((P[0] - P[1]) + (P[0] - P[2]) + (P[3] - P[2])) / u
        return z, float(((W[0] - W[1]) + (W[0] - W[2]) + (W[3] - W[2])) / u)

    def bc(p: np.ndarray) -> np.ndarray:
        z, _ = evaluate(p)
        d = p[0] - p[1] + p[2] - gh
        scale = g.radius_stf
        return np.array(
            [(z.real - gx) / scale, (z.imag - gy) / scale, math.sin(d), 1 - math.cos(d)]
        )

    p0 = np.array([*angles, lam_max])
    res = minimize(
        lambda p: evaluate(p)[1],
        p0,
        method="SLSQP",
        constraints=[{"type": "eq", "fun": lambda p: bc(p)[:3]}],
        bounds=[(0, 2 * math.pi)] * 3 + [(0, lam_max)],
        options={"maxiter": 500, "ftol": 1e-12},
    )
    if not res.success or np.max(np.abs(bc(res.x))) > 1e-8:
        return None
    return float(res.fun)


def _example_figure(figure_id: str, out_dir: pathlib.Path) -> FigureReport:
    ex = EXAMPLES[figure_id]
    sol = plan_example(figure_id)
    direct = plan_example(figure_id, "direct")
    name = figure_id.replace(".", "_") + ".png"
    draw_solution(sol, out_dir / name)
    dubins = float(sol.extras["dubins_cost"])
    gain = dubins - sol.cost
    pct = 100.0 * gain / dubins
    rows = [
        Comparison("best type, orientation", f"{sol.family} {sol.word}", ex["word"]),
        Comparison(
            "altitude loss (m)",
            f"{sol.cost:.4f}",
            "not reported",
            f"direct method {direct.cost:.4f} (independent solve {ex['direct']})",
        ),
        Comparison("Dubins path at v_stf (m)", f"{dubins:.4f}", "not reported"),
        Comparison(
            "improvement over Dubins",
            f"{gain:.2f} m ({pct:.1f}%)",
            f"{ex['gain']} m ({ex['percent']}%)",
        ),
    ]
    notes = ex.get("note", "")
    if sol.family == "BBB":
        stall = float(sol.candidates[0].info.get("saturated_time", 0.0))
        old = dissertation_family_bbb(sol)
        frac = stall / sol.path.duration if sol.path is not None else 0.0
        rows.append(
            Comparison(
                "time at v_stall",
                f"{stall:.1f} s ({100 * frac:.0f}% of "
                f"{sol.path.duration if sol.path else 0:.1f} s)",
                "reaches v_stall in the middle of the second turn",
            )
        )
        if old is not None:
            rows.append(
                Comparison(
                    "dissertation's family (lambda <= v_ms - v_stall)",
                    f"{old:.4f} m, {dubins - old:.2f} m "
                    f"({100 * (dubins - old) / dubins:.1f}%) better than Dubins",
                    f"{ex['gain']} m ({ex['percent']}%)",
                )
            )
        notes = (
            "The optimum's middle turn is a B arc clipped at v_stall (lambda > v_ms - v_stall), "
            "which the dissertation's family B excludes (Lemma 5.7.6). Restricted to that "
            "family, the best BBB RLR path reproduces the dissertation's 2.4 m (11%); the "
            "saturated arc saves a further few centimetres."
        )
    return FigureReport(
        files=(name,),
        rows=tuple(rows),
        notes=notes,
        data={"cost": sol.cost, "dubins_cost": dubins, "direct_cost": direct.cost},
    )


@reproducible(
    "fig5.5",
    title="Path synthesis for the goal (0, 1, 2pi/3) R_stf",
    dissertation="Fig 5.5: candidate paths with costs, Dubins at v_stf dashed, optimal "
    "control history; best BBB RLR, 2.4 m (11%) less altitude than the Dubins path",
)
def fig5_5(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example_figure("fig5.5", out_dir)


@reproducible(
    "fig5.6",
    title="Path synthesis for the goal (-3, 4, 0) R_stf",
    dissertation="Fig 5.6: best BSB LSR, 1.8 m (6.5%) less altitude than the Dubins path",
)
def fig5_6(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example_figure("fig5.6", out_dir)


@reproducible(
    "fig5.7",
    title="Path synthesis for the goal (0, 2, 7pi/4) R_stf",
    dissertation="Fig 5.7: best BSB LSL (the Dubins path is LSL too), 1.7 m (7.8%) less "
    "altitude than the Dubins path",
)
def fig5_7(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    return _example_figure("fig5.7", out_dir)
