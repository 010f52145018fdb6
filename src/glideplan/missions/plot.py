"""Draw a planned mission: track, waypoints, heading arrows, labelled legs (Matplotlib).

Geographic missions are drawn in a frame centred on the route: longitudes are unwrapped about
the route's centre lon_c (lon -> lon_c + ((lon - lon_c + 180) mod 360 - 180)), so a route
across 180 deg (e.g. near Fiji) is drawn over its own span, not around the globe; the tick
labels read the longitudes in -180..180.
"""

from __future__ import annotations

import pathlib
from typing import Any

import numpy as np

from glideplan.missions.field_mission import FieldMission
from glideplan.missions.plan import MissionPlan
from glideplan.missions.route import Route
from glideplan.missions.straight_legs import StraightLegList
from glideplan.units import wind_to_compass

__all__ = ["plot_mission", "route_centre_lon", "unwrap_lon"]


def route_centre_lon(route: Route) -> float:
    """The longitude (deg) the figure is centred on: the middle of the waypoints' span, the
    waypoints unwrapped one after the other (each within 180 deg of the previous)."""
    assert route.lon is not None
    lon = np.degrees(np.unwrap(np.radians(np.asarray(route.lon, dtype=float))))
    return 0.5 * (float(np.min(lon)) + float(np.max(lon)))


def unwrap_lon(lon: np.ndarray, centre: float) -> np.ndarray:
    """`lon` (deg) within 180 deg of `centre`: centre + ((lon - centre + 180) mod 360 - 180)."""
    return centre + (np.asarray(lon, dtype=float) - centre + 180.0) % 360.0 - 180.0


def _wrapped_lon_label(value: float, _pos: Any = None) -> str:
    """A tick label of an unwrapped longitude, read in -180..180 deg."""
    return f"{(value + 180.0) % 360.0 - 180.0:g}"


def _ground_scale_axes(ax: Any, lon: np.ndarray, lat: np.ndarray, origin: str) -> None:
    """Longitude / latitude axes (deg) at equal ground scale, with a km scale on top and right.

    The aspect (axis units of latitude per unit of longitude drawn the same length) is
    m_lat / m_lon, the WGS84 lengths of a degree of latitude and of longitude at the track's
    mid-point (`glideplan.routing.plot.frame_scales`; ~1 / cos(lat)), so that a km east is
    drawn as long as a km north. The top and right axes read km east / north of the first
    waypoint `origin` (lon, lat of the track's first point) on that local plane.
    """
    from matplotlib.ticker import FuncFormatter

    from glideplan.plotting import add_km_axes
    from glideplan.routing.plot import frame_scales

    lat_mid = 0.5 * (float(np.min(lat)) + float(np.max(lat)))
    # the ellipsoid is symmetric about its axis: the lengths of a degree do not depend on the
    # longitude, so they are taken at 0 E (clear of the +-180 limits of unwrapped longitudes)
    m_lat, m_lon = frame_scales(lat_mid, 0.0)
    lon0, lat0 = float(lon[0]), float(lat[0])
    ax.set_aspect(m_lat / m_lon, adjustable="datalim")
    ax.set_xlabel("longitude (deg E)")
    ax.set_ylabel("latitude (deg N)")
    ax.ticklabel_format(useOffset=False)
    ax.xaxis.set_major_formatter(FuncFormatter(_wrapped_lon_label))

    add_km_axes(ax, lat0, lon0, m_lat, m_lon, f"km east of {origin} (equal ground scale)",
                f"km north of {origin}")


def plot_mission(
    plan: MissionPlan | FieldMission, legs: StraightLegList | None = None, *, ax: Any = None
) -> Any:
    """A figure of `plan`: axes in degrees (lon, lat) at equal ground scale with km east /
    north of the first waypoint on the top and right axes for geographic routes, else metres.
    Drawn on `ax` when given (else a new figure); returns the figure."""
    import matplotlib.pyplot as plt

    if ax is None:
        fig, ax = plt.subplots(figsize=(10, 7))
    else:
        fig = ax.get_figure()
    r = plan.route
    track = plan.track()
    geo = r.projection is not None
    tx, ty = _drawn(r, track.x, track.y)
    ax.plot(tx, ty, "-", color="tab:blue", lw=1.6, label="planned track")
    if legs is not None:
        lx, ly = _drawn(r, legs.x, legs.y)
        ax.plot(lx, ly, "--", color="tab:orange", lw=0.9, marker=".", ms=4,
                label=f"straight legs (within {legs.tolerance_m:g} m)")
    given = _draw_waypoints(ax, plan, track)
    _label_legs(ax, plan, track, tx, ty)
    ax.plot([], [], color="tab:red", label="chosen heading (compass deg)")
    if np.any(given):
        ax.plot([], [], color="tab:green", label="given heading (compass deg)")
    if geo:
        assert r.lat is not None and r.lon is not None
        _ground_scale_axes(ax, tx, ty, r.names[0])
    else:
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
    ax.set_title(_title(plan), fontsize=9, loc="left")
    ax.grid(True, alpha=0.3)
    # Right of the axes, clear of the km scale on the right of geographic figures.
    ax.legend(loc="upper left", bbox_to_anchor=(1.11 if geo else 1.02, 1.0), borderaxespad=0.0,
              fontsize=8)
    fig.tight_layout()
    return fig


