"""The figure of a final glide: ground track, and altitude against distance flown over ground."""

from __future__ import annotations

import pathlib

import numpy as np

from glideplan.sailplane.request import FinalGlideDrawing

__all__ = ["draw_final_glide"]


def draw_final_glide(d: FinalGlideDrawing, filename: str | pathlib.Path) -> None:
    """Left: ground track (km, x east, y north) with start and goal. Right: altitude (m)
    against ground distance (km) with the goal elevation, the safety height and the goal."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.5))
    ax1.plot(d.x / 1000, d.y / 1000, color="C0", lw=1.8, label="ground track")
    ax1.plot(d.x[0] / 1000, d.y[0] / 1000, "o", color="C2", label="start")
    ax1.plot(d.x[-1] / 1000, d.y[-1] / 1000, "*", color="C3", ms=12, label="goal")
    ax1.set_xlabel("east (km)")
    ax1.set_ylabel("north (km)")
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.grid(alpha=0.3)
    ax1.legend(loc="best", fontsize=8)
    ax1.set_title("ground track")
    to_goal = np.hypot(d.x - d.x[-1], d.y - d.y[-1])
    near = to_goal <= max(1500.0, 0.06 * float(to_goal[0]))
    if to_goal[0] > 5000.0 and np.count_nonzero(near) > 2:
        inset = ax1.inset_axes((0.58, 0.08, 0.38, 0.38))
        inset.plot(d.x[near] / 1000, d.y[near] / 1000, color="C0", lw=1.5)
        inset.plot(d.x[-1] / 1000, d.y[-1] / 1000, "*", color="C3", ms=10)
        inset.set_aspect("equal", adjustable="datalim")
        inset.set_title("approach", fontsize=8)
        inset.tick_params(labelsize=7)
    s = d.distance / 1000
    ax2.plot(s, d.altitude, color="C0", lw=1.8, label="altitude")
    floor = d.goal_elevation + d.safety_height
    ax2.axhline(
        d.goal_elevation, color="0.3", lw=1, label=f"goal elevation {d.goal_elevation:.0f} m"
    )
    ax2.axhline(
        floor, color="C1", ls="--", lw=1.2, label=f"goal + safety height {d.safety_height:.0f} m"
    )
    if np.all(np.isfinite(d.altitude)):
        ax2.plot(s[-1], d.altitude[-1], "*", color="C3", ms=12, label="arrival")
    ax2.plot(s[-1], d.goal_elevation, "s", color="C3", label="goal")
    ax2.set_xlabel("distance over ground (km)")
    ax2.set_ylabel("altitude (m)")
    ax2.grid(alpha=0.3)
    ax2.legend(loc="best", fontsize=8)
    ax2.set_title("altitude profile")
    fig.suptitle(d.title)
    fig.tight_layout()
    fig.savefig(filename, dpi=110)
    plt.close(fig)
