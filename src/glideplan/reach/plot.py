"""Figures of a glide reach (map) and a turn-back point (map and altitude profile).

Map axes are longitude/latitude in degrees with the aspect 1 / cos(lat) (metres equal in
both directions), north up. The terrain is coloured by height (hypsometric: green lowlands,
tan and brown slopes, grey rock, white summits, over the terrain's own range) and shaded
(Matplotlib's LightSource, sun from the north-west at 45 deg, "soft" blend), with contour
lines at a round interval; a colour bar gives the elevation in m. A km scale bar, a north
arrow and the wind arrow (pointing where the wind blows) sit in the corners. Landables are
coloured by their arrival margin; out of reach: a red cross labelled with how much height
is missing ("-240 m"); on missing terrain: a hollow grey circle labelled "no terrain".
Labels are placed greedily so that they collide with no other label or marker
(`glideplan.plotting.place_labels`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np

if TYPE_CHECKING:
    from glideplan.reach.result import ReachResult
    from glideplan.reach.turnback import TurnbackResult
    from glideplan.terrain.grid import Terrain

__all__ = ["hypsometric_cmap", "plot_reach", "plot_turnback"]

_MAX_SHADE = 1200  # terrain samples per side drawn (strided beyond)
_MAX_CONTOUR = 400  # samples per side contoured
#: Hypsometric tints (fraction of the elevation range, colour): green - tan - brown - white.
_HYPSO = ((0.0, "#3d7a3a"), (0.12, "#74a95a"), (0.3, "#c8cf8a"), (0.45, "#d8b878"),
          (0.6, "#a8794b"), (0.75, "#86644e"), (0.88, "#b9b1aa"), (1.0, "#ffffff"))
_NO_DATA_RGBA = (0.82, 0.82, 0.82, 1.0)
_FOOTPRINT_EDGE = "#b0006e"  # magenta: apart from every terrain tint


def hypsometric_cmap() -> Any:
    """The terrain colour map (low green, tan, brown, grey rock, white top)."""
    from matplotlib.colors import LinearSegmentedColormap

    return LinearSegmentedColormap.from_list("glideplan_hypsometric", list(_HYPSO))


def _terrain_image(ax: Any, terrain: Terrain) -> tuple[Any, Any]:
    """Draw the tinted, shaded terrain and its contours; (ScalarMappable for the colour bar,
    the contour set or None)."""
    import matplotlib.pyplot as plt
    from matplotlib.colors import LightSource, Normalize
    from matplotlib.ticker import MaxNLocator

    step = max(1, math.ceil(max(terrain.shape) / _MAX_SHADE))
    z = np.asarray(terrain.z[::step, ::step], dtype=float)
    nodata = ~np.isfinite(z)
    lo = float(np.nanmin(z)) if not nodata.all() else 0.0
    hi = float(np.nanmax(z)) if not nodata.all() else 1.0
    norm = Normalize(lo, max(hi, lo + 100.0))  # a flat tile is not stretched to full range
    cmap = hypsometric_cmap()
    zf = np.where(nodata, lo, z)
    dx, dy = terrain.spacing_m
    ls = LightSource(azdeg=315, altdeg=45)
    rgb = ls.shade(zf[::-1], cmap=cmap, norm=norm, blend_mode="soft", vert_exag=1.0,
                   dx=dx * step, dy=dy * step)
    rgb[nodata[::-1]] = _NO_DATA_RGBA
    s, n, w, e = terrain.extent
    ax.imshow(rgb, extent=(w, e, s, n), origin="upper", interpolation="bilinear", zorder=0)
    cs = None
    levels = np.asarray(MaxNLocator(nbins=8, steps=[1, 2, 2.5, 5, 10]).tick_values(
        lo, max(hi, lo + 100.0)), dtype=np.float64)
    levels = levels[(levels > lo) & (levels < hi)]
    if levels.size:
        c = max(1, math.ceil(max(terrain.shape) / _MAX_CONTOUR))
        cs = ax.contour(terrain.lon[::c], terrain.lat[::c],
                        np.ma.masked_invalid(np.asarray(terrain.z[::c, ::c], dtype=float)),
                        levels=levels, colors="0.2", linewidths=0.4, alpha=0.55, zorder=1)
    return plt.cm.ScalarMappable(norm=norm, cmap=cmap), cs


def _elevation_colorbar(ax: Any, sm: Any, cs: Any) -> Any:
    """The terrain's colour bar (m), with the contour levels drawn on it."""
    fig = ax.get_figure()
    cb = fig.colorbar(sm, ax=ax, shrink=0.75, pad=0.02)
    label = "terrain elevation (m)"
    if cs is not None and len(cs.levels) > 1:
        label += f", contours every {cs.levels[1] - cs.levels[0]:g} m"
        cb.add_lines(cs.levels, ["0.2"] * len(cs.levels), [0.6] * len(cs.levels))
    cb.set_label(label, fontsize=8)
    cb.ax.tick_params(labelsize=7)
    return cb