def _drawn(r: Route, x: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Plane x, y (m) as drawn: (lon unwrapped about the route's centre, lat) for a
    geographic route, else unchanged."""
    proj = r.projection
    if proj is None:
        return x, y
    lat, lon = proj.to_geographic(x, y)
    return unwrap_lon(lon, route_centre_lon(r)), np.asarray(lat, dtype=float)


def _draw_waypoints(ax: Any, plan: MissionPlan | FieldMission, track: Any) -> np.ndarray:
    """The waypoints with their names and heading arrows (green given, red chosen); the
    mask of given headings."""
    r = plan.route
    span = max(float(np.ptp(track.x)), float(np.ptp(track.y)), plan.radius or 0.0)
    arrow = 0.06 * span
    wx, wy = _drawn(r, r.x, r.y)
    ax.plot(wx, wy, "o", color="k", ms=6, label="waypoints", zorder=5)
    hx, hy = _drawn(r, r.x + arrow * np.cos(plan.headings), r.y + arrow * np.sin(plan.headings))
    ax.plot(hx, hy, ls="none")  # the arrow tips inside the frame (else they are not drawn)
    ax.margins(0.07)  # room for the waypoint labels below and right of the points
    given = ~r.free if plan.radius is not None else np.zeros(r.n, dtype=bool)  # field: free
    for i in range(r.n):
        color = "tab:green" if given[i] else "tab:red"
        ax.annotate("", xy=(hx[i], hy[i]), xytext=(wx[i], wy[i]),
                    arrowprops={"arrowstyle": "->", "color": color, "lw": 1.6}, zorder=6)
        ax.annotate(f"{r.names[i]}\n{plan.headings_deg[i]:.0f}\N{DEGREE SIGN}",
                    (wx[i], wy[i]), textcoords="offset points", xytext=(6, -14), fontsize=8)
    return np.asarray(given)


def _label_legs(ax: Any, plan: MissionPlan | FieldMission, track: Any, tx: np.ndarray,
                ty: np.ndarray) -> None:
    """Each leg's number, turn word (or time, field legs) and length at its middle."""
    for leg in plan.legs:
        sel = np.nonzero(track.leg == leg.index)[0]
        mid = sel[len(sel) // 2]
        what = (f"{leg.duration_s / 3600:.1f} h" if isinstance(plan, FieldMission)
                else leg.word)  # a field leg has no turn word: its time instead
        ax.annotate(f"{leg.index + 1}: {what}, {leg.length_m:.0f} m",
                    (tx[mid], ty[mid]), fontsize=7, color="tab:blue",
                    bbox={"boxstyle": "round,pad=0.15", "fc": "white", "alpha": 0.7, "lw": 0})


def _title(plan: MissionPlan | FieldMission) -> str:
    """The problem (route file, waypoints, speed, how planned) and the answer (totals,
    status, endpoint error)."""
    r = plan.route
    if plan.radius is None:
        src = plan.field_info.get("source") if isinstance(plan, FieldMission) else None
        name = pathlib.Path(str(src)).name if src else ""
        how = f"time-optimal through the current field {name}".rstrip()
    else:
        compass = None if plan.wind_vector is None else wind_to_compass(*plan.wind_vector)
        wind = "" if compass is None else (
            f", wind {compass[0]:g} m/s from {compass[1]:g}\N{DEGREE SIGN}")
        how = f"Dubins legs, turn radius R = {plan.radius:g} m{wind}, {plan.objective} optimal"
    err = plan.stats.get("max_endpoint_error")
    status = "all legs planned" if plan.ok else "some legs FAILED (see the report)"
    if isinstance(err, float):
        status += f", max endpoint error {err:.1e} m"
    return (f"Mission {pathlib.Path(str(r.source)).name}: {r.n} waypoints, "
            f"speed {plan.speed:g} m/s, {how}\n"
            f"total {plan.total_length_m:.0f} m, {plan.total_duration_s / 3600:.2f} h; {status}")
