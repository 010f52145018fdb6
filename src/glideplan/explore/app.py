"""The explorer page: Panel widgets around a Bokeh figure, one `Explorer` per browser session.

The figure's start and goal are dragged with Bokeh's `PointDrawTool` (a second draggable point
per pose sets its heading); every change goes into an `ExploreState`, the URL query follows it
(with the zoom, `view=x0,y0,x1,y1`, kept by the browser), and the state is planned:

- synthesis planners (milliseconds) at once, in the input's own callback, their answer (cost
  strip, path, poses, the candidates' lines and table, the address) sent as one patch: one
  redraw per change (a second message for the candidates was a second redraw, competing
  with the next change); texts go through `FastHtml` (one innerHTML, no re-layout of the
  page);
- direct methods (seconds) on a worker thread (latest state wins), the shown answer marked
  stale ("computing") meanwhile.

Equal x/y scales are kept in the browser (`figures.ASPECT_JS`); the layout is a wrapping flex
box (controls left of the strip and the plot, or above them below 760 px). Imported only by
`glideplan explore` (Panel and Bokeh are heavy).
"""

from __future__ import annotations

import html
import threading
from collections.abc import Callable
from dataclasses import replace
from typing import Any

import panel as pn
from bokeh.events import Pan, PanEnd, PanStart

from glideplan.explore.catalog import Catalog, PlannerEntry, build_catalog, planner_key
from glideplan.explore.downloads import DownloadFiles, download_button
from glideplan.explore.figures import (
    PlanFigures,
    empty_candidates,
)
from glideplan.explore.inputs import InputControl, build_input
from glideplan.explore.layout import (  # the page's styles and shared pieces, one place
    BODY_CSS,
    LAYOUT_CSS,
    MAIN_CSS,
    MAP_MODES,
    PLOT_CSS,
    RIGHT_CSS,
    ROOT_CSS,
    SIDEBAR_CSS,
    _parse_view,
    _TextInput,
)
from glideplan.explore.plane_poses import PoseHandles, _with_pose
from glideplan.explore.solve import View, partition_image, solve_view, with_candidates
from glideplan.explore.state import (
    ExploreState,
    initial_state,
    state_from_query,
    state_to_query,
)
from glideplan.explore.texts import FastHtml, error_html, html_pane, strip_html, table_html
from glideplan.explore.worker import SessionWorker

__all__ = ["Explorer", "create_page"]

# A synthesis planned on the worker thread (one that may fall back to a direct method) is
# shown stale ("computing") only when its answer takes longer than this (ms): a 50 ms answer
# then costs one message and one redraw, not two.
BUSY_AFTER_MS = 250
# Answers with at most this many candidates carry them (Dubins and wind: 6, ~1.3 ms CPU);
# more candidates follow in a second message once the input rests CANDIDATES_DELAY_MS.
INLINE_CANDIDATES = 8
CANDIDATES_DELAY_MS = 120


