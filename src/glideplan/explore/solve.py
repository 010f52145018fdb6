"""Plan the explorer's request and turn the `Solution` into the figure's data (NumPy only).

`solve_view(catalog, state)` calls `glideplan.plan()` in-process and returns a `View`: the
optimal path (and, in a wind, its air-relative track x_air = x_ground - w t), every candidate
sampled along its path, the candidates table, the controls along the path for variable-speed
vehicles (speed, and bank angle / load factor where the vehicle defines them), and the texts
of the result strip. No plotting library is imported here.
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.explore.catalog import Catalog, PlannerEntry
from glideplan.explore.state import ExploreState, Request, one_line, request
from glideplan.results import BAD_INPUT

__all__ = ["View", "cost_unit", "partition_image", "solve_view", "with_candidates"]

_COST_UNITS: Mapping[str, str] = {"length": "m", "time": "s", "altitude": "m"}
_PATH_SAMPLES = 240
_CANDIDATE_SAMPLES = 40
_PROFILE_SAMPLES = 160


@dataclass(frozen=True, eq=False)
class View:
    """Everything the page draws for one state (arrays in world metres, headings in degrees)."""

    state: ExploreState
    entry: PlannerEntry | None
    errors: Mapping[str, str]
    solution: Any = None  # glideplan.Solution
    request: Request | None = None
    seconds: float = 0.0
    path: dict[str, np.ndarray] = field(
        default_factory=lambda: {"x": np.zeros(0), "y": np.zeros(0)}
    )
    air_path: dict[str, np.ndarray] | None = None
    candidates: dict[str, list[Any]] = field(default_factory=dict)
    profile: dict[str, np.ndarray] | None = None
    profile_labels: tuple[str, str] = ("speed (m/s)", "turn rate (deg/s)")
    wind: tuple[float, float] | None = None
    units: str = ""
    candidates_pending: bool = False  # solved, its candidates not yet sampled

    @property
    def ok(self) -> bool:
        return self.solution is not None and bool(self.solution.ok)

    @property
    def cost_text(self) -> str:
        """The optimal cost with 10 significant digits (the `gp-cost` element)."""
        return f"{self.solution.cost:.10g}" if self.ok else "n/a"

    @property
    def word(self) -> str:
        return str(self.solution.word) if self.ok else ""

    @property
    def family(self) -> str:
        return str(self.solution.family) if self.ok else ""

    @property
    def status(self) -> str:
        if self.errors:
            return BAD_INPUT
        if self.solution is None:
            return ""
        s = self.solution
        return str(s.status.value) + (f": {s.message}" if not s.ok and s.message else "")

    @property
    def method_text(self) -> str:
        """The method that answered: the planner's own, or the direct method where a
        synthesis found no candidate (its answer's `answered_by`); '' without an answer."""
        if self.entry is None or self.solution is None:
            return ""
        extras = getattr(self.solution, "extras", None) or {}
        answered = str(extras.get("answered_by", self.entry.method))
        if answered != self.entry.method:
            return f"{answered} ({self.entry.method}: no candidate)"
        return answered

    @property
    def endpoint_text(self) -> str:
        err = self.solution.endpoint_error if self.ok else None
        if err is None:
            return "n/a"
        unit = self.entry.length_unit if self.entry is not None else "m"
        return f"{err.position:.1e} {unit}, {math.degrees(err.heading):.1e} deg"

    @property
    def time_text(self) -> str:
        if self.solution is None:
            return "n/a"
        planner = float(self.solution.stats.get("planner_seconds", math.nan))
        return f"{1e3 * planner:.1f} ms planner, {1e3 * self.seconds:.1f} ms with verification"


def _units(entry: PlannerEntry) -> str:
    """The length unit of the entry's vehicle: 'm' or 'nondim.'."""
    return entry.length_unit


def _sample_path(path: Any, n: int) -> dict[str, np.ndarray]:
    s = path.sample(n=max(n, 40 * len(path.segments)))
    return {"x": s.x, "y": s.y, "t": s.t}


def _profile(path: Any, vehicle: Any) -> tuple[dict[str, np.ndarray], tuple[str, str]]:
    """Controls along the path against time, with both sides of every switch."""
    durations = np.array([seg.duration for seg in path.segments])
    edges = np.cumsum(durations)[:-1]
    total = float(durations.sum())
    eps = 1e-9 * max(total, 1.0)
    times = np.unique(
        np.concatenate(
            [np.linspace(0.0, total, _PROFILE_SAMPLES), edges, np.maximum(edges - eps, 0)]
        )
    )
    s = path.sample(times=times)
    out = {"t": s.t, "speed": s.speed}
    if hasattr(vehicle, "bank_angle") and hasattr(vehicle, "load_factor"):
        out["second"] = np.degrees(vehicle.bank_angle(s.speed, s.turn_rate))
        out["third"] = vehicle.load_factor(s.speed, s.turn_rate)
        return out, ("speed", "bank angle (deg)")
    out["second"] = np.degrees(s.turn_rate)  # degrees at the page's edge, as the inputs
    return out, ("speed", "turn rate (deg/s)")


def cost_unit(entry: PlannerEntry | None) -> str:
    """The unit of the entry's cost: m for length and altitude, s for time ('nondim.' for a
    nondimensional vehicle); '' without an entry."""
    if entry is None:
        return ""
    if entry.nondimensional:
        return "nondim."
    return {"length": "m", "time": "s", "altitude": "m"}.get(entry.objective, "")


def _variable_speed(vehicle: Any) -> bool:
    fields = getattr(type(vehicle), "__dataclass_fields__", {})
    return "speed" not in fields


def solve_view(catalog: Catalog, state: ExploreState, candidates: bool = True) -> View:
    """Plan `state` with `glideplan.plan()` and build the figure data (see the module doc).

    `candidates=False` leaves the candidates' lines and table for `with_candidates` (the
    page shows the answer first and the candidates a moment later)."""
    from glideplan import plan

    req, errors = request(catalog, state)
    entry = catalog.get(state.planner) if not errors.get("planner") else None
    if req is None:
        return View(state, entry, errors)
    assert entry is not None
    t0 = time.perf_counter()
    try:
        solution = plan(
            req.start,
            req.goal,
            req.vehicle,
            entry.objective,
            entry.method,
            **dict(req.options),
        )
    except InvalidParameterError as err:
        bare = err.name.lstrip("-").replace("-", "_")
        p = entry.parameter(bare)
        name = p.name if p is not None else (bare if bare in ("start", "goal") else "")
        if p is not None:
            err = InvalidParameterError(p.flag, err.value, err.rule)
        return View(state, entry, {name: one_line(err)}, request=req)
    seconds = time.perf_counter() - t0
    units = _units(entry)
    view: dict[str, Any] = {"units": units}
    wind = getattr(req.vehicle, "wind", None)
    if wind is not None:
        view["wind"] = (float(wind[0]), float(wind[1]))
    if solution.path is not None:
        path = _sample_path(solution.path, _PATH_SAMPLES)
        view["path"] = path
        if wind is not None:
            view["air_path"] = {
                "x": path["x"] - wind[0] * path["t"],
                "y": path["y"] - wind[1] * path["t"],
            }
        if _variable_speed(req.vehicle):
            view["profile"], view["profile_labels"] = _profile(solution.path, req.vehicle)
    if candidates:
        view["candidates"] = _candidates(solution)
    else:
        view["candidates_pending"] = True
    return View(state, entry, {}, solution, req, seconds, **view)


def with_candidates(view: View) -> View:
    """`view` with its candidates sampled (as `solve_view(..., candidates=True)`)."""
    if not view.candidates_pending or view.solution is None:
        return view
    return replace(view, candidates=_candidates(view.solution), candidates_pending=False)


def _candidates(solution: Any) -> dict[str, list[Any]]:
    """Columns of the candidates table and lines: every candidate, the feasible with a track."""
    cols: dict[str, list[Any]] = {
        k: [] for k in ("xs", "ys", "word", "family", "cost", "cost_text", "status", "rank")
    }
    best = solution.path
    for i, c in enumerate(solution.candidates):
        if c.path is not None and c.feasible:
            # grey background lines: 10 points per segment at least (they travel as JSON
            # numbers, whose encoding was the page's largest cost for minimum time's 13)
            s = c.path.sample(n=max(_CANDIDATE_SAMPLES, 10 * len(c.path.segments)))
            xs, ys = s.x, s.y
        else:
            xs, ys = np.zeros(0), np.zeros(0)
        cols["xs"].append(xs)
        cols["ys"].append(ys)
        cols["word"].append(c.word)
        cols["family"].append(c.family)
        finite = math.isfinite(c.cost)
        cols["cost"].append(float(c.cost) if finite else math.nan)
        cols["cost_text"].append(f"{c.cost:.8g}" if finite else "")
        optimal = best is not None and c.path is best
        cols["status"].append("optimal" if optimal else str(c.status))
        cols["rank"].append(i + 1)
    return cols


# ----- partition map background (Dubins car) ---------------------------------------------------
_WORD_COLOURS: Mapping[str, tuple[int, int, int]] = {
    "LSL": (78, 121, 167),
    "LSR": (242, 142, 43),
    "RSL": (89, 161, 79),
    "RSR": (225, 87, 89),
    "RLR": (176, 122, 161),
    "LRL": (118, 183, 178),
}


def partition_image(
    req: Request, bounds: tuple[float, float, float, float], n: int = 160
) -> dict[str, Any] | None:
    """The optimal Dubins word over the visible plane for the goal's heading (Fig 3.1).

    Computed with `glideplan.studies.maps.partition_map` in the start's frame (units of R0,
    radius R0 (1 + eps)^2), then looked up at an `n` x `n` grid over `bounds` = (x0, x1, y0, y1)
    in world metres. Returns an RGBA image (uint32, rows by y), its placement and one label
    point per word; None for vehicles without a single turn radius and no wind.
    """
    vehicle = req.vehicle
    if getattr(vehicle, "wind", None) is not None or not hasattr(vehicle, "turn_radius"):
        return None
    from glideplan.studies.maps import partition_map, partition_regions

    r0 = float(vehicle.turn_radius)
    eps = float(req.options.get("disturbance_ratio", 0.0))
    x0, x1, y0, y1 = bounds
    gx, gy = np.meshgrid(np.linspace(x0, x1, n), np.linspace(y0, y1, n))
    c, s = math.cos(req.start.heading), math.sin(req.start.heading)
    dx, dy = gx - req.start.x, gy - req.start.y
    u, v = (c * dx + s * dy) / r0, (-s * dx + c * dy) / r0
    extent = float(max(np.abs(u).max(), np.abs(v).max(), 1.0)) * 1.01
    m = 241
    pmap = partition_map(req.goal.heading - req.start.heading, extent=extent, n=m, eps=eps)
    step = 2.0 * extent / (m - 1)
    j = np.clip(np.rint((u + extent) / step).astype(int), 0, m - 1)
    i = np.clip(np.rint((v + extent) / step).astype(int), 0, m - 1)
    index = pmap.label_index[i, j]
    first = [lab.split("/")[0] for lab in pmap.labels]
    rgba = np.zeros((len(first), 4), dtype=np.uint8)
    for k, w in enumerate(first):
        rgba[k, :3] = _WORD_COLOURS.get(w, (200, 200, 200))
        rgba[k, 3] = 70
    img = rgba[index].view(np.uint32).reshape(n, n)
    labels: dict[str, list[Any]] = {"x": [], "y": [], "text": []}
    for region in partition_regions(pmap, min_points=max(12, m * m // 400)):
        wx = req.start.x + r0 * (c * region.x - s * region.y)
        wy = req.start.y + r0 * (s * region.x + c * region.y)
        if x0 <= wx <= x1 and y0 <= wy <= y1:
            labels["x"].append(wx)
            labels["y"].append(wy)
            labels["text"].append(region.label)
    return {"image": img, "x": x0, "y": y0, "dw": x1 - x0, "dh": y1 - y0, "labels": labels}
