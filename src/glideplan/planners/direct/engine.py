"""The direct-method engine: multi-start collocation with mesh refinement (see `solve_direct`)."""

from __future__ import annotations

import math
import time
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.direct.collocation import Transcription, build_transcription
from glideplan.planners.direct.multistart import (
    Converged,
    Deadline,
    Refined,
    check_options,
    failed,
    refine,
)
from glideplan.planners.direct.results import DirectResult, StartResult
from glideplan.planners.direct.system import ControlSystem
from glideplan.planners.direct.timing import fly_controls, retime
from glideplan.pose import TWO_PI, Pose, wrap_to_pi
from glideplan.segments import Sampled
from glideplan.solution import Status
from glideplan.validation import check_nonnegative, check_positive

__all__ = ["DirectResult", "StartResult", "fly_controls", "retime", "solve_direct"]

_OK_STATUSES = {"Solve_Succeeded", "Solved_To_Acceptable_Level"}


@dataclass
class _Solve:
    ok: bool
    status: str
    cost: float
    w: np.ndarray
    iterations: int
    transcription: Transcription
    fractions: np.ndarray


def _as_matrix(value: Any) -> np.ndarray:
    return np.asarray(value, dtype=float)


class _Problem:
    """Everything fixed for one `solve_direct` call."""

    def __init__(
        self,
        goal: Pose,
        system: ControlSystem,
        scheme: str,
        degree: int,
        length_scale: float,
        time_scale: float,
        ipopt_options: tuple[tuple[str, Any], ...],
        smoothing: float,
        retime: bool,
        clock: Deadline,
        drift: tuple[float, float] = (0.0, 0.0),
    ) -> None:
        self.drift = drift
        self.clock = clock
        self.smoothing = smoothing
        self.retime = retime
        self.goal = goal
        self.system = system
        self.scheme = scheme
        self.degree = degree
        self.Ls = length_scale
        self.Ts = time_scale
        self.ipopt_options = ipopt_options
        self.lower = np.array(system.lower)
        self.upper = np.array(system.upper)

    def transcription(self, n: int) -> Transcription:
        """The NLP on n intervals; with a time limit, IPOPT's `max_wall_time` is the budget."""
        opts = self.ipopt_options
        budget = self.clock.budget()
        if budget is not None:
            opts = tuple(sorted({**dict(opts), "max_wall_time": budget}.items()))
        return build_transcription(self.system, self.scheme, n, self.degree, opts)

    def params(self, k: int, fractions: np.ndarray, cost_scale: float) -> np.ndarray:
        g = self.goal
        return np.concatenate(
            [
                [g.x / self.Ls, g.y / self.Ls, g.heading + TWO_PI * k],
                fractions,
                [self.Ls, self.Ts, cost_scale, self.smoothing, *self.drift],
            ]
        )

    def bounds(self, tr: Transcription) -> tuple[np.ndarray, np.ndarray]:
        m = self.system.n_controls
        lbz = np.full((3, tr.n_state_points), -np.inf)
        ubz = np.full((3, tr.n_state_points), np.inf)
        lbz[:, 0] = ubz[:, 0] = 0.0
        lbu = np.repeat(self.lower[:, None], tr.n_control_points, axis=1).reshape(m, -1)
        ubu = np.repeat(self.upper[:, None], tr.n_control_points, axis=1).reshape(m, -1)
        return tr.pack(1e-6, lbz, lbu), tr.pack(np.inf, ubz, ubu)

    def solve(
        self,
        tr: Transcription,
        w0: np.ndarray,
        k: int,
        fractions: np.ndarray,
        cost_scale: float,
    ) -> _Solve:
        lbx, ubx = self.bounds(tr)
        w0 = np.clip(w0, lbx, ubx)
        p = self.params(k, fractions, cost_scale)
        sol = tr.solver(
            x0=w0,
            p=p,
            lbx=lbx,
            ubx=ubx,
            lbg=tr.lbg,
            ubg=tr.ubg,
        )
        st = tr.solver.stats()
        status = str(st.get("return_status", "unknown"))
        w = _as_matrix(sol["x"]).reshape(-1)
        cost = float(tr.objective(w, p))
        ok = status in _OK_STATUSES and bool(np.all(np.isfinite(w))) and math.isfinite(cost)
        if ok:  # IPOPT's "acceptable" level can hide a sizeable violation: check it
            g = _as_matrix(sol["g"]).reshape(-1)
            viol = np.maximum(tr.lbg - g, 0.0) + np.maximum(g - tr.ubg, 0.0)
            ok = bool(np.max(viol, initial=0.0) < 1e-6)
            if not ok:
                status = "constraint_violation"
        return _Solve(ok, status, cost, w, int(st.get("iter_count", -1)), tr, fractions)

    # ----- initial guesses -----------------------------------------------------------------
    def from_path(self, tr: Transcription, fractions: np.ndarray, path: Path) -> tuple:
        T0 = path.duration
        zs = path.sample(times=tr.state_tau(fractions) * T0)
        cs = path.sample(times=tr.control_tau(fractions) * T0)
        Z = np.stack([zs.x / self.Ls, zs.y / self.Ls, zs.heading])
        U = self.system.guess_controls(cs.speed, cs.turn_rate).T
        k = round((path.end.heading - self.goal.heading) / TWO_PI)
        return tr.pack(T0 / self.Ts, Z, U), int(k)

    def guess_cost(self, tr: Transcription, fractions: np.ndarray, w0: np.ndarray) -> float:
        T, _, U = tr.unpack(w0)
        tau = tr.control_tau(fractions)
        L = _as_matrix(tr.cost_rate(U)).reshape(-1)
        return float(abs(np.trapezoid(L, tau)) * T * self.Ts)

    # ----- refinement ----------------------------------------------------------------------
    def refine(self, prev: _Solve, k: int, cost_scale: float) -> _Solve:
        fr = np.repeat(prev.fractions / 2.0, 2)
        tr = self.transcription(prev.transcription.n_intervals * 2)
        T, _, _ = prev.transcription.unpack(prev.w)
        Z, _ = prev.transcription.interpolate(
            prev.w, prev.fractions, tr.state_tau(fr), self.Ls, self.Ts, self.drift
        )
        _, U = prev.transcription.interpolate(
            prev.w, prev.fractions, tr.control_tau(fr), self.Ls, self.Ts, self.drift
        )
        return self.solve(tr, tr.pack(T, Z, U), k, fr, cost_scale)

    # ----- output -------------------------------------------------------------------------
    def output(
        self, best: _Solve, density: int, k: int
    ) -> tuple[Path, dict[str, np.ndarray], dict[str, Any]]:
        tr, fr = best.transcription, best.fractions
        nodes = tr.mesh(fr)
        sub = np.arange(density) / density
        tau = np.concatenate([(nodes[:-1, None] + np.diff(nodes)[:, None] * sub).ravel(), [1.0]])
        _, U = tr.interpolate(best.w, fr, tau, self.Ls, self.Ts, self.drift)
        U = self._admissible(tr, fr, best.w, tau, U)
        T = tr.unpack(best.w)[0] * self.Ts
        t = tau * T
        speed_dm, turn_dm = tr.kinematics(U)
        speed = _as_matrix(speed_dm).reshape(-1)
        turn = _as_matrix(turn_dm).reshape(-1)
        g = self.goal
        info: dict[str, Any] = {"raw_endpoint_error": self._error(t, speed, turn)}
        if self.retime:
            target = np.array([g.x, g.y, g.heading + TWO_PI * k])
            t_new, stretch, ok = retime(
                t, speed, turn, target, length_scale=self.Ls, drift=self.drift
            )
            info["retime_stretch"] = stretch
            if ok:
                t = t_new
            else:
                raw = info["raw_endpoint_error"]
                info["retime_failed"] = (
                    "re-timing the controls to end exactly at the goal failed (stretch "
                    f"{stretch:.3g}, limit 0.05); the path keeps the collocation timing, "
                    f"whose controls miss the goal by {raw['position']:.3g} m and "
                    f"{raw['heading']:.3g} rad"
                )
        info["endpoint_error"] = self._error(t, speed, turn)
        x, y, psi = fly_controls(t, speed, turn, drift=self.drift)
        seg = Sampled(t, x, y, psi, speed, turn, label="D", info={"system": self.system.name})
        controls = {"t": t, "speed": speed, "turn_rate": turn}
        controls.update({n: U[i] for i, n in enumerate(self.system.control_names)})
        return Path((seg,)), controls, info

    def _admissible(
        self, tr: Transcription, fr: np.ndarray, w: np.ndarray, tau: np.ndarray, U: np.ndarray
    ) -> np.ndarray:
        """Clip interpolated controls to the box; repair nonlinear-constraint violations.

        Between collocation points the interpolant can leave a nonlinear constraint set
        (e.g. overshoot at a switch); such points take the control-space average of the
        neighbouring collocation points, or the nearer one if that is still inadmissible.
        """
        # Limit the interpolant to the range of the two bracketing collocation values: exact
        # to O(h^2) where the control is smooth, and no overshoot across a switch.
        _, _, Uc = tr.unpack(w)
        tc = tr.control_tau(fr)
        j = np.clip(np.searchsorted(tc, tau), 1, tc.size - 1)
        lower = np.minimum(Uc[:, j - 1], Uc[:, j])
        upper = np.maximum(Uc[:, j - 1], Uc[:, j])
        before, after = tau <= tc[0], tau >= tc[-1]
        lower[:, before], upper[:, before] = Uc[:, [0]], Uc[:, [0]]
        lower[:, after], upper[:, after] = Uc[:, [-1]], Uc[:, [-1]]
        inside = ~(before | after)
        U[:, inside] = np.clip(U[:, inside], lower[:, inside], upper[:, inside])
        U = np.clip(U, self.lower[:, None], self.upper[:, None])
        lo, hi = self._path_bounds(tr)
        if lo.size == 0:
            return U
        bad = self._violation(tr, U, lo, hi) > 1e-9
        if not np.any(bad):
            return U
        j = np.clip(np.searchsorted(tc, tau[bad]), 1, tc.size - 1)
        a, b = tc[j - 1], tc[j]
        lam = np.clip((tau[bad] - a) / (b - a), 0.0, 1.0)
        avg = Uc[:, j - 1] * (1 - lam) + Uc[:, j] * lam
        near = np.where(lam < 0.5, Uc[:, j - 1], Uc[:, j])
        still = self._violation(tr, avg, lo, hi) > 1e-9
        U[:, bad] = np.where(still, near, avg)
        return np.clip(U, self.lower[:, None], self.upper[:, None])

    @staticmethod
    def _path_bounds(tr: Transcription) -> tuple[np.ndarray, np.ndarray]:
        npc = tr.path.size1_out(0)
        return tr.lbg[-npc:] if npc else np.zeros(0), tr.ubg[-npc:] if npc else np.zeros(0)

    @staticmethod
    def _violation(tr: Transcription, U: np.ndarray, lo: np.ndarray, hi: np.ndarray) -> np.ndarray:
        G = _as_matrix(tr.path(U)).reshape(lo.size, -1)
        return np.max(np.maximum(lo[:, None] - G, 0.0) + np.maximum(G - hi[:, None], 0.0), axis=0)

    def _error(self, t: np.ndarray, speed: np.ndarray, turn: np.ndarray) -> dict[str, float]:
        x, y, psi = fly_controls(t, speed, turn, drift=self.drift)
        g = self.goal
        return {
            "position": math.hypot(x[-1] - g.x, y[-1] - g.y),
            "heading": abs(float(wrap_to_pi(psi[-1] - g.heading))),
        }


