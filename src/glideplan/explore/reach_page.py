"""The explorer's glide reach map: where can the glider still glide to, over terrain in wind?

A lon/lat map (equal metres per pixel; offline) of the terrain as a hillshade, the footprint
of `glideplan.reach.glide_reach` (where the glide arrives at least the safety height above
the terrain) and each landable coloured by its arrival margin (green: reachable, its margin
in m; red: not). The start drags; its altitude, the wind (speed m/s, FROM compass deg, as
`glide reach --wind`), MC and the safety height are inputs. The built-in example `ridge` (the
one of `glideplan glide reach --example ridge`) needs no file. `gp-cost` shows the number of
reachable landables. Reach takes a second or two: computed on a worker thread.

URL: `?planner=reach&example=ridge&from=LAT,LON,ALT&wind=SPEED,FROM_DEG&mc=M&safety=H`.
"""

from __future__ import annotations

import html
import math
import threading
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from typing import Any
from urllib.parse import quote, urlencode

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource, PointDrawTool, Range1d
from bokeh.plotting import figure
from panel.io.document import hold
from panel.io.state import set_curdoc

from glideplan.errors import InvalidParameterError
from glideplan.explore.figures import START, equal_scales, follow_url
from glideplan.explore.state import one_line
from glideplan.explore.texts import FastHtml, error_html, html_pane

__all__ = ["ReachPage", "ReachState", "hillshade", "reach_view"]

_SHADE_CELLS = 300  # hillshade samples across the terrain


@dataclass(frozen=True)
class ReachState:
    """The reach map's inputs as entered (text)."""

    start: str
    wind: str
    mc: str
    safety: str

    def query(self) -> str:
        items = [("planner", "reach"), ("example", "ridge"), ("from", self.start)]
        items += [("wind", self.wind), ("mc", self.mc), ("safety", self.safety)]
        return urlencode(items, safe=",", quote_via=quote)


@dataclass(frozen=True, eq=False)
class ReachView:
    state: ReachState
    result: Any = None
    errors: Mapping[str, str] | None = None


def _numbers(text: str, n: int, flag: str, what: str) -> list[float]:
    items = text.replace(",", " ").split()
    try:
        values = [float(v) for v in items]
    except ValueError:
        values = []
    if len(values) != n or not all(math.isfinite(v) for v in values):
        raise InvalidParameterError(flag, text, f"needs {n} finite numbers: {what}")
    return values


def reach_view(example: Any, polar: Any, state: ReachState) -> ReachView:
    """`glide_reach` of the example's terrain and landables for the state (the call of
    `glideplan glide reach --example ridge` with the same values)."""
    from glideplan.geodesy import wind_from_to_vector
    from glideplan.reach import glide_reach

    errors: dict[str, str] = {}
    values: dict[str, list[float]] = {}
    for name, text, n, flag, what in (
        ("from", state.start, 3, "--from", "LAT LON ALT_M"),
        ("wind", state.wind, 2, "--wind", "SPEED (m/s) FROM (deg)"),
        ("mc", state.mc, 1, "--mc", "MC (m/s)"),
        ("safety", state.safety, 1, "--safety-height", "HEIGHT (m)"),
    ):
        try:
            values[name] = _numbers(text, n, flag, what)
        except InvalidParameterError as err:
            errors[name] = one_line(err)
    if errors:
        return ReachView(state, None, errors)
    try:
        wind = wind_from_to_vector(*values["wind"])
        la, lo, alt = values["from"]
        result = glide_reach(
            example.terrain,
            (la, lo, alt),
            polar,
            landables=example.landables,
            mc=values["mc"][0],
            wind=wind,
            safety_height=values["safety"][0],
            resolution_m=example.resolution_m,
        )
    except InvalidParameterError as err:
        name = {"start": "from", "mc": "mc", "wind": "wind", "safety_height": "safety"}.get(
            err.name.lstrip("-"), ""
        )
        return ReachView(state, None, {name: one_line(err)})
    return ReachView(state, result, {})


def hillshade(z: np.ndarray, dx: float, dy: float, azimuth_deg: float = 315.0) -> np.ndarray:
    """Lambertian hillshade in [0, 1] of elevations `z` (rows south to north) with cell sizes
    dx, dy (m): the cosine between the surface normal and a light 45 deg high from
    `azimuth_deg` (compass)."""
    gy, gx = np.gradient(z.astype(float), dy, dx)
    az, alt = math.radians(azimuth_deg), math.radians(45.0)
    lx, ly, lz = math.sin(az) * math.cos(alt), math.cos(az) * math.cos(alt), math.sin(alt)
    shade = (-gx * lx - gy * ly + lz) / np.sqrt(gx * gx + gy * gy + 1.0)
    return np.clip(shade, 0.0, 1.0)


