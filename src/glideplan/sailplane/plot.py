"""The figure of a final glide: ground track, and altitude against distance flown over ground."""

from __future__ import annotations

import math
import pathlib
from typing import Any

import numpy as np

from glideplan.sailplane.request import FinalGlideDrawing

__all__ = ["draw_final_glide", "final_glide_figure", "glide_summary", "wind_text"]


def wind_text(d: FinalGlideDrawing) -> str:
    """`wind 8 m/s from 270°` (compass, where it blows FROM), or `no wind`."""
    from glideplan.plotting import wind_label

    return wind_label(d.wind)


def glide_summary(d: FinalGlideDrawing) -> str:
    """One line with the answer: altitude loss, arrival altitude and margin over the floor
    (goal elevation + safety height), all in m; "unreachable" when no altitude is known."""
    if not np.all(np.isfinite(d.altitude)):
        start_text = f"start {d.altitude[0]:.0f} m, " if np.isfinite(d.altitude[0]) else ""
        return (f"goal unreachable in this wind; {start_text}"
                f"goal elevation {d.goal_elevation:.0f} m")
    start, end = float(d.altitude[0]), float(d.altitude[-1])
    floor = d.goal_elevation + d.safety_height
    return (
        f"start {start:.0f} m, altitude loss {start - end:.0f} m, arrival {end:.0f} m, "
        f"margin {end - floor:+.0f} m over goal elevation {d.goal_elevation:.0f} m "
        f"+ safety height {d.safety_height:.0f} m"
    )


def _direction_arrow(ax: object, x: np.ndarray, y: np.ndarray, at_end: bool, colour: str,
                     size: float) -> None:
    """An arrow of length `size` (km) along the track's direction at its start or end."""
    k = slice(-2, None) if at_end else slice(0, 2)
    dx, dy = float(np.diff(x[k])[0]), float(np.diff(y[k])[0])
    norm = math.hypot(dx, dy)
    if norm <= 0.0:
        return
    x0, y0 = (float(x[-1]), float(y[-1])) if at_end else (float(x[0]), float(y[0]))
    tip = (x0 + size * dx / norm, y0 + size * dy / norm)
    # An invisible line to the tip keeps the arrow inside the autoscaled limits (an annotation
    # whose tip leaves the axes is not drawn at all).
    ax.plot([x0, tip[0]], [y0, tip[1]], ls="none")  # type: ignore[attr-defined]
    ax.annotate(  # type: ignore[attr-defined]
        "", xy=tip, xytext=(x0, y0),
        arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.6, "mutation_scale": 14},
        zorder=6,
    )


def _wind_arrow(ax: Any, fig: Any, d: FinalGlideDrawing, xk: np.ndarray, yk: np.ndarray,
                avoid_lower_right: bool) -> None:
    """An arrow where the wind blows TO, labelled `wind_text`, in the corner of the
    ground-track panel farthest from the track (the lower right is kept for the inset)."""
    from glideplan.plotting import wind_arrow

    if d.wind is None or math.hypot(*d.wind) <= 0.0:
        return
    fig.canvas.draw()  # the equal-aspect limits are final only once drawn
    to_axes = ax.transAxes.inverted()
    pts = to_axes.transform(ax.transData.transform(np.column_stack([xk, yk])))
    corners = [(0.14, 0.88), (0.86, 0.88), (0.14, 0.12)]
    if not avoid_lower_right:
        corners.append((0.86, 0.12))
    cx, cy = max(corners, key=lambda c: float(np.min(np.hypot(*(pts - np.array(c)).T))))
    # below the arrow in the upper corners, above it in the lower ones
    wind_arrow(ax, d.wind, (cx, cy), half=22.0, colour="tab:blue", lw=2.2,
               label="above" if cy < 0.5 else "below", mutation_scale=16, shrinkA=0.0,
               shrinkB=0.0)


def draw_final_glide(d: FinalGlideDrawing, filename: str | pathlib.Path) -> None:
    """Draw `final_glide_figure(d)` to `filename` (`plotting.save_figure`)."""
    from glideplan.plotting import save_figure

    save_figure(final_glide_figure(d), filename)


def _two_panels(ax: Any) -> tuple[Any, tuple[Any, Any]]:
    """The figure and the two panels: new, the pair given, or side by side inside one axes."""
    import matplotlib.pyplot as plt

    if ax is None:
        fig, pair = plt.subplots(1, 2, figsize=(12, 5.6), layout="constrained")
        return fig, (pair[0], pair[1])
    if isinstance(ax, (tuple, list)) or hasattr(ax, "flat"):
        ax1, ax2 = list(getattr(ax, "flat", ax))[:2]
        return ax1.figure, (ax1, ax2)
    ax.set_axis_off()
    return ax.figure, (ax.inset_axes((0.0, 0.0, 0.45, 1.0)), ax.inset_axes((0.55, 0.0, 0.45, 1.0)))


