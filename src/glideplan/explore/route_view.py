"""The route map's model, without Panel or Bokeh: its state (the link's inputs), the field it
routes through, the call of `glideplan route` (`route_view`) and the isochrones drawn from
the front's arrival-time map. The page itself is `route_page`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any
from urllib.parse import quote, urlencode

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.explore.state import one_line

__all__ = ["EXAMPLES", "RouteState", "RouteView", "isochrones", "load_field", "route_view"]

EXAMPLES: tuple[str, ...] = ("double-gyre",)
_ISOCHRONES = 8  # about this many isochrones up to the arrival


@dataclass(frozen=True)
class RouteState:
    """The route map's inputs as entered (text): field source, points, speed, departure."""

    example: str | None
    start: str
    goal: str
    speed: str
    depart: str = ""
    resolution: str = ""  # grid spacing (m) as `route --resolution`; empty: automatic

    def query(self) -> str:
        items = [("planner", "route")]
        if self.example:
            items.append(("example", self.example))
        items += [("from", self.start), ("to", self.goal), ("speed", self.speed)]
        if self.depart:
            items.append(("depart", self.depart))
        if self.resolution:
            items.append(("resolution", self.resolution))
        return urlencode(items, safe=",:", quote_via=quote)


def load_field(example: str | None, path: str | None) -> Any:
    """The flow field: the example `example` (no file), else the server's file `path`."""
    from glideplan.fields import double_gyre, open_field

    if example is not None:
        if example not in EXAMPLES:
            raise InvalidParameterError("example", example, f"must be one of {EXAMPLES}")
        return double_gyre()
    if path is None:
        return double_gyre()
    return open_field(path)


def _latlon(text: str, name: str) -> tuple[float, float]:
    items = text.replace(",", " ").split()
    if len(items) != 2:
        raise InvalidParameterError(name, text, "needs two numbers: LAT LON (degrees)")
    try:
        lat, lon = (float(v) for v in items)
    except ValueError:
        raise InvalidParameterError(name, text, "needs two numbers: LAT LON (degrees)") from None
    if not (math.isfinite(lat) and math.isfinite(lon)):
        raise InvalidParameterError(name, text, "latitude/longitude must be finite")
    return lat, lon


@dataclass(frozen=True, eq=False)
class RouteView:
    """One computed route for one state: the result, or the messages by input name."""

    state: RouteState
    result: Any = None
    errors: Mapping[str, str] | None = None

    @property
    def cost_text(self) -> str:
        r = self.result
        if r is None or r.duration_s is None:
            return "n/a"
        return f"{r.duration_s:.10g}"


def route_view(flow: Any, state: RouteState) -> RouteView:
    """`glideplan.routing.route` for the state's points, speed and departure (the call of
    `glideplan route`), or the one-line message of each bad input."""
    from glideplan.fields import parse_utc
    from glideplan.routing import route

    errors: dict[str, str] = {}
    pts: dict[str, tuple[float, float]] = {}
    for name, text in (("from", state.start), ("to", state.goal)):
        try:
            pts[name] = _latlon(text, f"--{name}")
        except InvalidParameterError as err:
            errors[name] = one_line(err)
    from glideplan.explore.catalog import parse_number
    from glideplan.validation import check_physical

    try:  # the rows of validation.PHYSICAL_RANGES that `glideplan route` checks
        speed = check_physical("--speed", parse_number("--speed", state.speed), "speed")
    except InvalidParameterError as err:
        errors["speed"] = one_line(err)
    when = None
    try:
        when = parse_utc(state.depart or None, "--depart")
    except InvalidParameterError as err:
        errors["depart"] = one_line(err)
    resolution = None
    if state.resolution.strip():
        try:
            resolution = check_physical(
                "--resolution", parse_number("--resolution", state.resolution), "distance")
        except InvalidParameterError as err:
            errors["resolution"] = one_line(err)
    if errors:
        return RouteView(state, None, errors)
    try:
        result = route(flow, pts["from"], pts["to"], speed, depart=when, resolution=resolution)
    except InvalidParameterError as err:
        name = {"start": "from", "goal": "to"}.get(err.name.lstrip("-"), err.name.lstrip("-"))
        key = name if name in ("from", "to", "speed", "depart", "resolution") else ""
        return RouteView(state, None, {key: one_line(err)})
    return RouteView(state, result, {})


def _nice_step(span: float, count: int) -> float:
    """A round step (1, 2, 5 x 10^k) giving about `count` steps over `span`."""
    raw = max(span / max(count, 1), 1e-9)
    p = 10.0 ** math.floor(math.log10(raw))
    return min((m * p for m in (1.0, 2.0, 5.0, 10.0)), key=lambda v: abs(v - raw))


def isochrones(front: Any, until_s: float) -> tuple[dict[str, list[Any]], float]:
    """Contours of the front's arrival-time map (s after departure) at round multiples of
    an hour up to `until_s`: lines (lon, lat lists), their labels, and the step (h)."""
    from contourpy import contour_generator

    out: dict[str, list[Any]] = {"xs": [], "ys": [], "label": []}
    arrival = np.asarray(front.arrival, dtype=float)
    if not np.isfinite(arrival).any() or until_s <= 0:
        return out, 0.0
    step_h = _nice_step(until_s / 3600.0, _ISOCHRONES)
    z = np.ma.masked_invalid(arrival / 3600.0)  # never reached: no contour along its edge
    gen = contour_generator(np.asarray(front.lon), np.asarray(front.lat), z)
    level = step_h
    while level < until_s / 3600.0:
        for line in gen.lines(level):
            xy = np.asarray(line, dtype=float)
            out["xs"].append(xy[:, 0])
            out["ys"].append(xy[:, 1])
            out["label"].append(f"{level:g} h")
        level += step_h
    return out, step_h
