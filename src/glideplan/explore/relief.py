"""Terrain on the explorer's reach map: colour relief with hillshade, labelled contours, a key.

The same picture as the CLI's figure (`glideplan.reach.plot`): hypsometric tints over the
tile's own elevation range (green lowlands, tan and brown slopes, grey rock, white tops;
`reach.plot.hypsometric_cmap`) shaded by Matplotlib's `LightSource` (sun from the north-west,
45 deg high, "soft" blend, vertical exaggeration 1, the cells' true sizes in metres); no-data
cells light grey. Contours at the round interval `contour_levels` picks from the relief
(1, 2, 2.5 or 5 x 10^n m, at most 8 intervals over the range, as the CLI), each line
labelled with its height where it is long enough. The colour key gives the elevation (m)
and the interval. Drawn once per page (the terrain does not change with the inputs).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

__all__ = ["add_relief", "contour_levels", "contour_lines", "relief_rgba"]

MAX_IMAGE = 700  # relief samples per side sent to the browser (strided beyond)
MAX_CONTOUR = 400  # samples per side contoured
_NO_DATA = (209, 209, 209, 255)


def contour_levels(lo: float, hi: float) -> NDArray[np.float64]:
    """Round contour heights strictly inside (lo, hi): MaxNLocator(8, steps 1, 2, 2.5, 5, 10)
    over (lo, max(hi, lo + 100)) -- the CLI figure's levels."""
    from matplotlib.ticker import MaxNLocator

    top = max(hi, lo + 100.0)
    levels = np.asarray(
        MaxNLocator(nbins=8, steps=[1, 2, 2.5, 5, 10]).tick_values(lo, top), dtype=np.float64
    )
    return levels[(levels > lo) & (levels < hi)]


def relief_rgba(terrain: Any, max_side: int = MAX_IMAGE) -> tuple[NDArray[np.uint32], int]:
    """The shaded hypsometric image of `terrain` (rows south to north, packed RGBA for Bokeh's
    `image_rgba`) and the stride used."""
    from matplotlib.colors import LightSource, Normalize

    from glideplan.reach.plot import hypsometric_cmap

    step = max(1, math.ceil(max(terrain.shape) / max_side))
    z = np.asarray(terrain.z[::step, ::step], dtype=float)
    lat = np.asarray(terrain.lat[::step], dtype=float)
    if lat[0] > lat[-1]:  # rows north to south: the image's rows go up
        z = z[::-1]
    nodata = ~np.isfinite(z)
    lo = float(np.nanmin(z)) if not nodata.all() else 0.0
    hi = float(np.nanmax(z)) if not nodata.all() else 1.0
    dx, dy = terrain.spacing_m
    shade = LightSource(azdeg=315, altdeg=45).shade(
        np.where(nodata, lo, z)[::-1],  # LightSource: row 0 at the top (north)
        cmap=hypsometric_cmap(),
        norm=Normalize(lo, max(hi, lo + 100.0)),
        blend_mode="soft",
        vert_exag=1.0,
        dx=dx * step,
        dy=dy * step,
    )[::-1]
    rgba = np.round(np.clip(shade, 0.0, 1.0) * 255).astype(np.uint8)
    rgba[..., 3] = 255
    rgba[nodata] = _NO_DATA
    return np.ascontiguousarray(rgba).view(np.uint32).reshape(z.shape), step