def solve_direct(
    goal: Pose,
    system: ControlSystem,
    *,
    guesses: Sequence[Path],
    n_intervals: int = 60,
    scheme: str = "hermite-simpson",
    mesh_tol: float = 1e-4,
    max_refinements: int = 4,
    length_scale: float = 1.0,
    time_scale: float = 1.0,
    ipopt_options: Mapping[str, Any] | None = None,
    degree: int = 3,
    refine_within: float = 0.02,
    max_refined_starts: int = 3,
    output_density: int = 4,
    smoothing: float = 1e-6,
    retime: bool = True,
    time_limit: float | None = None,
    drift: tuple[float, float] = (0.0, 0.0),
) -> DirectResult:
    """Minimise integral L(c) dt from the origin (0, 0, 0) to `goal`, free final time.

    Direct collocation (see `glideplan.planners.direct.collocation`) solved by IPOPT, one
    solve per guess (deterministic multi-start, in the order given). Each guess path fixes
    the heading branch psi(T) = goal.heading + 2 pi k (k from the guess's final heading) and
    the initial states, controls and final time. The best starts (within `refine_within`
    relative of the best, at most `max_refined_starts`) are refined by bisecting every mesh
    interval until the cost changes by less than `mesh_tol` (relative) between successive
    meshes or `max_refinements` doublings were made; the lowest refined cost wins.

    Args:
        goal: final pose (m, rad) in the frame of the start.
        system: the vehicle's controls, bounds and rates.
        guesses: initial-guess paths from the origin (e.g. Dubins paths at a few radii).
        n_intervals: mesh intervals of the first mesh.
        scheme: "hermite-simpson" or "radau" (with `degree` points per interval).
        mesh_tol: relative cost change that stops the refinement.
        max_refinements: at most this many mesh doublings.
        length_scale, time_scale: characteristic length (m) and time (s) for NLP scaling.
        ipopt_options: extra IPOPT options (e.g. {"max_iter": 200}).
        output_density: output nodes per mesh interval (>= 2 puts the Hermite-Simpson
            midpoints among them).
        smoothing: weight of a tiny penalty on control differences between consecutive
            collocation points (relative to the cost), which removes chattering on singular
            arcs; the reported cost excludes it.
        retime: re-time the output's control history (stretching time between nodes by at
            most 5% per piece, see `retime`) so that its controls, flown exactly, end at the
            goal; collocation alone leaves an endpoint error of about 1e-3 to 1e-6 (stats
            "raw_endpoint_error"); re-timing brings it to about 1e-12 without moving any
            control value.
        time_limit: wall-clock seconds (s) for the whole call, over all starts and meshes,
            or None for no limit. Each IPOPT solve gets the remaining time as
            `max_wall_time`; once the limit is reached the call stops and fails with the
            message "time limit of N s reached" (never a partial result).
        drift: a steady uniform wind or current (wx, wy) (m/s) added to the ground velocity,
            x' = v cos psi + wx, y' = v sin psi + wy (eq. A.4); an NLP parameter, so one
            built transcription serves every drift. The returned `Sampled` nodes are then
            ground positions, but its own interpolation knows no drift: drifting callers
            rebuild the segment from `controls` (see `glideplan.planners.final_glide`).

    Returns:
        A `DirectResult`; failures are reported in `status`, never returned as paths.
    """
    check_options(goal, guesses, n_intervals, scheme, mesh_tol, max_refinements, output_density)
    Ls = check_positive("length_scale", length_scale)
    Ts = check_positive("time_scale", time_scale)
    opts = tuple(sorted((ipopt_options or {}).items()))
    eps = check_nonnegative("smoothing", smoothing)
    t_start = time.perf_counter()
    clock = Deadline(t_start, time_limit)
    prob = _Problem(
        goal, system, scheme, int(degree), Ls, Ts, opts, eps, bool(retime), clock, _drift(drift)
    )
    N = int(n_intervals)
    prob.transcription(N)
    t_build = time.perf_counter() - t_start
    first, starts, iterations = _first_mesh(prob, guesses, N, clock)
    stats: dict[str, Any] = {
        "scheme": scheme,
        "starts_tried": len(starts),
        "starts_succeeded": len(first),
        "build_seconds": t_build,
    }
    if clock.expired():
        return clock.failure(stats, iterations, starts, len(guesses))
    if not first:
        statuses = ", ".join(sorted({s.status for s in starts}))
        message = f"no start converged (IPOPT: {statuses})"
        return failed(stats, iterations, t_start, starts, message)

    # the best starts (within refine_within of the cheapest), refined on finer meshes
    first.sort(key=lambda c: c.solve.cost)
    best_first = first[0].solve.cost
    chosen = [c for c in first if c.solve.cost <= best_first + refine_within * abs(best_first)]
    chosen = chosen[: max(1, int(max_refined_starts))]
    finals, iterations = _refine_all(prob, chosen, int(max_refinements), mesh_tol, iterations)
    if finals is None:
        return clock.failure(stats, iterations, starts, len(guesses))
    stats["refined_starts"] = len(chosen)
    best = min(finals, key=lambda f: f.solve.cost)
    return _solved(prob, best, starts, stats, int(output_density), mesh_tol,
                   (iterations, t_start))


