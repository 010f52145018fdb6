"""Chapter 7 spider plot (Fig 7.17) and the LBL positioning test (Fig 7.27).

Recomputed from `glideplan.design` (glide polar, acoustic positioning) and set beside the
values the dissertation prints (data below, with their source).
"""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.figures._common import pyplot, save_png
from glideplan.figures.registry import FigureReport, Printed, compare, reproducible, yes_no

TOP_SPEED = Printed("1.75", "section 7.4: a top forward speed of about 1.75 m/s", "m/s")
PINGS = Printed("75", "section 7.7: about 75 % of attempted pings were successful", "%")
LBL_ERROR = Printed("10", "section 7.7: estimates with an average error of about 10 m", "m")


@reproducible(
    "fig7.17",
    title="Spider plot: Seaglider-like polar with up to +-2.5 L",
    dissertation="Fig 7.17: hypothetical Seaglider with a +-2.5 L bladder; top forward speed "
    "about 1.75 m/s; lines of constant gamma (20-80 deg) and alpha (0.1-2 deg)",
)
def fig7_17(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Forward speed vs depth rate from (7.17)-(7.20) for 0.5-2.5 L net buoyancy."""
    from glideplan.design import SEA_WATER, SEAGLIDER_LIKE, max_forward_speed, spider_plot

    plt = pyplot()
    polar, env = SEAGLIDER_LIKE, SEA_WATER
    vols = np.array([0.5, 1.0, 1.5, 2.0, 2.5]) * 1e-3
    gammas = np.radians([20.0, 30.0, 40.0, 60.0, 80.0])
    alphas = np.radians([0.1, 0.25, 0.5, 1.0, 2.0])
    sp = spider_plot(
        polar, vols, env, gammas_rad=gammas, alphas_rad=alphas, num=400 if full else 200
    )
    fig, ax = plt.subplots(figsize=(6.5, 5))
    for i, v in enumerate(vols):
        ax.plot(sp.forward_m_s[i], sp.depth_rate_m_s[i], "b", lw=1)
        ax.annotate(
            f"{v * 1e3:g} L",
            (sp.forward_m_s[i].max(), sp.depth_rate_m_s[i][np.argmax(sp.forward_m_s[i])]),
            fontsize=7,
        )
    for g, (u, w) in sp.gamma_lines.items():
        ax.plot(np.r_[0.0, u], np.r_[0.0, w], "g--", lw=0.8)
        ax.annotate(f"gamma={math.degrees(g):.0f}", (u[-1], w[-1]), fontsize=7, color="g")
    for a, (u, w) in sp.alpha_lines.items():
        ax.plot(np.r_[0.0, u], np.r_[0.0, w], "r:", lw=0.8)
        # label at the 1.5 L point: alpha lines coincide with gamma lines (see the rows)
        ax.annotate(f"alpha={math.degrees(a):g}", (u[2], w[2]), fontsize=7, color="r")
    ax.set_xlabel("forward speed (m/s)")
    ax.set_ylabel("depth rate (m/s)")
    ax.set_title("Fig 7.17: spider plot (Seaglider-like stand-in polar)")
    ax.grid(True, alpha=0.3)
    files = (save_png(fig, out_dir / "fig7_17.png", crop=True).name,)
    u_max, g_max = max_forward_speed(polar, env.specific_weight_n_m3 * 2.5e-3, env)
    slopes = [float(np.ptp(np.arctan2(w, u))) for u, w in sp.alpha_lines.values()]
    rows = (
        compare(
            "top forward speed at 2.5 L",
            u_max,
            TOP_SPEED,
            note=f"{100 * (u_max / float(TOP_SPEED.value) - 1):+.0f} %, at gamma = "
            f"{math.degrees(g_max):.1f} deg: the Techy et al. (2010a) coefficients are "
            "unavailable; stand-in from Eriksen et al. (2001) (a = 0.0036/deg, b = 0.0098, "
            "c = 9.8e-6/deg^2, S = 1.8^2 m^2, q^-1/4 frozen at 1 m/s)",
        ),
        compare("shallowest glide gamma_min = atan(2 sqrt(K C_D0))",
                math.degrees(polar.min_glide_angle_rad), unit="deg"),
        compare("constant-alpha lines are straight through the origin",
                yes_no(max(slopes) < 1e-9),
                note=f"largest spread of the line's angle {max(slopes):.1e} rad: for a "
                "parabolic polar alpha fixes C_L and hence gamma (7.19), so the alpha lines "
                "are also lines of constant gamma"),
    )  # fmt: skip
    return FigureReport(files=files, rows=rows, data={"top_speed_m_s": u_max})


@reproducible(
    "fig7.27",
    title="LBL positioning: simulated lawn-mower survey with dropped pings and range noise",
    dissertation="Fig 7.27 / section 7.7: Claytor Lake, 3 beacons, about 75 % of pings "
    "answered, position estimates with an average error of about 10 m",
)
def fig7_27(out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Simulate the Track 1 survey and report error statistics (least squares and algebraic)."""
    import dataclasses

    from glideplan.design import LBLConfig, lawnmower_track, simulate_survey

    plt = pyplot()
    # Scenario (assumed, not from the dissertation): 3 m range noise, 75 % replies, sound speed
    # assumed 1480 m/s (fresh water ~20 degC) but 1447 m/s in a 10 degC November lake.
    cfg = LBLConfig(
        range_noise_std_m=3.0,
        ping_success_probability=0.75,
        sound_speed_assumed_m_s=1480.0,
        sound_speed_true_m_s=1447.0,
    )
    track = lawnmower_track((300.0, 900.0), (500.0, 900.0), 7, 5.0)
    seeds = list(range(20 if full else 5))
    ls = [simulate_survey(cfg, track, s) for s in seeds]
    al = [simulate_survey(dataclasses.replace(cfg, method="algebraic"), track, s) for s in seeds]
    nobias = dataclasses.replace(cfg, sound_speed_true_m_s=1480.0)
    nb = [simulate_survey(nobias, track, s) for s in seeds]

    def mean(results: list[Any], key: str) -> float:
        return float(np.mean([getattr(r.statistics, key) for r in results]))

    first = ls[0]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    b = np.asarray(cfg.beacons_m)
    ax1.plot(track[:, 0], track[:, 1], "k-", lw=0.6, label="track (GPS)")
    ax1.plot(first.estimates_m[:, 0], first.estimates_m[:, 1], "r.", ms=3, label="least squares")
    ax1.plot(b[:, 0], b[:, 1], "b^", ms=9, label="beacons")
    ax1.set_xlabel("x (m)")
    ax1.set_ylabel("y (m)")
    ax1.set_aspect("equal")
    ax1.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=3)
    ax1.set_title("(d) fixes along Track 1 (seed 0)")
    err = first.errors_m[np.isfinite(first.errors_m)]
    ax2.hist(err, bins=30, color="0.5")
    ax2.axvline(float(np.mean(err)), color="r", label=f"mean {np.mean(err):.1f} m")
    ax2.set_xlabel("position error (m)")
    ax2.set_ylabel("fixes")
    ax2.legend()
    ax2.set_title("error histogram")
    files = (save_png(fig, out_dir / "fig7_27.png", crop=True).name,)
    pings = 100 * mean(ls, "ping_success_fraction")
    n_pings = 3 * len(track) * len(seeds)
    se_pings = 100 * math.sqrt(0.75 * 0.25 / n_pings)
    err_ls, err_nb = mean(ls, "mean_error_m"), mean(nb, "mean_error_m")
    rows = (
        compare("pings answered", pings, PINGS,
                note=f"an input of the simulation (reply probability 0.75); binomial standard "
                f"error over {n_pings} pings {se_pings:.2f} %"),
        compare("epochs with a fix (all 3 beacons)", 100 * mean(ls, "fix_fraction"), unit="%",
                note="we require 3 non-collinear beacons; with 2 the fix is ambiguous"),
        compare("mean position error, least squares", err_ls, LBL_ERROR,
                note=f"scenario (assumed): 3 m range noise and a 2.2 % sound-speed error; "
                f"without the sound-speed error {err_nb:.1f} m"),
        compare("mean position error, algebraic", mean(al, "mean_error_m"), unit="m",
                note="linearised solution"),
        compare("mean position error without the sound-speed error", err_nb, unit="m"),
    )  # fmt: skip
    notes = (
        f"Averaged over {len(seeds)} seeds; beacon layout and noise are assumptions "
        "(Gode 2015 is not available)."
    )
    return FigureReport(files=files, rows=rows, notes=notes)
