"""Draw a route over its field (Matplotlib, imported inside; no plotting in the algorithms).

The figure reads on its own: the title states the problem (field, water speed, start, goal,
departure) and the answer (status, duration in h, distance sailed in km, the straight-line
crabbing time for comparison, the verified endpoint error); axes are longitude / latitude in
degrees with the aspect set so that a km east is as long as a km north (ratio of the WGS84
lengths of a degree of latitude and of longitude at the frame's mean latitude, ~1 / cos(lat)),
with a km scale of the local plane about the start on the top and right axes; the current
arrows show the field at one stated time (the departure) with a key in m/s; land (NaN in the
field) is shaded as land; start and goal are marked with the heading through the water there;
the legend and the arrow key sit outside the axes.
"""

from __future__ import annotations

import math
import pathlib
import textwrap
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from glideplan.fields.field import FlowField
from glideplan.plotting import add_km_axes
from glideplan.routing.route import RouteResult

if TYPE_CHECKING:
    from glideplan.routing.glider import GliderFollow

__all__ = [
    "frame_scales",
    "plot_route",
    "route_figure",
    "route_title",
    "water_speed_from_track",
]

_LAND_COLOUR = "#d8c9a3"
_TITLE_WIDTH = 95


def frame_scales(lat_mid: float, lon_mid: float) -> tuple[float, float]:
    """(m per degree of latitude, m per degree of longitude) on WGS84 at (lat_mid, lon_mid):
    geodesic lengths of 0.1-degree steps centred there (the aspect is their ratio,
    ~1 / cos(lat_mid))."""
    from glideplan.geodesy import geodesic_distance_bearing

    del lon_mid  # the ellipsoid is one of revolution: the lengths do not depend on longitude
    d, _ = geodesic_distance_bearing(
        [lat_mid - 0.05, lat_mid], [0.0, -0.05],
        [lat_mid + 0.05, lat_mid], [0.0, 0.05],
    )
    return float(d[0]) / 0.1, float(d[1]) / 0.1


def water_speed_from_track(result: RouteResult, field_: FlowField) -> float | None:
    """The water speed V (m/s) the route was planned for, recovered from its track:
    V = median |v_ground - c| over the steps, v_ground from the track's positions and times
    (local east/north metres per degree at each step), c the current at the step's midpoint.
    None when the track is too short or the field cannot be sampled along it."""
    if result.t.size < 3:
        return None
    lat, lon, t = result.lat, result.lon, result.t
    lat_m, lon_m = 0.5 * (lat[1:] + lat[:-1]), 0.5 * (lon[1:] + lon[:-1])
    dt = np.diff(t)
    ok = dt > 0.0
    m_lat, m_lon = frame_scales(float(np.mean(lat)), float(np.mean(lon)))
    ve = np.diff(lon)[ok] * m_lon / dt[ok]
    vn = np.diff(lat)[ok] * m_lat / dt[ok]
    try:
        u, v = field_.velocity(result.depart_s + 0.5 * (t[1:] + t[:-1])[ok], lat_m[ok], lon_m[ok])
    except ValueError:
        return None
    speed = np.hypot(ve - u, vn - v)
    speed = speed[np.isfinite(speed)]
    return float(np.median(speed)) if speed.size else None


def _field_name(info: Mapping[str, Any]) -> str:
    if info.get("name"):
        return f"{info['name']} ({info.get('kind', 'field')})"
    source = info.get("source")
    if isinstance(source, (list, tuple)) and source:
        names = [pathlib.Path(str(s)).name for s in source]
        return ", ".join(names[:2]) + (f" (+{len(names) - 2} files)" if len(names) > 2 else "")
    if source:
        return pathlib.Path(str(source)).name
    return str(info.get("kind", "field"))


