"""Chapter 3 path following: closed-loop examples (Fig 3.3) and the Monte Carlo study (Fig 3.4)."""

from __future__ import annotations

import math
import pathlib

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import Comparison, FigureReport, reproducible

EXAMPLES = {"a": (3.0, 3.0, 2.0 * math.pi / 3.0), "b": (1.0, 2.0, 0.0)}
# REFERENCE_NOTES §1.4 prototype (Euler, dt 0.01, Delta = R0, gamma = 1, phi_b = 0.05):
# final cross-track error / R0 with R0 and with R0'; the dissertation draws the tracks only.
PROTOTYPE = {"a": (0.19, 0.03), "b": (0.22, 0.04)}
REDUCED_SAMPLES = 45


def _follow_examples(eps: float = 0.25) -> dict[str, dict[str, object]]:
    from glideplan.simulation import (
        FollowerSettings,
        PathArrays,
        SteadyDisturbance,
        follow_paths,
    )

    settings = FollowerSettings()
    r0 = settings.min_radius
    out: dict[str, dict[str, object]] = {}
    for key, (x, y, psi) in EXAMPLES.items():
        goals = np.array([[x * r0, y * r0, psi]] * 2)
        radii = np.array([r0, r0 * (1.0 + eps) ** 2])
        paths = PathArrays.dubins(goals, radii)
        stream = SteadyDisturbance(eps * settings.speed, 0.0).stream(2, settings.dt)
        res = follow_paths(
            paths, stream, settings=settings, disturbance_bound=eps * settings.speed, record=True
        )
        out[key] = {"paths": paths, "result": res, "radii": radii / r0, "r0": r0}
    return out


