"""Matplotlib drawing of paths and solutions (Matplotlib is imported inside functions).

A solution figure reads as an engineering figure on its own: the title states the problem
(planner, vehicle, start and goal) and the answer (word, family, cost with its unit); axes are
in metres (or in the model's reference length, e.g. `l_ref = V_ref^2 / g`, for the
nondimensional load-factor glider); the aspect is equal; start and goal are marked with their
headings; the legend, placed outside the axes so that it never covers the paths, names the
optimal word and family and every candidate drawn.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

from glideplan.map_marks import (
    add_km_axes,
    add_north_arrow,
    add_scale_bar,
    marker_boxes,
    metres_per_degree_lon,
    nice_length,
    place_labels,
)

if TYPE_CHECKING:
    from glideplan.path import Path
    from glideplan.pose import Pose
    from glideplan.solution import Solution
    from glideplan.units import WindEN
    from glideplan.vehicles.base import Vehicle

__all__ = [
    "add_km_axes",
    "add_north_arrow",
    "add_scale_bar",
    "cost_unit",
    "describe_vehicle",
    "length_unit",
    "mark_pose",
    "marker_boxes",
    "metres_per_degree_lon",
    "nice_length",
    "place_labels",
    "plot_path",
    "plot_solution",
    "plot_track",
    "pose_text",
    "save_figure",
    "wind_arrow",
    "wind_label",
]

# One look for every figure glideplan writes: this resolution (dots per inch) and saver.
FIGURE_DPI = 130

# Candidates drawn one by one in the legend; the rest share one grey entry.
_MAX_LABELLED_CANDIDATES = 8
_CANDIDATE_STYLES = ("--", "-.", ":", (0, (5, 1, 1, 1)))
# What a cost is called in titles, by objective.
_COST_NAMES = {"length": "length", "time": "time", "altitude": "altitude loss"}
# Title lines wrap at this many characters (the figure stays as wide as the plot + legend).
_TITLE_WIDTH = 90


def _axes(ax: Any, figsize: tuple[float, float] = (6.0, 6.0)) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=figsize)
    return ax


def length_unit(vehicle: Vehicle | None) -> str:
    """The unit of lengths for this vehicle model: "m", or "l_ref" (nondimensional ch. 6)."""
    return "l_ref" if vehicle is not None and vehicle.model == "load_factor_glider" else "m"


def cost_unit(objective: str, vehicle: Vehicle | None) -> str:
    """The unit of a cost: m (length, altitude) or s (time); l_ref / t_ref when nondimensional."""
    nondim = length_unit(vehicle) != "m"
    if objective == "time":
        return "t_ref" if nondim else "s"
    return "l_ref" if nondim else "m"


def describe_vehicle(vehicle: Vehicle) -> str:
    """A short description of a vehicle and its parameters with units, for titles."""
    d = vehicle.to_dict()
    m = vehicle.model
    if m == "dubins_car":
        return f"Dubins car, v = {d['speed']:g} m/s, R0 = {d['turn_radius']:g} m"
    if m == "dubins_car_in_wind":
        return (
            f"Dubins car in wind, v = {d['speed']:g} m/s, R0 = {d['turn_radius']:g} m, "
            f"{wind_label(tuple(d['wind']))}"
        )
    if m == "variable_speed_car":
        return (
            f"variable-speed car, v in [{d['v_min']:g}, {d['v_max']:g}] m/s, "
            f"u_max = {d['u_max']:g} rad/s"
        )
    if m == "quadratic_polar_glider":
        return (
            f"glider (quadratic polar), v in [{d['v_stall']:.3g}, {d['v_max']:.3g}] m/s, "
            f"R_stf = {d['radius_stf']:.4g} m"
        )
    if m == "load_factor_glider":
        return (
            f"load-factor glider, (L/D)max = {d['l_over_d_max']:g}, v in "
            f"[{d['v_min']:g}, {d['v_max']:g}] V_ref, n_max = {d['n_max']:g}"
        )
    return m.replace("_", " ")


def pose_text(pose: Pose, unit: str, scale: float = 1.0) -> str:
    """`(x, y) unit, heading deg` of a pose whose lengths are divided by `scale`."""
    return (
        f"({pose.x / scale:.4g}, {pose.y / scale:.4g}) {unit}, "
        f"{math.degrees(pose.heading) % 360.0:.4g} deg"
    )


def mark_pose(
    ax: Any,
    pose: Pose,
    size: float,
    *,
    colour: str,
    marker: str,
    label: str,
    scale: float = 1.0,
) -> None:
    """A marker at the pose (lengths divided by `scale`) and an arrow of length `size` (axis
    units) along its heading; start: green circle, goal: red square, by convention."""
    x, y = pose.x / scale, pose.y / scale
    tip = (x + size * math.cos(pose.heading), y + size * math.sin(pose.heading))
    ax.plot(x, y, marker, color=colour, ms=8, zorder=5, label=label, ls="none")
    # An invisible line to the tip keeps the arrow inside autoscaled limits (an annotation
    # whose tip leaves the axes is not drawn at all).
    ax.plot([x, tip[0]], [y, tip[1]], ls="none")
    ax.annotate(
        "",
        xy=tip,
        xytext=(x, y),
        arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.6, "mutation_scale": 14},
        zorder=6,
    )


def _label_axes(ax: Any, unit: str) -> None:
    if not ax.get_xlabel():
        ax.set_xlabel(f"x ({unit})" if unit == "m" else f"x / {unit}")
    if not ax.get_ylabel():
        ax.set_ylabel(f"y ({unit})" if unit == "m" else f"y / {unit}")


def _switch_points(path: Path) -> np.ndarray:
    """(k, 2) starts of the segments after the first, zero-length segments ignored (m)."""
    tol = 1e-9 * max(path.length, 1.0)
    real = [seg for seg in path.segments if seg.length > tol]
    return np.array([[seg.start.x, seg.start.y] for seg in real[1:]]).reshape(-1, 2)


def _same_path(a: Path, b: Path, cost_a: float, cost_b: float) -> bool:
    """Two candidates draw the same curve: same word (zero-length segments dropped), and the
    same cost, length and points at a quarter, half and three quarters of the length, within
    1e-9 relative."""
    tol = 1e-9 * max(abs(cost_a), abs(cost_b), a.length, 1.0)
    if a.word != b.word or abs(cost_a - cost_b) > tol or abs(a.length - b.length) > tol:
        return False
    fractions = np.array([0.25, 0.5, 0.75])
    pa, pb = a.sample(lengths=fractions * a.length), b.sample(lengths=fractions * b.length)
    return bool(np.all(np.hypot(pa.x - pb.x, pa.y - pb.y) <= tol * 1e3))


def plot_path(
    path: Path,
    ax: Any = None,
    *,
    switch_markers: bool = True,
    pose_markers: bool = True,
    n: int = 400,
    unit: str | None = None,
    **line_kwargs: Any,
) -> Any:
    """Draw a path: the track, switching points (open circles) and boundary poses (arrows).

    `unit` names the length unit of the axis labels (default: the path's vehicle's, or m);
    labels already set on `ax` are kept.
    """
    ax = _axes(ax)
    smp = path.sample(n=max(n, 50 * len(path.segments)))
    (line,) = ax.plot(smp.x, smp.y, **({"lw": 1.8} | line_kwargs))
    colour = line.get_color()
    starts = _switch_points(path)
    if switch_markers and len(starts):
        ax.plot(starts[:, 0], starts[:, 1], "o", mfc="white", mec=colour, ms=5, zorder=4)
    if pose_markers:
        span = float(max(np.ptp(smp.x), np.ptp(smp.y), 1e-9))
        for p in (path.start, path.end):
            ax.annotate(
                "",
                xy=(p.x + 0.08 * span * np.cos(p.heading), p.y + 0.08 * span * np.sin(p.heading)),
                xytext=(p.x, p.y),
                arrowprops={"arrowstyle": "-|>", "color": colour},
            )
    ax.set_aspect("equal", adjustable="datalim")
    _label_axes(ax, unit or length_unit(path.vehicle))
    return ax


def _title(solution: Solution, unit: str, heading: str = "") -> str:
    head = f"{solution.planner} ({solution.objective}): {describe_vehicle(solution.vehicle)}"
    if heading:
        head = f"{heading}\n{head}"
    eps = solution.extras.get("disturbance_ratio")
    radius = solution.extras.get("radius")
    if isinstance(eps, float) and eps > 0.0 and isinstance(radius, float):
        head += f"\nplanned with R0' = R0 (1 + eps)^2 = {radius:.4g} m (eps = {eps:g})"
    problem = f"start {pose_text(solution.start, unit)} -> goal {pose_text(solution.goal, unit)}"
    if solution.ok:
        word = solution.word or "(none: start = goal)"
        result = (
            f"optimal word {word}, family {solution.family or '-'}, "
            f"{_COST_NAMES.get(solution.objective, solution.objective + ' cost')} "
            f"{solution.cost:.5g} "
            f"{cost_unit(solution.objective, solution.vehicle)}"
        )
    else:
        result = f"status {solution.status.value}: {solution.message}"
    import textwrap

    lines = f"{head}\n{problem}\n{result}".split("\n")
    return "\n".join(textwrap.fill(line, _TITLE_WIDTH, break_long_words=False) for line in lines)


def _distinct_candidates(solution: Solution) -> tuple[list[Any], int]:
    """The feasible candidates other than the optimal, each drawing a curve of its own, and
    how many coincide with one kept (e.g. LSL, LSR, RSL, RSR with zero-length turns on a
    straight path are drawn once)."""
    others: list[Any] = []
    kept = [] if solution.path is None else [(solution.path, solution.cost)]
    coincide = 0
    for c in solution.candidates:
        if c.path is None or not c.feasible or c.path is solution.path:
            continue
        if any(_same_path(c.path, p, c.cost, cost) for p, cost in kept):
            coincide += 1
            continue
        kept.append((c.path, c.cost))
        others.append(c)
    return others, coincide


def _draw_candidates(ax: Any, others: list[Any], unit: str, cost_u: str) -> list[Any]:
    """Draw the candidates (the first `_MAX_LABELLED_CANDIDATES` styled and labelled, the rest
    grey); return the labelled paths (the frame follows them; the grey rest may be clipped)."""
    drawn = []
    for i, c in enumerate(others):
        assert c.path is not None
        labelled = i < _MAX_LABELLED_CANDIDATES
        if labelled:
            label = f"candidate {c.path.word or '-'} ({c.family or '-'}), {c.cost:.4g} {cost_u}"
        elif i == _MAX_LABELLED_CANDIDATES:
            label = f"{len(others) - i} more candidates"
        else:
            label = "_nolegend_"
        plot_path(
            c.path,
            ax,
            switch_markers=False,
            pose_markers=False,
            unit=unit,
            lw=1.0,
            alpha=0.8 if labelled else 0.35,
            ls=_CANDIDATE_STYLES[i % len(_CANDIDATE_STYLES)] if labelled else "-",
            color=None if labelled else "0.6",
            label=label,
        )
        if labelled:
            drawn.append(c.path)
    return drawn


def _frame(ax: Any, solution: Solution, drawn: list[Any]) -> float:
    """Set the limits: the data with a margin for the heading arrows, never narrower than 0.6
    of its length (a thin strip reads badly) nor smaller than the vehicle's length scale;
    return the span (the heading arrows are 0.08 of it)."""
    xs = [solution.start.x, solution.goal.x]
    ys = [solution.start.y, solution.goal.y]
    for p in drawn:
        smp = p.sample(n=200)
        xs += [float(np.min(smp.x)), float(np.max(smp.x))]
        ys += [float(np.min(smp.y)), float(np.max(smp.y))]
    floor = max(solution.vehicle.length_scale, 1e-6)
    span = max(max(xs) - min(xs), max(ys) - min(ys), floor)
    half = 0.5 * span + 0.12 * span
    for lim, vals in ((ax.set_xlim, xs), (ax.set_ylim, ys)):
        mid = 0.5 * (min(vals) + max(vals))
        half_k = max(0.5 * (max(vals) - min(vals)) + 0.12 * span, 0.6 * half)
        lim(mid - half_k, mid + half_k)
    return span


def plot_solution(
    solution: Solution, ax: Any = None, *, candidates: bool = False, heading: str = ""
) -> Any:
    """Draw a solution: the optimal path, optionally the other feasible candidates, the start
    and goal with their headings, a title stating problem and answer (after `heading`, e.g.
    the example's name, when given), and a legend outside the axes."""
    ax = _axes(ax, figsize=(9.0, 6.0))
    unit = length_unit(solution.vehicle)
    cost_u = cost_unit(solution.objective, solution.vehicle)
    drawn: list[Any] = []
    coincide = 0
    if candidates:
        others, coincide = _distinct_candidates(solution)
        drawn = _draw_candidates(ax, others, unit, cost_u)
    if solution.path is not None:
        word = solution.word or "-"
        plot_path(
            solution.path,
            ax,
            pose_markers=False,
            unit=unit,
            lw=2.4,
            color="black",
            zorder=3,
            label=(
                f"optimal {word} ({solution.family or '-'}), {solution.cost:.5g} {cost_u}"
                if solution.path.length > 0.0
                else f"zero-length path (start = goal), 0 {cost_u}"
            ),
        )
        drawn.append(solution.path)
    if candidates and coincide:
        ax.plot([], [], ls="none", label=f"({coincide} more candidates coincide with one drawn)")
    switches = solution.path is not None and len(_switch_points(solution.path)) > 0
    arrow = 0.08 * _frame(ax, solution, drawn)
    mark_pose(ax, solution.start, arrow, colour="tab:green", marker="o", label="start (heading)")
    mark_pose(ax, solution.goal, arrow, colour="tab:red", marker="s", label="goal (heading)")
    if switches:
        ax.plot([], [], "o", mfc="white", mec="black", ms=5, ls="none", label="switch point")
    ax.set_aspect("equal", adjustable="box")
    _label_axes(ax, unit)
    wind = getattr(solution.vehicle, "wind", None)
    if wind is not None:
        wind_arrow(ax, wind, (0.1, 0.88), colour="tab:blue", lw=1.8, label="below")
    ax.grid(True, lw=0.4, alpha=0.5)
    ax.set_title(_title(solution, unit, heading), fontsize=9, loc="left")
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), borderaxespad=0.0, fontsize=8)
    return ax


