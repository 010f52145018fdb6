"""What the explorer's lon/lat map pages (route, mission, glide reach) share.

`MapPage`: a session's document lock, the planner select that leaves for another page, the
worker thread that computes the latest state (latest state wins; the shown answer is marked
stale meanwhile) and the error panes. Module functions: the map figure, its drag tool and
legend, the text inputs, the download buttons, the page skeleton and the result strip.
"""

from __future__ import annotations

import html
import threading
from collections.abc import Callable, Iterable, Mapping
from dataclasses import replace
from typing import Any

import panel as pn
from bokeh.models import PointDrawTool

from glideplan.explore.figures import equal_scales, follow_url, plain_figure
from glideplan.explore.texts import error_html, html_pane
from glideplan.explore.worker import SessionWorker

__all__ = [
    "MapPage",
    "busy_html",
    "download_row",
    "finish_map",
    "map_figure",
    "named_points",
    "page_layout",
    "strip_item",
    "text_inputs",
    "warnings_item",
]


class MapPage(SessionWorker):
    """The shared machinery of a map page; a page sets `MODE` and defines `_compute` (state ->
    view, run on the worker thread), `_failed` (the view of an internal error), `_apply`
    and `_strip_html`, and calls `_start_session` first and `_finish_session` last."""

    MODE = ""
    strip: Any
    state: Any
    view: Any
    error_panes: dict[str, Any]
    general_error: Any
    x_range: Any
    y_range: Any
    fig: Any

    def _start_session(self) -> None:
        self.on_mode: Callable[[str], None] | None = None
        self._doc = pn.state.curdoc
        self._lock = threading.Lock()
        self._pending: Any = None
        self._running = False
        self._closed = False
        self._syncing = False
        self.view = None

    def _finish_session(self, query: Mapping[str, str]) -> None:
        """A link's zoom (the browser grows a side to equal scales), then the first answer."""
        from glideplan.explore.layout import _parse_view

        linked = _parse_view(query.get("view"))
        if linked is not None:
            self.x_range.update(start=linked[0], end=linked[2])
            self.y_range.update(start=linked[1], end=linked[3])
        if self._doc is not None:
            self._doc.on_session_destroyed(self._on_closed)
        self.solve()

    def _on_closed(self, _context: Any) -> None:
        self._closed = True

    def _mode_select(self) -> Any:
        """The planner select (the catalog's planners and the map modes), this page chosen."""
        from glideplan.explore.catalog import build_catalog
        from glideplan.explore.layout import MAP_MODES

        options = {e.label: e.key for e in build_catalog().entries}
        options.update(MAP_MODES)
        select = pn.widgets.Select(
            label="Planner", options=options, value=self.MODE, sizing_mode="stretch_width"
        )
        select.param.watch(self._on_mode, "value")
        return select

    def _on_mode(self, event: Any) -> None:
        if event.new != self.MODE and self.on_mode is not None:
            self._locked(lambda: self.on_mode(event.new) if self.on_mode else None)

    def _make_watcher(self, attr: str) -> Callable[[Any], None]:
        """A text input's watcher: the state with `attr` as typed (not while the page itself
        sets the input)."""

        def watch(event: Any) -> None:
            if not self._syncing:
                state = replace(self.state, **{attr: event.new})
                self._locked(lambda: self.set_state(state))

        return watch

    def _texts(self) -> tuple[Any, ...]:
        """The page's `FastHtml` texts."""
        return (self.strip,)

    def _redraw(self, old: Any) -> None:
        """Redraw what depends on the state (it was `old`)."""
        raise NotImplementedError

    def push_url(self) -> None:
        """The texts that changed while the browser built the page, and the state's query
        into the browser's address."""
        for text in self._texts():
            text.sync()
        self.fig.tags = ["?" + self.state.query()]

    def set_state(self, state: Any) -> None:
        old, self.state = self.state, state
        self._redraw(old)
        self.push_url()
        self.solve()

    def _deliver(self, answer: Any) -> None:
        self._apply(answer)

    def _apply(self, view: Any) -> None:
        raise NotImplementedError

    def _strip_html(self, view: Any, stale: bool = False) -> str:
        raise NotImplementedError

    def solve(self) -> None:
        """Compute the current state on the worker thread (latest state wins)."""
        if self._doc is None:
            self._apply(self._compute(self.state))
            return
        self._show_stale()
        self._submit(f"glideplan-{self.MODE}")

    def _show_stale(self) -> None:
        self.strip.object = self._strip_html(self.view, stale=True)

    def _show_errors(self, view: Any) -> None:
        """Each input's message under it, the rest under the inputs, and the strip."""
        errors = dict(view.errors or {})
        for name, pane in self.error_panes.items():
            pane.object = error_html(errors.get(name, ""))
        self.general_error.object = error_html(errors.get("", ""))
        self.strip.object = self._strip_html(view)

    def _messages(self) -> str:
        errors = dict(self.view.errors or {}) if self.view is not None else {"": "no answer yet"}
        return "; ".join(v for v in errors.values() if v)