class ReachPage:
    """The glide reach map of one session (module docstring); `layout` is its Panel view."""

    def __init__(self, query: Mapping[str, str] | None = None) -> None:
        from glideplan.cli.glide import _polar
        from glideplan.reach.examples import example

        query = dict(query or {})
        self.on_mode: Callable[[str], None] | None = None
        self._doc = pn.state.curdoc
        self._lock = threading.Lock()
        self._pending: ReachState | None = None
        self._running = False
        self._closed = False
        self._syncing = False
        self.view: ReachView | None = None
        self.example = example("ridge")
        self.polar = _polar(self.example.polar_file, None, 0.0, 0.0, "--polar")
        ex = self.example
        self.state = ReachState(
            start=query.get("from", ",".join(f"{v:g}" for v in ex.start)),
            wind=query.get("wind", f"{ex.wind_speed_ms:g},{ex.wind_from_deg:g}"),
            mc=query.get("mc", f"{ex.mc:g}"),
            safety=query.get("safety", f"{ex.safety_height:g}"),
        )
        self.k = math.cos(math.radians(float(ex.start[0])))
        self._build()
        from glideplan.explore.app import _parse_view

        linked = _parse_view(query.get("view"))
        if linked is not None:  # a link's zoom (the browser grows a side to equal scales)
            self.x_range.update(start=linked[0], end=linked[2])
            self.y_range.update(start=linked[1], end=linked[3])
        if self._doc is not None:
            self._doc.on_session_destroyed(self._on_closed)
        self.solve()

    def _on_closed(self, _context: Any) -> None:
        self._closed = True

    def _build(self) -> None:
        from glideplan.explore.app import (
            BODY_CSS,
            LAYOUT_CSS,
            MAIN_CSS,
            MAP_MODES,
            PLOT_CSS,
            ROOT_CSS,
            SIDEBAR_CSS,
            _TextInput,
        )
        from glideplan.explore.catalog import build_catalog

        options = {e.label: e.key for e in build_catalog().entries}
        options.update(MAP_MODES)
        self.mode_select = pn.widgets.Select(
            label="Planner", options=options, value="reach", sizing_mode="stretch_width"
        )
        self.mode_select.param.watch(self._on_mode, "value")
        self.inputs: dict[str, Any] = {}
        self.error_panes: dict[str, Any] = {}
        labels = {
            "from": ("start", "from: lat (deg), lon (deg), altitude (m MSL)"),
            "wind": ("wind", "wind: speed (m/s), from (deg compass)"),
            "mc": ("mc", "MacCready setting (m/s)"),
            "safety": ("safety", "safety height above terrain (m)"),
        }
        for name, (attr, label) in labels.items():
            w = _TextInput(
                label=label,
                value=getattr(self.state, attr),
                sizing_mode="stretch_width",
                css_classes=[f"gp-input-{name}"],
            )
            w.param.watch(self._make_watcher(attr), "value")
            self.inputs[name] = w
            self.error_panes[name] = html_pane(sizing_mode="stretch_width")
        self.general_error = html_pane(sizing_mode="stretch_width")
        self.strip = FastHtml()
        self._figure()
        sidebar = pn.Column(
            self.mode_select,
            html_pane(
                '<div class="gp-help">Example <b>ridge</b>: '
                f"{html.escape(self.example.description)}. Drag the glider.</div>",
                sizing_mode="stretch_width",
            ),
            *[x for n in labels for x in (self.inputs[n], self.error_panes[n])],
            self.general_error,
            stylesheets=[SIDEBAR_CSS],
        )
        self.fig.stylesheets = [PLOT_CSS]
        body = pn.FlexBox(pn.pane.Bokeh(self.fig), flex_wrap="wrap", stylesheets=[BODY_CSS])
        main = pn.Column(self.strip.pane, body, stylesheets=[MAIN_CSS])
        header = pn.Row(
            html_pane(
                '<div class="gp-title">glideplan explore: glide reach</div>'
                '<div class="gp-sub">Where the glider can still glide to over terrain in '
                "wind, each landable's path verified</div>"
            ),
            styles={"background": "#1f3b5c", "border-radius": "6px"},
            sizing_mode="stretch_width",
            margin=(5, 5, 10, 5),
        )
        page = pn.FlexBox(sidebar, main, flex_wrap="wrap", stylesheets=[LAYOUT_CSS])
        self.layout = pn.Column(header, page, sizing_mode="stretch_width", stylesheets=[ROOT_CSS])

    def _figure(self) -> None:
        t = self.example.terrain
        lat, lon = np.asarray(t.lat, dtype=float), np.asarray(t.lon, dtype=float)
        self.x_range = Range1d(start=float(lon.min()), end=float(lon.max()))
        self.y_range = Range1d(start=float(lat.min()), end=float(lat.max()))
        fig = figure(
            sizing_mode="stretch_both",
            min_width=240,
            min_height=240,
            x_range=self.x_range,
            y_range=self.y_range,
            tools="pan,wheel_zoom,box_zoom,reset,save",
            toolbar_location="above",
            x_axis_label="longitude (deg E)",
            y_axis_label="latitude (deg N)",
            output_backend="canvas",
        )
        step = max(1, len(lon) // _SHADE_CELLS)
        z = np.asarray(t.z, dtype=float)[::step, ::step]
        la, lo = lat[::step], lon[::step]
        if la[0] > la[-1]:  # rows north to south: the image's rows go up
            z, la = z[::-1], la[::-1]
        r = 6_371_000.0
        dy = math.radians(abs(la[1] - la[0])) * r
        dx = math.radians(abs(lo[1] - lo[0])) * r * self.k
        shade = hillshade(np.nan_to_num(z), dx, dy)
        grey = (60 + 180 * shade).astype(np.uint8)
        rgba = np.dstack([grey, grey, grey, np.full_like(grey, 255)])
        image: Any = np.ascontiguousarray(rgba).view(np.uint32).reshape(grey.shape)
        fig.image_rgba(
            image=[image],
            x=float(lo.min()),
            y=float(la.min()),
            dw=float(lo.max() - lo.min()),
            dh=float(la.max() - la.min()),
        )
        self.foot_src = ColumnDataSource({"xs": [], "ys": []})
        fig.multi_polygons(
            "xs",
            "ys",
            source=self.foot_src,
            fill_color="#2e86de",
            fill_alpha=0.25,
            line_color="#1f5fa8",
            line_width=1.5,
            legend_label="footprint (safety height kept)",
        )
        self.land_src = ColumnDataSource({"x": [], "y": [], "c": [], "text": []})
        fig.scatter(
            "x",
            "y",
            source=self.land_src,
            marker="square",
            size=12,
            fill_color="c",
            line_color="white",
            legend_label="landables (margin)",
        )
        fig.text(
            "x",
            "y",
            "text",
            source=self.land_src,
            x_offset=9,
            y_offset=-7,
            text_font_size="11px",
            text_color="c",
        )
        self.track_src = ColumnDataSource({"xs": [], "ys": []})
        fig.multi_line(
            "xs",
            "ys",
            source=self.track_src,
            line_color="#27ae60",
            line_alpha=0.7,
            line_width=1.5,
            legend_label="verified paths",
        )
        self.start_src = ColumnDataSource({"x": [], "y": []})
        pts = fig.scatter(
            "x",
            "y",
            source=self.start_src,
            size=15,
            fill_color=START,
            line_color="white",
            line_width=2,
        )
        draw = PointDrawTool(renderers=[pts], add=False, drag=True)  # type: ignore[list-item]
        fig.add_tools(draw)
        fig.toolbar.active_drag = draw
        legend = fig.legend[0]
        legend.location = "top_left"
        legend.background_fill_alpha = 0.8
        legend.label_text_font_size = "11px"
        legend.click_policy = "hide"
        equal_scales(fig, self.x_range, self.y_range, self.k)
        follow_url(fig)
        self.fig = fig
        self.start_src.on_change("data", self._on_points)
        self._draw_start()

    def _draw_start(self) -> None:
        try:
            la, lo, _ = _numbers(self.state.start, 3, "--from", "")
        except InvalidParameterError:
            return
        self._syncing = True
        try:
            self.start_src.data = {"x": [lo], "y": [la]}
        finally:
            self._syncing = False

    def _on_points(self, attr: str, old: Any, new: Any) -> None:
        if self._syncing or not new.get("x"):
            return
        try:
            alt = _numbers(self.state.start, 3, "--from", "")[2]
        except InvalidParameterError:
            alt = float(self.example.start[2])
        text = f"{float(new['y'][0]):.4f},{float(new['x'][0]):.4f},{alt:g}"
        state = replace(self.state, start=text)
        self._syncing = True
        try:
            self.inputs["from"].value = text
        finally:
            self._syncing = False
        self._locked(lambda: self.set_state(state))

    def _make_watcher(self, attr: str) -> Callable[[Any], None]:
        def watch(event: Any) -> None:
            if not self._syncing:
                state = replace(self.state, **{attr: event.new})
                self._locked(lambda: self.set_state(state))

        return watch

    def _on_mode(self, event: Any) -> None:
        if event.new != "reach" and self.on_mode is not None:
            self._locked(lambda: self.on_mode(event.new) if self.on_mode else None)

    def _locked(self, fn: Callable[[], None]) -> None:
        if self._doc is None:
            fn()
        else:
            self._doc.add_next_tick_callback(lambda: self._held(fn))

    def _held(self, fn: Callable[[], None]) -> None:
        if self._closed or self._doc is None:
            return
        with set_curdoc(self._doc), hold(self._doc):
            fn()

    def push_url(self) -> None:
        self.strip.sync()
        self.fig.tags = ["?" + self.state.query()]

    def set_state(self, state: ReachState) -> None:
        self.state = state
        self._draw_start()
        self.push_url()
        self.solve()

    def solve(self) -> None:
        """Compute the reach on the worker thread (latest state wins)."""
        if self._doc is None:
            self._apply(reach_view(self.example, self.polar, self.state))
            return
        with self._lock:
            self._pending = self.state
            start = not self._running
            self._running = True
        self.strip.object = self._strip_html(self.view, stale=True)
        if start:
            threading.Thread(target=self._work, daemon=True, name="glideplan-reach").start()

    def _work(self) -> None:
        while True:
            with self._lock:
                state, self._pending = self._pending, None
                if state is None:
                    self._running = False
                    return
            try:
                view = reach_view(self.example, self.polar, state)
            except Exception as exc:  # a bug: show it rather than lose the thread
                view = ReachView(state, None, {"": f"internal error: {exc!r}"})
            with self._lock:
                latest = self._pending is None
            if latest and not self._closed and self._doc is not None:
                try:
                    self._doc.add_next_tick_callback(
                        lambda v=view: self._held(lambda: self._apply(v))  # type: ignore[misc]
                    )
                except Exception:  # the session went away meanwhile
                    self._closed = True

    def _apply(self, view: ReachView) -> None:
        if view.state != self.state:
            return
        self.view = view
        errors = dict(view.errors or {})
        for name, pane in self.error_panes.items():
            pane.object = error_html(errors.get(name, ""))
        self.general_error.object = error_html(errors.get("", ""))
        self.strip.object = self._strip_html(view)
        r = view.result
        if r is None:
            self.foot_src.data = {"xs": [], "ys": []}
            self.land_src.data = {"x": [], "y": [], "c": [], "text": []}
            self.track_src.data = {"xs": [], "ys": []}
            return
        xs: list[Any] = []
        ys: list[Any] = []
        for poly in r.footprint:
            xs.append([[np.asarray(ring)[:, 0] for ring in poly]])
            ys.append([[np.asarray(ring)[:, 1] for ring in poly]])
        self.foot_src.data = {"xs": xs, "ys": ys}
        land: dict[str, list[Any]] = {"x": [], "y": [], "c": [], "text": []}
        tx: list[Any] = []
        ty: list[Any] = []
        for pt in r.points:
            land["x"].append(pt.landable.lon)
            land["y"].append(pt.landable.lat)
            ok = pt.reachable and pt.arrival_margin_m is not None
            land["c"].append("#1e8449" if ok else "#c0392b")
            margin = f"+{pt.arrival_margin_m:.0f} m" if ok else "not reachable"
            land["text"].append(f"{pt.landable.name} {margin}")
            if pt.track is not None and pt.track.lat is not None:
                tx.append(np.asarray(pt.track.lon))
                ty.append(np.asarray(pt.track.lat))
        self.land_src.data = land
        self.track_src.data = {"xs": tx, "ys": ty}

    def _strip_html(self, view: ReachView | None, stale: bool = False) -> str:
        def item(k: str, v: str, cls: str = "") -> str:
            return (
                f'<div class="gp-item"><span class="gp-k">{k}</span>'
                f'<span class="gp-v {cls}">{v}</span></div>'
            )

        r = view.result if view is not None else None
        if r is not None:
            n = sum(1 for p in r.points if p.reachable)
            cost, total = str(n), f"of {len(r.points)}"
            margins = [p.arrival_margin_m for p in r.points if p.reachable and p.arrival_margin_m]
            best = f"{max(margins):.0f} m" if margins else "&ndash;"
            status = str(getattr(r.status, "value", r.status))
        else:
            cost, total, best = "n/a", "", "&ndash;"
            status = "bad input" if view is not None and view.errors else ""
        busy = (
            (
                '<div class="gp-item gp-computing"><span class="gp-busy">computing&hellip;'
                "</span></div>"
            )
            if stale
            else ""
        )
        return (
            f'<div class="gp-strip{" gp-stale" if stale else ""}">'
            + item("reachable landables", f"{html.escape(cost)} {total}", "gp-cost")
            + item("best margin", best, "gp-word")
            + item("status", html.escape(status), "gp-small gp-status")
            + busy
            + "</div>"
        )