def save_figure(ax_or_fig: Any, filename: Any, *, crop: bool = True, tight: bool = True) -> Any:
    """Save the figure owning `ax_or_fig` at `FIGURE_DPI` and close it; return `filename`.

    The one saver of the library (solution, route, mission, glide and chapter figures). With
    `tight` the subplots are spaced by `tight_layout` (unless the figure has a layout engine);
    with `crop` the image is cropped to what is drawn, so a legend outside the axes is kept.
    It never switches Matplotlib's backend (only `glideplan reproduce` does).
    """
    import matplotlib.pyplot as plt

    fig = ax_or_fig.get_figure() if hasattr(ax_or_fig, "get_figure") else ax_or_fig
    if tight and fig.get_layout_engine() is None:  # a constrained layout spaces itself
        fig.tight_layout()
    fig.savefig(filename, dpi=FIGURE_DPI, **({"bbox_inches": "tight"} if crop else {}))
    plt.close(fig)
    return filename


def plot_track(track: Any, ax: Any = None, *, label: str = "track", title: str = "",
               **kwargs: Any) -> Any:
    """Draw a `glideplan.track.Track`: lon/lat (deg) when geographic, else x/y (m); the axes."""
    ax = _axes(ax)
    if track.geographic:
        ax.plot(track.lon, track.lat, label=label, **kwargs)
        ax.set_xlabel("longitude (deg E)")
        ax.set_ylabel("latitude (deg N)")
        mid = math.radians(float(np.mean(track.lat)))
        ax.set_aspect(1.0 / max(math.cos(mid), 1e-6), adjustable="datalim")
    else:
        ax.plot(track.x, track.y, label=label, **kwargs)
        _label_axes(ax, "m")
    if track.size:
        ax.legend(loc="best", fontsize=8)
    if title:
        ax.set_title(title, fontsize=9, loc="left")
    return ax


