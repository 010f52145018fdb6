"""The turn-back search (`reach.turnback`): probes of the return home from points along the
course (`_Prober`), the search along the course (`_search`) and the backward search's
crossing (`_graph_crossing`). Split from `turnback.py` to keep each module under 500 lines.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.flight import FlownPath, fly, front_candidates
from glideplan.reach.grid import ReachGrid
from glideplan.reach.model import Glide
from glideplan.reach.problem import ReachProblem
from glideplan.results import Reason
from glideplan.terrain.grid import Terrain

if TYPE_CHECKING:
    from glideplan.reach.turnback import TurnbackRequest, _Outbound

__all__ = ["grid_contains"]

FloatArray = NDArray[np.float64]
_REFINE_TOL_M = 1.0
_MAX_PROBES = 60


class _Prober:
    """The returns home from points along the course: the backward search from home on the
    terrain's own grid (with terrain), a probe at s (the straight return and the search's
    node path, string-pulled and flown; the best that arrives clear), and the flights of a
    known return's tail from further out. `probes`: (s, reachable) of every probe."""

    def __init__(self, req: TurnbackRequest, problem: ReachProblem, grid: ReachGrid,
                 way: _Outbound) -> None:
        self.req, self.way, self.fine = req, way, problem.terrain
        self.probes: list[tuple[float, bool]] = []
        self.notes: list[str] = []
        self.spacing = grid.spacing_m  # the search's grid (the terrain's own unless pooled)
        self.cell = grid.spacing_m
        home = req.home
        self.home_in = bool(grid_contains(grid, np.array(home.lat), np.array(home.lon)))
        self.back_s: Any = None
        self.sterrain: Terrain | None = None
        if req.terrain is not None and self.home_in:
            from glideplan.reach.grid import native_terrain
            from glideplan.reach.native import native_back_search

            sterrain, _, notes, _ = native_terrain(problem, req.glide.max_ratio,
                                                   req.clearance_m)
            self.notes += notes
            self.sterrain = sterrain
            self.spacing = max(sterrain.spacing_m)
            self.cell = min(sterrain.spacing_m)
            self.back_s = native_back_search(
                sterrain, (home.lat, home.lon, home.elevation_m + req.arrival_m), req.glide,
                req.clearance_m, way.alt + 1.0)

    def arrives(self, f: FlownPath) -> bool:
        """The flight keeps the clearance and arrives at or above home + arrival height."""
        return f.clear and (f.arrival_altitude - self.req.home.elevation_m
                            - self.req.arrival_m >= -1e-6)

    def probe(self, s: float) -> tuple[bool, FlownPath | None]:
        """Is home reachable from s metres out? The best verified return, or None."""
        req, home = self.req, self.req.home
        la, lo, a = self.way.at(s)
        cands = [fly(req.glide, self.fine, req.clearance_m, np.array([la, home.lat]),
                     np.array([lo, home.lon]), a)]
        if self.back_s is not None and self.sterrain is not None:
            from glideplan.reach.native import back_path, need_at

            nd, i, j = need_at(self.back_s, self.sterrain, req.glide, la, lo)
            if math.isfinite(nd):
                bla, blo = back_path(self.back_s, self.sterrain, i, j)
                cands += front_candidates(req.glide, self.fine, req.clearance_m,
                                          np.concatenate([[la], bla, [home.lat]]),
                                          np.concatenate([[lo], blo, [home.lon]]), a)
        good = [c for c in cands if self.arrives(c)]
        best = max(good, key=lambda c: c.arrival_altitude) if good else None
        self.probes.append((s, best is not None))
        return best is not None, best

    def flight(self, s: float, tail_la: FloatArray, tail_lo: FloatArray) -> FlownPath:
        """The return from s metres out along the given tail of waypoints, flown."""
        la, lo, a = self.way.at(s)
        return fly(self.req.glide, self.fine, self.req.clearance_m,
                   np.concatenate([[la], tail_la]), np.concatenate([[lo], tail_lo]), a)

    def along_path(self, path: FlownPath, a_: float, b_: float) -> tuple[float, FlownPath]:
        """Largest s in [a_, b_] from which the path's tail (its waypoints after the first)
        still works, flown (bisection to 1 m); (a_, path) if not even at a_."""
        tail_la, tail_lo = path.waypoints_lat[1:], path.waypoints_lon[1:]
        best = self.flight(a_, tail_la, tail_lo)
        if not self.arrives(best):
            return a_, path
        end = self.flight(b_, tail_la, tail_lo)
        if self.arrives(end):
            return b_, end
        while b_ - a_ > _REFINE_TOL_M:
            mid = 0.5 * (a_ + b_)
            f = self.flight(mid, tail_la, tail_lo)
            if self.arrives(f):
                a_, best = mid, f
            else:
                b_ = mid
        return a_, best