class Explorer(PoseHandles, DownloadFiles, SessionWorker):
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
        linked = _parse_view((query or {}).get("view") if isinstance(query, dict) else None)
        self.on_mode: Callable[[str], None] | None = None  # switch to a map mode (the page)
        self.on_switch: Callable[[Any], None] | None = None  # another planner: a history entry
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
        self._closed = False
        self._keep_view = linked is not None  # a link's zoom is kept for its first answer
        self.figs = PlanFigures()
        self._hook_figures()
        self._build_widgets()
        self._set_planner_inputs()
        if linked is not None:
            self.figs.set_box(*linked)
        else:
            self._reset_ranges()
        self._draw_poses()
        self.layout = self._layout()
        if self._doc is not None:
            self._doc.on_session_destroyed(self._on_closed)
        self.solve()

    def _on_closed(self, _context: Any) -> None:
        """The tab is gone: a result still being planned is dropped, not sent."""
        self._closed = True

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
        options.update(MAP_MODES)
        self.planner_select = pn.widgets.Select(
            label="Planner", options=options, value=self.state.planner, sizing_mode="stretch_width"
        )
        self.planner_select.param.watch(self._on_planner, "value")
        self.planner_help = html_pane(sizing_mode="stretch_width")
        self.pose_inputs: dict[str, pn.widgets.TextInput] = {}
        self.error_panes: dict[str, pn.pane.HTML] = {}
        for name in ("start", "goal"):
            w = _TextInput(
                label=self._pose_label(name),
                value=getattr(self.state, name),
                sizing_mode="stretch_width",
                css_classes=[f"gp-input-{name}"],
            )
            w.param.watch(self._make_pose_watcher(name), "value")
            self.pose_inputs[name] = w
            self.error_panes[name] = html_pane(sizing_mode="stretch_width")
        self.vehicle_box = pn.Column(margin=0)
        self.option_box = pn.Column(margin=0)
        self.options_card = pn.Card(
            self.option_box,
            title="Planner options",
            collapsed=True,
            sizing_mode="stretch_width",
            margin=(5, 5),
        )
        self.candidates_toggle = pn.widgets.Checkbox(
            label="show every candidate", value=self.state.candidates
        )
        self.candidates_toggle.param.watch(self._on_flags, "value")
        self.partition_toggle = pn.widgets.Checkbox(
            label="partition map background (Fig 3.1)", value=self.state.partition
        )
        self.partition_toggle.param.watch(self._on_flags, "value")
        self.general_error = html_pane(sizing_mode="stretch_width")
        self.table = FastHtml()
        self.strip = FastHtml()
        self.downloads = pn.Row(
            download_button(self._json_file, "glideplan-solution.json", "JSON"),
            download_button(self._csv_file, "glideplan-path.csv", "CSV"),
            download_button(self._png_file, "glideplan-figure.png", "PNG"),
            margin=(5, 0),
        )

    def _pose_label(self, name: str) -> str:
        unit = self.entry.length_unit
        return f"{name}: x, y ({unit}), heading (deg CCW from +x)"

    def _set_planner_inputs(self) -> None:
        entry = self.entry
        # the planner's one line, not the vehicle's docstring (radians and "towards" inside)
        self.planner_help.object = (
            f'<div class="gp-help">{html.escape(entry.spec.description.replace("`", ""))}<br>'
            "<i>Angles in degrees; a wind is the compass direction it blows FROM.</i></div>"
        )
        for name, w in self.pose_inputs.items():
            w.label = self._pose_label(name)
        self.figs.set_units(entry.length_unit, "nondim." if entry.nondimensional else "m/s")
        self.param_inputs: dict[str, InputControl] = {}
        vehicle: list[Any] = []
        option: list[Any] = []
        for p in entry.parameters:
            control = build_input(
                p,
                self.state.values.get(p.name, p.default),
                entry.nondimensional,
                self._make_value_watcher(p.name),
                wind_unit=self.state.wind_unit,
                on_unit=self._on_wind_unit,
            )
            self.param_inputs[p.name] = control
            self.error_panes[p.name] = html_pane(sizing_mode="stretch_width")
            (vehicle if p.target == "vehicle" else option).extend(
                [*control.widgets, self.error_panes[p.name]]
            )
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
            stylesheets=[SIDEBAR_CSS],
        )
        self.figs.fig.stylesheets = [PLOT_CSS]  # the pane is the figure itself
        self.plot_pane = pn.pane.Bokeh(self.figs.fig)
        right = pn.Column(
            self.table.pane,
            pn.pane.Bokeh(self.figs.profile_col, sizing_mode="stretch_width"),
            stylesheets=[RIGHT_CSS],
        )
        body = pn.FlexBox(self.plot_pane, right, flex_wrap="wrap", stylesheets=[BODY_CSS])
        main = pn.Column(self.strip.pane, body, stylesheets=[MAIN_CSS])
        page = pn.FlexBox(sidebar, main, flex_wrap="wrap", stylesheets=[LAYOUT_CSS])
        return pn.Column(header, page, sizing_mode="stretch_width", stylesheets=[ROOT_CSS])

    # ----- state ------------------------------------------------------------------------------
    @property
    def entry(self) -> PlannerEntry:
        return self.catalog.get(self.state.planner)

    def set_state(self, state: ExploreState) -> None:
        """Show `state`: update the URL and the poses, and plan it."""
        self.state = state
        if self._dragging is None:  # the browser is moving the point itself
            self._draw_poses()
        if self.sync or self.entry.background or self._doc is None:
            self._push_url()  # else with the answer, in the same message
        self.solve()

    def set_goal(self, x: float, y: float, heading_deg: float | None = None) -> None:
        """Move the goal (m) as a drag does; the heading (deg) is kept unless given."""
        self._move_pose("goal", x, y, heading_deg)

    def push_url(self) -> None:
        """The state's query into the browser's address (once the page is shown), and the
        texts that changed while the browser built the page."""
        self.strip.sync()
        self.table.sync()
        self._push_url()
        if self.entry.slow and hasattr(self, "plot_pane"):
            # the busy veil's last change can be lost like the answer's data (a slow planner
            # answered while the browser built the page: "solved" under a spinner): send it
            busy = self.view is None or self.view.state != self.state
            self.plot_pane.loading = not busy
            self.plot_pane.loading = busy

    def _push_url(self) -> None:
        """Put the state's query in the browser's address (history.replaceState, no reload)."""
        self.figs.fig.tags = ["?" + state_to_query(self.catalog, self.state)]

    def _on_planner(self, event: Any) -> None:
        if event.new in MAP_MODES.values():
            if self.on_mode is not None:
                self._locked(lambda: self.on_mode(event.new) if self.on_mode else None)
            return
        if event.new != self.state.planner:
            self._locked(lambda: self._switch_planner(event.new))

    def _switch_planner(self, key: str) -> None:
        """Another planner: its inputs and defaults, the start and goal kept (as entered)."""
        entry = self.catalog.get(key)
        self._planner_note = ""
        old = self.state
        self.state = replace(
            initial_state(entry),
            start=old.start,
            goal=old.goal,
            candidates=old.candidates,
            partition=old.partition,
        )
        if self.on_switch is not None:  # the new history entry, before the answer's address
            self.on_switch(self.state)  # (same message, in this order) replaces its query
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

    def _make_value_watcher(self, name: str) -> Callable[[str], None]:
        def watch(text: str) -> None:
            if not self._syncing:
                self._locked(lambda: self.set_state(self.state.with_values(**{name: text})))

        return watch

    def _on_wind_unit(self, unit: str) -> None:
        """Another unit for the wind's speed: the same wind, the URL remembers the unit."""
        if not self._syncing:
            self._locked(lambda: self._set_wind_unit(unit))

    def _set_wind_unit(self, unit: str) -> None:
        self.state = replace(self.state, wind_unit=unit)
        self._push_url()

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

    # ----- solving ----------------------------------------------------------------------------
    def solve(self) -> None:
        """Plan the current state: at once for the synthesis planners (milliseconds; the
        answer goes out with the input's echo in one message), on the worker thread for
        the direct methods (seconds; the old answer is shown as stale meanwhile) and for a
        synthesis that may fall back to one (shown stale after BUSY_AFTER_MS)."""
        if self.sync or not self.entry.background:
            # the answer, its candidates and the address in one message (one redraw), unless
            # the candidates are many (minimum time's 13: sampling and sending them cost
            # ~10 ms before the cost could show): those follow once the input rests
            view, part = self._compute(self.state, candidates=self.sync or self._doc is None)
            if view.candidates_pending and view.solution is not None and (
                len(view.solution.candidates) <= INLINE_CANDIDATES
            ):
                view = with_candidates(view)
            self._apply(view, part)
            if self._doc is not None:
                self._push_url()
            if view.candidates_pending and self._doc is not None:
                # once the input rests: each answer's timer acts only if no newer answer
                # came (a timer set 120 ms before sampled the answer of 60 ms before, and
                # its message raced the next change's while the goal was being dragged)
                self._candidates_for = view
                self._doc.add_timeout_callback(
                    lambda v=view: self._held(lambda: self._add_candidates(v)),
                    CANDIDATES_DELAY_MS,
                )
            return
        if self.entry.slow:
            self._show_busy(True)
        elif self._doc is not None:  # a synthesis (tens of ms): stale only if it takes longer
            state = self.state
            self._doc.add_timeout_callback(
                lambda: self._held(lambda: self._busy_if_pending(state)), BUSY_AFTER_MS
            )
        self._submit("glideplan-explore")

    def _busy_if_pending(self, state: ExploreState) -> None:
        if self.state == state and (self.view is None or self.view.state != state):
            self._show_busy(True)

    def _failed(self, state: ExploreState, message: str) -> tuple[View, Any]:
        return (View(state, None, {"": message}), None)

    def _deliver(self, answer: tuple[View, Any]) -> None:
        self._apply(*answer)

    def _add_candidates(self, answer: View | None = None) -> None:
        """The shown answer's candidates (`answer`'s, if it is still the newest answer):
        lines, table and the view fitted to them."""
        view = self.view
        if answer is not None and getattr(self, "_candidates_for", None) is not answer:
            return  # a newer answer came meanwhile: its own timer will follow
        if view is None or not view.candidates_pending or view.state != self.state:
            return  # a newer change came meanwhile: its own candidates will follow
        self.view = view = with_candidates(view)
        self.figs.show_candidates(view, self.state.candidates)
        self.table.object = table_html(view.candidates or empty_candidates())
        if self._dragging is None:
            self._expand_ranges(view)

    def _compute(
        self, state: ExploreState, candidates: bool = True
    ) -> tuple[View, dict[str, Any] | None]:
        view = solve_view(self.catalog, state, candidates)
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
        """Mark the shown answer stale ("computing") while a newer state is planned."""
        if self.view is not None:
            self.strip.object = strip_html(self.view, stale=busy)
        elif busy:
            self.strip.object = (
                '<div class="gp-strip gp-stale"><span class="gp-busy">'
                "computing&hellip;</span></div>"
            )
        if self.entry.slow and hasattr(self, "plot_pane"):
            self.plot_pane.loading = busy

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
        if not view.candidates_pending:
            self.table.object = table_html(view.candidates or empty_candidates())
        if self._dragging is None and not self._keep_view:
            self._expand_ranges(view)
        self._keep_view = False
        if self.entry.slow:
            self.plot_pane.loading = False


def create_page(*args: Any, **kw: Any) -> Any:
    """The page of one session (`glideplan.explore.page.create_page`, kept here for old
    imports)."""
    from glideplan.explore.page import create_page as page

    return page(*args, **kw)
