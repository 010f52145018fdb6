"""What every explorer map carries besides its data: a scale bar and a north arrow.

Both are drawn in the browser from the figure's current ranges (a CustomJS on the ranges and
the frame size), so they follow every pan and zoom without a round trip. The bar's length is
the largest 1, 2 or 5 x 10^n km (or m) not over a fifth of the view's width, measured along
the parallel through the view's middle: 1 deg of longitude = 111.32 km cos(lat) (the sphere
of radius 6371 km; the error against WGS-84 at the scale shown is < 0.5 %).
"""

from __future__ import annotations

from typing import Any

__all__ = ["add_scale_and_north"]

_JS = """
const x0 = xr.start, x1 = xr.end, y0 = yr.start, y1 = yr.end;
if (![x0, x1, y0, y1].every(Number.isFinite) || x1 <= x0 || y1 <= y0) return;
const w = x1 - x0, h = y1 - y0;
const lat = Math.max(-89.9, Math.min(89.9, 0.5 * (y0 + y1)));
const km_per_deg = 111.32 * Math.cos(lat * Math.PI / 180);
const target = w * km_per_deg / 5;
const p = Math.pow(10, Math.floor(Math.log10(target)));
let nice = p;
for (const m of [1, 2, 5]) if (m * p <= target) nice = m * p;
const dx = nice / km_per_deg;
const sx = x0 + 0.04 * w, sy = y0 + 0.05 * h, t = 0.012 * h;
bar.data = {xs: [[sx, sx + dx], [sx, sx], [sx + dx, sx + dx]],
            ys: [[sy, sy], [sy - t, sy + t], [sy - t, sy + t]]};
const text = nice >= 1 ? `${+nice.toPrecision(3)} km` : `${Math.round(nice * 1000)} m`;
bar_label.data = {x: [sx + dx / 2], y: [sy + 1.5 * t], text: [text]};
const nx = x1 - 0.05 * w;
north.data = {x_start: [nx], y_start: [y1 - 0.17 * h], x_end: [nx], y_end: [y1 - 0.07 * h]};
north_label.data = {x: [nx], y: [y1 - 0.17 * h], text: ["N"]};
if (wind != null) {
  const d = wind.data, n = (d.to_deg || []).length;
  if (n === 0) {
    wind_arrow.data = {x_start: [], y_start: [], x_end: [], y_end: []};
    wind_label.data = {x: [], y: [], text: []};
  } else {
    // towards `to_deg` (compass), 0.1 of the view's height long, centred below the N arrow
    const a = d.to_deg[0] * Math.PI / 180, L = 0.1 * h, cx = x1 - 0.12 * w, cy = y1 - 0.33 * h;
    const k = Math.cos(lat * Math.PI / 180);
    const ex = 0.5 * L * Math.sin(a) / k, ey = 0.5 * L * Math.cos(a);
    wind_arrow.data = {x_start: [cx - ex], y_start: [cy - ey], x_end: [cx + ex], y_end: [cy + ey]};
    wind_label.data = {x: [cx], y: [cy - 0.09 * h], text: [d.text[0]]};
  }
}
"""


def add_scale_and_north(fig: Any, x_range: Any, y_range: Any, wind: Any = None) -> None:
    """A scale bar (bottom left, km or m) and a north arrow (top right) on a lon/lat map; with
    `wind` (a data source of `to_deg`, compass, and `text`), a wind arrow below the N."""
    from bokeh.models import ColumnDataSource, CustomJS
    from bokeh.models.annotations.arrows import Arrow, NormalHead

    bar = ColumnDataSource({"xs": [], "ys": []})
    bar_label = ColumnDataSource({"x": [], "y": [], "text": []})
    north = ColumnDataSource({"x_start": [], "y_start": [], "x_end": [], "y_end": []})
    north_label = ColumnDataSource({"x": [], "y": [], "text": []})
    fig.multi_line("xs", "ys", source=bar, line_color="white", line_width=6, line_alpha=0.8)
    fig.multi_line("xs", "ys", source=bar, line_color="#1b2733", line_width=2.5)
    fig.text("x", "y", "text", source=bar_label, text_align="center", text_font_size="11px",
             text_color="#1b2733", text_font_style="bold", background_fill_color="white",
             background_fill_alpha=0.6)
    body: dict[str, Any] = {"line_width": 3, "line_color": "#1b2733"}  # (typed as body_*)
    fig.add_layout(Arrow(end=NormalHead(size=14, fill_color="#1b2733", line_color="white"),
                         source=north, x_start="x_start", y_start="y_start", x_end="x_end",
                         y_end="y_end", **body))
    fig.text("x", "y", "text", source=north_label, text_align="center", text_baseline="top",
             text_font_size="13px", text_font_style="bold", text_color="#1b2733",
             background_fill_color="white", background_fill_alpha=0.6)
    wind_arrow = ColumnDataSource({"x_start": [], "y_start": [], "x_end": [], "y_end": []})
    wind_label = ColumnDataSource({"x": [], "y": [], "text": []})
    if wind is not None:
        blue: dict[str, Any] = {"line_width": 4, "line_color": "#0f7c8c"}
        fig.add_layout(Arrow(end=NormalHead(size=16, fill_color="#0f7c8c", line_color="white"),
                             source=wind_arrow, x_start="x_start", y_start="y_start",
                             x_end="x_end", y_end="y_end", **blue))
        fig.text("x", "y", "text", source=wind_label, text_align="center", text_baseline="top",
                 text_font_size="11px", text_font_style="bold", text_color="#0f7c8c",
                 background_fill_color="white", background_fill_alpha=0.7)
    cb = CustomJS(args={"xr": x_range, "yr": y_range, "bar": bar, "bar_label": bar_label,
                        "north": north, "north_label": north_label, "wind": wind,
                        "wind_arrow": wind_arrow, "wind_label": wind_label}, code=_JS)
    if wind is not None:
        wind.js_on_change("data", cb)
    for model in (x_range, y_range):
        model.js_on_change("start", cb)
        model.js_on_change("end", cb)
    fig.js_on_change("inner_width", cb)
    fig.js_on_change("inner_height", cb)