def _latlon_text(lat: float, lon: float) -> str:
    lon = (lon + 180.0) % 360.0 - 180.0
    return f"{abs(lat):.4g}°{'N' if lat >= 0 else 'S'} {abs(lon):.4g}°{'E' if lon >= 0 else 'W'}"


def _time_text(field_: FlowField, t: float) -> str:
    text = field_.format_time(t)
    return text[:16] + "Z" if field_.epoch is not None else text


def route_title(
    result: RouteResult,
    field_: FlowField | None,
    start: tuple[float, float] | None,
    goal: tuple[float, float] | None,
    speed: float | None,
    speed_inferred: bool = False,
    glider: GliderFollow | None = None,
) -> str:
    """The title: the problem (field, water speed, start, goal, departure), then the answer
    (status, duration h, distance km, straight-line crabbing time, endpoint error)."""
    sp = "water speed not given" if speed is None else (
        f"water speed {speed:.3g} m/s" + (" (from the track)" if speed_inferred else ""))
    head = f"Time-optimal route through {_field_name(result.field_info)}, {sp}"
    where = ""
    if start is not None and goal is not None:
        from glideplan.geodesy import geodesic_distance_bearing

        d, _ = geodesic_distance_bearing(start[0], start[1], goal[0], goal[1])
        where = (f"from {_latlon_text(*start)} to {_latlon_text(*goal)} "
                 f"({float(d) / 1000:.4g} km apart), ")
    when = (f"t={result.depart_s:g}s" if field_ is None else _time_text(field_, result.depart_s))
    problem = f"{where}departing {when}"
    straight = result.straight_line_duration_s
    if result.ok and result.duration_s is not None:
        hours = result.duration_s / 3600.0
        answer = (f"{result.status}: {hours:.2f} h over {result.distance_m / 1000:.4g} km "
                  f"({result.method})")
        if result.endpoint_error_m is not None:
            answer += f", verified endpoint error {result.endpoint_error_m:.3g} m"
        if straight is not None and math.isfinite(straight) and straight > 0.0:
            gain = 1.0 - result.duration_s / straight
            answer += f"; straight line with crabbing {straight / 3600:.2f} h"
            if gain > 0.0:
                answer += f" (the route takes {gain:.0%} less time)"
        else:
            answer += "; no straight-line crossing (land or too strong a current in the way)"
        if result.message and result.message != "solved":
            answer += f". Note: {result.message}"
    else:
        reason = f" ({result.unreachable_reason})" if result.unreachable_reason else ""
        answer = f"{result.status}{reason}: " + (result.message or (
            f"the reachable set came within {result.best_distance_m / 1000:.3g} km of the goal"))
    lines = [head, problem, answer]
    if glider is not None:
        g = f"glider R0 = {glider.radius_m:.4g} m: {glider.status}"
        if glider.max_cross_track_m is not None:
            g += f", max cross-track {glider.max_cross_track_m:.3g} m"
        if glider.final_distance_m is not None:
            g += f", miss at goal {glider.final_distance_m:.3g} m"
        if glider.message:
            g += f" ({glider.message})"
        lines.append(g)
    return "\n".join(textwrap.fill(s, _TITLE_WIDTH, break_long_words=False) for s in lines)


