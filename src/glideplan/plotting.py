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
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from glideplan.path import Path
    from glideplan.pose import Pose
    from glideplan.solution import Solution
    from glideplan.units import WindEN
    from glideplan.vehicles.base import Vehicle

__all__ = [
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
    if candidates:
        # Candidates that draw the same curve as the optimal or an earlier candidate (e.g.
        # LSL, LSR, RSL, RSR with zero-length turns on a straight path) are drawn once.
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
        for i, c in enumerate(others):
            assert c.path is not None
            labelled = i < _MAX_LABELLED_CANDIDATES
            if labelled:
                label = (
                    f"candidate {c.path.word or '-'} ({c.family or '-'}), {c.cost:.4g} {cost_u}"
                )
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
            if labelled:  # the frame follows the labelled paths; the grey rest may be clipped
                drawn.append(c.path)
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
    xs = [solution.start.x, solution.goal.x]
    ys = [solution.start.y, solution.goal.y]
    for p in drawn:
        smp = p.sample(n=200)
        xs += [float(np.min(smp.x)), float(np.max(smp.x))]
        ys += [float(np.min(smp.y)), float(np.max(smp.y))]
    # The frame: the data with a margin for the heading arrows, never narrower than 0.6 of
    # its length (a thin strip reads badly) nor smaller than the vehicle's length scale.
    floor = max(solution.vehicle.length_scale, 1e-6)
    span = max(max(xs) - min(xs), max(ys) - min(ys), floor)
    arrow = 0.08 * span
    mark_pose(ax, solution.start, arrow, colour="tab:green", marker="o", label="start (heading)")
    mark_pose(ax, solution.goal, arrow, colour="tab:red", marker="s", label="goal (heading)")
    if switches:
        ax.plot([], [], "o", mfc="white", mec="black", ms=5, ls="none", label="switch point")
    half = 0.5 * span + 0.12 * span
    for lim, vals in ((ax.set_xlim, xs), (ax.set_ylim, ys)):
        mid = 0.5 * (min(vals) + max(vals))
        half_k = max(0.5 * (max(vals) - min(vals)) + 0.12 * span, 0.6 * half)
        lim(mid - half_k, mid + half_k)
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


def add_km_axes(
    ax: Any,
    ref_lat: float,
    ref_lon: float,
    m_per_deg_lat: float,
    m_per_deg_lon: float,
    east_label: str,
    north_label: str,
) -> None:
    """Secondary axes in km east / north of (ref_lat, ref_lon) on a lon/lat plot.

    x_km = (lon - ref_lon) m_lon / 1000, y_km = (lat - ref_lat) m_lat / 1000, with the metres
    per degree at the frame's mean latitude (linear: fine for frames of a few hundred km).
    """

    def east_km(lon_deg: Any) -> Any:
        return (np.asarray(lon_deg, dtype=float) - ref_lon) * m_per_deg_lon / 1000.0

    def km_east(km: Any) -> Any:
        return ref_lon + np.asarray(km, dtype=float) * 1000.0 / m_per_deg_lon

    def north_km(lat_deg: Any) -> Any:
        return (np.asarray(lat_deg, dtype=float) - ref_lat) * m_per_deg_lat / 1000.0

    def km_north(km: Any) -> Any:
        return ref_lat + np.asarray(km, dtype=float) * 1000.0 / m_per_deg_lat

    top = ax.secondary_xaxis("top", functions=(east_km, km_east))
    top.set_xlabel(east_label, fontsize=8)
    right = ax.secondary_yaxis("right", functions=(north_km, km_north))
    right.set_ylabel(north_label, fontsize=8)
    for sec in (top, right):
        sec.tick_params(labelsize=8)


# ----- map furniture: scale bar, north arrow (lon/lat axes with north up) -----------------------
#: WGS84 semi-major axis (m) and first eccentricity squared, for metres per degree of longitude.
_WGS84_A = 6378137.0
_WGS84_E2 = 6.69437999014e-3


def nice_length(x: float) -> float:
    """The largest of 1, 2, 5 x 10^k not above `x` (> 0): a scale bar's round length."""
    k = math.floor(math.log10(x))
    for m in (5.0, 2.0, 1.0):
        if m * 10.0**k <= x * (1 + 1e-12):
            return m * 10.0**k
    return 10.0**k  # pragma: no cover  (m = 1 always fits)


def metres_per_degree_lon(lat_deg: float) -> float:
    """Length (m) of one degree of longitude along the parallel at `lat_deg` on WGS84:
    pi/180 a cos(phi) / sqrt(1 - e^2 sin^2 phi) (the prime vertical radius times cos phi)."""
    phi = math.radians(lat_deg)
    return math.radians(1.0) * _WGS84_A * math.cos(phi) / math.sqrt(
        1.0 - _WGS84_E2 * math.sin(phi) ** 2)


def add_scale_bar(ax: Any, *, geographic: bool = True, loc: tuple[float, float] = (0.05, 0.05),
                  fraction: float = 0.2) -> float:
    """A scale bar of a round length (km) about `fraction` of the axes' width, its left end
    at `loc` (axes fraction); returns its length in km. The axes' limits must be final.

    `geographic`: x is longitude, y latitude (degrees); the bar lies along the parallel at
    its own latitude, lon span = L / metres_per_degree_lon(lat). Else x is in metres.
    The bar is a Line2D with gid "scale_bar" (its label a Text with gid "scale_bar_label").
    """
    import matplotlib.patheffects as pe

    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    bx, by = x0 + loc[0] * (x1 - x0), y0 + loc[1] * (y1 - y0)
    per_unit = metres_per_degree_lon(by) if geographic else 1.0  # metres per x unit
    width_m = abs(x1 - x0) * per_unit
    if not width_m > 0 or not math.isfinite(width_m):  # a pole, or empty axes: no bar
        return 0.0
    length_m = nice_length(max(fraction * width_m, 1e-3))
    span = length_m / per_unit
    halo = [pe.withStroke(linewidth=5, foreground="white")]
    ax.plot([bx, bx + span], [by, by], color="k", lw=3, solid_capstyle="butt", zorder=20,
            gid="scale_bar", path_effects=halo)
    km = length_m / 1000.0
    text = f"{km:g} km" if km >= 1 else f"{length_m:g} m"
    ax.annotate(text, (bx + span / 2, by), xytext=(0, 4), textcoords="offset points",
                ha="center", va="bottom", fontsize=8, zorder=20, gid="scale_bar_label",
                path_effects=[pe.withStroke(linewidth=3, foreground="white")])
    return km


def add_north_arrow(ax: Any, loc: tuple[float, float] = (0.95, 0.95)) -> Any:
    """An arrow pointing up (north, on axes with north up) with an "N", its tip at `loc`
    (axes fraction); gid "north_arrow"."""
    import matplotlib.patheffects as pe

    return ax.annotate("N", xy=loc, xytext=(0, -34), xycoords="axes fraction",
                       textcoords="offset points", ha="center", va="top", fontsize=10,
                       fontweight="bold", zorder=20, gid="north_arrow",
                       arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 1.5},
                       path_effects=[pe.withStroke(linewidth=3, foreground="white")])


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
_LABEL_OFFSETS = ((1, 1, "left", "bottom"), (1, 0, "left", "center"),
                  (1, -1, "left", "top"), (0, -1, "center", "top"),
                  (-1, -1, "right", "top"), (-1, 0, "right", "center"),
                  (-1, 1, "right", "bottom"), (0, 1, "center", "bottom"))


