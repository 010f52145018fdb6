"""Chapter 4 figures: control set, hodograph, Table 4.3 / Figs 4.7-4.8 and the goal grids.

Normalised model of section 4.9: v_max = 1, u_max = 1 (R = 1), v_min = 0.3 (r = 0.3). The
computations beyond `plan()` (Table 4.3's rows re-solved in the dissertation's
parameterisation) live in `glideplan.studies.min_time_table`.
"""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import (
    Comparison,
    FigureReport,
    Printed,
    compare,
    reproducible,
    yes_no,
)
from glideplan.pose import Pose
from glideplan.studies.min_time_table import (
    EXAMPLE_GOAL,
    WEAK_TYPES,
    descent_from,
    dissertation_minimum,
    example_car,
)

__all__ = ["EXAMPLE_GOAL", "TABLE_4_3"]

PI = math.pi

# Table 4.3 as printed: (group, sequence, orientation, time as printed)
TABLE_4_3 = (
    ("TST", "BCBSBCB", "RSR", "11.278"),
    ("TST", "BCBSB", "RSL", "6.615"),
    ("TST", "CBSBCB", "RSR", "11.359"),
    ("TST", "CBSBC", "LSL", "3.176"),
    ("TST", "CBSB", "LSL", "2.883"),
    ("TST", "CBSB", "LSR", "2.875"),
    ("TTTT", "BCBB", "LR", "2.887"),
    ("TTTT", "BTB", "RLR", "3.219"),
    ("umax", "CBBCB", "LL", "8.378"),
    ("Dubins", "BBB", "RLR", "5.980"),
    ("Dubins", "BSB", "LSR", "9.378"),
    ("Dubins", "BBB", "RSL", "8.015"),
    ("Dubins", "BSB", "RSR", "14.078"),
)
TABLE_SOURCE = "Table 4.3"
# Printed types that cannot be right, and the type we compare with instead (with why).
_TYPO = {
    "BSB LSR": ("BSB LSL", "printed as LSR, but the Dubins LSR path does not exist for this "
                "goal; the LSL path has this time"),
    "BBB RSL": ("BSB RSL", "printed as BBB RSL (an RSL word is a BSB path)"),
}  # fmt: skip
PRINTED_COUNT = Printed("13", "section 4.9: 13 of 72 candidate paths converged")
PRINTED_RATIO = Printed(
    "2", "section 4.9: the Dubins path at maximum speed takes about twice as long"
)
PRINTED_RADII = {
    "R": Printed("1", "section 4.9: R = 1", "m"),
    "r": Printed("0.3", "section 4.9: r = 0.3", "m"),
}


def _printed_time(type_name: str) -> Printed | None:
    """The printed time of a type of Table 4.3 (our reading of the two typos included)."""
    for _, seq, orient, value in TABLE_4_3:
        name = f"{seq} {orient}"
        if _TYPO.get(name, (name, ""))[0] == type_name:
            return Printed(value, f"{TABLE_SOURCE}, row {name}", "s")
    return None


def _plan_example() -> Any:
    from glideplan.planning import plan

    return plan(Pose(), EXAMPLE_GOAL, example_car()).raise_for_status()


def _plt() -> Any:
    return pyplot()


def _car() -> Any:
    return example_car()