def text_inputs(
    state: Any,
    labels: Mapping[str, tuple[str, str]],
    watcher: Callable[[str], Any],
    numbers: Mapping[str, str] | None = None,
) -> tuple[dict[str, Any], dict[str, Any]]:
    """A text input (class `gp-input-NAME`, value the state's `attr`) and an error pane for
    each `name: (attr, label)`; `watcher(attr)` watches the input's value. A name in
    `numbers` gets a spinner limited to `PHYSICAL_RANGES[numbers[name]]` instead ("wind":
    the wind's speed with its unit and compass FROM, text `SPEED_MS,FROM_DEG`)."""
    from types import SimpleNamespace

    from glideplan.explore.inputs import number_input, wind_input
    from glideplan.explore.layout import _TextInput

    inputs: dict[str, Any] = {}
    panes: dict[str, Any] = {}
    for name, (attr, label) in labels.items():
        kind = (numbers or {}).get(name)
        if kind is not None:
            watch = watcher(attr)
            on_text = lambda text, w=watch: w(SimpleNamespace(new=text))  # noqa: E731
            text = getattr(state, attr)
            control = (
                wind_input(name, text, on_text)
                if kind == "wind"
                else number_input(name, label, text, kind, on_text)
            )
            inputs[name] = pn.Column(*control.widgets, margin=0, sizing_mode="stretch_width")
            panes[name] = html_pane(sizing_mode="stretch_width")
            continue
        w = _TextInput(
            label=label,
            value=getattr(state, attr),
            sizing_mode="stretch_width",
            css_classes=[f"gp-input-{name}"],
        )
        w.param.watch(watcher(attr), "value")
        inputs[name] = w
        panes[name] = html_pane(sizing_mode="stretch_width")
    return inputs, panes


def download_row(*buttons: tuple[Callable[[], Any], str, str]) -> Any:
    """A row of download buttons, each (callback, filename, label)."""
    return pn.Row(
        *(
            pn.widgets.FileDownload(
                callback=callback,
                filename=filename,
                label=label,
                color="primary",
                width=92,
                embed=False,
            )
            for callback, filename, label in buttons
        ),
        margin=(5, 0),
    )


def map_figure(x_range: Any, y_range: Any) -> Any:
    """A lon/lat figure on the given ranges."""
    return plain_figure(x_range, y_range, "longitude (deg E)", "latitude (deg N)")