def final_glide_figure(d: FinalGlideDrawing, ax: Any = None) -> Any:
    """Left: ground track (km, x east, y north) with start and goal and the track direction
    there, and the wind (arrow where it blows to, labelled with speed and the direction it
    blows from). Right: altitude (m) against ground distance (km) with the goal elevation,
    the safety height and the arrival. Legends below the panels; the title states the problem
    (`d.title`, the wind) and the answer (`glide_summary`). `ax`: a pair of axes for the two
    panels, or one axes whose area the two panels share (None: a new figure)."""
    fig, (ax1, ax2) = _two_panels(ax)
    below = {"loc": "upper center", "bbox_to_anchor": (0.5, -0.14), "borderaxespad": 0.0,
             "fontsize": 8, "ncol": 2}
    xk, yk = d.x / 1000, d.y / 1000
    span = float(max(np.ptp(xk), np.ptp(yk), 1e-6))
    reachable = bool(np.all(np.isfinite(d.altitude)))
    ax1.plot(xk, yk, color="C0", lw=1.8, label="ground track" if reachable else
             "line to the goal (no progress possible against this wind)",
             ls="-" if reachable else ":")
    ax1.plot(xk[0], yk[0], "o", color="tab:green", ms=8, label="start (track direction)")
    ax1.plot(xk[-1], yk[-1], "s", color="tab:red", ms=8, label="goal (track direction)")
    _direction_arrow(ax1, xk, yk, False, "tab:green", 0.08 * span)
    _direction_arrow(ax1, xk, yk, True, "tab:red", 0.08 * span)
    ax1.set_xlabel("east (km)")
    ax1.set_ylabel("north (km)")
    ax1.set_aspect("equal", adjustable="datalim")
    ax1.grid(alpha=0.3)
    ax1.legend(**below)
    ax1.set_title("ground track", fontsize=10)
    to_goal = np.hypot(d.x - d.x[-1], d.y - d.y[-1])
    near = to_goal <= max(1500.0, 0.06 * float(to_goal[0]))
    inset_drawn = bool(to_goal[0] > 5000.0 and np.count_nonzero(near) > 2)
    if inset_drawn:
        inset = ax1.inset_axes((0.58, 0.08, 0.38, 0.38))
        inset.plot(xk[near], yk[near], color="C0", lw=1.5)
        inset.plot(xk[-1], yk[-1], "s", color="tab:red", ms=7)
        inset.set_aspect("equal", adjustable="datalim")
        inset.set_title("approach (km)", fontsize=8)
        inset.tick_params(labelsize=7)
    s = d.distance / 1000
    if reachable:
        ax2.plot(s, d.altitude, color="C0", lw=1.8, label="altitude")
    floor = d.goal_elevation + d.safety_height
    ax2.axhline(
        d.goal_elevation, color="0.3", lw=1, label=f"goal elevation {d.goal_elevation:.0f} m"
    )
    ax2.axhline(
        floor, color="C1", ls="--", lw=1.2,
        label=f"goal elevation + safety height {d.safety_height:.0f} m",
    )
    if reachable:
        ax2.plot(s[-1], d.altitude[-1], "*", color="tab:red", ms=12,
                 label=f"arrival {d.altitude[-1]:.0f} m")
    else:
        ax2.plot(s[0], d.altitude[0], "o", color="tab:green", ms=8,
                 label=f"start {d.altitude[0]:.0f} m")
        ax2.set_xlim(-0.05 * s[-1], 1.05 * s[-1])
        ax2.text(0.5, 0.5, "goal unreachable:\nno airspeed makes progress against this wind",
                 transform=ax2.transAxes, ha="center", va="center", fontsize=9, color="tab:red")
    ax2.plot(s[-1], d.goal_elevation, "s", color="tab:red", label="goal")
    ax2.set_xlabel("distance over ground (km)")
    ax2.set_ylabel("altitude (m)")
    ax2.grid(alpha=0.3)
    ax2.legend(**below)
    ax2.set_title("altitude profile", fontsize=10)
    fig.suptitle(f"{d.title}, {wind_text(d)}\n{glide_summary(d)}", fontsize=10)
    _wind_arrow(ax1, fig, d, xk, yk, inset_drawn)
    return fig
