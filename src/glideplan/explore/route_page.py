"""The explorer's route map: drag the start and goal of a route through a current or wind field.

A lon/lat map (equal metres per pixel in x and y at the field's middle latitude, no map tiles:
the page works offline) of the field: land where its currents are NaN, arrows of the current
at the departure time plus the time slider's offset, the route of `glideplan.routing.route`,
its isochrones (contours of the front's arrival-time map, at round intervals) and the start
and goal, which drag. The result strip's cost (`gp-cost`) is the route's `duration_s` with 10
significant digits, as `glideplan route --json` prints it for the same field, points, speed
and departure. The field is a file given to `glideplan explore --field FILE` (read on the
server) or a built-in example (`example=double-gyre`, no file needed).

URL: `?planner=route&example=double-gyre&from=LAT,LON&to=LAT,LON&speed=V[&depart=ISO]`.
Routes take seconds: they are computed on a worker thread, the shown one marked stale.
"""

from __future__ import annotations

import html
import io
import math
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

import numpy as np
import panel as pn
from bokeh.models import ColumnDataSource, Range1d

from glideplan.errors import InvalidParameterError
from glideplan.explore.figures import GOAL, START, columns
from glideplan.explore.map_page import (
    MapPage,
    busy_html,
    download_row,
    finish_map,
    map_figure,
    named_points,
    page_layout,
    strip_item,
    text_inputs,
    warnings_item,
)
from glideplan.explore.route_layers import current_layer, isochrone_layer, route_layers
from glideplan.explore.route_view import (  # the model; re-exported for old imports
    EXAMPLES,
    RouteState,
    RouteView,
    _latlon,
    _nice_step,
    isochrones,
    load_field,
    route_view,
)
from glideplan.explore.state import one_line
from glideplan.explore.texts import FastHtml, error_html, html_pane
from glideplan.results import BAD_INPUT

__all__ = ["EXAMPLES", "RoutePage", "RouteState", "load_field", "route_view"]

_ARROWS_X = 22  # current arrows across the field's width
_LAND_CELLS = 200  # land mask samples across the field's width


