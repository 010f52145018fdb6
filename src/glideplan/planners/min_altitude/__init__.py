"""Minimum altitude loss with a quadratic glide polar (dissertation chapter 5, appendix C).

The glider x' = v cos psi, y' = v sin psi, psi' = u with v in [v_stall, v_max], |u| <= u_max
loses altitude at w(v) = a v^2 + b v + c (5.1)-(5.4). Two planners are registered for
`QuadraticPolarGlider` and the objective "altitude": method "synthesis" (the default; every
candidate of the sufficient set below, `synthesis.py`) and method "direct" (collocation +
IPOPT, `direct.py`, the independent check).

Extremals, re-derived (Table 5.1)
---------------------------------
With the adjoints eta0, eta_x = eta cos theta, eta_y = eta sin theta, eta_psi and
phi = psi - theta, the Hamiltonian is H = eta0 w(v) + eta v cos(phi) + eta_psi u (5.11).
Normal extremals (eta0 = 1, lambda = eta / 2a) minimise it with u = -sgn(eta_psi) u_max and

    v = clip(v_ms - lambda cos(phi), v_stall, v_max).                    (5.16, clipped)

Because the problem is autonomous with free final time, H = 0 along the whole extremal.
Where v is not clipped this gives |eta_psi| u_max = c - a v^2 = a (v_stf^2 - v^2), so

* eta_psi = 0 exactly where v = v_stf: a B arc flies at v <= v_stf, and turn switches
  happen where the heading-dependent speed reaches v_stf, i.e. at phi = +-s with
  cos s = -(v_stf - v_ms) / lambda (so a switch needs lambda >= v_stf - v_ms);
* S (eta_psi = 0 on an interval) needs phi = pi and v = v_ms + lambda = v_stf, i.e.
  lambda = v_stf - v_ms (Lemma 5.6.6), as the dissertation finds.

Beyond the dissertation: saturated B arcs
-----------------------------------------
Lemma 5.6.7 argues that the speed cannot sit at a bound on a turning extremal because "a
fixed v cannot satisfy H = 0". It can: H is constant along any extremal, and on a piece
where v = v_stall, H = w(v_stall) + 2 a lambda v_stall cos(phi) - |eta_psi| u_max = 0 simply
fixes |eta_psi|, which evolves by (5.10) consistently. So for lambda > v_ms - v_stall the B
arc flies at v_stall on the band |phi| < phi_s = arccos((v_ms - v_stall) / lambda) and at
v_ms - lambda cos(phi) elsewhere; Lemma 5.7.6's bound lambda <= v_ms - v_stall is an
artefact. The direct method finds such an optimum for the goal (0, 1, 2 pi/3) R_stf: a BBB
RLR path whose middle turn holds v_stall for about a quarter of the flight (19.4289 m of
altitude; the best unsaturated candidate loses 19.8762 m).

Saturation at v_max cannot occur. On a piece clipped at v_max, v_ms - lambda cos(phi) > v_max,
so 2 a lambda cos(phi) < -2 a (v_max - v_ms) and
|eta_psi| u_max = w(v_max) + 2 a lambda v_max cos(phi) < w(v_max) - 2 a v_max (v_max - v_ms)
= c - a v_max^2 < 0 since v_max > v_stf (Assumption 5.2.3): impossible. (Likewise no switch
can sit inside the stall band: eta_psi = 0 there would need cos(phi) < 0.) Hence v_max never
binds and optimal paths do not depend on v_max > v_stf.

Which sequences remain (the extended Theorem 5.7.1)
---------------------------------------------------
The clipped speed v(phi) is still even in phi and positive, which is all that Lemmas 5.7.7,
5.7.8, 5.7.10 and 5.7.11 use: eta_psi(phi) = +-(eta/u_max) (F(phi) - F(phi_0)) with
F' = v(phi) sin(phi) odd (F even), so an arc that starts and ends with eta_psi = 0 is
symmetric about phi = 0 (here: from -s to s, a heading change 2 s in (pi, 2 pi)), interior arcs
are antisymmetric, and three of them admit the shortcut of Lemma 5.7.11. In BSB,
lambda = v_stf - v_ms < v_ms - v_stall (Assumption 5.2.4), so BSB arcs are never clipped.
The sufficient set keeps its shape, with B arcs that may now be clipped at v_stall:

    Gamma = {BSB, BBBB (and BBB, BB, B), B_ms, B_stall^4 (and B_stall^3, ^2, ^1)},

tabulated with each family's constraints in `families.FAMILIES`. (A lone B arc may turn
psi1 + 2 pi, a loop to a goal just behind the start, as long as it holds at most one heading
phi = pi, Lemma 5.7.7; with lambda < v_stf - v_ms it never meets v = v_stf.) H = 0 also
removes a parameter from the dissertation's BBBB problem (C.22): the interior arcs turn exactly
2 s(lambda) and the last arc follows from the final heading, so a chain is fixed by
(lambda, first arc) and the boundary conditions have isolated solutions (root finding, not
optimisation). Two caveats, checked numerically instead of proved: Lemma 5.7.11's shortcut
needs the interior arcs to advance along theta (integral of v cos(phi) over [-s, s] > 0),
which fails for interior loops longer than about 335 degrees (s > 167.5 deg) with the DG-1001M
polar; and the first and last arcs of BBB/BBBB are allowed their full range [0, 2 s] rather
than the dissertation's "no heading theta" restriction. Allowing five and six B arcs changed
no optimal path in the validation (`benchmarks/min_altitude_vs_direct.py`), and the
synthesis matches the direct method on random goals.

The abnormal B_stall^n candidates of (C.26)-(C.28) must also satisfy the y equation that the
extracted text omits; they, and B_ms, reach only a measure-zero set of goals.
"""