def _wind_arrow(ax: Any, wind: tuple[float, float], lat: float) -> None:
    """`plotting.wind_arrow` in the top-left corner, and the wind's speed and FROM direction
    above it (display space, so its direction is true on an equal-metre map)."""
    from glideplan.plotting import wind_arrow, wind_label

    del lat  # the map's aspect makes display directions true
    kw = {"transform": ax.transAxes, "va": "top", "fontsize": 8, "zorder": 20}
    wind_arrow(ax, wind, (0.1, 0.83))
    text = wind_label(wind)
    ax.text(0.03, 0.97, text, **kw, **({} if text == "no wind" else {
        "color": "navy", "bbox": {"boxstyle": "round", "fc": "white", "alpha": 0.7, "lw": 0}}))


def _footprint(ax: Any, result: ReachResult) -> None:
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    for poly in result.footprint:
        verts = np.vstack(poly)
        codes = np.concatenate([[MplPath.MOVETO] + [MplPath.LINETO] * (len(r) - 2)
                                + [MplPath.CLOSEPOLY] for r in poly])
        ax.add_patch(PathPatch(MplPath(verts, codes), facecolor=(0.69, 0.0, 0.43, 0.10),
                               edgecolor=_FOOTPRINT_EDGE, lw=1.6, zorder=2))


def _landables(ax: Any, result: ReachResult, paths: bool) -> tuple[list[str], Any, float]:
    """Draw the landables (and their paths); (their labels, the margin colour map, its top)."""
    import matplotlib.pyplot as plt

    margins = [p.arrival_margin_m if p.reachable and p.arrival_margin_m is not None else np.nan
               for p in result.points]
    finite = [m for m in margins if np.isfinite(m)]
    vmax = max(max(finite) if finite else 1.0, 1.0)
    cmap = plt.get_cmap("RdYlGn")
    labels = []
    for p, m in zip(result.points, margins, strict=True):
        lnd = p.landable
        if paths and p.path is not None and p.reachable:
            ax.plot(p.path.lon, p.path.lat, color="tab:blue", lw=1.2, zorder=4)
        short = getattr(p, "short_by_m", None)
        if getattr(p, "terrain_missing", False):
            ax.scatter([lnd.lon], [lnd.lat], s=60, facecolors="none", edgecolors="0.45",
                       linewidths=1.8, zorder=7, gid="landable_no_terrain")
            labels.append(f"{lnd.name}: no terrain")
        elif np.isfinite(m):
            ax.scatter([lnd.lon], [lnd.lat], c=[m], cmap=cmap, vmin=0.0, vmax=vmax, s=60,
                       edgecolors="k", zorder=7, gid="landable_reachable")
            labels.append(f"{lnd.name} +{m:.0f} m")
        else:
            ax.plot(lnd.lon, lnd.lat, marker="x", color="red", ms=8, mew=2, zorder=7,
                    gid="landable_out_of_reach")
            labels.append(f"{lnd.name} -{short:.0f} m" if short is not None
                          and math.isfinite(short) else f"{lnd.name} (out of reach)")
    return labels, (cmap if finite else None), vmax


