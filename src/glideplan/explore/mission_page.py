"""The explorer's mission map: drag the waypoints of a route file and watch the mission's legs.

A lon/lat map (equal metres per pixel at the route's middle latitude; offline) of a route file
read on the server (`glideplan explore --route FILE`; without it the bundled Buzzard's Bay
example), planned by `glideplan.missions.plan_mission` for a Dubins vehicle of the entered
speed and turn radius, as `glideplan mission plan` does: the track, each leg's word, length
and duration, and the totals (`gp-cost` is the total length in m, 10 significant digits).
Waypoints drag; the plan follows on a worker thread (about a second). Downloads: the mission
JSON (the CLI's `--json` object) and a GPX of the track (written by `formats.export`).

URL: `?planner=mission&speed=V&radius=R[&moved=I:LAT:LON;...]` (moved waypoints).
"""

from __future__ import annotations

import html
import io
import math
import pathlib
import tempfile
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any
from urllib.parse import quote, urlencode

import numpy as np
from bokeh.models import ColumnDataSource, Range1d

from glideplan.errors import InvalidParameterError
from glideplan.explore.figures import BLUE, GOAL
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
)
from glideplan.explore.state import one_line
from glideplan.explore.texts import FastHtml, error_html, html_pane
from glideplan.results import BAD_INPUT

__all__ = ["EXAMPLE_ROUTE", "MissionPage", "MissionState", "mission_view"]

EXAMPLE_ROUTE = pathlib.Path(__file__).parents[1] / "missions" / "data" / "buzzards_bay.gpx"


@dataclass(frozen=True)
class MissionState:
    """The mission's inputs: waypoints (lat, lon deg), speed and radius as entered."""

    names: tuple[str, ...]
    lat: tuple[float, ...]
    lon: tuple[float, ...]
    speed: str = "1"
    radius: str = "100"
    moved: tuple[tuple[int, float, float], ...] = ()

    def query(self) -> str:
        items = [("planner", "mission"), ("speed", self.speed), ("radius", self.radius)]
        if self.moved:
            items.append(("moved", ";".join(f"{i}:{la:.6f}:{lo:.6f}" for i, la, lo in self.moved)))
        return urlencode(items, safe=",:;", quote_via=quote)

    def with_move(self, i: int, lat: float, lon: float) -> MissionState:
        lats, lons = list(self.lat), list(self.lon)
        lats[i], lons[i] = lat, lon
        moved = (*(m for m in self.moved if m[0] != i), (i, lat, lon))
        return replace(self, lat=tuple(lats), lon=tuple(lons), moved=moved)


@dataclass(frozen=True, eq=False)
class MissionView:
    state: MissionState
    plan: Any = None
    errors: Mapping[str, str] | None = None

    @property
    def cost_text(self) -> str:
        p = self.plan
        return f"{p.total_length_m:.10g}" if p is not None and p.ok else "n/a"


def mission_view(state: MissionState, source: str) -> MissionView:
    """`plan_mission` of the state's waypoints (compass headings free) at its speed and radius,
    or the one-line message of each bad input."""
    from glideplan.missions import Route, plan_mission

    errors: dict[str, str] = {}
    values: dict[str, float] = {}
    for name in ("speed", "radius"):
        text = getattr(state, name)
        try:
            values[name] = float(text)
        except ValueError:
            errors[name] = one_line(InvalidParameterError(f"--{name}", text, "must be a number"))
    if errors:
        return MissionView(state, None, errors)
    try:
        route = Route.from_geographic(state.names, state.lat, state.lon, source=source)
        plan = plan_mission(route, speed=values["speed"], radius=values["radius"])
    except InvalidParameterError as err:
        name = err.name.lstrip("-")
        return MissionView(
            state, None, {name if name in ("speed", "radius") else "": one_line(err)}
        )
    return MissionView(state, plan, {})