from __future__ import annotations

import time
from typing import Any

from glideplan.planners.min_altitude.direct import (
    control_system,
    direct_guesses,
    solve_min_altitude_direct,
)
from glideplan.planners.min_altitude.extremals import (
    Change,
    Kernel,
    b_arc_change,
    b_arc_change_unclipped,
    b_arc_segments,
    constant_speed_arc_change,
    straight_change,
)
from glideplan.planners.min_altitude.families import FAMILIES, Family, family_named
from glideplan.planners.min_altitude.reporting import dubins_reference, flight_profile
from glideplan.planners.min_altitude.synthesis import DEFAULT_GRID, synthesize
from glideplan.planning import PlannerOutput, Problem, register_planner
from glideplan.segments import Sampled
from glideplan.solution import Candidate, Status
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = [
    "DEFAULT_GRID",
    "FAMILIES",
    "Change",
    "Family",
    "Kernel",
    "b_arc_change",
    "b_arc_change_unclipped",
    "b_arc_segments",
    "constant_speed_arc_change",
    "control_system",
    "direct_guesses",
    "dubins_reference",
    "family_named",
    "flight_profile",
    "plan_min_altitude",
    "plan_min_altitude_direct",
    "solve_min_altitude_direct",
    "straight_change",
    "synthesize",
]


def _reference_extras(problem: Problem) -> dict[str, object]:
    assert isinstance(problem.vehicle, QuadraticPolarGlider)
    ref = dubins_reference(problem.start, problem.goal, problem.vehicle)
    if ref is None:
        return {"dubins_cost": None, "dubins_word": ""}
    return {"dubins_cost": ref.cost, "dubins_word": ref.word}


@register_planner(
    "min_altitude",
    vehicle=QuadraticPolarGlider,
    objective="altitude",
    method="synthesis",
    description="Minimum altitude loss, quadratic polar: synthesis over the extended "
    "sufficient set {BSB, BBBB, Bms, Bstall^4} with stall-saturated B arcs (5.7-5.8, C)",
)
def plan_min_altitude(problem: Problem) -> PlannerOutput:
    """Every candidate of the extended sufficient set (section 5.8); extras: `dubins_cost`
    (altitude loss of the Dubins path at v_stf, m) and `dubins_word`."""
    assert isinstance(problem.vehicle, QuadraticPolarGlider)
    t0 = time.perf_counter()
    cands = synthesize(problem.goal, problem.vehicle)
    seconds = time.perf_counter() - t0
    return PlannerOutput(
        candidates=cands,
        stats={"synthesis_seconds": seconds, "candidates": len(cands)},
        message="" if cands else "no candidate of the sufficient set reaches the goal",
        extras=_reference_extras(problem),
    )


@register_planner(
    "min_altitude_direct",
    vehicle=QuadraticPolarGlider,
    objective="altitude",
    method="direct",
    default=False,
    description="Minimum altitude loss, quadratic polar: direct collocation + IPOPT, "
    "multi-started from the synthesis candidates and Dubins paths at v_stf",
)
def plan_min_altitude_direct(
    problem: Problem,
    *,
    seeds: str = "all",
    max_starts: int = 6,
    n_intervals: int = 60,
    time_limit: float | None = None,
) -> PlannerOutput:
    """Direct method (see `direct.solve_min_altitude_direct`); the candidate's cost is the
    altitude loss of the returned (piecewise-linear control) path. `time_limit`: wall-clock
    seconds for the direct solve (all starts), or None for no limit."""
    glider = problem.vehicle
    assert isinstance(glider, QuadraticPolarGlider)
    res = solve_min_altitude_direct(
        problem.goal,
        glider,
        seeds=seeds,
        max_starts=max_starts,
        n_intervals=n_intervals,
        time_limit=time_limit,
    )
    stats: dict[str, Any] = {
        k: v for k, v in res.stats.items() if isinstance(v, (int, float, str, bool))
    }
    stats["starts"] = [s.to_dict() for s in res.starts]
    extras = _reference_extras(problem)
    if not res.ok or res.path is None:
        return PlannerOutput(
            (),
            stats,
            res.message or "IPOPT failed",
            extras,
            failure=Status.SOLVER_FAILED,
            warnings=res.warnings,
        )
    path = res.path.with_vehicle(glider)
    seg = path.segments[0]
    word = seg.turn_word(0.05 * glider.u_max) if isinstance(seg, Sampled) else path.word
    info = {"collocation_cost": res.cost}
    cand = Candidate(word, "direct", path.cost("altitude"), path, Status.FEASIBLE, info)
    return PlannerOutput((cand,), stats, "", extras, warnings=res.warnings)
