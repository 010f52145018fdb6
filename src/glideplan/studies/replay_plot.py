"""The replay study's figure: success rate per controller, duration against hindsight."""

from __future__ import annotations

import pathlib
from typing import Any

__all__ = ["plot_study"]


def plot_study(answer: dict[str, Any], path: str | pathlib.Path) -> pathlib.Path:
    """Left: success rate of replan / plan_once / naive over the missions feasible in
    hindsight (and those feasible with 10 % to spare); right: each controller's duration over
    hindsight's, per mission that both reached."""
    import matplotlib.pyplot as plt
    import numpy as np

    from glideplan.plotting import save_figure

    s = answer["summary"]
    ctrls = ["replan", "plan_once", "naive"]
    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4.2))
    x = np.arange(len(ctrls))
    for k, (key, label) in enumerate((("success_rate", f"feasible ({s['feasible']})"),
                                      ("success_rate_10pct_margin",
                                       f"10 % to spare ({s['feasible_10pct_margin']})"))):
        vals = [100 * (s[key][c] or 0.0) for c in ctrls]
        a.bar(x + (k - 0.5) * 0.38, vals, 0.38, label=label)
        for xi, v in zip(x, vals, strict=True):
            a.text(xi + (k - 0.5) * 0.38, v + 1, f"{v:.0f}", ha="center", fontsize=8)
    a.set_xticks(x, ctrls)
    a.set_ylim(0, 110)
    a.set_ylabel("missions reached (% of those feasible in hindsight)")
    a.legend(fontsize=8, loc="lower left")
    a.set_title(f"{s['missions']} missions")
    for c, color in zip(ctrls, ("crimson", "0.4", "0.7"), strict=True):
        ratios = []
        for m in answer["missions"]:
            h = m["baselines"]["hindsight"]
            d = m if c == "replan" else m["baselines"][c]
            if h["status"] == "solved" and d["status"] == "solved":
                ratios.append(d["duration_s"] / h["duration_s"])
        if ratios:
            b.hist(ratios, bins=20, histtype="step", color=color, lw=1.6,
                   label=f"{c}: median {np.median(ratios):.3f}")
    b.axvline(1.0, color="k", lw=0.8)
    b.set_xlabel("duration / hindsight duration")
    b.set_ylabel("missions")
    b.legend(fontsize=8)
    return pathlib.Path(save_figure(fig, pathlib.Path(path)))