def _search(prober: _Prober, s_hi: float, path0: FlownPath, limited: Reason,
            warnings: list[str]) -> tuple[float, FlownPath, Reason]:
    """The turn-back distance along the course (module docstring): s_hi if its return
    works, else the backward search's crossing (`_graph_crossing`), then the verified
    return's tail flown from further out and a probe a third of a cell beyond, until the
    probe fails; SEARCH_BUDGET (and a warning) when _MAX_PROBES run out."""
    s_lo, back = 0.0, path0
    ok_hi, path_hi = prober.probe(s_hi) if s_hi > 0 else (True, path0)
    if ok_hi and path_hi is not None:
        return s_hi, path_hi, limited
    cell = prober.cell
    if prober.back_s is not None and prober.sterrain is not None:
        s_lo, back = _graph_crossing(prober.back_s, prober.sterrain, prober.req.glide,
                                     prober.way.at, s_hi, cell, prober.probe, s_lo, back)
    for _ in range(_MAX_PROBES):
        s_lo, back = prober.along_path(back, s_lo, s_hi)
        s_next = s_lo + cell / 3.0
        if s_next >= s_hi:
            break
        ok, path = prober.probe(s_next)
        if not ok or path is None:
            break
        s_lo, back = s_next, path
    else:
        limited = Reason.SEARCH_BUDGET
        warnings.append(f"the search stopped after {_MAX_PROBES} probes: the turn-back "
                        f"point is at least {s_lo / 1000:.2f} km out (a lower bound)")
    return s_lo, back, limited


def _graph_crossing(back_s: Any, sterrain: Terrain, glide: Glide, P: Any, s_hi: float,
                    cell: float, probe: Any, s_lo: float, back: FlownPath
                    ) -> tuple[float, FlownPath]:
    """The backward search's answer along the course, verified: walk s in thirds of a cell
    from 0 to the first point where the altitude there is below the altitude needed
    (`native.need_at`), then the largest s before it whose return flies clear (a probe there;
    if the flight does not verify, bisection on s with probes down to s_lo)."""
    from glideplan.reach.native import need_at

    ss = np.arange(0.0, s_hi, cell / 3.0)
    s_graph = s_lo
    for s in ss[1:]:
        la, lo, a = P(float(s))
        if need_at(back_s, sterrain, glide, la, lo)[0] > a:
            break
        s_graph = float(s)
    if s_graph <= s_lo:
        return s_lo, back
    ok, path = probe(s_graph)
    if ok and path is not None:
        return s_graph, path
    a_, b_ = s_lo, s_graph
    while b_ - a_ > cell / 3.0:
        mid = 0.5 * (a_ + b_)
        ok, path = probe(mid)
        if ok and path is not None:
            a_, back = mid, path
        else:
            b_ = mid
    return a_, back


def grid_contains(grid: ReachGrid, lat: FloatArray, lon: FloatArray) -> NDArray[np.bool_]:
    """Inside the front's grid (its nodes' extent)."""
    return ((lat >= grid.lat[0]) & (lat <= grid.lat[-1]) & (lon >= grid.lon[0])
            & (lon <= grid.lon[-1]))
