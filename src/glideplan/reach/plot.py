"""Figures of a glide reach (map) and a turn-back point (map and altitude profile).

Map axes are longitude/latitude in degrees with the aspect 1 / cos(lat) (metres equal in
both directions). Hillshade: Matplotlib's LightSource (sun from the north-west, 45 deg).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from glideplan.reach.result import ReachResult
    from glideplan.reach.turnback import TurnbackResult
    from glideplan.terrain.grid import Terrain

__all__ = ["plot_reach", "plot_turnback"]

_MAX_SHADE = 1200  # terrain samples per side drawn (strided beyond)


def _hillshade(ax: Any, terrain: Terrain) -> None:
    from matplotlib.colors import LightSource

    step = max(1, math.ceil(max(terrain.shape) / _MAX_SHADE))
    z = np.asarray(terrain.z[::step, ::step], dtype=float)
    z = np.where(np.isfinite(z), z, np.nanmin(z) if np.any(np.isfinite(z)) else 0.0)
    dx, dy = terrain.spacing_m
    ls = LightSource(azdeg=315, altdeg=45)
    shade = ls.hillshade(z[::-1], vert_exag=1.0, dx=dx * step, dy=dy * step)
    s, n, w, e = terrain.extent
    ax.imshow(shade, cmap="gray", vmin=0.0, vmax=1.0, extent=(w, e, s, n), origin="upper",
              alpha=0.8,
              interpolation="bilinear", zorder=0)


def _wind_arrow(ax: Any, wind: tuple[float, float], lat: float) -> None:
    speed = math.hypot(*wind)
    if speed == 0:
        ax.text(0.03, 0.97, "no wind", transform=ax.transAxes, va="top", fontsize=8)
        return
    c = math.cos(math.radians(lat))
    u, v = wind[0] / speed, wind[1] / speed
    ax.annotate("", xy=(0.1 + 0.06 * u / max(c, 0.2) * c, 0.88 + 0.06 * v),
                xytext=(0.1, 0.88), xycoords="axes fraction",
                arrowprops={"arrowstyle": "->", "color": "navy", "lw": 2})
    frm = (math.degrees(math.atan2(-wind[0], -wind[1])) + 360.0) % 360.0
    ax.text(0.03, 0.97, f"wind {speed:.3g} m/s from {frm:.0f}°", transform=ax.transAxes,
            va="top", fontsize=8, color="navy")


def plot_reach(result: ReachResult, ax: Any = None, *, paths: bool = True) -> Any:
    """Hillshade, the footprint (green), landables coloured by arrival margin (red-green,
    crosses where out of reach), the flown paths, the start and the wind."""
    import matplotlib.pyplot as plt
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    if ax is None:
        _, ax = plt.subplots(figsize=(8, 7))
    _hillshade(ax, result.terrain)
    for poly in result.footprint:
        verts = np.vstack(poly)
        codes = np.concatenate([[MplPath.MOVETO] + [MplPath.LINETO] * (len(r) - 2)
                                + [MplPath.CLOSEPOLY] for r in poly])
        ax.add_patch(PathPatch(MplPath(verts, codes), facecolor=(0.1, 0.8, 0.2, 0.25),
                               edgecolor="green", lw=1.2, zorder=2))
    lat0, lon0, alt = result.start
    ax.plot(lon0, lat0, marker="^", color="k", ms=9, zorder=6, label=f"start {alt:.0f} m")
    margins = [p.arrival_margin_m if p.reachable and p.arrival_margin_m is not None else np.nan
               for p in result.points]
    finite = [m for m in margins if np.isfinite(m)]
    vmax = max(finite) if finite else 1.0
    cmap = plt.get_cmap("RdYlGn")
    for p, m in zip(result.points, margins, strict=True):
        lnd = p.landable
        if paths and p.path is not None and p.reachable:
            ax.plot(p.path.lon, p.path.lat, color="tab:blue", lw=1.2, zorder=4)
        if np.isfinite(m):
            ax.scatter([lnd.lon], [lnd.lat], c=[m], cmap=cmap, vmin=0.0, vmax=max(vmax, 1.0),
                       s=60, edgecolors="k", zorder=7)
            label = f"{lnd.name} +{m:.0f} m"
        else:
            ax.plot(lnd.lon, lnd.lat, marker="x", color="red", ms=8, mew=2, zorder=7)
            label = f"{lnd.name} (out of reach)"
        ax.annotate(label, (lnd.lon, lnd.lat), xytext=(4, 4), textcoords="offset points",
                    fontsize=7, zorder=8)
    if finite:
        sm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0.0, max(vmax, 1.0)))
        ax.get_figure().colorbar(sm, ax=ax, shrink=0.7,
                                 label="arrival margin over safety height (m)")
    _wind_arrow(ax, result.glide.wind, lat0)
    s, n, w, e = result.terrain.extent
    ax.set_xlim(w, e)
    ax.set_ylim(s, n)
    ax.set_aspect(1.0 / max(math.cos(math.radians(lat0)), 1e-3))
    ax.set_xlabel("longitude (deg)")
    ax.set_ylabel("latitude (deg)")
    g = result.glide
    ax.set_title(f"glide reach from {alt:.0f} m, {g.polar.name}, MC {g.mc:g} m/s, safety "
                 f"{result.safety_height:g} m\n{result.message}", fontsize=9)
    return ax


def plot_turnback(result: TurnbackResult, ax: Any = None) -> Any:
    """Left: the map (outbound, turn-back point, return home); right: altitude against
    distance flown, out and back, with the terrain under the track and the safety floor."""
    import matplotlib.pyplot as plt

    from glideplan.reach.flight import rhumb

    if ax is None:
        _, (ax_map, ax_prof) = plt.subplots(1, 2, figsize=(12, 5))
    else:
        ax_map, ax_prof = ax, None
    lat0, lon0, alt = result.start
    home = result.home
    pieces = [(result.outbound, "tab:orange", "outbound"), (result.back, "tab:blue", "return")]
    lats = [lat0, home.lat] + [float(v) for f, _, _ in pieces if f is not None
                               for v in (f.lat.min(), f.lat.max())]
    lons = [lon0, home.lon] + [float(v) for f, _, _ in pieces if f is not None
                               for v in (f.lon.min(), f.lon.max())]
    if result.terrain is not None:
        _hillshade(ax_map, result.terrain)
    for f, colour, label in pieces:
        if f is not None:
            ax_map.plot(f.lon, f.lat, color=colour, lw=1.5, label=label)
    ax_map.plot(lon0, lat0, "k^", ms=8, label=f"start {alt:.0f} m")
    ax_map.plot(home.lon, home.lat, "gs", ms=8, label=f"home {home.elevation_m:.0f} m")
    ax_map.plot(result.lon, result.lat, "r*", ms=12,
                label=f"turn back {result.distance_m / 1000:.2f} km")
    pad_lat = 0.1 * (max(lats) - min(lats)) + 0.01
    pad_lon = 0.1 * (max(lons) - min(lons)) + 0.01
    ax_map.set_xlim(min(lons) - pad_lon, max(lons) + pad_lon)
    ax_map.set_ylim(min(lats) - pad_lat, max(lats) + pad_lat)
    ax_map.set_aspect(1.0 / max(math.cos(math.radians(lat0)), 1e-3))
    ax_map.set_xlabel("longitude (deg)")
    ax_map.set_ylabel("latitude (deg)")
    _wind_arrow(ax_map, result.glide.wind, lat0)
    ax_map.legend(fontsize=7, loc="lower right")
    ax_map.get_figure().suptitle(result.message, fontsize=9)
    if ax_prof is not None:
        s0 = 0.0
        for f, colour, label in pieces:
            if f is None:
                continue
            d, _ = rhumb(f.lat[:-1], f.lon[:-1], f.lat[1:], f.lon[1:])
            s = s0 + np.concatenate([[0.0], np.cumsum(d)])
            ax_prof.plot(s / 1000, f.altitude, color=colour, lw=1.5, label=f"{label} altitude")
            ax_prof.fill_between(s / 1000, f.ground, np.nanmin(f.ground) - 50, color="0.6",
                                 alpha=0.6)
            ax_prof.plot(s / 1000, f.ground + result.safety_height, color="0.3", lw=0.8,
                         ls="--")
            s0 = float(s[-1])
        # the altitude a straight glide home needs from each point of the course (terrain
        # ignored): the outbound line meets it at the turn-back point when no terrain binds
        from glideplan.reach.turnback import destination

        lat0_, lon0_, _ = result.start
        chi = math.radians(90.0 - result.course_deg)
        ss = np.linspace(0.0, 1.3 * max(result.distance_m, 1.0), 200)
        pla, plo = destination(lat0_, lon0_, chi, ss)
        n = ss.size
        dd, cc = rhumb(pla, plo, np.full(n, home.lat), np.full(n, home.lon))
        need = home.elevation_m + result.safety_height + dd / result.glide.ratio(cc)
        ax_prof.plot(ss / 1000, need, color="purple", lw=1, ls="-.",
                     label="needed to glide home straight (terrain ignored)")
        ax_prof.axvline(result.distance_m / 1000, color="r", ls=":", label="turn back")
        ax_prof.axhline(home.elevation_m + result.safety_height, color="g", ls=":",
                        label="home + safety height")
        ax_prof.set_xlabel("distance flown (km)")
        ax_prof.set_ylabel("altitude (m MSL)")
        ax_prof.legend(fontsize=7)
        ax_prof.set_title("altitude out and back (terrain under the track, dashed: + safety)",
                          fontsize=8)
    return ax_map
