"""The explorer's Bokeh figures: the plane (paths, candidates, draggable poses, wind, partition
map) and the controls along the path, with the data sources the page writes into."""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
from bokeh.models import ColumnDataSource, CustomJS, HoverTool, PointDrawTool, Range1d
from bokeh.models.annotations import Legend, LegendItem
from bokeh.models.annotations.arrows import Arrow, VeeHead
from bokeh.plotting import figure

from glideplan.explore.profile_plots import BLUE, ProfilePlots, sticky_range
from glideplan.explore.solve import View
from glideplan.plotting import wind_label

__all__ = ["ASPECT_JS", "PlanFigures", "columns", "equal_scales", "follow_url", "sticky_range"]

START = "#2e8540"
GOAL = "#c0392b"
WIND = "#0f7c8c"
GREY = "#7f8c8d"
POINT_COLUMNS = ("x", "y", "name", "role", "c", "fill", "size")
# The partition map's words and colours (as `solve._WORD_COLOURS`), for its legend.
PARTITION_WORDS = ("LSL", "LSR", "RSL", "RSR", "RLR", "LRL")

# Equal scales (metres per pixel) in x and y whatever the frame's shape: after a layout or a
# range change, the range with the larger scale grows about its centre until both match, so
# that everything in view stays in view (turn circles stay circles). `k` is the metres per x
# unit over the metres per y unit (1 on the plane; cos(latitude) on a lon/lat map). The view
# then goes into the address as `view=x0,y0,x1,y1` (a link restores the zoom).
ASPECT_JS = """
const w = fig.inner_width, h = fig.inner_height;
if (!(w > 0 && h > 0)) return;
const x0 = xr.start, x1 = xr.end, y0 = yr.start, y1 = yr.end;
const dx = x1 - x0, dy = y1 - y0;
if (!(dx > 0 && dy > 0)) return;
const sx = w / (dx * k), sy = h / dy;
if (Math.abs(sx - sy) > 1e-9 * Math.max(sx, sy)) {
  const s = Math.min(sx, sy), cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
  const hx = 0.5 * w / (s * k), hy = 0.5 * h / s;
  xr.setv({start: cx - hx, end: cx + hx});
  yr.setv({start: cy - hy, end: cy + hy});
  return;  // the change calls this again, which writes the address
}
if (!fig.tags.length) return;
const span = Math.max(dx, dy);
const digits = Math.max(1, Math.ceil(-Math.log10(span)) + 4);
const f = (v) => String(Number(v.toFixed(Math.min(digits, 12))));
const view = [x0, y0, x1, y1].map(f).join(',');
const params = new URLSearchParams(window.location.search);
if (params.get('view') === view) return;
const q = fig.tags[0] ? fig.tags[0].replace(/^[?]/, '') : params.toString();
const next = new URLSearchParams(q);
next.set('view', view);
window.history.replaceState(null, '', window.location.pathname + '?' +
  next.toString().replace(/%2C/g, ','));
"""


def equal_scales(fig: Any, x_range: Any, y_range: Any, k: float = 1.0) -> None:
    """Keep `fig`'s scales equal in the browser (`ASPECT_JS`; `k` metres per x unit over
    metres per y unit) and its view in the address."""
    aspect = CustomJS(args={"fig": fig, "xr": x_range, "yr": y_range, "k": k}, code=ASPECT_JS)
    for model in (x_range, y_range):
        model.js_on_change("start", aspect)
        model.js_on_change("end", aspect)
    fig.js_on_change("inner_width", aspect)
    fig.js_on_change("inner_height", aspect)


URL_JS = """const q = cb_obj.tags[0]; if (!q) return; const p = new URLSearchParams(q);
const v = new URLSearchParams(window.location.search).get('view');
if (v) p.set('view', v); const s = '?' + p.toString().replace(/%2C/g, ',');
if (window.location.search !== s) {
  window.history.replaceState(null, '', window.location.pathname + s); }"""


def follow_url(fig: Any) -> None:
    """The browser's address follows `fig.tags[0]` (a query the server sets), keeping the view
    (history.replaceState: Panel's Location would push a history entry per drag)."""
    fig.js_on_change("tags", CustomJS(code=URL_JS))


