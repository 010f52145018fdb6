"""The explorer's Bokeh figures: the plane (paths, candidates, draggable poses, wind, partition
map) and the controls along the path, with the data sources the page writes into."""

from __future__ import annotations

import math
from typing import Any, cast

import numpy as np
from bokeh.layouts import column
from bokeh.models import ColumnDataSource, CustomJS, HoverTool, PointDrawTool, Range1d
from bokeh.models.annotations.arrows import Arrow, VeeHead
from bokeh.models.widgets import Div
from bokeh.plotting import figure

from glideplan.explore.solve import View

__all__ = ["PlanFigures"]

BLUE = "#1f5fa8"
START = "#2e8540"
GOAL = "#c0392b"
WIND = "#0f7c8c"
GREY = "#7f8c8d"
POINT_COLUMNS = ("x", "y", "name", "role", "c", "fill", "size")


def empty_points() -> dict[str, list[Any]]:
    return {k: [] for k in POINT_COLUMNS}


def empty_candidates() -> dict[str, list[Any]]:
    return {k: [] for k in ("xs", "ys", "word", "family", "cost", "cost_text", "status", "rank")}


class PlanFigures:
    """The figures and their data sources (one set per page)."""

    def __init__(self) -> None:
        self.x_range, self.y_range = Range1d(start=-1.0, end=1.0), Range1d(start=-1.0, end=1.0)
        fig = figure(
            frame_width=600,
            frame_height=600,
            x_range=self.x_range,
            y_range=self.y_range,
            tools="pan,wheel_zoom,box_zoom,reset,save",
            toolbar_location="above",
            x_axis_label="x",
            y_axis_label="y",
            output_backend="canvas",
        )
        fig.background_fill_color = "#fbfcfe"
        fig.grid.grid_line_color = "#e3e9f0"
        fig.outline_line_color = "#c9d3de"
        self.part_src = ColumnDataSource({"image": [], "x": [], "y": [], "dw": [], "dh": []})
        self.part_labels = ColumnDataSource({"x": [], "y": [], "text": []})
        self.cand_src = ColumnDataSource(empty_candidates())
        self.path_src = ColumnDataSource({"x": [], "y": []})
        self.air_src = ColumnDataSource({"x": [], "y": []})
        self.heading_src = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "c": []})
        # start, goal and their heading handles: one source, so one drag is one change
        self.points_src = ColumnDataSource(empty_points())
        self.labels_src = ColumnDataSource({"x": [], "y": [], "name": [], "c": []})
        self.wind_src = ColumnDataSource({"x_start": [], "y_start": [], "x_end": [], "y_end": []})
        self.wind_label = ColumnDataSource({"x": [], "y": [], "text": []})
        self.part_renderer = fig.image_rgba(
            "image", x="x", y="y", dw="dw", dh="dh", source=self.part_src
        )
        self.part_text = fig.text(
            "x",
            "y",
            "text",
            source=self.part_labels,
            text_align="center",
            text_baseline="middle",
            text_font_size="12px",
            text_color="#2c3e50",
            text_alpha=0.8,
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
        self._legend_items: list[Any] = list(fig.legend.items)
        fig.legend.location = "top_left"
        fig.legend.background_fill_alpha = 0.8
        fig.legend.label_text_font_size = "11px"
        fig.legend.click_policy = "hide"
        self.fig = fig
        # The page's URL follows the state: the server sets the figure's tag, the browser
        # replaces the address (Panel's Location pushes history entries on every drag).
        fig.js_on_change(
            "tags",
            CustomJS(
                code="const q = cb_obj.tags[0]; if (q && window.location.search !== q) "
                "{ window.history.replaceState(null, '', window.location.pathname + q); }"
            ),
        )
        self.prof_src = ColumnDataSource({"t": [], "speed": [], "second": [], "third": []})
        self.speed_fig = self._profile_figure("speed", "speed", BLUE)
        x_range = self.speed_fig.x_range
        self.second_fig = self._profile_figure("second", "turn rate", "#8e44ad", x_range)
        self.third_fig = self._profile_figure("third", "load factor", "#d35400", x_range)
        for f in (self.speed_fig, self.second_fig, self.third_fig):
            f.background_fill_color = "#fbfcfe"
            f.grid.grid_line_color = "#e3e9f0"
        self.profile_col = column(
            Div(text="<b>Controls along the path</b>", styles={"color": "#3b4a59"}),
            self.speed_fig,
            self.second_fig,
            self.third_fig,
        )

    def _profile_figure(
        self, key: str, label: str, color: str, x_range: Any | None = None
    ) -> Any:
        """A small plot of the profile column `key` against time (shared time axis)."""
        extra = {} if x_range is None else {"x_range": x_range}
        fig = figure(
            height=170,
            width=430,
            **extra,
            x_axis_label="time",
            y_axis_label=label,
            tools="save,reset",
            toolbar_location=None,
        )
        fig.line("t", key, source=self.prof_src, line_color=color, line_width=2)
        return fig

    def box(self) -> tuple[float, float, float, float]:
        """The view's data box (x0, x1, y0, y1) in m."""
        r = (self.x_range.start, self.x_range.end, self.y_range.start, self.y_range.end)
        return cast(tuple[float, float, float, float], tuple(float(cast(float, v)) for v in r))

    def set_square(self, lo: np.ndarray, hi: np.ndarray) -> None:
        centre, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo))
        self.x_range.update(start=centre[0] - half, end=centre[0] + half)
        self.y_range.update(start=centre[1] - half, end=centre[1] + half)

    def show(self, view: View, part: dict[str, Any] | None, candidates: bool) -> None:
        """Write a computed view into the sources (paths, candidates, profile, wind, map)."""
        self.path_src.data = {"x": view.path["x"], "y": view.path["y"]}
        air = view.air_path
        self.air_src.data = {"x": air["x"], "y": air["y"]} if air else {"x": [], "y": []}
        self.air_renderer.visible = air is not None
        self.fig.legend.items = [
            it for it in self._legend_items if it.renderers[0] is not self.air_renderer or air
        ]
        cands = view.candidates or empty_candidates()
        self.cand_src.selected.indices = []
        self.cand_src.data = {k: v for k, v in cands.items() if k != "cost"} | {
            "cost": np.asarray(cands["cost"], dtype=float)
        }
        self.cand_renderer.visible = candidates
        self.show_profile(view)
        self.show_wind(view)
        if part is not None:
            self.part_src.data = {k: [part[k]] for k in ("image", "x", "y", "dw", "dh")}
            self.part_labels.data = part["labels"]
        else:
            self.part_src.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
            self.part_labels.data = {"x": [], "y": [], "text": []}

    def show_profile(self, view: View) -> None:
        prof = view.profile
        self.profile_col.visible = prof is not None
        if prof is None:
            self.prof_src.data = {"t": [], "speed": [], "second": [], "third": []}
            return
        third = prof.get("third")
        self.prof_src.data = {
            "t": prof["t"],
            "speed": prof["speed"],
            "second": prof["second"],
            "third": third if third is not None else np.full_like(prof["t"], np.nan),
        }
        self.second_fig.yaxis.axis_label = view.profile_labels[1]
        self.third_fig.visible = third is not None

    def show_wind(self, view: View) -> None:
        if view.wind is None or view.request is None:
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
        direction = math.degrees(math.atan2(wy, wx)) if w > 0 else 0.0
        self.wind_src.data = {"x_start": [x0], "y_start": [y0], "x_end": [x1], "y_end": [y1]}
        self.wind_label.data = {
            "x": [x0],
            "y": [y0 + 0.03 * span],
            "text": [f"wind {w:.3g} m/s towards {direction:.0f} deg"],
        }