def _overlap_area(a: Any, b: Any) -> float:
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


def place_labels(ax: Any, points: list[tuple[float, float]], texts: list[str], *,
                 obstacles: Sequence[Any] = (), gap_pt: float = 7.0, gid: str = "label",
                 **text_kw: Any) -> list[Any]:
    """Labels that do not collide, placed greedily in the given order: for each point (data
    coordinates) the 8 offsets of `_LABEL_OFFSETS` (NE first) at `gap_pt` points are tried,
    and the first whose box (measured by the renderer) lies inside the axes and meets no
    label placed before and no box of `obstacles` (display-space Bboxes: markers, legends)
    is kept; if none is free, the one with the least overlap. Boxes are padded by 1.5 points
    (room for a halo). The figure's layout must be final (call after the limits, aspect and
    colour bars are set)."""
    fig = ax.get_figure()
    pad = 1.5 * fig.dpi / 72.0
    renderer = fig.canvas.get_renderer()
    ax.apply_aspect()
    frame = ax.get_window_extent(renderer)
    placed = list(obstacles)
    out = []
    for xy, text in zip(points, texts, strict=True):
        best: tuple[float, Any] | None = None
        for dx, dy, ha, va in _LABEL_OFFSETS:
            t = ax.annotate(text, xy, xytext=(dx * gap_pt, dy * gap_pt),
                            textcoords="offset points", ha=ha, va=va, gid=gid, **text_kw)
            bb = t.get_window_extent(renderer).padded(pad)
            inside = _overlap_area(bb, frame)
            cost = (bb.width * bb.height - inside) + sum(_overlap_area(bb, o) for o in placed)
            if best is None or cost < best[0]:
                if best is not None:
                    best[1].remove()
                best = (cost, t)
            else:
                t.remove()
            if cost == 0:
                break
        assert best is not None
        placed.append(best[1].get_window_extent(renderer).padded(pad))
        out.append(best[1])
    return out


def marker_boxes(ax: Any, points: list[tuple[float, float]], radius_pt: float) -> list[Any]:
    """Display-space boxes of markers of `radius_pt` points at data `points` (obstacles for
    `place_labels`)."""
    from matplotlib.transforms import Bbox

    r = radius_pt * ax.get_figure().dpi / 72.0
    xy = ax.transData.transform(np.asarray(points, dtype=float).reshape(-1, 2))
    return [Bbox([[x - r, y - r], [x + r, y + r]]) for x, y in xy]
