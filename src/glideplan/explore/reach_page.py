"""The explorer's glide reach map: where can the glider still glide to, over terrain in wind?

A lon/lat map (equal metres per pixel; offline) of the terrain in colour relief with
hillshade and labelled contours (`explore.relief`), the footprint of
`glideplan.reach.glide_reach` on the DEM's own grid (`reach.native`; where the glide arrives
at least the safety height above the terrain) and each landable coloured by its arrival
margin (green: reachable, its margin in m; red: not, "-240 m" short). The start drags; its
altitude, the wind (speed m/s, FROM compass deg, as `glide reach --wind`), MC and the safety
height are inputs. The built-in example `ridge` (the one of `glideplan glide reach --example
ridge`) needs no file. `gp-cost` shows the number of reachable landables. Reach takes ~1.2 s
of CPU (at the DEM's 93 m): a worker thread.

URL: `?planner=reach&example=ridge&from=LAT,LON,ALT&wind=SPEED,FROM_DEG&mc=M&safety=H`.
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any
from urllib.parse import quote, urlencode

import numpy as np
from bokeh.models import ColumnDataSource, Range1d

from glideplan.errors import InvalidParameterError
from glideplan.explore.figures import START
from glideplan.explore.map_page import (
    MapPage,
    busy_html,
    finish_map,
    map_figure,
    page_layout,
    strip_item,
    text_inputs,
    warnings_item,
)
from glideplan.explore.state import one_line
from glideplan.explore.texts import FastHtml, html_pane
from glideplan.results import BAD_INPUT

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
    from glideplan.reach import glide_reach
    from glideplan.units import wind_from_compass

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
        wind = wind_from_compass(*values["wind"])
        la, lo, alt = values["from"]
        result = glide_reach(
            example.terrain,
            (la, lo, alt),
            polar,
            landables=example.landables,
            mc=values["mc"][0],
            wind=wind,
            safety_height=values["safety"][0],
            resolution_m=None,  # the DEM's own grid (reach.native), not the example's 700 m
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


class ReachPage(MapPage):
    """The glide reach map of one session (module docstring); `layout` is its Panel view."""

    MODE = "reach"

    def __init__(self, query: Mapping[str, str] | None = None) -> None:
        from glideplan.reach.examples import example
        from glideplan.sailplane import load_polar

        query = dict(query or {})
        self._start_session()
        self.view: ReachView | None = None
        self.example = example("ridge")
        self.polar = load_polar(self.example.polar_file)
        ex = self.example
        self.state = ReachState(
            start=query.get("from", ",".join(f"{v:g}" for v in ex.start)),
            wind=query.get("wind", f"{ex.wind_speed_ms:g},{ex.wind_from_deg:g}"),
            mc=query.get("mc", f"{ex.mc:g}"),
            safety=query.get("safety", f"{ex.safety_height:g}"),
        )
        self.k = math.cos(math.radians(float(ex.start[0])))
        self._build()
        self._finish_session(query)

    def _build(self) -> None:
        self.mode_select = self._mode_select()
        labels = {
            "from": ("start", "from: lat (deg), lon (deg), altitude (m MSL)"),
            "wind": ("wind", "wind: speed (m/s), from (deg compass)"),
            "mc": ("mc", "MacCready setting (m/s)"),
            "safety": ("safety", "safety height above terrain (m)"),
        }
        numbers = {"wind": "wind", "mc": "mc", "safety": "height"}
        self.inputs, self.error_panes = text_inputs(
            self.state, labels, self._make_watcher, numbers
        )
        self.general_error = html_pane(sizing_mode="stretch_width")
        self.strip = FastHtml()
        self._figure()
        sidebar = (
            self.mode_select,
            html_pane(
                '<div class="gp-help">Example <b>ridge</b>: '
                f"{html.escape(self.example.description)}. Drag the glider.</div>",
                sizing_mode="stretch_width",
            ),
            *[x for n in labels for x in (self.inputs[n], self.error_panes[n])],
            self.general_error,
        )
        self.layout = page_layout(
            sidebar,
            self.fig,
            self.strip,
            [],
            "glide reach",
            "Where the glider can still glide to over terrain in wind, each landable's path "
            "verified",
        )

    def _figure(self) -> None:
        t = self.example.terrain
        lat, lon = np.asarray(t.lat, dtype=float), np.asarray(t.lon, dtype=float)
        self.x_range = Range1d(start=float(lon.min()), end=float(lon.max()))
        self.y_range = Range1d(start=float(lat.min()), end=float(lat.max()))
        fig = map_figure(self.x_range, self.y_range)
        from glideplan.explore.relief import add_relief

        add_relief(fig, t)  # colour relief, hillshade, labelled contours, elevation key
        self.foot_src = ColumnDataSource({"xs": [], "ys": []}, name="gp-answer")
        fig.multi_polygons(
            "xs",
            "ys",
            source=self.foot_src,
            fill_color="#2e86de",
            fill_alpha=0.18,
            line_color="#1f5fa8",
            line_width=1.5,
            legend_label="footprint (safety height kept)",
        )
        self.land_src = ColumnDataSource({"x": [], "y": [], "c": [], "text": []}, name="gp-answer")
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
        self.wind_src = ColumnDataSource({"to_deg": [], "text": []})
        self._draw_wind()
        finish_map(fig, pts, self.x_range, self.y_range, self.k, hide=True, wind=self.wind_src)
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

    def _redraw(self, old: ReachState) -> None:
        self._draw_start()
        self._draw_wind()

    def _draw_wind(self) -> None:
        """The wind arrow's direction (towards, compass) and label (speed, FROM as typed)."""
        try:
            speed, frm = _numbers(self.state.wind, 2, "--wind", "")
        except InvalidParameterError:
            self.wind_src.data = {"to_deg": [], "text": []}
            return
        if speed <= 0:
            self.wind_src.data = {"to_deg": [], "text": []}
            return
        self.wind_src.data = {
            "to_deg": [(frm + 180.0) % 360.0],
            "text": [f"wind {speed:g} m/s from {frm:g}\N{DEGREE SIGN}"],
        }

    def _compute(self, state: ReachState) -> ReachView:
        return reach_view(self.example, self.polar, state)

    def _failed(self, state: ReachState, message: str) -> ReachView:
        return ReachView(state, None, {"": message})

    def _apply(self, view: ReachView) -> None:
        if view.state != self.state:
            return
        self.view = view
        self._show_errors(view)
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
            short = getattr(pt, "short_by_m", None)  # as the CLI figure: "-240 m"
            margin = (f"+{pt.arrival_margin_m:.0f} m" if ok else
                      f"\N{MINUS SIGN}{short:.0f} m" if short is not None else "not reachable")
            land["text"].append(f"{pt.landable.name} {margin}")
            if pt.track is not None and pt.track.lat is not None:
                tx.append(np.asarray(pt.track.lon))
                ty.append(np.asarray(pt.track.lat))
        self.land_src.data = land
        self.track_src.data = {"xs": tx, "ys": ty}

    def _strip_html(self, view: ReachView | None, stale: bool = False) -> str:
        item = strip_item
        r = view.result if view is not None else None
        if r is not None:
            n = sum(1 for p in r.points if p.reachable)
            cost, total = str(n), f"of {len(r.points)}"
            margins = [p.arrival_margin_m for p in r.points if p.reachable and p.arrival_margin_m]
            best = f"{max(margins):.0f} m" if margins else "&ndash;"
            status = str(getattr(r.status, "value", r.status))
        else:
            cost, total, best = "n/a", "", "&ndash;"
            status = BAD_INPUT if view is not None and view.errors else ""
        return busy_html(
            item("reachable landables", f"{html.escape(cost)} {total}", "gp-cost")
            + item("best margin", best, "gp-word")
            + item("status", html.escape(status), "gp-small gp-status")
            + (item("grid", f"{r.resolution_m:.0f} m", "gp-small gp-grid") if r is not None else "")
            + warnings_item(r),
            stale,
        )