def _front_layers(ax: Any, result: RouteResult, frame: Any) -> list[Any]:
    """Isochrones of the front (arrival time, a few round hours) and, when unreachable, the
    front's furthest reach (the boundary of the reached nodes); legend handles."""
    from matplotlib.lines import Line2D

    fm = result.front
    if fm is None or fm.arrival.size == 0:
        return []
    arr = np.asarray(fm.arrival, dtype=float)
    reached = np.isfinite(arr)
    if not reached.any():
        return []
    lon = np.asarray(frame(fm.lon), dtype=float)
    order = np.argsort(lon)
    lon, arr, reached = lon[order], arr[:, order], reached[:, order]
    handles: list[Any] = []
    t_end = result.duration_s if result.duration_s else float(np.max(arr[reached]))
    if t_end > 0:
        step_h = _nice(t_end / 3600.0 / 6.0)
        levels = np.arange(step_h, t_end / 3600.0, step_h)
        if levels.size:
            hours = np.where(reached, arr / 3600.0, np.nan)
            ax.contour(lon, fm.lat, hours, levels=levels, colors="tab:blue", linewidths=0.6,
                       alpha=0.6, zorder=3)
            handles.append(Line2D([], [], color="tab:blue", lw=0.6, alpha=0.6,
                                  label=f"isochrones every {step_h:g} h (front)"))
    if not result.ok and result.duration_s is None:
        ax.contour(lon, fm.lat, reached.astype(float), levels=[0.5], colors="tab:purple",
                   linewidths=1.6, zorder=4)
        handles.append(Line2D([], [], color="tab:purple", lw=1.6,
                              label="furthest reach of the front"))
    return handles


def _nice(value: float) -> float:
    """The largest of 1, 2, 5 x 10^k not above `value` (> 0)."""
    k = math.floor(math.log10(value))
    for m in (5.0, 2.0, 1.0):
        if m * 10.0**k <= value:
            return m * 10.0**k
    return 10.0**k  # pragma: no cover - m = 1 always fits


def _heading_arrow(ax: Any, lat: float, lon: float, compass_deg: float, size_m: float,
                   m_lat: float, m_lon: float, colour: str) -> None:
    """An arrow of `size_m` ground metres from (lat, lon) along a compass heading."""
    b = math.radians(compass_deg)
    tip = (lon + size_m * math.sin(b) / m_lon, lat + size_m * math.cos(b) / m_lat)
    ax.annotate("", xy=tip, xytext=(lon, lat), zorder=6,
                arrowprops={"arrowstyle": "-|>", "color": colour, "lw": 1.6,
                            "mutation_scale": 14})


def plot_route(
    result: RouteResult,
    field_: FlowField,
    filename: str | pathlib.Path,
    arrows: int = 25,
    *,
    speed: float | None = None,
    start: tuple[float, float] | None = None,
    goal: tuple[float, float] | None = None,
    glider: GliderFollow | None = None,
) -> pathlib.Path:
    """Draw the route (`route_figure`, same arguments) to `filename`; returns its path."""
    from glideplan.plotting import save_figure

    fig = route_figure(result, field_, arrows, speed=speed, start=start, goal=goal,
                       glider=glider)
    return pathlib.Path(save_figure(fig, pathlib.Path(filename), tight=False))


def route_figure(
    result: RouteResult,
    field_: FlowField | None = None,
    arrows: int = 25,
    *,
    ax: Any = None,
    speed: float | None = None,
    start: tuple[float, float] | None = None,
    goal: tuple[float, float] | None = None,
    glider: GliderFollow | None = None,
) -> Any:
    """The Matplotlib figure of a route: track (lon, lat) over the field's current at
    departure (`arrows` across the longer side), land, the front's isochrones, and when the
    goal is unreachable the front's furthest reach.

    The frame is centred on the route (longitudes unwrapped about it: no wrap-around at
    180 deg). field_: the FlowField (None: no land or current); ax: draw into these axes;
    speed: the water speed (m/s) for the title (default: the result's); start, goal:
    (lat, lon) (default: the result's); glider: the followed flyable path
    (`routing.glider.follow_route`), drawn when given.
    """
    import matplotlib.pyplot as plt

    start, goal, speed, inferred = _ends(result, field_, start, goal, speed)
    fr = _frame(result, field_, start, goal)
    if ax is None:
        fig, ax = plt.subplots(figsize=(10.5, 6.2))
    else:
        fig = ax.figure
    handles, quiver_key = _draw_current(ax, result, field_, fr, arrows)
    handles += _front_layers(ax, result, fr.unwrap)
    handles += _draw_route(ax, result, fr, start, goal, glider)
    _finish_axes(ax, fr, start)
    ax.set_title(route_title(result, field_, start, goal, speed, inferred, glider),
                 fontsize=9, loc="left", pad=30)
    _legend(fig, ax, handles, quiver_key)
    return fig


