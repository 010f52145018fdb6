"""The explorer's state and its URL query: `?planner=dubins&goal=4,3,90&radius=1`.

Poses are `x,y,heading_deg` (m, m, degrees counter-clockwise from +x, as `--goal`), the wind
`speed,direction_deg`, every other input named like its command-line option with `_` for `-`.
Values are kept as the text the user entered, so that a bad value can be shown with its
one-line message next to its input; `request()` turns them into a vehicle and options.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any
from urllib.parse import parse_qsl, quote, urlencode

from glideplan.errors import InvalidParameterError
from glideplan.explore.catalog import Catalog, PlannerEntry, parse_number
from glideplan.pose import Pose

__all__ = [
    "POSE_NAMES",
    "ExploreState",
    "Request",
    "format_pose",
    "initial_state",
    "parse_pose_text",
    "request",
    "state_from_query",
    "state_to_query",
]

POSE_NAMES = ("start", "goal")
# The wind speed's display unit in the URL (`wind_unit=kt`); the wind itself stays in m/s.
_WIND_UNIT_KEYS = {"m/s": "ms", "km/h": "kmh", "kt": "kt"}
_WIND_UNIT_NAMES = {v: k for k, v in _WIND_UNIT_KEYS.items()}


def _num(value: float) -> str:
    text = f"{value:.10g}"
    return "0" if text == "-0" else text


def format_pose(x: float, y: float, heading_deg: float) -> str:
    """`x,y,heading_deg` with up to 10 significant digits."""
    return ",".join(_num(v) for v in (x, y, heading_deg))


def parse_pose_text(text: str, name: str) -> Pose:
    """`x,y,heading_deg` (commas or spaces) to a `Pose` in m and radians."""
    items = text.replace(",", " ").split()
    if len(items) != 3:
        raise InvalidParameterError(name, text, "needs three numbers: X Y HEADING_DEG")
    x, y, h = (parse_number(f"{name} {c}", v) for c, v in zip("xyh", items, strict=True))
    return Pose(x, y, math.radians(h))


@dataclass(frozen=True)
class ExploreState:
    """What the page shows: the planner, the poses and every input as entered (text)."""

    planner: str
    start: str
    goal: str
    values: Mapping[str, str] = field(default_factory=dict)
    candidates: bool = True
    partition: bool = False
    wind_unit: str = "m/s"  # how the wind's speed is shown (m/s, km/h, kt); the URL keeps m/s

    def with_values(self, **values: str) -> ExploreState:
        return replace(self, values={**self.values, **values})


def initial_state(entry: PlannerEntry) -> ExploreState:
    """The planner's defaults, with the goal at (4, 3) length scales heading 90 degrees."""
    scale = _nice(entry.length_scale)
    return ExploreState(
        planner=entry.key,
        start=format_pose(0.0, 0.0, 0.0),
        goal=format_pose(4.0 * scale, 3.0 * scale, 90.0),
        values={p.name: p.default for p in entry.parameters},
    )


def _nice(scale: float) -> float:
    """A round number near `scale` (1, 2, 5 times a power of ten)."""
    if not math.isfinite(scale) or scale <= 0.0:
        return 1.0
    p = 10.0 ** math.floor(math.log10(scale))
    return min((1.0, 2.0, 5.0, 10.0), key=lambda m: abs(math.log(m * p / scale))) * p