class RoutePage(MapPage):
    """The route map of one session (module docstring); `layout` is its Panel view."""

    MODE = "route"

    def __init__(
        self, query: Mapping[str, str] | None = None, field_path: str | None = None
    ) -> None:
        query = dict(query or {})
        self.field_path = field_path
        example = query.get("example") or (None if field_path else "double-gyre")
        self._start_session()
        self.view: RouteView | None = None
        self.field_error = ""
        try:
            self.flow = load_field(example, field_path)
        except (InvalidParameterError, OSError, ValueError) as err:
            self.field_error = one_line(err)
            example = "double-gyre"
            self.flow = load_field(example, None)
        ext = self.flow.extent
        lat_c = 0.5 * (ext.lat_min + ext.lat_max)
        self.k = math.cos(math.radians(lat_c))
        default_from, default_to = self._defaults(ext)
        self.state = RouteState(
            example=example,
            start=query.get("from", default_from),
            goal=query.get("to", default_to),
            speed=query.get("speed", "0.5"),
            depart=query.get("depart", ""),
            resolution=query.get("resolution", ""),
        )
        self._build()
        self._finish_session(query)

    @staticmethod
    def _defaults(ext: Any) -> tuple[str, str]:
        lat = 0.5 * (ext.lat_min + ext.lat_max)
        w = ext.lon_max - ext.lon_min
        a, b = ext.lon_min + 0.1 * w, ext.lon_min + 0.9 * w
        return f"{lat:.4f},{a:.4f}", f"{lat:.4f},{b:.4f}"

    # ----- widgets and figure -----------------------------------------------------------------
    def _build(self) -> None:
        self.mode_select = self._mode_select()
        info = self.flow.describe()
        source = (
            f"built-in example <b>{html.escape(self.state.example)}</b>"
            if self.state.example
            else f"file <code>{html.escape(str(self.field_path))}</code>"
        )
        self.field_help = html_pane(
            f'<div class="gp-help">Field: {source} ({html.escape(str(info.get("name", "")))})'
            ". Drag the start and goal; the route is the fastest at the speed through the "
            "water (air) below.</div>" + error_html(self.field_error),
            sizing_mode="stretch_width",
        )
        labels = {
            "from": ("start", "from: lat (deg), lon (deg)"),
            "to": ("goal", "to: lat (deg), lon (deg)"),
            "speed": ("speed", "speed through the water (m/s)"),
            "depart": ("depart", "depart (ISO 8601 UTC; empty: the field's first time)"),
            "resolution": ("resolution", "grid spacing (m; empty: ~200 cells across)"),
        }
        numbers = {"speed": "speed"}
        self.inputs, self.error_panes = text_inputs(
            self.state, labels, self._make_watcher, numbers
        )
        self.general_error = html_pane(sizing_mode="stretch_width")
        self.slider = pn.widgets.FloatSlider(
            label="currents at (h after departure)",
            start=0.0,
            end=1.0,
            step=0.1,
            value=0.0,
            sizing_mode="stretch_width",
        )
        self.slider.param.watch(self._on_slider, "value")
        self.downloads = download_row(
            (self._json_file, "glideplan-route.json", "JSON"),
            (self._csv_file, "glideplan-route.csv", "CSV"),
        )
        self.strip = FastHtml()
        self._figure()
        sidebar = (
            self.mode_select,
            self.field_help,
            *[
                x
                for n in ("from", "to", "speed", "depart", "resolution")
                for x in (self.inputs[n], self.error_panes[n])
            ],
            self.slider,
            self.general_error,
            html_pane(
                '<div class="gp-help">Download the route (as <code>route --json</code>) '
                "and its track (CSV)</div>"
            ),
            self.downloads,
        )
        self.layout = page_layout(
            sidebar,
            self.fig,
            self.strip,
            [],
            "route",
            "The fastest route through currents or winds (front propagation, refined, "
            "verified through the field)",
        )

    def _figure(self) -> None:
        ext = self.flow.extent
        pad_x, pad_y = 0.03 * (ext.lon_max - ext.lon_min), 0.03 * (ext.lat_max - ext.lat_min)
        self.x_range = Range1d(ext.lon_min - pad_x, ext.lon_max + pad_x)
        self.y_range = Range1d(ext.lat_min - pad_y, ext.lat_max + pad_y)
        fig = map_figure(self.x_range, self.y_range)
        fig.background_fill_color = "#eef5fb"
        fig.grid.grid_line_color = "#d9e3ee"
        self.land_src = ColumnDataSource({"image": [], "x": [], "y": [], "dw": [], "dh": []})
        fig.image_rgba("image", x="x", y="y", dw="dw", dh="dh", source=self.land_src)
        self.arrow_src, self.speed_mapper = current_layer(fig)
        self.iso_src, self.iso_label_src = isochrone_layer(fig)
        self.route_src, self.unverified_src, self.vehicle_src = route_layers(fig)
        self.points_src = ColumnDataSource({"x": [], "y": [], "name": [], "c": []})
        pts = named_points(fig, self.points_src, 15, "c", "c", (10, -8), "12px")
        finish_map(fig, pts, self.x_range, self.y_range, self.k, hide=True)
        self.fig = fig
        self.points_src.on_change("data", self._on_points)
        self._draw_land()
        self._draw_points()
        self._draw_arrows()

    # ----- drawing ----------------------------------------------------------------------------
    def _t0(self) -> float:
        """The departure (s since the field's epoch), as `route` takes it."""
        from glideplan.fields import parse_utc, to_seconds

        try:
            when = parse_utc(self.state.depart or None, "--depart")
        except InvalidParameterError:
            when = None
        if when is None:
            span = self.flow.time_span
            return float(span[0]) if span is not None else 0.0
        return float(to_seconds(when, self.flow.epoch))

    def _grid(self, nx: int) -> tuple[np.ndarray, np.ndarray]:
        ext = self.flow.extent
        w, h = ext.lon_max - ext.lon_min, ext.lat_max - ext.lat_min
        ny = max(2, round(nx * h / (w * self.k)))
        lon = ext.lon_min + (np.arange(nx) + 0.5) * w / nx
        lat = ext.lat_min + (np.arange(ny) + 0.5) * h / ny
        return np.meshgrid(lon, lat)

    def _velocity(self, t: float, lat: np.ndarray, lon: np.ndarray) -> tuple[Any, Any]:
        try:
            if self.flow.time_span is not None:
                lo, hi = self.flow.time_span
                t = min(max(t, lo), hi)
            return self.flow.velocity(t, lat, lon)
        except InvalidParameterError:
            nan = np.full(lat.shape, np.nan)
            return nan, nan

    def _draw_land(self) -> None:
        """Grey where the field's currents are NaN at the departure (land, missing data)."""
        lon, lat = self._grid(_LAND_CELLS)
        u, v = self._velocity(self._t0(), lat, lon)
        land = ~(np.isfinite(u) & np.isfinite(v))
        if not land.any():
            self.land_src.data = {"image": [], "x": [], "y": [], "dw": [], "dh": []}
            return
        rgba = np.zeros((*land.shape, 4), dtype=np.uint8)
        rgba[land] = (196, 190, 172, 255)
        ext = self.flow.extent
        self.land_src.data = {
            "image": [rgba.view(np.uint32).reshape(land.shape)],
            "x": [ext.lon_min],
            "y": [ext.lat_min],
            "dw": [ext.lon_max - ext.lon_min],
            "dh": [ext.lat_max - ext.lat_min],
        }

    def _draw_arrows(self) -> None:
        """Current arrows at departure + the slider's hours (longest: 0.8 of a cell)."""
        lon, lat = self._grid(_ARROWS_X)
        u, v = self._velocity(self._t0() + 3600.0 * float(self.slider.value or 0.0), lat, lon)
        u, v = np.nan_to_num(u), np.nan_to_num(v)
        speed = np.hypot(u, v)
        top = float(speed.max()) if speed.size else 0.0
        cell = (lon[0, 1] - lon[0, 0]) if lon.shape[1] > 1 else 1.0
        scale = 0.8 * cell / top if top > 0 else 0.0  # degrees of longitude per m/s
        x1 = lon + scale * u
        y1 = lat + scale * v * self.k  # north metres -> degrees of latitude
        keep = speed > 0.02 * top
        self.arrow_src.data = columns({
            "x0": lon[keep],
            "y0": lat[keep],
            "x1": x1[keep],
            "y1": y1[keep],
            "angle": np.arctan2(v, u)[keep] - 0.5 * math.pi,
            "speed": speed[keep],
        })
        self.speed_mapper.high = float(f"{top:.2g}") if top > 0 else 1.0
        self._draw_vehicle()

    def _draw_vehicle(self) -> None:
        """The vehicle on the route at the slider's hours after departure (linear in time
        between the track's samples; none before departure or after arrival)."""
        r = self.view.result if self.view is not None else None
        hours = float(self.slider.value or 0.0)
        data: dict[str, list[Any]] = {"x": [], "y": [], "text": []}
        if r is not None and r.lat.size > 1 and r.t.size == r.lat.size:
            t = 3600.0 * hours
            if r.t[0] <= t <= r.t[-1]:
                data = {
                    "x": [float(np.interp(t, r.t, r.lon))],
                    "y": [float(np.interp(t, r.t, r.lat))],
                    "text": [f"+{hours:g} h"],
                }
        self.vehicle_src.data = data

    def _draw_points(self) -> None:
        data: dict[str, list[Any]] = {"x": [], "y": [], "name": [], "c": []}
        for name, text, colour in (
            ("start", self.state.start, START),
            ("goal", self.state.goal, GOAL),
        ):
            try:
                lat, lon = _latlon(text, name)
            except InvalidParameterError:
                continue
            for k, val in zip(("x", "y", "name", "c"), (lon, lat, name, colour), strict=True):
                data[k].append(val)
        self._drawn = data
        self._syncing = True
        try:
            self.points_src.data = data
        finally:
            self._syncing = False

    def _on_points(self, attr: str, old: Any, new: Any) -> None:
        """A dragged start or goal: its new lat, lon (4 decimals, about 10 m)."""
        if getattr(self, "_syncing", False):
            return
        moved = {
            name: f"{float(y):.4f},{float(x):.4f}"
            for x, y, name in zip(
                new.get("x", []), new.get("y", []), new.get("name", []), strict=False
            )
        }
        state = self.state
        for name, attr in (("start", "start"), ("goal", "goal")):
            if name not in moved:
                continue
            try:
                was = _latlon(getattr(state, attr), name)
                now = _latlon(moved[name], name)
            except InvalidParameterError:
                was, now = (math.nan, math.nan), (0.0, 0.0)
            if max(abs(was[0] - now[0]), abs(was[1] - now[1])) > 1e-4:  # this one moved
                state = replace(state, **{attr: moved[name]})
        if state != self.state:
            self._set_inputs(state)
            self._locked(lambda: self.set_state(state))

    def _set_inputs(self, state: RouteState) -> None:
        self._syncing = True
        try:
            self.inputs["from"].value = state.start
            self.inputs["to"].value = state.goal
        finally:
            self._syncing = False

    # ----- state ------------------------------------------------------------------------------
    def _on_slider(self, event: Any) -> None:
        self._locked(self._draw_arrows)

    def _redraw(self, old: RouteState) -> None:
        self._draw_points()
        if self.state.depart != old.depart:
            self._draw_land()
            self._draw_arrows()

    # ----- solving ----------------------------------------------------------------------------
    def _compute(self, state: RouteState) -> RouteView:
        return route_view(self.flow, state)

    def _failed(self, state: RouteState, message: str) -> RouteView:
        return RouteView(state, None, {"": message})

    def _apply(self, view: RouteView) -> None:
        if view.state != self.state:
            return
        self.view = view
        self._show_errors(view)
        r = view.result
        empty: dict[str, Any] = {"x": [], "y": []}
        line = (
            {"x": np.asarray(r.lon), "y": np.asarray(r.lat)}
            if r is not None and r.lat.size
            else empty
        )
        verified = r is not None and r.ok
        self.route_src.data = line if verified else empty
        self.unverified_src.data = empty if verified else line
        self._draw_vehicle()
        front = getattr(r, "front", None)
        if r is not None and front is not None:
            until = (
                r.duration_s
                if r.duration_s
                else float(np.nanmax(np.where(np.isfinite(front.arrival), front.arrival, np.nan)))
            )
            lines, _ = isochrones(front, until)
            self.iso_src.data = lines
            self.iso_label_src.data = {
                "x": [xs[len(xs) // 2] for xs in lines["xs"]],
                "y": [ys[len(ys) // 2] for ys in lines["ys"]],
                "text": lines["label"],
            }
        else:
            self.iso_src.data = {"xs": [], "ys": [], "label": []}
            self.iso_label_src.data = {"x": [], "y": [], "text": []}
        if r is not None and r.duration_s:
            hours = r.duration_s / 3600.0
            end = max(1.0, math.ceil(hours))
            self.slider.param.update(end=end, step=_nice_step(end, 50))

    def _strip_html(self, view: RouteView | None, stale: bool = False) -> str:
        item = strip_item
        r = view.result if view is not None else None
        cost = view.cost_text if view is not None else "n/a"
        if view is not None and view.errors:
            status = BAD_INPUT
        elif r is not None:
            status = str(getattr(r.status, "value", r.status))
            if not r.ok and r.message:
                status += f": {r.message}"
        else:
            status = ""
        ok = r is not None and r.ok
        hours = f"{r.duration_s / 3600.0:.2f} h" if r is not None and r.duration_s else "&ndash;"
        dist = f"{r.distance_m / 1000.0:.1f} km" if r is not None and r.distance_m else "&ndash;"
        err = (
            f"{r.endpoint_error_m:.2f} m"
            if r is not None and r.endpoint_error_m is not None
            else "n/a"
        )
        straight = (
            f"{r.straight_line_duration_s / 3600.0:.2f} h"
            if r is not None and r.straight_line_duration_s
            else "n/a"
        )
        return busy_html(
            item("duration (s)", html.escape(cost), "gp-cost")
            + item("duration", hours, "gp-word")
            + item("distance", dist, "gp-small")
            + item(
                "status",
                html.escape(status),
                "gp-small gp-status" + ("" if ok else " gp-status-bad"),
            )
            + item("endpoint error", err, "gp-small gp-endpoint")
            + item("straight line", straight, "gp-small")
            + warnings_item(r),
            stale,
        )

    # ----- downloads --------------------------------------------------------------------------
    def _json_file(self) -> io.StringIO:
        from glideplan.jsonio import to_json
        from glideplan.results import no_outcome_dict

        r = self.view.result if self.view is not None else None
        if r is None:
            out: dict[str, Any] = no_outcome_dict(self._messages() or "no route")
        else:
            out = r.to_dict()
            source: dict[str, Any] = (
                {"file": None, "example": self.state.example}
                if self.state.example
                else {"file": [str(self.field_path)]}
            )
            out["field"] = {**source, **out.get("field", {})}
        return io.StringIO(to_json(out) + "\n")

    def _csv_file(self) -> io.StringIO:
        import csv

        buf = io.StringIO()
        writer = csv.writer(buf, lineterminator="\n")
        r = self.view.result if self.view is not None else None
        if r is None or not r.lat.size:
            writer.writerow(["error"])
            writer.writerow([self._messages() or (r.message if r is not None else "no route")])
        else:
            writer.writerow(["t", "lat", "lon", "heading_deg"])
            for row in zip(r.t, r.lat, r.lon, r.heading_deg, strict=True):
                writer.writerow([f"{v:.10g}" for v in row])
        return io.StringIO(buf.getvalue())