def _ends(result: RouteResult, field_: FlowField | None, start: tuple[float, float] | None,
          goal: tuple[float, float] | None, speed: float | None) -> tuple[
              tuple[float, float] | None, tuple[float, float] | None, float | None, bool]:
    """Start, goal and water speed of the drawing (given, else the result's, else the
    track's ends and the speed inferred from it); whether the speed was inferred."""
    has_track = result.lat.size > 0
    if start is None:
        start = (float(result.start[0]), float(result.start[1])) if result.speed > 0 else (
            (float(result.lat[0]), float(result.lon[0])) if has_track else None)
    if goal is None:
        goal = (float(result.goal[0]), float(result.goal[1])) if result.speed > 0 else (
            (float(result.lat[-1]), float(result.lon[-1])) if has_track else None)
    inferred = speed is None and result.speed <= 0
    if speed is None:
        speed = result.speed if result.speed > 0 else (
            None if field_ is None else water_speed_from_track(result, field_))
    return start, goal, speed, inferred


@dataclass(frozen=True)
class _Frame:
    """The drawing's frame: longitudes unwrapped about `ref_lon`, limits (deg), metres per
    degree of latitude and longitude at its mean latitude, the data's span (m)."""

    ref_lon: float
    la0: float
    la1: float
    lo0: float
    lo1: float
    m_lat: float
    m_lon: float
    span_m: float

    def unwrap(self, lon_deg: Any) -> Any:
        """Longitudes unwrapped about the route's middle."""
        from glideplan.routing.sphere import unwrap_lon

        return unwrap_lon(lon_deg, self.ref_lon)


def _frame(result: RouteResult, field_: FlowField | None, start: tuple[float, float] | None,
           goal: tuple[float, float] | None) -> _Frame:
    """The frame centred on the route: the data with a margin of 0.15 of its span, each side
    at least 0.6 of the span long (a thin strip along a straight route hides the field
    around it), cut to the field."""
    from glideplan.routing.sphere import unwrap_lon

    has_track = result.lat.size > 0
    ext = None if field_ is None else field_.extent
    ref_lon = start[1] if start is not None else (
        float(result.lon[0]) if has_track else (0.0 if ext is None else ext.lon_min))
    if start is not None and goal is not None:
        ref_lon = float(start[1] + 0.5 * float(unwrap_lon(goal[1], start[1]) - start[1]))

    def frame(lon_deg: Any) -> Any:  # longitudes unwrapped about the route's middle
        return unwrap_lon(lon_deg, ref_lon)

    lats = [p[0] for p in (start, goal) if p is not None]
    lons = [float(frame(p[1])) for p in (start, goal) if p is not None]
    if has_track:
        lats += [float(result.lat.min()), float(result.lat.max())]
        lons += [float(np.min(frame(result.lon))), float(np.max(frame(result.lon)))]
    if not lats:  # nothing to centre on: the whole field (or a 2-degree box)
        lats, lons = ([ext.lat_min, ext.lat_max], [ext.lon_min, ext.lon_max]) if ext else (
            [-1.0, 1.0], [ref_lon - 1.0, ref_lon + 1.0])
    la_mid, lo_mid = 0.5 * (min(lats) + max(lats)), 0.5 * (min(lons) + max(lons))
    m_lat, m_lon = frame_scales(max(min(la_mid, 89.0), -89.0), (lo_mid + 180) % 360 - 180)
    span_m = max((max(lats) - min(lats)) * m_lat, (max(lons) - min(lons)) * m_lon, 1000.0)
    half_la = max(0.5 * (max(lats) - min(lats)) * m_lat + 0.15 * span_m, 0.3 * span_m) / m_lat
    half_lo = max(0.5 * (max(lons) - min(lons)) * m_lon + 0.15 * span_m, 0.3 * span_m) / m_lon
    half_lo = min(half_lo, 180.0)
    la0, la1 = max(la_mid - half_la, -89.9), min(la_mid + half_la, 89.9)
    lo0, lo1 = lo_mid - half_lo, lo_mid + half_lo
    if ext is not None:
        la0, la1 = max(la0, ext.lat_min), min(la1, ext.lat_max)
        if not ext.periodic:  # the field's extent in the route's frame
            e0 = float(frame(0.5 * (ext.lon_min + ext.lon_max))) - 0.5 * (
                ext.lon_max - ext.lon_min)
            lo0, lo1 = max(lo0, e0), min(lo1, e0 + ext.lon_max - ext.lon_min)
    # The aspect: equal ground distances at the frame's mean latitude.
    m_lat, m_lon = frame_scales(0.5 * (la0 + la1), ((lo0 + lo1) / 2 + 180) % 360 - 180)
    return _Frame(ref_lon, la0, la1, lo0, lo1, m_lat, m_lon, span_m)


