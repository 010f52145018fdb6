"""A grid too coarse for a current stronger than the vehicle: the front again on finer grids.

Where the current reaches the vehicle's speed V, the route is the front's characteristic
flown with its own times and headings (`routing.extract`). On a grid coarse against the
field's features the front's arrival map is itself wrong and its characteristic cannot be
flown: the double gyre (L = 100 km, 0.3 m/s) from (30.2, -39.8) to (30.7, -38.3) at 0.05 m/s
has its front arrive in 517.6 h on a 3000 m grid and 512.8 h on 1500 m (both routes leave
the field when flown; their held legs claim 24,959 h and 17,989 h), 345.6 h on 750 m
(solved), 339.3 h on the default 617 m (solved).

The criterion is the one that decides `solved`: verification. A spacing rule such as h <= k
L V / |c|max would need k between 0.045 and 0.09 on that one field (0.05 m/s fails at 1500
m, 0.07 m/s flies at 1500 m and fails at 3000 m), so it would refine routes that fly and
keep ones that do not. When a route in such a current does not verify on a grid coarser than
the default one (the start-goal distance over the default `RouteSettings.cells`), `route()`
runs again at half the spacing, down to the default grid, and keeps the first route that
verifies, with a warning naming the grid used and why. A front on such a grid can also stop
short of the goal by its own limits (the double gyre at 0.05 m/s on a 12 km grid is
"unreachable within 8,564 h", a 345.6 h route on 750 m): that answer is not rerun (the
default grid's front to the time limit costs a minute and more: 62 s for 0.02 m/s from an 8
km grid, which then ends not verified), its message advises the default grid's --resolution.
The front's cost grows about as h^-3 (nodes x steps), so the coarser fronts add about 1/8 +
1/64 + ... of the last one, but each grid also pays its backtrack, tracking and
verification: the 0.05 m/s case from 3000 m took 11.0 s against 21.1 s for the default grid
alone in one run, 17.3 s against 13.5 s in another (a shared machine, load 1-6). Routes that
verify (every route on the default grid that does) pay nothing: the ladder starts only after
a failed verification. Without refinement (`refine=False`, the replanner's quick routes)
there is no ladder.

When no grid verifies, the answer stays `not_verified` with one sentence naming the grid,
why, and a `--resolution` that may fly it (half the finest tried), and carries no duration
(`duration_s` None): the held legs' time is not a flown time. The front's arrival stays in
`grid_duration_s`, the track and its times as they were.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

from glideplan.errors import InvalidParameterError
from glideplan.routing.settings import RouteSettings
from glideplan.solution import Status

__all__ = ["Attempt", "default_spacing", "finer", "ladder"]


#: The unreachable answers of the front's own limits, which a finer grid may overturn (the
#: others -- window_limit, missing_data, polar_limit, outside_drift_cone -- it cannot).
RETRY_REASONS = ("front_stopped", "field_extent", "time_span", "max_duration")


@dataclass(frozen=True)
class Attempt:
    """One grid's answer: the result, whether the current reached the vehicle's speed on
    its window (`strong`), that peak (m/s) and how the flown controls missed ("" when no
    route was found)."""

    result: Any
    strong: bool = False
    peak_mps: float = 0.0
    miss: str = ""


def default_spacing(problem: Any) -> float:
    """The default routing spacing (m): the start-goal distance over the default cells."""
    return max(problem.distance_m / RouteSettings().cells, 1.0)


def ladder(h0: float, floor: float) -> list[float]:
    """The finer spacings to try after h0 (m): halving, the last clamped to `floor`;
    h_k = max(h0 / 2^k, floor) while h_{k-1} > floor."""
    out: list[float] = []
    h = h0
    while h > floor * (1 + 1e-9):
        h = max(h / 2.0, floor)
        out.append(h)
    return out


def finer(problem: Any, first: Attempt, run: Callable[[Any], Attempt]) -> Any:
    """The route when `first` (in a current stronger than the vehicle) failed. Not
    verified: the first finer grid's route that verifies (with a warning), else `first`'s
    result without a duration in the one sentence of the module docstring. Unreachable by
    the front's own limit on a grid coarser than the default: `first`'s result with the
    advice to check on the default grid (nothing rerun)."""
    h0 = float(first.result.stats["spacing_m"])
    floor = default_spacing(problem)
    if first.result.status is Status.UNREACHABLE:
        return _advised(problem, first, h0, floor)
    steps = ladder(h0, floor) if problem.settings.refine else []
    tried: list[tuple[float, Attempt, float]] = [(h0, first, _wall(first.result))]
    for h in steps:
        t = time.perf_counter()
        try:
            att = run(replace(problem, settings=replace(problem.settings, resolution=h)))
        except InvalidParameterError:  # e.g. the window would exceed max_nodes
            break
        if att.result.status is Status.UNREACHABLE:  # a finer front stops short: stop here
            break
        tried.append((h, att, time.perf_counter() - t))
        if att.result.ok:
            return _used(problem, tried)
    return _not_flown(problem, tried)


def _advised(problem: Any, first: Attempt, h0: float, floor: float) -> Any:
    """An unreachable answer of the front's own limit on a grid coarser than the default,
    with the advice to check it there (a coarse front can stall short of a reachable goal:
    the double gyre at 0.05 m/s on 12 km is unreachable within 8,564 h, a 345.6 h route on
    750 m); rerunning it would cost the default grid's front to the time limit (62 s for
    the double gyre at 0.02 m/s from 8 km), so it is advice only."""
    res = first.result
    if res.unreachable_reason not in RETRY_REASONS or h0 <= floor * (1 + 1e-9):
        return res
    advice = (f"; the front ran on a {h0:.0f} m grid in a current faster than the vehicle "
              f"({first.peak_mps:.2g} against {problem.speed:g} m/s), where a coarse grid "
              f"can stall it short of a reachable goal: --resolution {floor:.0f} (the "
              "default grid) checks")
    return replace(res, message=res.message + advice)


def _wall(result: Any) -> float:
    """The phases' wall time (s) recorded in a result's stats."""
    return float(sum(v for k, v in result.stats.items()
                     if k.endswith("_s") and isinstance(v, float)))


def _stats(result: Any, tried: list[tuple[float, Attempt, float]]) -> dict[str, Any]:
    """`result`'s stats with the grids tried: spacing (m), status, the front's arrival (s
    after departure) and wall time (s) of each."""
    return {**result.stats, "grids": [
        {"spacing_m": h, "status": a.result.status.value,
         "front_duration_s": a.result.grid_duration_s, "wall_s": round(w, 4)}
        for h, a, w in tried]}


def _used(problem: Any, tried: list[tuple[float, Attempt, float]]) -> Any:
    """The verified route of the last grid tried, warning why the user's grid was left."""
    h0, first, _ = tried[0]
    h, att, _ = tried[-1]
    middle = [f"{g:.0f} m" for g, _, _ in tried[1:-1]]
    warning = (
        f"the {h0:.0f} m routing grid is too coarse for this route: the current reaches "
        f"{first.peak_mps:.2g} m/s, faster than the vehicle's {problem.speed:g} m/s, and "
        f"the route the front found on it cannot be flown ({first.miss}); routed on a "
        f"{h:.0f} m grid instead"
        + (f" ({', '.join(middle)} gave no flyable route either)" if middle else "")
        + f"; --resolution {h:.0f} gives this route at once")
    res = att.result
    return replace(res, warnings=(*res.warnings, warning), stats=_stats(res, tried))


def _not_flown(problem: Any, tried: list[tuple[float, Attempt, float]]) -> Any:
    """The first grid's result (every grid tried was not verified): one sentence, no
    duration."""
    h0, first, _ = tried[0]
    finest = min(h for h, _, _ in tried)
    finer_ones = [f"{h:.0f} m" for h, _, _ in tried[1:]]
    message = (
        f"the route the front found on the {h0:.0f} m grid cannot be flown ({first.miss})"
        + (f", nor can those on {', '.join(finer_ones)}" if finer_ones else "")
        + f": the current reaches {first.peak_mps:.2g} m/s, faster than the vehicle's "
        f"{problem.speed:g} m/s, and {'these grids are' if finer_ones else 'the grid may be'}"
        f" too coarse for it; a --resolution of {finest / 2:.0f} m or finer may fly it (no "
        "duration is given: none was flown)")
    res = first.result
    return replace(res, message=message, duration_s=None, stats=_stats(res, tried))