class MissionPage(MapPage):
    """The mission map of one session (module docstring); `layout` is its Panel view."""

    MODE = "mission"

    def __init__(
        self, query: Mapping[str, str] | None = None, route_path: str | None = None
    ) -> None:
        from glideplan.formats.readers import read_route

        query = dict(query or {})
        self._start_session()
        self.view: MissionView | None = None
        self.file_error = ""
        path = pathlib.Path(route_path) if route_path else EXAMPLE_ROUTE
        try:
            route = read_route(path)
        except (InvalidParameterError, OSError, ValueError) as err:
            self.file_error = one_line(err)
            path = EXAMPLE_ROUTE
            route = read_route(path)
        self.path = path
        if route.lat is None or route.lon is None:
            raise InvalidParameterError("--route", str(path), "needs latitudes and longitudes")
        state = MissionState(
            names=tuple(route.names),
            lat=tuple(float(v) for v in route.lat),
            lon=tuple(float(v) for v in route.lon),
            speed=query.get("speed", "1"),
            radius=query.get("radius", "100"),
        )
        for item in (query.get("moved") or "").split(";"):
            try:
                i, la, lo = item.split(":")
                if 0 <= int(i) < len(state.names):
                    state = state.with_move(int(i), float(la), float(lo))
            except ValueError:
                continue
        self.state = state
        self.k = math.cos(math.radians(float(np.mean(state.lat))))
        self._build()
        self._finish_session(query)

    def _build(self) -> None:
        self.mode_select = self._mode_select()
        help_text = (
            f'<div class="gp-help">Route file <code>{html.escape(self.path.name)}</code> '
            f"({len(self.state.names)} waypoints). Drag a waypoint; the mission's Dubins legs "
            "(headings chosen at each waypoint) follow.</div>" + error_html(self.file_error)
        )
        labels = {"speed": ("speed", "speed (m/s)"), "radius": ("radius", "turn radius (m)")}
        numbers = {"speed": "speed", "radius": "turn_radius"}
        self.inputs, self.error_panes = text_inputs(
            self.state, labels, self._make_watcher, numbers
        )
        self.general_error = html_pane(sizing_mode="stretch_width")
        self.strip = FastHtml()
        self.table = FastHtml()
        self.downloads = download_row(
            (self._json_file, "glideplan-mission.json", "JSON"),
            (self._gpx_file, "glideplan-mission.gpx", "GPX"),
        )
        self._figure()
        sidebar = (
            self.mode_select,
            html_pane(help_text, sizing_mode="stretch_width"),
            self.inputs["speed"],
            self.error_panes["speed"],
            self.inputs["radius"],
            self.error_panes["radius"],
            self.general_error,
            html_pane(
                '<div class="gp-help">Download the mission (as <code>mission plan --json'
                "</code>) and its track (GPX)</div>"
            ),
            self.downloads,
        )
        self.layout = page_layout(
            sidebar,
            self.fig,
            self.strip,
            [self.table.pane],
            "mission",
            "Waypoints of a route file, flown as Dubins legs",
        )

    def _figure(self) -> None:
        lat, lon = np.array(self.state.lat), np.array(self.state.lon)
        pad = 0.15 * max(float(np.ptp(lat)), float(np.ptp(lon)) * self.k, 1e-3)
        from glideplan.explore.land import view_with_coast

        w, s, e, n = view_with_coast(  # the nearest coast in view
            lon.min() - pad / self.k, lat.min() - pad, lon.max() + pad / self.k, lat.max() + pad
        )
        self.x_range = Range1d(start=w, end=e)
        self.y_range = Range1d(start=s, end=n)
        fig = map_figure(self.x_range, self.y_range)
        fig.background_fill_color = "#eef5fb"
        fig.grid.grid_line_color = "#d9e3ee"
        self.legs_src = ColumnDataSource({"x": [], "y": []})
        fig.line(
            "x",
            "y",
            source=self.legs_src,
            line_color="#9aa5b1",
            line_dash="dotted",
            line_width=1.5,
            legend_label="waypoint order",
        )
        self.track_src = ColumnDataSource({"x": [], "y": []}, name="gp-answer")
        fig.line(
            "x",
            "y",
            source=self.track_src,
            line_color=BLUE,
            line_width=3,
            legend_label="mission track",
        )
        self.points_src = ColumnDataSource({"x": [], "y": [], "name": []})
        pts = named_points(fig, self.points_src, 13, GOAL, "#2c3e50", (9, -7), "11px")
        finish_map(fig, pts, self.x_range, self.y_range, self.k)
        self.fig = fig
        self.points_src.on_change("data", self._on_points)
        self._draw_points()

    def _draw_points(self) -> None:
        self._syncing = True
        try:
            self.points_src.data = {
                "x": list(self.state.lon),
                "y": list(self.state.lat),
                "name": list(self.state.names),
            }
            self.legs_src.data = {"x": list(self.state.lon), "y": list(self.state.lat)}
        finally:
            self._syncing = False

    def _on_points(self, attr: str, old: Any, new: Any) -> None:
        if self._syncing:
            return
        xs, ys = list(new.get("x", [])), list(new.get("y", []))
        if len(xs) != len(self.state.names):
            self._locked(self._draw_points)  # a deleted point comes back
            return
        state = self.state
        for i, (x, y) in enumerate(zip(xs, ys, strict=True)):
            if abs(x - state.lon[i]) > 1e-9 or abs(y - state.lat[i]) > 1e-9:
                state = state.with_move(i, round(float(y), 6), round(float(x), 6))
        if state != self.state:
            self._locked(lambda: self.set_state(state))

    def _texts(self) -> tuple[FastHtml, ...]:
        return (self.strip, self.table)

    def _redraw(self, old: MissionState) -> None:
        self._draw_points()

    def _compute(self, state: MissionState) -> MissionView:
        return mission_view(state, self.path.name)

    def _failed(self, state: MissionState, message: str) -> MissionView:
        return MissionView(state, None, {"": message})

    def _apply(self, view: MissionView) -> None:
        if view.state != self.state:
            return
        self.view = view
        self._show_errors(view)
        p = view.plan
        if p is not None and p.ok:
            track = p.track()
            lat, lon = p.route.projection.to_geographic(track.x, track.y)
            self.track_src.data = {"x": np.asarray(lon), "y": np.asarray(lat)}
        else:
            self.track_src.data = {"x": [], "y": []}
        self.table.object = self._table_html(p)

    def _strip_html(self, view: MissionView | None, stale: bool = False) -> str:
        item = strip_item
        p = view.plan if view is not None else None
        cost = view.cost_text if view is not None else "n/a"
        status = (
            BAD_INPUT
            if view is not None and view.errors
            else (str(getattr(p.status, "value", p.status)) if p is not None else "")
        )
        dur = f"{p.total_duration_s / 60.0:.1f} min" if p is not None and p.ok else "&ndash;"
        return busy_html(
            item("total length (m)", html.escape(cost), "gp-cost")
            + item("duration", dur, "gp-word")
            + item("legs", str(len(p.legs)) if p is not None else "&ndash;", "gp-small")
            + item("status", html.escape(status), "gp-small gp-status"),
            stale,
        )

    def _table_html(self, p: Any) -> str:
        if p is None:
            return ""
        names = p.route.names
        rows = "".join(
            f"<tr><td>{leg.index + 1}</td><td>{html.escape(names[leg.start])} &rarr; "
            f"{html.escape(names[leg.end])}</td><td>{html.escape(str(leg.word))}</td>"
            f"<td>{leg.length_m:.1f}</td><td>{leg.duration_s:.1f}</td></tr>"
            for leg in p.legs
        )
        head = "".join(f"<th>{h}</th>" for h in ("#", "leg", "word", "length (m)", "duration (s)"))
        return (
            '<div class="gp-help"><b>Legs</b></div><div class="gp-table-wrap">'
            f'<table class="gp-table"><thead><tr>{head}</tr></thead><tbody>{rows}</tbody>'
            "</table></div>"
        )

    def _messages(self) -> str:
        return super()._messages() or "no mission"

    def _json_file(self) -> io.StringIO:
        from glideplan.jsonio import to_json
        from glideplan.results import no_outcome_dict

        p = self.view.plan if self.view is not None else None
        out = p.to_dict() if p is not None else no_outcome_dict(self._messages())
        return io.StringIO(to_json(out) + "\n")

    def _gpx_file(self) -> io.BytesIO:
        from glideplan.formats.export import export_mission

        p = self.view.plan if self.view is not None else None
        if p is None or not p.ok:
            text = f"<!-- no mission: {html.escape(self._messages())} -->\n"
            return io.BytesIO(text.encode())
        with tempfile.TemporaryDirectory() as tmp:
            files, _ = export_mission(p, pathlib.Path(tmp), ("gpx",))
            return io.BytesIO(pathlib.Path(str(files["gpx"])).read_bytes())
