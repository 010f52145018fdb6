"""The explorer page: Panel widgets around a Bokeh figure, one `Explorer` per browser session.

The figure's start and goal are dragged with Bokeh's `PointDrawTool` (a second draggable point
per pose sets its heading); every change goes into an `ExploreState`, the URL query follows it,
and the state is planned by `solve_view` on a worker thread (latest state wins), so a slow
planner never blocks the page. The result is applied to the Bokeh data sources on the
document's own thread. Imported only by `glideplan explore` (Panel and Bokeh are heavy).
"""

from __future__ import annotations

import html
import io
import math
import threading
from collections.abc import Callable
from dataclasses import replace
from typing import Any, cast

import numpy as np
import panel as pn
from bokeh.events import Pan, PanEnd, PanStart
from bokeh.models import ColumnDataSource, CustomJS, HoverTool, PointDrawTool, Range1d
from bokeh.models.annotations.arrows import Arrow, VeeHead
from bokeh.plotting import figure

from glideplan.explore.catalog import Catalog, PlannerEntry, build_catalog, planner_key
from glideplan.explore.downloads import path_csv, solution_json, solution_png
from glideplan.explore.solve import View, partition_image, solve_view
from glideplan.explore.state import (
    ExploreState,
    format_pose,
    initial_state,
    parse_pose_text,
    state_from_query,
    state_to_query,
)

__all__ = ["Explorer", "create_page"]

BLUE = "#1f5fa8"
START = "#2e8540"
GOAL = "#c0392b"
WIND = "#0f7c8c"
GREY = "#7f8c8d"

PAGE_CSS = """
:host { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; }
.gp-strip { display: flex; flex-wrap: wrap; gap: 6px 22px; align-items: baseline;
  padding: 8px 12px; background: #f4f7fb; border: 1px solid #d6e0ec; border-radius: 6px; }
.gp-item { display: flex; flex-direction: column; }
.gp-item .gp-k { font-size: 11px; color: #5b6b7b; text-transform: uppercase;
  letter-spacing: .04em; }
.gp-item .gp-v { font-size: 17px; color: #1b2733; font-variant-numeric: tabular-nums; }
.gp-cost, .gp-word { font-weight: 600; }
.gp-small { font-size: 13px !important; color: #3b4a59 !important; }
.gp-status-bad { color: #b03a2e !important; }
.gp-error { color: #b03a2e; font-size: 12.5px; line-height: 1.3; margin: -2px 0 4px 2px; }
.gp-busy { color: #1f5fa8; font-size: 13px; font-weight: 600; }
.gp-busy::before { content: ""; display: inline-block; width: 10px; height: 10px;
  margin-right: 6px; border: 2px solid #1f5fa8; border-right-color: transparent;
  border-radius: 50%; animation: gp-spin .8s linear infinite; vertical-align: -1px; }
@keyframes gp-spin { to { transform: rotate(360deg); } }
.gp-table-wrap { max-height: 260px; overflow-y: auto; border: 1px solid #d6e0ec;
  border-radius: 6px; }
.gp-table { border-collapse: collapse; width: 100%; font-size: 13px;
  font-variant-numeric: tabular-nums; }
.gp-table th { position: sticky; top: 0; background: #eef3f9; text-align: left;
  padding: 4px 8px; color: #3b4a59; }
.gp-table td { padding: 3px 8px; border-top: 1px solid #edf1f6; }
.gp-table tr.gp-opt td { background: #e4efff; font-weight: 600; color: #1f5fa8; }
.gp-help { font-size: 12px; color: #5b6b7b; line-height: 1.35; }
.gp-title { font-size: 20px; font-weight: 650; color: #fff; }
.gp-sub { font-size: 12.5px; color: #d8e4f2; }
"""


def _html(text: str = "", **kw: Any) -> pn.pane.HTML:
    return pn.pane.HTML(text, stylesheets=[PAGE_CSS], margin=(0, 5), **kw)


def _error_html(message: str) -> str:
    return f'<div class="gp-error">{html.escape(message)}</div>' if message else ""