def plain_figure(x_range: Any, y_range: Any, x_label: str, y_label: str, **extra: Any) -> Any:
    """The explorer's figure: stretching, pan/zoom tools above, canvas drawn, on the ranges."""
    fig = figure(
        sizing_mode="stretch_both",
        min_width=240,
        min_height=240,
        x_range=x_range,
        y_range=y_range,
        tools="pan,wheel_zoom,box_zoom,reset,save",
        toolbar_location="above",
        x_axis_label=x_label,
        y_axis_label=y_label,
        output_backend="canvas",
        **extra,
    )
    from bokeh.models import WheelZoomTool

    wheel = next(t for t in fig.toolbar.tools if isinstance(t, WheelZoomTool))
    fig.toolbar.active_scroll = wheel  # the wheel zooms at once, no tool to pick first
    return fig


def empty_points() -> dict[str, list[Any]]:
    return {k: [] for k in POINT_COLUMNS}


def empty_candidates() -> dict[str, list[Any]]:
    return {k: [] for k in ("xs", "ys", "word", "family", "cost", "cost_text", "status", "rank")}


def columns(data: dict[str, Any]) -> dict[str, Any]:
    """A data source's columns safe to send: all of one length (else every column emptied),
    an empty NumPy array as an empty list (Bokeh's binary buffer of length 0 makes BokehJS
    throw "RangeError: Offset is outside the bounds of the DataView" on this and every later
    message -- seen after one unreadable Dubins goal)."""
    lengths = {len(v) for v in data.values()}
    if len(lengths) > 1:
        return {k: [] for k in data}
    return {k: [] if isinstance(v, np.ndarray) and v.size == 0 else v for k, v in data.items()}