def _draw_current(ax: Any, result: RouteResult, field_: FlowField | None, fr: _Frame,
                  arrows: int) -> tuple[list[Any], tuple[Any, float] | None]:
    """Current arrows at departure on a grid square in ground distance, land on a finer
    grid; legend handles and the arrow key (quiver, m/s) when there is a current."""
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    la0, la1, lo0, lo1 = fr.la0, fr.la1, fr.lo0, fr.lo1
    handles: list[Any] = []
    quiver_key: tuple[Any, float] | None = None
    w_m, h_m = (lo1 - lo0) * fr.m_lon, (la1 - la0) * fr.m_lat
    n_lo = arrows if w_m >= h_m else max(5, round(arrows * w_m / h_m))
    n_la = arrows if h_m > w_m else max(5, round(arrows * h_m / w_m))
    snapshot = "" if field_ is None else _time_text(field_, result.depart_s)
    try:
        if field_ is None:
            raise ValueError("no field")
        LA, LO = np.meshgrid(np.linspace(la0, la1, 4 * n_la), np.linspace(lo0, lo1, 4 * n_lo),
                             indexing="ij")
        uf, _ = field_.velocity(result.depart_s, LA, LO)
        land = ~np.isfinite(uf)
        if np.any(land):
            ax.contourf(LO, LA, land.astype(float), levels=[0.5, 1.5], colors=[_LAND_COLOUR],
                        zorder=1)
            handles.append(Patch(facecolor=_LAND_COLOUR, label="land (no current data)"))
        LA, LO = np.meshgrid(np.linspace(la0, la1, n_la), np.linspace(lo0, lo1, n_lo),
                             indexing="ij")
        u, v = field_.velocity(result.depart_s, LA, LO)
        water = np.isfinite(u) & np.isfinite(v)
        c_max = float(np.max(np.hypot(u[water], v[water]))) if np.any(water) else 0.0
        if c_max > 0.0:
            q = ax.quiver(LO[water], LA[water], u[water], v[water], color="0.55", zorder=2,
                          width=0.0022)
            quiver_key = (q, _nice(c_max))
            handles.append(Line2D([], [], ls="none", marker=r"$\rightarrow$", ms=12,
                                  color="0.55", label=f"current at departure, {snapshot}"))
        elif np.any(water):
            handles.append(Line2D([], [], ls="none", label="still water (no current)"))
    except ValueError:  # a field that cannot be drawn here: draw the track alone
        pass
    return handles, quiver_key