def state_from_query(catalog: Catalog, query: Mapping[str, str] | str) -> ExploreState:
    """The state a URL query describes; unknown keys are ignored, missing ones take defaults.

    A bad planner name falls back to the first planner (the page shows the message); bad
    values are kept as text and reported by `request()`.
    """
    if isinstance(query, str):
        query = dict(parse_qsl(query.lstrip("?"), keep_blank_values=True))
    key = str(query.get("planner", catalog.entries[0].key))
    objective = query.get("objective")
    if objective:
        key = f"{key}/{objective}"
    try:
        entry = catalog.get(key)
    except InvalidParameterError:
        try:
            entry = catalog.get(key.split("/")[0])
        except InvalidParameterError:
            entry = catalog.entries[0]
    state = initial_state(entry)
    values = dict(state.values)
    for p in entry.parameters:
        if p.name in query:
            values[p.name] = query[p.name]

    def flag(name: str, default: bool) -> bool:
        text = query.get(name)
        return default if text is None else text.lower() in ("1", "true", "yes", "on")

    return replace(
        state,
        start=query.get("start", state.start),
        goal=query.get("goal", state.goal),
        values=values,
        candidates=flag("candidates", state.candidates),
        partition=flag("partition", state.partition),
        wind_unit=_WIND_UNIT_NAMES.get(str(query.get("wind_unit", "")).lower(), "m/s"),
    )


def state_to_query(catalog: Catalog, state: ExploreState) -> str:
    """The URL query (without '?') for `state`: planner, poses, vehicle inputs, changed options."""
    entry = catalog.get(state.planner)
    name, _, objective = entry.key.partition("/")
    items: list[tuple[str, str]] = [("planner", name)]
    if objective:
        items.append(("objective", objective))
    if state.start.replace(" ", "") not in ("0,0,0", ""):
        items.append(("start", state.start))
    items.append(("goal", state.goal))
    for p in entry.parameters:
        text = state.values.get(p.name, p.default)
        if p.target == "vehicle" or text != p.default:
            items.append((p.name, text))
    if not state.candidates:
        items.append(("candidates", "0"))
    if state.partition:
        items.append(("partition", "1"))
    if state.wind_unit != "m/s" and entry.parameter("wind") is not None:
        items.append(("wind_unit", _WIND_UNIT_KEYS.get(state.wind_unit, "ms")))
    return urlencode(items, safe=",/", quote_via=quote)


@dataclass(frozen=True)
class Request:
    """A validated request: the arguments of `plan()`."""

    entry: PlannerEntry
    start: Pose
    goal: Pose
    vehicle: Any
    options: Mapping[str, Any]


def request(catalog: Catalog, state: ExploreState) -> tuple[Request | None, dict[str, str]]:
    """The `plan()` arguments for `state`, or the one-line message of each bad input.

    Errors are keyed by input name ("goal", "radius", ...; "" for one no input owns).
    A vehicle's own check that names a field reports it under the field's option name,
    as the command line does (`radius=-1.0: must be > 0`).
    """
    errors: dict[str, str] = {}
    try:
        entry = catalog.get(state.planner)
    except InvalidParameterError as err:
        return None, {"planner": one_line(err)}
    poses: dict[str, Pose] = {}
    for name in POSE_NAMES:
        try:
            poses[name] = parse_pose_text(getattr(state, name), f"--{name}")
        except InvalidParameterError as err:
            errors[name] = one_line(err)
    fields: dict[str, Any] = {}
    options: dict[str, Any] = {}
    for p in entry.parameters:
        text = state.values.get(p.name, p.default)
        try:
            parsed = p.parse(text)
        except InvalidParameterError as err:
            errors[p.name] = one_line(err)
            continue
        (fields if p.target == "vehicle" else options).update(parsed)
    if errors:
        return None, errors
    try:
        vehicle = entry.build_vehicle(fields)
    except InvalidParameterError as err:
        owner = entry.parameter(err.name)
        name = owner.name if owner is not None else ""
        if owner is not None:
            err = InvalidParameterError(owner.flag, err.value, err.rule)
        return None, {name: one_line(err)}
    except (TypeError, ValueError) as err:
        return None, {"": one_line(err)}
    return Request(entry, poses["start"], poses["goal"], vehicle, options), {}


def one_line(err: BaseException) -> str:
    """The CLI's one-line message (whitespace collapsed), without the 'glideplan: error:'."""
    return " ".join(str(err).split())