def wind_label(wind: WindEN | None, sep: str = " ") -> str:
    """`wind 8 m/s from 270°` (the compass direction it blows FROM) of an (east, north) wind,
    or `no wind`; `sep` goes between the speed and "from" (a newline under an arrow)."""
    from glideplan.units import wind_to_compass

    speed, frm = (0.0, 0.0) if wind is None else wind_to_compass(*wind)
    if speed <= 0.0:
        return "no wind"
    return f"wind {speed:.3g} m/s{sep}from {frm:.0f}°"


def wind_arrow(ax: Any, wind: WindEN, at: tuple[float, float] = (0.1, 0.83), *,
               half: float = 11.0, colour: str = "navy", lw: float = 2.0,
               label: str | None = None, **arrowprops: Any) -> Any:
    """The one wind arrow of every figure: `half`-point half-length arrow centred on `at` (axes
    fraction) pointing where the (east, north) wind blows TOWARDS, in display space (so its
    direction is true on equal-aspect east/north axes); gid "wind_arrow". With `label`
    ("below" or "above") `wind_label(wind, "\n")` is written under or over it. Nothing is
    drawn in a calm. Returns the arrow's annotation (or None)."""
    from matplotlib.transforms import offset_copy

    speed = math.hypot(*wind)
    if not speed > 0.0:
        return None
    ux, uy = wind[0] / speed, wind[1] / speed
    tip = offset_copy(ax.transAxes, fig=ax.get_figure(), x=half * ux, y=half * uy,
                      units="points")
    props = {"arrowstyle": "-|>", "color": colour, "lw": lw, **arrowprops}
    arrow = ax.annotate("", xy=at, xycoords=tip, xytext=(-2 * half * ux, -2 * half * uy),
                        textcoords="offset points", gid="wind_arrow", zorder=20,
                        arrowprops=props)
    if label is not None:
        up = label == "above"
        ax.annotate(
            wind_label(wind, "\n"), xy=at, xycoords="axes fraction",
            xytext=(0.0, (half * abs(uy) + 6.0) * (1.0 if up else -1.0)),
            textcoords="offset points", ha="center", va="bottom" if up else "top",
            fontsize=8, color=colour, gid="wind_label", zorder=20,
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "none", "alpha": 0.8},
        )
    return arrow


#: The 8 places a label may take round its point, in the order tried: (dx, dy, ha, va).
