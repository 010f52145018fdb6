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
from typing import Any

import numpy as np
import panel as pn
from bokeh.events import Pan, PanEnd, PanStart

from glideplan.explore.catalog import Catalog, PlannerEntry, build_catalog, planner_key
from glideplan.explore.downloads import path_csv, solution_json, solution_png
from glideplan.explore.figures import (
    GOAL,
    POINT_COLUMNS,
    START,
    PlanFigures,
    empty_candidates,
    empty_points,
)
from glideplan.explore.solve import View, partition_image, solve_view
from glideplan.explore.state import (
    ExploreState,
    format_pose,
    initial_state,
    parse_pose_text,
    state_from_query,
    state_to_query,
)
from glideplan.explore.texts import error_html, html_pane, strip_html, table_html

__all__ = ["Explorer", "create_page"]


def _download_button(callback: Callable[[], Any], filename: str, label: str) -> Any:
    """A download button that builds the file `filename` on click (not embedded in the page)."""
    return pn.widgets.FileDownload(
        callback=callback, filename=filename, label=label, color="primary", width=92, embed=False
    )


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
        self.figs = PlanFigures()
        self._hook_figures()
        self._build_widgets()
        self._set_planner_inputs()
        self._reset_ranges()
        self._draw_poses()
        self.layout = self._layout()
        self.solve()

    # ----- figures ----------------------------------------------------------------------------
    def _hook_figures(self) -> None:
        fig = self.figs.fig
        self.figs.points_src.on_change("data", self._on_points)
        # live re-planning while a point is dragged (the drop then commits it)
        fig.on_event(PanStart, self._on_pan_start)
        fig.on_event(Pan, self._on_pan)
        fig.on_event(PanEnd, self._on_pan_end)

    # ----- widgets ----------------------------------------------------------------------------
    def _build_widgets(self) -> None:
        options = {e.label: e.key for e in self.catalog.entries}
        self.planner_select = pn.widgets.Select(
            label="Planner", options=options, value=self.state.planner, width=290
        )
        self.planner_select.param.watch(self._on_planner, "value")
        self.planner_help = html_pane(width=290)
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
            self.error_panes[name] = html_pane(width=290)
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
        self.general_error = html_pane(width=290)
        self.table = html_pane(width=440)
        self.strip = html_pane(sizing_mode="stretch_width")
        self.busy = html_pane(width=200, height=24)
        self.downloads = pn.Row(
            _download_button(self._json_file, "glideplan-solution.json", "JSON"),
            _download_button(self._csv_file, "glideplan-path.csv", "CSV"),
            _download_button(self._png_file, "glideplan-figure.png", "PNG"),
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
            self.error_panes[p.name] = html_pane(width=290)
            (vehicle if p.target == "vehicle" else option).extend([w, self.error_panes[p.name]])
        self.vehicle_box.objects = vehicle
        self.option_box.objects = option or [html_pane('<span class="gp-help">none</span>')]
        self.partition_toggle.visible = hasattr(
            entry.default_vehicle, "turn_radius"
        ) and not hasattr(entry.default_vehicle, "wind")

    def _layout(self) -> pn.viewable.Viewable:
        header = pn.Row(
            html_pane(
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
            html_pane(
                '<div class="gp-help">Download the solution (as <code>plan --json</code>), '
                "the path, the figure</div>"
            ),
            self.downloads,
            width=320,
        )
        self.plot_pane = pn.pane.Bokeh(self.figs.fig)
        right = pn.Column(self.table, pn.pane.Bokeh(self.figs.profile_col), width=450)
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
        self.figs.fig.tags = ["?" + state_to_query(self.catalog, self.state)]

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

    def _handle_length(self) -> float:
        x0, x1, _, _ = self.figs.box()
        return 0.12 * (x1 - x0)

    def _draw_poses(self) -> None:
        poses = self._poses()
        h = self._handle_length()
        pts = empty_points()
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
                for k, v in zip(POINT_COLUMNS, row, strict=True):
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
            self.figs.points_src.data = pts
            self.figs.labels_src.data = labels
            self.figs.heading_src.data = seg
        finally:
            self._syncing = False

    def _snap(self, v: float) -> float:
        q = 10.0 ** math.floor(math.log10(max(self.entry.length_scale, 1e-12))) * 1e-3
        return float(f"{round(v / q) * q:.10g}")

    def _on_pan_start(self, event: Any) -> None:
        """Which point a drag holds: the drawn point nearest the pointer (within 3% of the view)."""
        x0, x1, _, _ = self.figs.box()
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
        return self.figs.box()

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
            pane.object = error_html(view.errors.get(name, ""))
        unowned = {k: v for k, v in view.errors.items() if k not in self.error_panes}
        if self._planner_note:
            unowned = {"planner": self._planner_note, **unowned}
        self.general_error.object = "".join(error_html(v) for v in unowned.values())
        self.strip.object = strip_html(view)
        self.figs.show(view, part, self.state.candidates)
        self.table.object = table_html(view.candidates or empty_candidates())
        if self._dragging is None:
            self._expand_ranges(view)
        self._show_busy(False)

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
        self.figs.set_square(lo, hi)

    def _expand_ranges(self, view: View) -> None:
        xs, ys = view.path["x"], view.path["y"]
        if len(xs) == 0:
            return
        bx0, bx1, by0, by1 = self.figs.box()
        lo = np.array([min(xs.min(), bx0), min(ys.min(), by0)])
        hi = np.array([max(xs.max(), bx1), max(ys.max(), by1)])
        inside = xs.min() >= bx0 and xs.max() <= bx1 and ys.min() >= by0 and ys.max() <= by1
        if not inside:
            pad = 0.08 * float(np.max(hi - lo))
            self.figs.set_square(lo - pad, hi + pad)
            self._draw_poses()

    # ----- downloads --------------------------------------------------------------------------
    def _json_file(self) -> io.StringIO:
        return io.StringIO(solution_json(self.view.solution if self.view else None))

    def _csv_file(self) -> io.StringIO:
        return io.StringIO(path_csv(self.view.solution if self.view else None))

    def _png_file(self) -> io.BytesIO:
        return io.BytesIO(solution_png(self.view.solution if self.view else None))


def _with_pose(state: ExploreState, name: str, text: str) -> ExploreState:
    return replace(state, start=text) if name == "start" else replace(state, goal=text)


def create_page(catalog: Catalog | None = None) -> pn.viewable.Viewable:
    """The page of one session, its state read from the URL query."""
    args = pn.state.session_args or {}
    query = {
        k: v[0].decode() if isinstance(v[0], bytes) else str(v[0]) for k, v in args.items() if v
    }
    explorer = Explorer(catalog, query)
    pn.state.onload(explorer._push_url)
    return explorer.layout