@reproducible(
    "fig4.1",
    title="Control constraint set",
    dissertation="Fig 4.1: Omega = {(kappa, v): v_min <= v <= 1, |kappa| <= u_max/v} with the "
    "extremal controls S (kappa = 0, v = 1), B (|kappa| = u_max, v = 1) and C "
    "(|kappa| = u_max/v_min, v = v_min) marked.",
)
def fig4_1(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """The set Omega of (4.5) for v_min = 0.3, u_max = 1, with S, B and C."""
    plt = _plt()
    car = _car()
    v = np.linspace(car.v_min, car.v_max, 200)
    k = car.u_max / v
    fig, ax = plt.subplots(figsize=(6, 4.5))
    ax.fill_betweenx(v, -k, k, color="tab:blue", alpha=0.2, label="Omega")
    ax.plot(k, v, "k-", lw=1.2)
    ax.plot(-k, v, "k-", lw=1.2)
    ax.plot([-k[0], k[0]], [v[0], v[0]], "k-", lw=1.2)
    ax.plot([-k[-1], k[-1]], [v[-1], v[-1]], "k-", lw=1.2)
    pts = {"S": (0.0, car.v_max), "B": (car.u_max / car.v_max, car.v_max),
           "C": (car.u_max / car.v_min, car.v_min)}  # fmt: skip
    for name, (kk, vv) in pts.items():
        for sgn in (1, -1) if kk else (1,):
            ax.plot(sgn * kk, vv, "o", color="tab:red")
            ax.annotate(name, (sgn * kk, vv), textcoords="offset points", xytext=(6, 6))
    ax.set_xlabel("curvature kappa = u/v (1/m)")
    ax.set_ylabel("speed v (m/s)")
    ax.set_title("control constraint set (v_min = 0.3, u_max = 1)")
    ax.grid(alpha=0.3)
    f = save_png(fig, out_dir / "fig4_1_control_set.png")
    rows = (
        compare("sharpest turn |kappa| = u_max/v_min", car.u_max / car.v_min, unit="1/m"),
        compare("B arc radius R = v_max/u_max", car.bang_radius, PRINTED_RADII["R"]),
        compare("C arc radius r = v_min/u_max", car.corner_radius, PRINTED_RADII["r"]),
    )
    return FigureReport(files=(f.name,), rows=rows)


def _hodograph_minimiser(eta_psi: float, eta0: float, car: Any) -> str:
    """Which vertex (or edge) of the hodograph minimises H_c = eta_psi f_psi + eta0 f0."""
    f0 = np.array([1.0 / car.v_max, 1.0 / car.v_min])
    verts = {
        "B": (car.u_max * f0[0] * -np.sign(eta_psi or 1.0), f0[0]),
        "C": (car.u_max * f0[1] * -np.sign(eta_psi or 1.0), f0[1]),
        "S": (0.0, f0[0]),
    }
    h = {k: eta_psi * p[0] + eta0 * p[1] for k, p in verts.items()}
    return min(h, key=lambda k: (round(h[k], 12), "SBC".index(k)))


@reproducible(
    "fig4.2",
    title="Hodograph with lines of constant H_c",
    dissertation="Fig 4.2: the hodograph {(f_psi, f0) = (kappa, 1/v)} (a convex trapezoid) with "
    "dotted lines of constant H_c = eta_psi kappa + eta0/v; for the adjoint vector shown the "
    "separating plane touches the corner of maximum turn rate and minimum speed (a C arc).",
)
def fig4_2(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """The hodograph of (4.14) and the minimising vertex for three adjoint vectors."""
    plt = _plt()
    car = _car()
    f0a, f0b = 1.0 / car.v_max, 1.0 / car.v_min
    ua, ub = car.u_max * f0a, car.u_max * f0b
    poly = np.array([[-ua, f0a], [ua, f0a], [ub, f0b], [-ub, f0b], [-ua, f0a]])
    fig, ax = plt.subplots(figsize=(6.5, 5))
    ax.fill(poly[:, 0], poly[:, 1], color="tab:blue", alpha=0.2)
    ax.plot(poly[:, 0], poly[:, 1], "k-", lw=1.2)
    eta_psi, eta0 = -1.5, 1.0  # eta0/|eta_psi| < u_max: the C corner (as in Fig 4.2)
    fpsi = np.linspace(-ub - 0.5, ub + 0.5, 50)
    corner = np.array([ub, f0b])
    hmin = eta_psi * corner[0] + eta0 * corner[1]
    for c in hmin + np.arange(0, 6) * 1.0:
        ax.plot(fpsi, (c - eta_psi * fpsi) / eta0, "k:", lw=0.8)
    ax.plot(fpsi, (hmin - eta_psi * fpsi) / eta0, "r-", lw=1.5, label="separating plane P")
    ax.annotate(
        "",
        xy=corner + 0.8 * np.array([eta_psi, eta0]) / math.hypot(eta_psi, eta0),
        xytext=corner,
        arrowprops={"arrowstyle": "->", "color": "r"},
    )
    for name, p in {"S": (0, f0a), "B": (ua, f0a), "C": (ub, f0b)}.items():
        ax.plot(*p, "o", color="tab:red")
        ax.annotate(name, p, textcoords="offset points", xytext=(6, -12))
    ax.set_xlim(-ub - 0.5, ub + 0.5)
    ax.set_ylim(0.0, f0b + 1.0)
    ax.set_xlabel("state rate f_psi = kappa")
    ax.set_ylabel("cost rate f0 = 1/v")
    ax.set_title(f"hodograph, adjoint (eta_psi, eta0) = ({eta_psi}, {eta0})")
    ax.legend(loc="lower left", fontsize=8)
    f = save_png(fig, out_dir / "fig4_2_hodograph.png")
    rows = []
    for ep, e0 in ((0.0, 1.0), (-0.5, 1.0), (-1.5, 1.0), (-1.0, 0.0)):
        ours = _hodograph_minimiser(ep, e0, car)
        rule = _minimum_principle_rule(ep, e0, car)
        rows.append(
            compare(
                f"minimiser of H_c for (eta_psi, eta0) = ({ep}, {e0})",
                ours,
                reference=rule,
                reference_source="the rule of section 4.4 (Table 4.1): S if eta_psi = 0, "
                "B if eta0/|eta_psi| > u_max, C if below",
                note="" if ours == rule else "the vertex search and the rule disagree",
            )
        )
    return FigureReport(files=(f.name,), rows=tuple(rows))


def _minimum_principle_rule(eta_psi: float, eta0: float, car: Any) -> str:
    """The extremal control the Minimum Principle names for an adjoint (section 4.4)."""
    if eta_psi == 0.0:
        return "S"
    return "B" if eta0 / abs(eta_psi) > car.u_max else "C"


def table_4_3_rows(weak_starts: int = 20) -> tuple[list[Comparison], Any]:
    """Our candidates for x1 = (0, 2, 2 pi/3), R = 1, r = 0.3, beside Table 4.3's rows."""
    sol = _plan_example()
    ours = {c.info.get("type"): c for c in sol.candidates if c.feasible}
    rows = []
    extremal = 0
    for group, seq, orient, value in TABLE_4_3:
        name = f"{seq} {orient}"
        target, reading = _TYPO.get(name, (name, ""))
        printed = Printed(value, f"{TABLE_SOURCE}, row {name}", "s")
        cand = ours.get(target)
        if cand is not None:
            extremal += 1
            rows.append(_extremal_row(name, group, target, reading, cand, printed))
        else:
            rows += _weak_rows(name, printed, weak_starts)
    listed = {_TYPO.get(f"{s} {o}", (f"{s} {o}", ""))[0] for _, s, o, _ in TABLE_4_3}
    extra = [c for t, c in ours.items() if t not in listed]
    for c in extra:
        note = (
            "a rigid sequence that (4.26) leaves out (B.4, (4.24)); solved because B.4 fails "
            "for some goals, not optimal here"
            if not c.info.get("in_dissertation", True)
            else "also a locally optimal candidate here (found by the synthesis)"
        )
        rows.append(compare(f"{c.info['type']}: time (not in Table 4.3)", c.cost, unit="s",
                            note=note))  # fmt: skip
    in_72 = [c for c in extra if c.info.get("in_dissertation", True)]
    count = extremal + len(in_72)
    rows.append(
        compare(
            "candidates of the 72 that are locally optimal",
            count,
            PRINTED_COUNT,
            note="" if count == 13 else (
                f"{extremal} printed rows are extremals, {13 - extremal} are not (rows above); "
                f"{len(in_72)} candidates of the 72 that the table does not list are "
                f"({', '.join(c.info['type'] for c in in_72)})"
            ),
        )
    )  # fmt: skip
    dub = min(
        c.cost
        for c in sol.candidates
        if c.info.get("group") == "Dubins" and c.info["type"].split()[0] in ("BSB", "BBB")
    )
    rows.append(compare("Dubins at v_max / optimal time", dub / sol.cost, PRINTED_RATIO,
                        unit=""))  # fmt: skip
    return rows, sol


def _extremal_row(name: str, group: str, target: str, reading: str, cand: Any,
                  printed: Printed) -> Comparison:
    """A printed row our synthesis has as an extremal: its time against the printed one."""
    note = reading
    if group == "umax":
        note = (
            f"fixed turn rate, speed profile not unique (singular arc); the profile "
            f"built is {cand.family} ({cand.info['parameters']['loops']} extra loop)"
        )
    if abs(cand.cost - printed.value) > (printed.tolerance or 0.0):
        note = (note + "; " if note else "") + (
            f"ours - printed = {cand.cost - float(printed.value):+.4f} s, the synthesis "
            f"path verified by integration"
        )
    return compare(f"{name}: time" + (f" (ours: {target})" if reading else ""),
                   cand.cost, printed, note=note)  # fmt: skip


def _weak_rows(name: str, printed: Printed, weak_starts: int) -> list[Comparison]:
    """A printed row that is no extremal of ours: the minimum of (4.27) in the dissertation's
    parameterisation, and whether the direct method started there descends (not a local
    optimum of the control problem)."""
    weak = dissertation_minimum(name, weak_starts) if name in WEAK_TYPES else None
    direct = descent_from(weak) if weak is not None else None
    if weak is None:
        note = "no extremal of this type, and (4.27) did not converge"
        return [compare(f"{name}: time", None, printed, note=note)]
    return [
        compare(
            f"{name}: minimum of (4.27) in the dissertation's parameterisation",
            weak.cost,
            printed,
            note=f"bounds active there: {', '.join(weak.active) or 'none'}",
        ),
        compare(
            f"{name}: a local optimum of the control problem",
            yes_no(direct is None or direct >= weak.cost - 1e-6),
            Printed("yes", f"{TABLE_SOURCE} lists {name} as locally optimal", word=True),
            note="" if direct is None or direct >= weak.cost - 1e-6 else (
                f"the direct method started from the (4.27) minimum {weak.cost:.6f} descends "
                f"to {direct:.6f}; the minimum sits on a bound ({', '.join(weak.active)}), "
                "violates H = 0 and is no extremal"
            ),
        ),
    ]  # fmt: skip


@reproducible(
    "table4.3",
    title="Locally optimal solutions for x1 = (0, 2, 2pi/3)",
    dissertation="Table 4.3: 13 of 72 candidates converged; lowest CBSB LSR 2.875, then CBSB LSL "
    "2.883, BCBB LR 2.887, CBSBC LSL 3.176, BTB RLR 3.219, BBB RLR 5.980, BCBSB RSL 6.615, "
    "BBB RSL 8.015, CBBCB LL 8.378, BSB LSR 9.378, BCBSBCB RSR 11.278, CBSBCB RSR 11.359, "
    "BSB RSR 14.078.",
)
def table4_3(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Every candidate the synthesis finds, matched with the dissertation's rows."""
    rows, sol = table_4_3_rows(weak_starts=200 if full else 20)
    f = out_dir / "table4_3.md"
    lines = ["| quantity | ours | Table 4.3 | verdict | note |", "|---|---|---|---|---|"]
    lines += [
        f"| {r.quantity} | {r.ours if isinstance(r.ours, str) else f'{r.ours:.4f}'} | "
        f"{r.dissertation if r.dissertation is not None else '-'} | {r.verdict} | {r.note} |"
        for r in rows
    ]
    f.write_text("\n".join(lines) + "\n")
    notes = (
        f"Best: {sol.family} {sol.word} {sol.cost:.6f} (verified by integration, endpoint error "
        f"{sol.endpoint_error.max:.1e}); {sum(c.feasible for c in sol.candidates)} distinct "
        "candidates. Rows without an extremal are re-solved as (4.27) in the dissertation's "
        "parameterisation (glideplan.studies.min_time_table) and the direct method is started "
        "from that minimum."
    )
    return FigureReport(files=(f.name,), rows=tuple(rows), notes=notes)


def _draw_candidates(cands: list, filename: pathlib.Path, title: str) -> pathlib.Path:
    from glideplan.plotting import plot_path

    plt = _plt()
    fig, ax = plt.subplots(figsize=(7, 6.5))
    for c in cands:
        plot_path(c.path, ax, lw=1.4, label=f"{c.info['type']} {c.cost:.3f} s")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(alpha=0.3)
    ax.set_xlabel("x (m, R = 1)")
    ax.set_ylabel("y (m)")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_title(title)
    return save_png(fig, filename, crop=True)


def _candidate_rows(cands: list) -> list[Comparison]:
    rows = []
    for c in cands:
        printed = _printed_time(c.info["type"])
        note = ""
        if printed is not None and abs(c.cost - float(printed.value)) > (printed.tolerance or 0):
            note = f"ours - printed = {c.cost - float(printed.value):+.4f} s"
        rows.append(compare(f"{c.info['type']}: time", c.cost, printed, unit="s", note=note))
    return rows


@reproducible(
    "fig4.7",
    title="Locally optimal paths from Gamma_TTTT, Gamma_TST and Gamma_umax",
    dissertation="Fig 4.7: the converged candidates of Gamma_TTTT u Gamma_TST u Gamma_umax for "
    "x1 = (0, 2, 2pi/3), R = 1, r = 0.3; filled circles boundary poses, open circles switches.",
)
def fig4_7(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    sol = _plan_example()
    cands = [c for c in sol.candidates if c.feasible and c.info.get("group") != "Dubins"]
    listed = [c for c in cands if c.info.get("in_dissertation", True)]
    f = _draw_candidates(listed, out_dir / "fig4_7_candidates.png",
                         "x1 = (0, 2, 2pi/3): TTTT, TST and umax candidates")  # fmt: skip
    rows = _candidate_rows(listed)
    extra = [c for c in cands if c not in listed]
    if extra:
        rows.append(
            compare(
                "rigid sequences left out of (4.26), not drawn",
                ", ".join(f"{c.info['type']} {c.cost:.3f}" for c in extra),
                note="solved because B.4 fails for some goals (see table4.3)",
            )
        )
    return FigureReport(files=(f.name,), rows=tuple(rows))


@reproducible(
    "fig4.8",
    title="Locally optimal paths from Gamma_Dubins",
    dissertation="Fig 4.8: the Dubins-like candidates (BSB, BBB at R; CCC at r) for "
    "x1 = (0, 2, 2pi/3); the goal is too far for CCC; BSB and BBB need much manoeuvring.",
)
def fig4_8(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    sol = _plan_example()
    cands = [c for c in sol.candidates if c.feasible and c.info.get("group") == "Dubins"]
    f = _draw_candidates(cands, out_dir / "fig4_8_dubins.png",
                         "x1 = (0, 2, 2pi/3): Dubins-like candidates")  # fmt: skip
    ccc = [c for c in cands if c.info["type"].startswith("CCC")]
    rows = _candidate_rows(cands)
    rows.append(
        compare(
            "CCC candidates",
            len(ccc),
            Printed("0", "section 4.9: too far away for a CCC Dubins-like solution"),
            note=", ".join(c.info["type"] for c in ccc),
        )
    )
    return FigureReport(files=(f.name,), rows=tuple(rows))