def named_points(
    fig: Any,
    source: Any,
    size: float,
    fill: str,
    text_color: str,
    offset: tuple[float, float],
    font_size: str,
) -> Any:
    """Points (`x`, `y` of `source`, white edged) labelled with its `name` column, the label
    shifted by `offset` (x, y screen pixels); returns the points' renderer (to drag)."""
    pts = fig.scatter(
        "x", "y", source=source, size=size, fill_color=fill, line_color="white", line_width=2
    )
    fig.text(
        "x",
        "y",
        "name",
        source=source,
        x_offset=offset[0],
        y_offset=offset[1],
        text_font_size=font_size,
        text_color=text_color,
    )
    return pts


def finish_map(
    fig: Any, draggable: Any, x_range: Any, y_range: Any, k: float, hide: bool = False,
    wind: Any = None,
) -> None:
    """Drag `draggable`'s points, the legend top left (click hides a layer if `hide`), equal
    metres per pixel at cos(lat) = k, the view in the browser's address."""
    draw = PointDrawTool(renderers=[draggable], add=False, drag=True)
    fig.add_tools(draw)
    fig.toolbar.active_drag = draw
    legend = fig.legend[0]
    legend.location = "top_left"
    legend.background_fill_alpha = 0.8
    legend.label_text_font_size = "11px"
    if hide:
        legend.click_policy = "hide"
    equal_scales(fig, x_range, y_range, k)
    follow_url(fig)
    from glideplan.explore.land import add_land
    from glideplan.explore.map_furniture import add_scale_and_north

    add_scale_and_north(fig, x_range, y_range, wind)
    add_land(fig, x_range, y_range)


def page_layout(
    sidebar: Iterable[Any], fig: Any, strip: Any, right: Iterable[Any], title: str, sub: str
) -> Any:
    """The page: header (title, subtitle html), the sidebar, the strip above the figure and
    what stands right of it."""
    from glideplan.explore.layout import (
        BODY_CSS,
        LAYOUT_CSS,
        MAIN_CSS,
        PLOT_CSS,
        RIGHT_CSS,
        ROOT_CSS,
        SIDEBAR_CSS,
    )

    side = pn.Column(*sidebar, stylesheets=[SIDEBAR_CSS])
    fig.stylesheets = [PLOT_CSS]
    right = list(right)
    beside = [pn.Column(*right, stylesheets=[RIGHT_CSS])] if right else []
    body = pn.FlexBox(pn.pane.Bokeh(fig), *beside, flex_wrap="wrap", stylesheets=[BODY_CSS])
    main = pn.Column(strip.pane, body, stylesheets=[MAIN_CSS])
    header = pn.Row(
        html_pane(
            f'<div class="gp-title">glideplan explore: {html.escape(title)}</div>'
            f'<div class="gp-sub">{sub}</div>'
        ),
        styles={"background": "#1f3b5c", "border-radius": "6px"},
        sizing_mode="stretch_width",
        margin=(5, 5, 10, 5),
    )
    page = pn.FlexBox(side, main, flex_wrap="wrap", stylesheets=[LAYOUT_CSS])
    return pn.Column(header, page, sizing_mode="stretch_width", stylesheets=[ROOT_CSS])


def strip_item(k: str, v: str, cls: str = "") -> str:
    """One key/value of the result strip (html; `v` already escaped)."""
    return (
        f'<div class="gp-item"><span class="gp-k">{k}</span>'
        f'<span class="gp-v {cls}">{v}</span></div>'
    )


def busy_html(items: str, stale: bool) -> str:
    """The result strip of `items`, marked stale and "computing" while a newer state runs."""
    busy = (
        '<div class="gp-item gp-computing"><span class="gp-busy">computing&hellip;</span></div>'
        if stale
        else ""
    )
    return f'<div class="gp-strip{" gp-stale" if stale else ""}">' + items + busy + "</div>"


def warnings_item(result: Any) -> str:
    """The result's warnings as one strip item (class `gp-warn`), or nothing."""
    notes = tuple(getattr(result, "warnings", ()) or ())
    if not notes:
        return ""
    return strip_item("warnings", "<br>".join(html.escape(n) for n in notes), "gp-warn")