def _refine_all(prob: _Problem, chosen: list[Converged], max_refinements: int, mesh_tol: float,
                iterations: int) -> tuple[list[Refined] | None, int]:
    """Refine each chosen start in turn (`multistart.refine`); None once the time limit
    stopped one; the IPOPT iterations counted on."""
    finals: list[Refined] = []
    for start in chosen:
        refined = refine(prob, start, max_refinements, mesh_tol, prob.clock)
        iterations += refined.iterations
        if refined.timed_out:
            return None, iterations
        finals.append(refined)
    return finals, iterations


def _drift(drift: tuple[float, float]) -> tuple[float, float]:
    """The steady drift (wx, wy) in m/s, checked: a finite pair."""
    try:
        wx, wy = (float(d) for d in drift)
    except (TypeError, ValueError):
        raise InvalidParameterError("drift", drift, "must be a pair (wx, wy) in m/s") from None
    if not (math.isfinite(wx) and math.isfinite(wy)):
        raise InvalidParameterError("drift", drift, "must be finite (m/s)")
    return wx, wy


def _first_mesh(prob: _Problem, guesses: Sequence[Path], N: int, clock: Deadline
                ) -> tuple[list[Converged], list[StartResult], int]:
    """One IPOPT solve per guess on the first mesh (in order, until the time limit): the
    starts that converged, every start's result, the IPOPT iterations spent."""
    fr = np.full(N, 1.0 / N)
    first: list[Converged] = []
    starts: list[StartResult] = []
    iterations = 0
    for i, guess in enumerate(guesses):
        tr = prob.transcription(N)  # the same NLP; a smaller IPOPT wall-time budget late on
        w0, k = prob.from_path(tr, fr, guess)
        js = max(prob.guess_cost(tr, fr, w0), 1e-12)
        res = prob.solve(tr, w0, k, fr, js)
        iterations += max(res.iterations, 0)
        label = guess.word
        starts.append(
            StartResult(i, res.cost if res.ok else math.inf, res.status, res.iterations, k, label)
        )
        if res.ok:
            first.append(Converged(res, k, js, i))
        if clock.expired():
            break
    return first, starts, iterations


