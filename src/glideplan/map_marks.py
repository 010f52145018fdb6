"""Map furniture for the figures (Matplotlib is imported inside functions): kilometre axes,
the scale bar, the north arrow, and labels placed beside their points without overlapping.

Split from `glideplan.plotting` (which re-exports every name here) to keep each module
short. A degree of longitude is (pi / 180) N(phi) cos(phi) metres on the WGS84 ellipsoid,
N = a / sqrt(1 - e^2 sin^2 phi) (`metres_per_degree_lon`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

__all__ = [
    "add_km_axes",
    "add_north_arrow",
    "add_scale_bar",
    "marker_boxes",
    "metres_per_degree_lon",
    "nice_length",
    "place_labels",
]


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