@reproducible(
    "fig3.3",
    title="Closed-loop following of paths planned with R0 and R0' in a steady wind",
    dissertation=(
        "Fig 3.3 (section 3.4): goals x1 = (3, 3, 2pi/3) and (1, 2, 0) in units of R0, "
        "eps = 0.25, wind along +x; Dubins paths planned with R0 (dashed) and R0' (dash-dot), "
        "simulated tracks (solid): the R0' path is followed more closely, reaching the end "
        "point and final course more accurately."
    ),
)
def fig3_3(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Both examples: planned paths, simulated tracks, final cross-track errors."""
    runs = _follow_examples()
    fig, axes = pyplot().subplots(1, 2, figsize=(12, 5.8))
    rows = []
    for ax, (key, data) in zip(axes, runs.items(), strict=True):
        paths = data["paths"]
        res = data["result"]
        r0 = float(data["r0"])  # type: ignore[arg-type]
        for i, (style, name) in enumerate((("--", "R0"), ("-.", "R0'"))):
            s = np.linspace(0.0, paths.length[i], 400)  # type: ignore[attr-defined]
            sel = paths.take(np.array([i] * s.size))  # type: ignore[attr-defined]
            px, py, _ = sel.point(s)
            (line,) = ax.plot(px / r0, py / r0, style, lw=1.6, label=f"path, {name}")
            tr = res.tracks[:, i, :] / r0  # type: ignore[attr-defined]
            ax.plot(tr[:, 0], tr[:, 1], "-", color=line.get_color(), lw=1.0, label=f"flown, {name}")
            err = float(res.error[i]) / r0  # type: ignore[attr-defined]
            rows.append(
                Comparison(
                    f"({key}) final cross-track error / R0, planned with {name}",
                    f"{err:.3f}",
                    "R0' followed more closely",
                    f"prototype in REFERENCE_NOTES §1.4: {PROTOTYPE[key][i]:.2f}",
                )
            )
        gx, gy, gpsi = EXAMPLES[key]
        ax.plot(0, 0, "ko", ms=5)
        ax.annotate("START", (0, 0), textcoords="offset points", xytext=(5, -12))
        ax.plot(gx, gy, "ks", ms=5)
        ax.annotate("END", (gx, gy), textcoords="offset points", xytext=(5, 5))
        ax.set_title(f"({key}) x1 = ({gx:g}, {gy:g}, {gpsi:.3g}), eps = 0.25, wind +x")
        ax.set_xlabel("x / R0")
        ax.set_ylabel("y / R0")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(fontsize=8)
    file = save_png(fig, out_dir / "fig3_3.png")
    better = all(
        float(d["result"].error[1]) < float(d["result"].error[0])  # type: ignore[attr-defined]
        for d in runs.values()
    )
    return FigureReport(
        files=(str(file),),
        rows=tuple(rows),
        notes=(
            "Guidance: Breivik-Fossen lookahead (Delta = R0, gamma = 1/s), saturated bang-bang "
            "course control (phi_b = 0.2 rad), dt = 0.05 s; the dissertation's gains are not "
            f"reported. R0' tracked better in both examples: {better}."
        ),
    )


@reproducible(
    "fig3.4",
    title="Mean final cross-track error vs planning radius (Monte Carlo)",
    dissertation=(
        "Fig 3.4 (section 3.4): mean final cross-track error / R0 vs R_plan / R0 in "
        "{1.0, ..., 4.0} for eps = 0.25, 0.5, 0.75, 0.95, 900 goals per point; (a) steady "
        "wind: errors up to about 0.6 at R_plan = 1, the knee near R0' = (1 + eps)^2; "
        "(b) unsteady Dryden gusts: errors below about 0.2, R0' conservative."
    ),
)
def fig3_4(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Run (or resume) the study in out_dir/fig3_4_study and draw both panels.

    Default: 45 goals per point (a few minutes' worth of runs cut to seconds); `full`: 900.
    """
    from glideplan.studies.cross_track import CrossTrackConfig, run_cross_track_study

    samples = 900 if full else REDUCED_SAMPLES
    cfg = CrossTrackConfig(samples=samples, chunk=100 if full else 15)
    res = run_cross_track_study(out_dir / f"fig3_4_study_{samples}", cfg, progress=False)
    fig, axes = pyplot().subplots(1, 2, figsize=(12, 4.8))
    rows = []
    for ax, case in zip(axes, cfg.cases, strict=True):
        for eps in cfg.eps:
            pts = [s for s in res.summary if s["case"] == case and s["eps"] == eps]
            r = np.array([p["r_plan"] for p in pts])
            e = np.array([np.nan if p["mean_error"] is None else p["mean_error"] for p in pts])
            (line,) = ax.plot(r, e, "o-", ms=3, lw=1.2, mfc="none", label=f"eps = {eps:g}")
            rf = (1.0 + eps) ** 2
            i = int(np.argmin(np.abs(r - rf)))
            ax.plot(r[i], e[i], "o", color=line.get_color(), ms=7)
            k = res.knees[case][eps]
            j = int(np.argmin(np.abs(r - k)))
            ax.plot(r[j], e[j], "v", color=line.get_color(), ms=8, mfc="none")
            rows.append(
                Comparison(
                    f"{case} eps={eps:g}: E(1), E(R0'={rf:.2f}), E(4); knee",
                    f"{e[0]:.3f}, {e[i]:.3f}, {e[-1]:.3f}; knee {k:.1f}",
                    "knee near (1+eps)^2" if case == "steady" else "R0' conservative",
                    f"failures {sum(p['failures'] for p in pts)}",
                )
            )
        ax.set_title(f"({'a' if case == 'steady' else 'b'}) {case} disturbance")
        ax.set_xlabel("planning radius R_plan / R0")
        ax.set_ylabel("mean final cross-track error / R0")
        ax.set_ylim(bottom=0.0)
        ax.legend(fontsize=8)
    file = save_png(fig, out_dir / "fig3_4.png")
    return FigureReport(
        files=(str(file), str(res.directory / "summary.json")),
        rows=tuple(rows),
        notes=(
            f"{samples} goals per point (full study with --full: 900). Filled markers: R_plan "
            "nearest R0' = (1 + eps)^2; open triangles: the knee (smallest R_plan within 10% "
            "of the curve's drop above its minimum). Dryden: 2-D gusts, L = 263 m, V = 20 m/s, "
            "RMS magnitude eps v, saturated at eps v."
        ),
    )