def _solved(prob: _Problem, best: Refined, starts: list[StartResult], stats: dict[str, Any],
            output_density: int, mesh_tol: float, effort: tuple[int, float]) -> DirectResult:
    """The solved `DirectResult` of the best refined start: its path and controls (sampled
    `output_density` per interval), the effort (IPOPT iterations, seconds since the call's
    start `effort[1]`) and the mesh history in `stats`, a message if the mesh did not settle
    and a warning if re-timing failed."""
    best_k = starts[best.index].heading_turns
    path, controls, out_info = prob.output(best.solve, output_density, best_k)
    refined_starts = stats.pop("refined_starts")
    stats.update(
        iterations=effort[0],
        seconds=time.perf_counter() - effort[1],
        mesh_sizes=best.meshes,
        mesh_costs=best.costs,
        mesh_converged=best.converged,
        refined_starts=refined_starts,
        best_start=best.index,
        heading_turns=best_k,
        **out_info,
        nodes=int(controls["t"].size),
    )
    message = (
        ""
        if best.converged
        else (
            f"mesh refinement stopped before the cost changed by < {mesh_tol:g} "
            f"(costs {', '.join(f'{c:.6g}' for c in best.costs)})"
        )
    )
    warnings = (out_info["retime_failed"],) if "retime_failed" in out_info else ()
    return DirectResult(
        status=Status.SOLVED, path=path, cost=best.solve.cost, stats=stats,
        starts=tuple(starts), controls=controls, message=message, warnings=warnings,
    )