class PlanFigures(ProfilePlots):
    """The figures and their data sources (one set per page)."""

    def __init__(self) -> None:
        self.x_range, self.y_range = Range1d(start=-1.0, end=1.0), Range1d(start=-1.0, end=1.0)
        fig = plain_figure(self.x_range, self.y_range, "x (m)", "y (m)", match_aspect=True)
        fig.background_fill_color = "#fbfcfe"
        fig.grid.grid_line_color = "#e3e9f0"
        fig.outline_line_color = "#c9d3de"
        self.part_src = ColumnDataSource({"image": [], "x": [], "y": [], "dw": [], "dh": []})
        self.part_labels = ColumnDataSource({"x": [], "y": [], "text": []})
        self.cand_src = ColumnDataSource(empty_candidates())
        self.path_src = ColumnDataSource({"x": [], "y": []}, name="gp-answer")
        self.air_src = ColumnDataSource({"x": [], "y": []})
        self.heading_src = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "c": []})
        # start, goal and their heading handles: one source, so one drag is one change
        self.points_src = ColumnDataSource(empty_points())
        self.labels_src = ColumnDataSource({"x": [], "y": [], "name": [], "c": []})
        self.wind_src = ColumnDataSource({"x_start": [], "y_start": [], "x_end": [], "y_end": []})
        self.wind_label = ColumnDataSource({"x": [], "y": [], "text": []})
        self._add_answer_layers(fig)
        self._add_pose_layers(fig)
        self._add_partition_legend(fig)
        self.fig = fig
        equal_scales(fig, self.x_range, self.y_range)
        # The page's URL follows the state: the server sets the figure's tag, the browser
        # replaces the address (Panel's Location pushes history entries on every drag).
        follow_url(fig)
        self._add_profiles()

    def _add_answer_layers(self, fig: Any) -> None:
        """The partition map, the candidates (with their hover), the air-relative and the
        optimal paths."""
        self.part_renderer = fig.image_rgba(
            "image", x="x", y="y", dw="dw", dh="dh", source=self.part_src
        )
        self.cand_renderer = fig.multi_line(
            "xs",
            "ys",
            source=self.cand_src,
            line_color=GREY,
            line_alpha=0.45,
            line_width=1.3,
            selection_line_color="#e67e22",
            selection_line_alpha=1.0,
            nonselection_line_color=GREY,
            nonselection_line_alpha=0.3,
            legend_label="candidates",
        )
        fig.add_tools(
            HoverTool(
                renderers=[self.cand_renderer],
                tooltips=[("word", "@word"), ("family", "@family"), ("cost", "@cost_text")],
            )
        )
        self.air_renderer = fig.line(
            "x",
            "y",
            source=self.air_src,
            line_color=BLUE,
            line_dash="dashed",
            line_width=2,
            line_alpha=0.7,
            legend_label="air-relative path",
        )
        self.path_renderer = fig.line(
            "x",
            "y",
            source=self.path_src,
            line_color=BLUE,
            line_width=3.5,
            legend_label="optimal path",
        )

    def _add_pose_layers(self, fig: Any) -> None:
        """The heading handles' segments, the wind arrow and its label, the draggable start
        and goal (the drag tool active) with their names, and the legend's style."""
        fig.segment("x0", "y0", "x1", "y1", source=self.heading_src, line_color="c", line_width=2)
        body: dict[str, Any] = {"line_color": WIND, "line_width": 3}  # the stubs lag the runtime
        wind = Arrow(
            end=VeeHead(size=14, fill_color=WIND, line_color=WIND),
            **body,
            source=self.wind_src,
            x_start="x_start",
            y_start="y_start",
            x_end="x_end",
            y_end="y_end",
        )
        fig.add_layout(wind)
        fig.text(
            "x",
            "y",
            "text",
            source=self.wind_label,
            text_color=WIND,
            text_font_size="12px",
            text_baseline="bottom",
        )
        points = fig.scatter(
            "x",
            "y",
            source=self.points_src,
            size="size",
            fill_color="fill",
            line_color="c",
            line_width=2.5,
        )
        fig.text(
            "x",
            "y",
            "name",
            source=self.labels_src,
            x_offset=10,
            y_offset=-8,
            text_font_size="12px",
            text_color="c",
        )
        draw = PointDrawTool(renderers=[cast(Any, points)], add=False, drag=True)
        fig.add_tools(draw)
        fig.toolbar.active_drag = draw
        self.legend = fig.legend[0]
        self._legend_items: list[Any] = list(self.legend.items)
        self.legend.location = "top_left"
        self.legend.background_fill_alpha = 0.8
        self.legend.label_text_font_size = "11px"
        self.legend.click_policy = "hide"

    def _add_partition_legend(self, fig: Any) -> None:
        """The partition map's legend: one coloured square per word (no labels on the map)."""
        from glideplan.explore.solve import _WORD_COLOURS

        swatches = [
            fig.scatter(
                x=[math.nan],  # one point, never drawn: the legend draws its square
                y=[math.nan],
                marker="square",
                size=12,
                fill_color="#{:02x}{:02x}{:02x}".format(*_WORD_COLOURS[w]),
                fill_alpha=0.6,
                line_color=None,
            )
            for w in PARTITION_WORDS
        ]
        self.part_legend = Legend(
            items=[
                LegendItem(label=w, renderers=[cast(Any, r)])
                for w, r in zip(PARTITION_WORDS, swatches, strict=True)
            ],
            location="bottom_right",
            orientation="horizontal",
            title="optimal word (partition map)",
            title_text_font_size="10px",
            label_text_font_size="10px",
            background_fill_alpha=0.8,
            visible=False,
            spacing=4,
        )
        fig.add_layout(self.part_legend)

    def box(self) -> tuple[float, float, float, float]:
        """The view's data box (x0, x1, y0, y1) in m."""
        r = (self.x_range.start, self.x_range.end, self.y_range.start, self.y_range.end)
        return cast(tuple[float, float, float, float], tuple(float(cast(float, v)) for v in r))

    def set_units(self, length: str, speed: str) -> None:
        """Axis labels for lengths in `length` ('m' or 'nondim.') and speeds in `speed`."""
        self.fig.xaxis.axis_label = f"x ({length})"
        self.fig.yaxis.axis_label = f"y ({length})"
        self.speed_fig.yaxis.axis_label = f"speed ({speed})"
        time = "nondim." if length == "nondim." else "s"
        for f in (self.speed_fig, self.second_fig, self.third_fig):
            f.xaxis.axis_label = f"time ({time})"

    def set_box(self, x0: float, y0: float, x1: float, y1: float) -> None:
        """Show the data box (the browser grows one side to equal scales)."""
        self.x_range.update(start=x0, end=x1)
        self.y_range.update(start=y0, end=y1)

    def set_square(self, lo: np.ndarray, hi: np.ndarray) -> None:
        centre, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo))
        self.x_range.update(start=centre[0] - half, end=centre[0] + half)
        self.y_range.update(start=centre[1] - half, end=centre[1] + half)

    def show(self, view: View, part: dict[str, Any] | None, candidates: bool) -> None:
        """Write a computed view into the sources (paths, candidates, profile, wind, map)."""
        self.path_src.data = columns({"x": view.path["x"], "y": view.path["y"]})
        self._mark_verified(view.solution is None or view.ok)
        air = view.air_path
        self.air_src.data = columns({"x": air["x"], "y": air["y"]} if air else {"x": [], "y": []})
        self.air_renderer.visible = air is not None
        items = [it for it in self._legend_items if it.renderers[0] is not self.air_renderer or air]
        if list(self.legend.items) != items:
            self.legend.items = items
        if not view.candidates_pending:
            self.show_candidates(view, candidates)
        self.show_profile(view)
        self.show_wind(view)
        if part is not None:
            self.part_src.data = {k: [part[k]] for k in ("image", "x", "y", "dw", "dh")}
        elif len(self.part_src.data["image"]):
            self.part_src.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
        if self.part_legend.visible != (part is not None):
            self.part_legend.visible = part is not None

    def _mark_verified(self, verified: bool) -> None:
        """The optimal path solid blue, or dashed, muted orange and labelled when the
        re-integration did not confirm it (status not_verified)."""
        glyph = self.path_renderer.glyph
        dash = "solid" if verified else "dashed"
        if getattr(self, "_dash", "solid") != dash:  # change the glyph only when it changes
            self._dash = dash
            glyph.line_dash = dash
            glyph.line_color = BLUE if verified else "#b9770e"
            glyph.line_alpha = 1.0 if verified else 0.75
            label = "optimal path" if verified else "path (not verified)"
            for item in self._legend_items:
                if item.renderers and item.renderers[0] is self.path_renderer:
                    item.label = {"value": label}

    def show_candidates(self, view: View, visible: bool) -> None:
        """Every candidate's line (grey), shown when `visible`."""
        cands = view.candidates or empty_candidates()
        if self.cand_src.selected.indices:
            self.cand_src.selected.indices = []
        # lists, not arrays: the numbers inline in the message's JSON instead of one binary
        # frame pair per line (29 websocket frames per change before), to 6 significant
        # digits of the largest coordinate (sub-pixel; 17 digits made 90 kB per change)
        lines = [np.asarray(a, dtype=float) for k in ("xs", "ys") for a in cands[k]]
        top = max((float(np.abs(a).max()) for a in lines if a.size), default=1.0)
        decimals = max(0, 5 - math.floor(math.log10(top))) if top > 0 else 6
        self.cand_src.data = columns(
            {k: v for k, v in cands.items() if k not in ("xs", "ys", "cost")}
            | {
                k: [np.round(np.asarray(a, dtype=float), decimals).tolist() for a in cands[k]]
                for k in ("xs", "ys")
            }
            | {"cost": [float(c) for c in cands["cost"]]}
        )
        if self.cand_renderer.visible != visible:
            self.cand_renderer.visible = visible

    def show_wind(self, view: View) -> None:
        if view.wind is None or view.request is None:
            if len(self.wind_src.data["x_start"]):
                self.wind_src.data = {"x_start": [], "y_start": [], "x_end": [], "y_end": []}
                self.wind_label.data = {"x": [], "y": [], "text": []}
            return
        wx, wy = view.wind
        w = math.hypot(wx, wy)
        bx0, bx1, _, by1 = self.box()
        span = bx1 - bx0
        x0 = bx1 - 0.3 * span
        y0 = by1 - 0.12 * span
        if w > 0:
            length = 0.1 * span * w / max(view.request.vehicle.speed, w)
            x1, y1 = x0 + length * wx / w, y0 + length * wy / w
        else:
            x1, y1 = x0, y0
        arrow = {"x_start": [x0], "y_start": [y0], "x_end": [x1], "y_end": [y1]}
        if dict(self.wind_src.data) == arrow:
            return  # the same wind in the same view
        self.wind_src.data = arrow
        self.wind_label.data = {
            "x": [x0],
            "y": [y0 + 0.03 * span],
            "text": [wind_label((wx, wy))],  # compass FROM: the page's edge
        }