def plot_reach(result: ReachResult, ax: Any = None, *, paths: bool = True) -> Any:
    """The map of a glide reach (module docstring): tinted, shaded terrain with contours
    and its colour bar, the footprint (magenta), landables coloured by arrival margin
    (red-green; crosses out of reach, hollow grey on missing terrain) with labels that do
    not collide, the flown paths, the start, the wind, a km scale bar and a north arrow."""
    import matplotlib.patheffects as pe
    import matplotlib.pyplot as plt

    from glideplan.plotting import add_north_arrow, add_scale_bar, marker_boxes, place_labels

    own = ax is None
    if own:
        _, ax = plt.subplots(figsize=(9, 7.5))
    fig = ax.get_figure()
    sm, cs = _terrain_image(ax, result.terrain)
    _footprint(ax, result)
    lat0, lon0, alt = result.start
    ax.plot(lon0, lat0, marker="^", color="k", ms=9, zorder=6, label=f"start {alt:.0f} m")
    labels, cmap, vmax = _landables(ax, result, paths)
    s, n, w, e = result.terrain.extent
    ax.set_xlim(w, e)
    ax.set_ylim(s, n)
    ax.set_aspect(1.0 / max(math.cos(math.radians(lat0)), 1e-3))
    ax.set_xlabel("longitude (deg)")
    ax.set_ylabel("latitude (deg)")
    g = result.glide
    ax.set_title(f"glide reach from {alt:.0f} m, {g.polar.name}, MC {g.mc:g} m/s, safety "
                 f"{result.safety_height:g} m\n{result.message}", fontsize=9)
    _elevation_colorbar(ax, sm, cs)
    if cmap is not None:
        mm = plt.cm.ScalarMappable(cmap=cmap, norm=plt.Normalize(0.0, vmax))
        cb = fig.colorbar(mm, ax=ax, shrink=0.75, pad=0.02)
        cb.set_label("arrival margin over safety height (m)", fontsize=8)
        cb.ax.tick_params(labelsize=7)
    _wind_arrow(ax, g.wind, lat0)
    if own:
        fig.tight_layout()
    ax.apply_aspect()
    add_scale_bar(ax)
    add_north_arrow(ax)
    renderer = fig.canvas.get_renderer()  # (limits, aspect and layout are final)
    pts = [(p.landable.lon, p.landable.lat) for p in result.points]
    furniture = [a.get_window_extent(renderer) for a in (*ax.texts, *ax.lines)
                 if a.get_gid() in ("scale_bar", "scale_bar_label", "north_arrow")]
    furniture += [t.get_window_extent(renderer) for t in ax.texts if t.get_gid() is None]
    obstacles = marker_boxes(ax, [*pts, (lon0, lat0)], 5.0) + furniture
    halo = [pe.withStroke(linewidth=2.5, foreground="white", alpha=0.85)]
    place_labels(ax, pts, labels, obstacles=obstacles, gid="landable_label", fontsize=7,
                 zorder=8, path_effects=halo)
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
    tinted = _terrain_image(ax_map, result.terrain) if result.terrain is not None else None
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
    if tinted is not None:
        _elevation_colorbar(ax_map, *tinted)
    from glideplan.plotting import add_north_arrow, add_scale_bar

    ax_map.apply_aspect()
    add_scale_bar(ax_map)
    add_north_arrow(ax_map)
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
            clear_h = (result.safety_height if result.terrain_clearance is None
                       else result.terrain_clearance)
            ax_prof.plot(s / 1000, f.ground + clear_h, color="0.3", lw=0.8, ls="--")
            s0 = float(s[-1])
        # the altitude a straight glide home needs from each point of the course (terrain
        # ignored): the outbound line meets it at the turn-back point when no terrain binds
        from glideplan.geodesy import rhumb_destination

        lat0_, lon0_, _ = result.start
        chi = math.radians(90.0 - result.course_deg)
        ss = np.linspace(0.0, 1.3 * max(result.distance_m, 1.0), 200)
        pla, plo = rhumb_destination(lat0_, lon0_, chi, ss)
        n = ss.size
        dd, cc = rhumb(pla, plo, np.full(n, home.lat), np.full(n, home.lon))
        need = home.elevation_m + result.safety_height + dd / result.glide.ratio(cc)
        ax_prof.plot(ss / 1000, need, color="purple", lw=1, ls="-.",
                     label="needed to glide home straight (terrain ignored)")
        ax_prof.axvline(result.distance_m / 1000, color="r", ls=":", label="turn back")
        ax_prof.axhline(home.elevation_m + result.safety_height, color="g", ls=":",
                        label="home + arrival height")
        ax_prof.set_xlabel("distance flown (km)")
        ax_prof.set_ylabel("altitude (m MSL)")
        ax_prof.legend(fontsize=7)
        ax_prof.set_title("altitude out and back (terrain under the track, dashed: + clearance)",
                          fontsize=8)
    return ax_map