class Explorer:
    """One page: widgets, figures and the state they show (see the module docstring).

    `sync=True` plans in the calling thread and applies at once (benchmarks and tests
    without a browser); otherwise planning runs on a worker thread.
    """

    def __init__(
        self,
        catalog: Catalog | None = None,
        query: str | dict[str, str] | None = None,
        *,
        sync: bool = False,
    ) -> None:
        self.catalog = catalog or build_catalog()
        self.state = state_from_query(self.catalog, query or {})
        asked = (query or {}).get("planner") if isinstance(query, dict) else None
        self._planner_note = (
            f"planner={asked!r}: must be one of {', '.join(self.catalog.keys)}"
            if asked
            and asked not in self.catalog.keys
            and planner_key(asked) != self.state.planner.split("/")[0]
            else ""
        )
        self.view: View | None = None
        self.sync = sync
        self._doc = pn.state.curdoc if not sync else None
        self._lock = threading.Lock()
        self._pending: ExploreState | None = None
        self._running = False
        self._syncing = False
        self._errors: dict[str, str] = {}
        self._drawn: dict[tuple[str, str], tuple[float, float]] = {}
        self._dragging: tuple[str, str, float, float] | None = None
        self._partition_cache: tuple[Any, dict[str, Any] | None] | None = None
        self._build_figures()
        self._build_widgets()
        self._set_planner_inputs()
        self._reset_ranges()
        self._draw_poses()
        self.layout = self._layout()
        self.solve()

    # ----- figures ----------------------------------------------------------------------------
    def _build_figures(self) -> None:
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
        self.cand_src = ColumnDataSource(_empty_candidates())
        self.path_src = ColumnDataSource({"x": [], "y": []})
        self.air_src = ColumnDataSource({"x": [], "y": []})
        self.heading_src = ColumnDataSource({"x0": [], "y0": [], "x1": [], "y1": [], "c": []})
        # start, goal and their heading handles: one source, so one drag is one change
        self.points_src = ColumnDataSource(_empty_points())
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
        self.points_src.on_change("data", self._on_points)
        # live re-planning while a point is dragged (the drop then commits it)
        fig.on_event(PanStart, self._on_pan_start)
        fig.on_event(Pan, self._on_pan)
        fig.on_event(PanEnd, self._on_pan_end)

        self.prof_src = ColumnDataSource({"t": [], "speed": [], "second": [], "third": []})
        self.speed_fig = figure(
            height=170,
            width=430,
            x_axis_label="time",
            y_axis_label="speed",
            tools="save,reset",
            toolbar_location=None,
        )
        self.speed_fig.line("t", "speed", source=self.prof_src, line_color=BLUE, line_width=2)
        self.second_fig = figure(
            height=170,
            width=430,
            x_range=self.speed_fig.x_range,
            x_axis_label="time",
            y_axis_label="turn rate",
            tools="save,reset",
            toolbar_location=None,
        )
        self.second_fig.line(
            "t", "second", source=self.prof_src, line_color="#8e44ad", line_width=2
        )
        self.third_fig = figure(
            height=170,
            width=430,
            x_range=self.speed_fig.x_range,
            x_axis_label="time",
            y_axis_label="load factor",
            tools="save,reset",
            toolbar_location=None,
        )
        self.third_fig.line("t", "third", source=self.prof_src, line_color="#d35400", line_width=2)
        for f in (self.speed_fig, self.second_fig, self.third_fig):
            f.background_fill_color = "#fbfcfe"
            f.grid.grid_line_color = "#e3e9f0"

    # ----- widgets ----------------------------------------------------------------------------
    def _build_widgets(self) -> None:
        options = {e.label: e.key for e in self.catalog.entries}
        self.planner_select = pn.widgets.Select(
            label="Planner", options=options, value=self.state.planner, width=290
        )
        self.planner_select.param.watch(self._on_planner, "value")
        self.planner_help = _html(width=290)
        self.pose_inputs: dict[str, pn.widgets.TextInput] = {}
        self.error_panes: dict[str, pn.pane.HTML] = {}
        for name in ("start", "goal"):
            w = pn.widgets.TextInput(
                label=f"{name} (x, y, heading deg)",
                value=getattr(self.state, name),
                width=290,
                css_classes=[f"gp-input-{name}"],
            )
            w.param.watch(self._make_pose_watcher(name), "value")
            self.pose_inputs[name] = w
            self.error_panes[name] = _html(width=290)
        self.vehicle_box = pn.Column(margin=0)
        self.option_box = pn.Column(margin=0)
        self.options_card = pn.Card(
            self.option_box, title="Planner options", collapsed=True, width=300, margin=(5, 5)
        )
        self.candidates_toggle = pn.widgets.Checkbox(
            label="show every candidate", value=self.state.candidates
        )
        self.candidates_toggle.param.watch(self._on_flags, "value")
        self.partition_toggle = pn.widgets.Checkbox(
            label="partition map background (Fig 3.1)", value=self.state.partition
        )
        self.partition_toggle.param.watch(self._on_flags, "value")
        self.general_error = _html(width=290)
        self.table = _html(width=440)
        self.strip = _html(sizing_mode="stretch_width")
        self.busy = _html(width=200, height=24)
        self.downloads = pn.Row(
            pn.widgets.FileDownload(
                callback=self._json_file,
                filename="glideplan-solution.json",
                label="JSON",
                color="primary",
                width=92,
                embed=False,
            ),
            pn.widgets.FileDownload(
                callback=self._csv_file,
                filename="glideplan-path.csv",
                label="CSV",
                color="primary",
                width=92,
                embed=False,
            ),
            pn.widgets.FileDownload(
                callback=self._png_file,
                filename="glideplan-figure.png",
                label="PNG",
                color="primary",
                width=92,
                embed=False,
            ),
            margin=(5, 0),
        )

    def _set_planner_inputs(self) -> None:
        entry = self.entry
        self.planner_help.object = (
            f'<div class="gp-help">{html.escape(entry.spec.description)}<br>'
            f"<i>{html.escape(entry.help)}</i></div>"
        )
        self.param_inputs: dict[str, pn.widgets.TextInput] = {}
        vehicle: list[Any] = []
        option: list[Any] = []
        for p in entry.parameters:
            hint = ""
            if p.kind == "group":
                items = [
                    f.rpartition(".")[2] + (" deg" if u == "deg" else "")
                    for f, u in zip(p.fields, p.units, strict=True)
                ]
                hint = f" ({', '.join(items)})"
            w = pn.widgets.TextInput(
                label=f"{p.label}{hint}",
                value=self.state.values.get(p.name, p.default),
                width=290 if p.target == "vehicle" else 270,
                css_classes=[f"gp-input-{p.name}"],
            )
            w.param.watch(self._make_value_watcher(p.name), "value")
            self.param_inputs[p.name] = w
            self.error_panes[p.name] = _html(width=290)
            (vehicle if p.target == "vehicle" else option).extend([w, self.error_panes[p.name]])
        self.vehicle_box.objects = vehicle
        self.option_box.objects = option or [_html('<span class="gp-help">none</span>')]
        self.partition_toggle.visible = hasattr(
            entry.default_vehicle, "turn_radius"
        ) and not hasattr(entry.default_vehicle, "wind")

    def _layout(self) -> pn.viewable.Viewable:
        header = pn.Row(
            _html(
                '<div class="gp-title">glideplan explore</div>'
                '<div class="gp-sub">Drag the start and goal (and the open handles to turn '
                "them); optimal paths in gliding flight (Wolek 2015)</div>"
            ),
            styles={"background": "#1f3b5c", "border-radius": "6px"},
            sizing_mode="stretch_width",
            margin=(5, 5, 10, 5),
        )
        sidebar = pn.Column(
            self.planner_select,
            self.planner_help,
            self.pose_inputs["start"],
            self.error_panes["start"],
            self.pose_inputs["goal"],
            self.error_panes["goal"],
            self.vehicle_box,
            self.options_card,
            self.candidates_toggle,
            self.partition_toggle,
            self.general_error,
            _html(
                '<div class="gp-help">Download the solution (as <code>plan --json</code>), '
                "the path, the figure</div>"
            ),
            self.downloads,
            width=320,
        )
        from bokeh.layouts import column
        from bokeh.models.widgets import Div

        self.profile_title = Div(text="<b>Controls along the path</b>", styles={"color": "#3b4a59"})
        self.profile_col = column(
            self.profile_title, self.speed_fig, self.second_fig, self.third_fig
        )
        self.plot_pane = pn.pane.Bokeh(self.fig)
        right = pn.Column(self.table, pn.pane.Bokeh(self.profile_col), width=450)
        main = pn.Column(
            pn.Row(self.strip, self.busy, sizing_mode="stretch_width"),
            pn.Row(self.plot_pane, right),
        )
        return pn.Column(header, pn.Row(sidebar, main), sizing_mode="stretch_width")

    # ----- state ------------------------------------------------------------------------------
    @property
    def entry(self) -> PlannerEntry:
        return self.catalog.get(self.state.planner)

    def set_state(self, state: ExploreState) -> None:
        """Show `state`: update the URL and the poses, and plan it."""
        self.state = state
        if self._dragging is None:  # the browser is moving the point itself
            self._draw_poses()
        self._push_url()
        self.solve()

    def set_goal(self, x: float, y: float, heading_deg: float | None = None) -> None:
        """Move the goal (m) as a drag does; the heading (deg) is kept unless given."""
        self._move_pose("goal", x, y, heading_deg)

    def _push_url(self) -> None:
        """Put the state's query in the browser's address (history.replaceState, no reload)."""
        self.fig.tags = ["?" + state_to_query(self.catalog, self.state)]

    def _on_planner(self, event: Any) -> None:
        if event.new != self.state.planner:
            self._locked(lambda: self._switch_planner(event.new))

    def _locked(self, fn: Callable[[], None]) -> None:
        """Run `fn` holding the document's lock (Panel's widget callbacks do not hold it,
        and Bokeh models may only change under it)."""
        if self._doc is None:
            fn()
        else:
            self._doc.add_next_tick_callback(fn)

    def _switch_planner(self, key: str) -> None:
        entry = self.catalog.get(key)
        self._planner_note = ""
        self.state = initial_state(entry)
        self._set_inputs_from_state()
        self._set_planner_inputs()
        self._reset_ranges()
        self.set_state(self.state)

    def _set_inputs_from_state(self) -> None:
        self._syncing = True
        try:
            for name, w in self.pose_inputs.items():
                w.value = getattr(self.state, name)
        finally:
            self._syncing = False

    def _make_pose_watcher(self, name: str) -> Callable[[Any], None]:
        def watch(event: Any) -> None:
            if not self._syncing:
                self._locked(lambda: self.set_state(_with_pose(self.state, name, event.new)))

        return watch

    def _make_value_watcher(self, name: str) -> Callable[[Any], None]:
        def watch(event: Any) -> None:
            if not self._syncing:
                self._locked(lambda: self.set_state(self.state.with_values(**{name: event.new})))

        return watch

    def _on_flags(self, event: Any) -> None:
        self._locked(
            lambda: self.set_state(
                replace(
                    self.state,
                    candidates=self.candidates_toggle.value,
                    partition=self.partition_toggle.value,
                )
            )
        )

    # ----- dragging ---------------------------------------------------------------------------
    def _poses(self) -> dict[str, tuple[float, float, float] | None]:
        out: dict[str, tuple[float, float, float] | None] = {}
        for name in ("start", "goal"):
            try:
                p = parse_pose_text(getattr(self.state, name), name)
                out[name] = (p.x, p.y, p.heading)
            except ValueError:
                out[name] = None
        return out

    def _box(self) -> tuple[float, float, float, float]:
        """The view's data box (x0, x1, y0, y1) in m."""
        r = (self.x_range.start, self.x_range.end, self.y_range.start, self.y_range.end)
        return cast(tuple[float, float, float, float], tuple(float(cast(float, v)) for v in r))

    def _handle_length(self) -> float:
        x0, x1, _, _ = self._box()
        return 0.12 * (x1 - x0)

    def _draw_poses(self) -> None:
        poses = self._poses()
        h = self._handle_length()
        pts = _empty_points()
        labels: dict[str, list[Any]] = {"x": [], "y": [], "name": [], "c": []}
        seg: dict[str, list[Any]] = {"x0": [], "y0": [], "x1": [], "y1": [], "c": []}
        for name, colour in (("start", START), ("goal", GOAL)):
            p = poses[name]
            if p is None:
                continue
            hx, hy = p[0] + h * math.cos(p[2]), p[1] + h * math.sin(p[2])
            for row in (
                (p[0], p[1], name, "pose", colour, colour, 15),
                (hx, hy, name, "handle", colour, "white", 11),
            ):
                for k, v in zip(_POINT_COLUMNS, row, strict=True):
                    pts[k].append(v)
            for k, v in zip(("x", "y", "name", "c"), (p[0], p[1], name, colour), strict=True):
                labels[k].append(v)
            for k, v in zip(
                ("x0", "y0", "x1", "y1", "c"), (p[0], p[1], hx, hy, colour), strict=True
            ):
                seg[k].append(v)
        self._drawn = {
            (n, r): (x, y)
            for x, y, n, r in zip(pts["x"], pts["y"], pts["name"], pts["role"], strict=True)
        }
        self._syncing = True
        try:
            self.points_src.data = pts
            self.labels_src.data = labels
            self.heading_src.data = seg
        finally:
            self._syncing = False

    def _snap(self, v: float) -> float:
        q = 10.0 ** math.floor(math.log10(max(self.entry.length_scale, 1e-12))) * 1e-3
        return float(f"{round(v / q) * q:.10g}")

    def _on_pan_start(self, event: Any) -> None:
        """Which point a drag holds: the drawn point nearest the pointer (within 3% of the view)."""
        x0, x1, _, _ = self._box()
        best = min(
            self._drawn.items(),
            key=lambda kv: math.dist(kv[1], (event.x, event.y)),
            default=None,
        )
        if best is not None and math.dist(best[1], (event.x, event.y)) <= 0.03 * (x1 - x0):
            (name, role), (px, py) = best
            self._dragging = (name, role, px - event.x, py - event.y)

    def _on_pan(self, event: Any) -> None:
        if self._dragging is None:
            return
        name, role, dx, dy = self._dragging
        self._drag_to(name, role, event.x + dx, event.y + dy)

    def _on_pan_end(self, event: Any) -> None:
        self._dragging = None

    def _drag_to(self, name: str, role: str, x: float, y: float) -> None:
        p = self._poses()[name]
        if role == "pose" or p is None:
            self._move_pose(name, x, y, None)
        else:
            self._move_pose(name, p[0], p[1], math.degrees(math.atan2(y - p[1], x - p[0])))

    def _move_pose(self, name: str, x: float, y: float, heading_deg: float | None) -> None:
        old = self._poses()[name]
        if heading_deg is None:
            heading_deg = math.degrees(old[2]) if old is not None else 0.0
        text = format_pose(self._snap(x), self._snap(y), round(heading_deg, 2))
        self._syncing = True
        try:
            self.pose_inputs[name].value = text
        finally:
            self._syncing = False
        self.set_state(_with_pose(self.state, name, text))

    def _on_points(self, attr: str, old: Any, new: Any) -> None:
        """A drag ended: a moved pose keeps its heading, a moved handle turns its pose."""
        if self._syncing:
            return
        if self._dragging is not None:
            # the drop: live updates moved the state, but the browser's points are the truth
            self._dragging = None
        rows = zip(
            new.get("x", []),
            new.get("y", []),
            new.get("name", []),
            new.get("role", []),
            strict=False,
        )
        moved = [
            (n, r, float(x), float(y))
            for x, y, n, r in rows
            if (n, r) in self._drawn and math.dist((x, y), self._drawn[(n, r)]) > 1e-12
        ]
        if len(new.get("x", [])) != len(self._drawn) or not moved:
            self._draw_poses()  # a deleted point comes back
            return
        name, role, x, y = next((m for m in moved if m[1] == "pose"), moved[0])
        self._drag_to(name, role, x, y)

    # ----- solving ----------------------------------------------------------------------------
    def solve(self) -> None:
        """Plan the current state (on the worker thread unless `sync`)."""
        if self.sync:
            self._apply(*self._compute(self.state))
            return
        with self._lock:
            self._pending = self.state
            start = not self._running
            self._running = True
        self._show_busy(True)
        if start:
            threading.Thread(target=self._work, daemon=True, name="glideplan-explore").start()

    def _work(self) -> None:
        while True:
            with self._lock:
                state, self._pending = self._pending, None
                if state is None:
                    self._running = False
                    return
            try:
                result = self._compute(state)
            except Exception as exc:  # a bug: show it on the page rather than lose the thread
                result = (View(state, None, {"": f"internal error: {exc!r}"}), None)
            with self._lock:
                latest = self._pending is None
            if latest:
                self._schedule(lambda r=result: self._apply(*r))  # type: ignore[misc]

    def _schedule(self, fn: Callable[[], None]) -> None:
        if self._doc is None:
            fn()
        else:
            self._doc.add_next_tick_callback(fn)

    def _compute(self, state: ExploreState) -> tuple[View, dict[str, Any] | None]:
        view = solve_view(self.catalog, state)
        part = None
        if state.partition and view.request is not None:
            req = view.request
            # the map depends on the start, the goal's heading, the vehicle, eps and the view
            key = (
                req.start,
                req.goal.heading,
                req.vehicle,
                tuple(req.options.items()),
                self._bounds_for(view),
            )
            cached = self._partition_cache
            if cached is None or cached[0] != key:
                cached = (key, partition_image(req, key[-1]))
                self._partition_cache = cached
            part = cached[1]
        return view, part

    def _bounds_for(self, view: View) -> tuple[float, float, float, float]:
        return self._box()

    def _show_busy(self, busy: bool) -> None:
        text = '<span class="gp-busy">computing&hellip;</span>' if busy else ""
        self.busy.object = text
        if self.entry.slow:
            self.plot_pane.loading = busy if hasattr(self, "plot_pane") else False

    def _apply(self, view: View, part: dict[str, Any] | None) -> None:
        """Put a computed view into the figure's data sources and the text panes."""
        if view.state != self.state:
            return  # stale: a newer state is being planned
        self.view = view
        self._errors = dict(view.errors)
        for name, pane in self.error_panes.items():
            pane.object = _error_html(view.errors.get(name, ""))
        unowned = {k: v for k, v in view.errors.items() if k not in self.error_panes}
        if self._planner_note:
            unowned = {"planner": self._planner_note, **unowned}
        self.general_error.object = "".join(_error_html(v) for v in unowned.values())
        self.strip.object = self._strip_html(view)
        self.path_src.data = {"x": view.path["x"], "y": view.path["y"]}
        air = view.air_path
        self.air_src.data = {"x": air["x"], "y": air["y"]} if air else {"x": [], "y": []}
        self.air_renderer.visible = air is not None
        self.fig.legend.items = [
            it for it in self._legend_items if it.renderers[0] is not self.air_renderer or air
        ]
        cands = view.candidates or _empty_candidates()
        self.cand_src.selected.indices = []
        self.cand_src.data = {k: v for k, v in cands.items() if k != "cost"} | {
            "cost": np.asarray(cands["cost"], dtype=float)
        }
        self.table.object = _table_html(cands)
        self.cand_renderer.visible = self.state.candidates
        self._apply_profile(view)
        self._apply_wind(view)
        if part is not None:
            self.part_src.data = {k: [part[k]] for k in ("image", "x", "y", "dw", "dh")}
            self.part_labels.data = part["labels"]
        else:
            self.part_src.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
            self.part_labels.data = {"x": [], "y": [], "text": []}
        if self._dragging is None:
            self._expand_ranges(view)
        self._show_busy(False)

    def _apply_profile(self, view: View) -> None:
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

    def _apply_wind(self, view: View) -> None:
        if view.wind is None or view.request is None:
            self.wind_src.data = {"x_start": [], "y_start": [], "x_end": [], "y_end": []}
            self.wind_label.data = {"x": [], "y": [], "text": []}
            return
        wx, wy = view.wind
        w = math.hypot(wx, wy)
        bx0, bx1, _, by1 = self._box()
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

    def _strip_html(self, view: View) -> str:
        unit = (
            {"length": "m", "time": "s", "altitude": "m"}.get(view.entry.objective, "")
            if view.entry
            else ""
        )
        if not view.units and view.entry is not None and view.entry.objective != "time":
            unit = "(nondim.)"
        objective = view.entry.objective if view.entry else ""
        status = html.escape(view.status or "")
        bad = "" if view.ok else " gp-status-bad"

        def item(k: str, v: str, cls: str = "") -> str:
            return (
                f'<div class="gp-item"><span class="gp-k">{k}</span>'
                f'<span class="gp-v {cls}">{v}</span></div>'
            )

        return (
            '<div class="gp-strip">'
            + item(f"cost ({objective}, {unit})", html.escape(view.cost_text), "gp-cost")
            + item("word", html.escape(view.word) or "&ndash;", "gp-word")
            + item("family", html.escape(view.family) or "&ndash;", "gp-family")
            + item("status", status, "gp-small gp-status" + bad)
            + item("endpoint error", html.escape(view.endpoint_text), "gp-small gp-endpoint")
            + item("time", html.escape(view.time_text), "gp-small gp-time")
            + "</div>"
        )

    # ----- view range -------------------------------------------------------------------------
    def _points(self) -> np.ndarray:
        pts = [p[:2] for p in self._poses().values() if p is not None]
        return np.array(pts, dtype=float).reshape(-1, 2)

    def _reset_ranges(self) -> None:
        """A square view around the start and goal with room for turns."""
        pts = self._points()
        scale = self.entry.length_scale
        if pts.size == 0:
            pts = np.zeros((1, 2))
        lo, hi = pts.min(axis=0) - 3.0 * scale, pts.max(axis=0) + 3.0 * scale
        self._set_square(lo, hi)

    def _set_square(self, lo: np.ndarray, hi: np.ndarray) -> None:
        centre, half = 0.5 * (lo + hi), 0.5 * float(np.max(hi - lo))
        self.x_range.update(start=centre[0] - half, end=centre[0] + half)
        self.y_range.update(start=centre[1] - half, end=centre[1] + half)

    def _expand_ranges(self, view: View) -> None:
        xs, ys = view.path["x"], view.path["y"]
        if len(xs) == 0:
            return
        bx0, bx1, by0, by1 = self._box()
        lo = np.array([min(xs.min(), bx0), min(ys.min(), by0)])
        hi = np.array([max(xs.max(), bx1), max(ys.max(), by1)])
        inside = xs.min() >= bx0 and xs.max() <= bx1 and ys.min() >= by0 and ys.max() <= by1
        if not inside:
            pad = 0.08 * float(np.max(hi - lo))
            self._set_square(lo - pad, hi + pad)
            self._draw_poses()

    # ----- downloads --------------------------------------------------------------------------
    def _json_file(self) -> io.StringIO:
        return io.StringIO(solution_json(self.view.solution if self.view else None))

    def _csv_file(self) -> io.StringIO:
        return io.StringIO(path_csv(self.view.solution if self.view else None))

    def _png_file(self) -> io.BytesIO:
        return io.BytesIO(solution_png(self.view.solution if self.view else None))