def _draw_route(ax: Any, result: RouteResult, fr: _Frame, start: tuple[float, float] | None,
                goal: tuple[float, float] | None, glider: GliderFollow | None) -> list[Any]:
    """The straight line, the route, the glider's flyable path, start and goal with their
    headings through the water; legend handles."""
    frame = fr.unwrap
    has_track = result.lat.size > 0
    handles: list[Any] = []
    if start is not None and goal is not None:
        (line,) = ax.plot([frame(start[1]), frame(goal[1])], [start[0], goal[0]], ":",
                          color="0.25", lw=1.2, zorder=3)
        line.set_label("straight line (crabbing time in the title)")
        handles.append(line)
    if has_track:
        lon_t = frame(result.lon)
        label = f"route ({result.method})"
        if result.duration_s is not None:
            label += f", {result.duration_s / 3600:.2f} h"
        (line,) = ax.plot(lon_t, result.lat, color="C3", lw=2.2, label=label, zorder=4)
        handles.append(line)
    if glider is not None and glider.track.size:
        (line,) = ax.plot(frame(glider.track.lon), glider.track.lat, "--",
                          color="black", lw=1.0, zorder=4,
                          label=f"glider following, R0 = {glider.radius_m:.4g} m")
        handles.append(line)
    arrow_m = 0.07 * fr.span_m
    for p, colour, marker, name, k in ((start, "tab:green", "o", "start", 0),
                                       (goal, "tab:red", "s", "goal", -1)):
        if p is None:
            continue
        text = name
        if has_track and result.heading_deg.size:
            hdg = float(result.heading_deg[k])
            _heading_arrow(ax, p[0], float(frame(p[1])), hdg, arrow_m, fr.m_lat, fr.m_lon,
                           colour)
            text += f", heading {hdg:.0f}° (through water)"
        (mk,) = ax.plot(frame(p[1]), p[0], marker, color=colour, ms=8, zorder=5, ls="none",
                        label=text)
        handles.append(mk)
    return handles


def _finish_axes(ax: Any, fr: _Frame, start: tuple[float, float] | None) -> None:
    """Limits, equal ground aspect, degree and km axes, scale bar, north arrow, grid."""
    from matplotlib.ticker import FuncFormatter

    from glideplan.plotting import add_north_arrow, add_scale_bar

    ax.set_xlim(fr.lo0, fr.lo1)
    ax.set_ylim(fr.la0, fr.la1)
    ax.set_aspect(fr.m_lat / fr.m_lon, adjustable="box")
    ax.set_xlabel("longitude (deg E)")
    # the frame is unwrapped about the route (continuous across 180): ticks read -180..180
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _p: f"{(v + 180.0) % 360.0 - 180.0:g}"))
    ax.set_ylabel("latitude (deg N)")
    ref_lat = fr.la0 if start is None else start[0]
    ref_lon = fr.lo0 if start is None else float(fr.unwrap(start[1]))
    ref = "the frame's corner" if start is None else "start"
    add_km_axes(ax, ref_lat, ref_lon, fr.m_lat, fr.m_lon, f"km east of {ref}",
                f"km north of {ref}")
    add_scale_bar(ax)  # (limits and aspect are final: adjustable "box")
    add_north_arrow(ax)
    ax.grid(True, lw=0.4, alpha=0.5)


def _legend(fig: Any, ax: Any, handles: list[Any], quiver_key: tuple[Any, float] | None) -> None:
    """The legend outside the axes and the current's arrow key just below it."""
    if handles:
        legend = ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.12, 1.0),
                           borderaxespad=0.0, fontsize=8)
    if quiver_key is not None:  # the arrow key just below the legend, outside the axes
        fig.canvas.draw()
        if handles:
            box = legend.get_window_extent().transformed(fig.transFigure.inverted())
            x, y = box.x0 + 0.025, box.y0 - 0.05
        else:
            box = ax.get_position()
            x, y = box.x1 + 0.12, box.y1 - 0.05
        q, key = quiver_key
        ax.quiverkey(q, x, y, key, f"key: current {key:g} m/s", labelpos="E",
                     coordinates="figure", fontproperties={"size": 8})