def contour_lines(terrain: Any, levels: NDArray[np.float64], min_label_cells: int = 30,
                  label_gap: float = 0.04) -> tuple[dict[str, list[Any]], dict[str, list[Any]]]:
    """The contour lines ({"xs", "ys"}, lon/lat) and their labels ({"x", "y", "text",
    "angle"}): on each line at least `min_label_cells` samples long, at the first of 1/2,
    1/3, 2/3, 1/6, 5/6 of its length that is `label_gap` of the tile's width (in metres) from
    every label placed, turned along the line on the map's equal-metre scale."""
    import contourpy

    c = max(1, math.ceil(max(terrain.shape) / MAX_CONTOUR))
    lon = np.asarray(terrain.lon[::c], dtype=float)
    lat = np.asarray(terrain.lat[::c], dtype=float)
    z = np.ma.masked_invalid(np.asarray(terrain.z[::c, ::c], dtype=float))
    gen = contourpy.contour_generator(lon, lat, z, line_type="Separate")
    k = math.cos(math.radians(float(np.mean(lat))))
    gap = label_gap * float(np.ptp(lon)) * k  # in degrees of latitude
    lines: dict[str, list[Any]] = {"xs": [], "ys": []}
    labels: dict[str, list[Any]] = {"x": [], "y": [], "text": [], "angle": []}
    for level in levels:
        for seg in gen.lines(float(level)):
            seg = np.asarray(seg)
            lines["xs"].append(seg[:, 0])
            lines["ys"].append(seg[:, 1])
            if len(seg) < min_label_cells:
                continue
            for f in (1 / 2, 1 / 3, 2 / 3, 1 / 6, 5 / 6):
                m = int(f * (len(seg) - 1))
                x, y = float(seg[m, 0]), float(seg[m, 1])
                px, py = np.asarray(labels["x"]), np.asarray(labels["y"])
                if px.size and np.min(np.hypot((px - x) * k, py - y)) < gap:
                    continue
                d = seg[min(m + 2, len(seg) - 1)] - seg[max(m - 2, 0)]
                angle = math.atan2(d[1], d[0] * k)
                if abs(angle) > math.pi / 2:  # text upright
                    angle -= math.copysign(math.pi, angle)
                labels["x"].append(x)
                labels["y"].append(y)
                labels["text"].append(f"{level:g}")
                labels["angle"].append(angle)
                break
    return lines, labels


def add_relief(fig: Any, terrain: Any) -> float | None:
    """Draw the terrain's relief, contours (labelled) and elevation key on `fig` (lon/lat),
    under what is drawn later; returns the contour interval (m) or None."""
    from bokeh.models import ColumnDataSource, FixedTicker, LinearColorMapper
    from bokeh.models.annotations import ColorBar
    from matplotlib.colors import to_hex

    from glideplan.reach.plot import hypsometric_cmap

    image, _ = relief_rgba(terrain)
    s, n, w, e = terrain.extent
    fig.image_rgba(image=[image], x=w, y=s, dw=e - w, dh=n - s, name="gp-relief")
    z = np.asarray(terrain.z, dtype=float)
    lo, hi = (float(np.nanmin(z)), float(np.nanmax(z))) if np.isfinite(z).any() else (0.0, 1.0)
    levels = contour_levels(lo, hi)
    interval = float(levels[1] - levels[0]) if levels.size > 1 else None
    if levels.size:
        lines, labels = contour_lines(terrain, levels)
        fig.multi_line("xs", "ys", source=ColumnDataSource(lines, name="gp-contours"),
                       line_color="#333333", line_alpha=0.5, line_width=0.7)
        fig.text("x", "y", "text", angle="angle", source=ColumnDataSource(labels),
                 text_font_size="9px", text_color="#333333", text_align="center",
                 text_baseline="middle", background_fill_color="#ffffff",
                 background_fill_alpha=0.55)
    cmap = hypsometric_cmap()
    palette = [to_hex(cmap(i / 255.0)) for i in range(256)]
    mapper = LinearColorMapper(palette=palette, low=lo, high=max(hi, lo + 100.0))
    title = "terrain (m)" + (f", contours every {interval:g} m" if interval else "")
    fig.add_layout(ColorBar(color_mapper=mapper, title=title, width=10,
                            title_text_font_size="10px", major_label_text_font_size="9px",
                            ticker=FixedTicker(ticks=[float(v) for v in levels])), "right")
    return interval