def _table_html(cands: dict[str, list[Any]]) -> str:
    """The candidates table: rank, word, family, cost and status (optimal first)."""
    rows = []
    for i in range(len(cands["word"])):
        cls = ' class="gp-opt"' if cands["status"][i] == "optimal" else ""
        cells = (
            cands["rank"][i],
            cands["word"][i],
            cands["family"][i],
            cands["cost_text"][i] or "&ndash;",
            cands["status"][i],
        )
        rows.append(
            f"<tr{cls}>"
            + "".join(f"<td>{html.escape(str(c)) if c != '&ndash;' else c}</td>" for c in cells)
            + "</tr>"
        )
    head = "".join(f"<th>{h}</th>" for h in ("#", "word", "family", "cost", "status"))
    return (
        '<div class="gp-help"><b>Candidates</b> (hover a grey path for its word and cost)</div>'
        f'<div class="gp-table-wrap"><table class="gp-table"><thead><tr>{head}</tr></thead>'
        f"<tbody>{''.join(rows)}</tbody></table></div>"
    )


def _with_pose(state: ExploreState, name: str, text: str) -> ExploreState:
    return replace(state, start=text) if name == "start" else replace(state, goal=text)


_POINT_COLUMNS = ("x", "y", "name", "role", "c", "fill", "size")


def _empty_points() -> dict[str, list[Any]]:
    return {k: [] for k in _POINT_COLUMNS}


def _empty_candidates() -> dict[str, list[Any]]:
    return {k: [] for k in ("xs", "ys", "word", "family", "cost", "cost_text", "status", "rank")}


def create_page(catalog: Catalog | None = None) -> pn.viewable.Viewable:
    """The page of one session, its state read from the URL query."""
    args = pn.state.session_args or {}
    query = {
        k: v[0].decode() if isinstance(v[0], bytes) else str(v[0]) for k, v in args.items() if v
    }
    explorer = Explorer(catalog, query)
    pn.state.onload(explorer._push_url)
    return explorer.layout
