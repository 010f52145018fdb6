"""The direct method for minimum altitude loss: collocation + IPOPT (the independent check).

The glider is handed to the shared engine (`glideplan.planners.direct`) as controls
(v, u) in [v_stall, v_max] x [-u_max, u_max] with cost rate w(v); the NLP is scaled by R_stf
and 1/u_max. Starts: the synthesis candidates (lowest cost first, one per turn word) and
the Dubins paths flown at v_stf with radius R_stf, so the engine both polishes the
synthesis and searches from guesses that know nothing of chapter 5's families.
"""

from __future__ import annotations

from collections.abc import Sequence

from glideplan.errors import InvalidParameterError
from glideplan.path import Path
from glideplan.planners.direct import ControlSystem, DirectResult, solve_direct
from glideplan.planners.dubins import WORDS, dubins_path
from glideplan.planners.min_altitude.synthesis import synthesize
from glideplan.pose import Pose
from glideplan.validation import check_integer
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = ["SEEDS", "control_system", "direct_guesses", "solve_min_altitude_direct"]

SEEDS = ("all", "synthesis", "dubins")


def control_system(glider: QuadraticPolarGlider) -> ControlSystem:
    """The glider for the direct engine: controls (v, u), box bounds, cost rate w(v) (5.4)."""
    a, b, c = glider.a, glider.b, glider.c
    return ControlSystem(
        name="quadratic-polar-glider",
        control_names=("speed", "turn_rate"),
        lower=(glider.v_stall, -glider.u_max),
        upper=(glider.v_max, glider.u_max),
        kinematics=lambda q: (q[0], q[1]),
        cost_rate=lambda q: (a * q[0] + b) * q[0] + c,
    )


def direct_guesses(
    goal: Pose, glider: QuadraticPolarGlider, *, seeds: str = "all", max_starts: int = 6
) -> list[Path]:
    """Initial guesses: synthesis candidates (distinct words, cheapest first) and Dubins
    paths at v_stf (shortest first), interleaved, at most `max_starts`."""
    if seeds not in SEEDS:
        raise InvalidParameterError("seeds", seeds, f"must be one of {', '.join(SEEDS)}")
    check_integer("max_starts", max_starts, 1)
    synth: list[Path] = []
    if seeds in ("all", "synthesis"):
        words: set[str] = set()
        for cand in synthesize(goal, glider):
            if cand.path is not None and cand.word not in words:
                words.add(cand.word)
                synth.append(cand.path)
    dubins: list[Path] = []
    if seeds in ("all", "dubins"):
        paths = (dubins_path(Pose(), goal, glider.radius_stf, glider.v_stf, word) for word in WORDS)
        dubins = sorted((p for p in paths if p is not None), key=lambda p: p.length)
    guesses: list[Path] = []
    for k in range(max(len(synth), len(dubins))):
        guesses += [p for p in (synth[k : k + 1] + dubins[k : k + 1]) if p.duration > 0.0]
    return guesses[: int(max_starts)]


def solve_min_altitude_direct(
    goal: Pose,
    glider: QuadraticPolarGlider,
    *,
    seeds: str = "all",
    max_starts: int = 6,
    n_intervals: int = 60,
    mesh_tol: float = 1e-5,
    guesses: Sequence[Path] | None = None,
    time_limit: float | None = None,
) -> DirectResult:
    """Minimum altitude loss from the origin to `goal` by direct collocation (multi-start).

    Args:
        goal: final pose (m, rad) in the frame of the start.
        glider: the vehicle.
        seeds: initial guesses from "all" (synthesis and Dubins), "synthesis" or "dubins".
        max_starts: at most this many IPOPT starts.
        n_intervals: collocation intervals of the first mesh (refined by bisection).
        mesh_tol: relative cost change that stops the mesh refinement.
        guesses: explicit initial-guess paths (overrides `seeds`).
        time_limit: wall-clock seconds for the direct solve (all starts), or None for no limit.
    """
    starts = (
        list(guesses)
        if guesses is not None
        else direct_guesses(goal, glider, seeds=seeds, max_starts=max_starts)
    )
    return solve_direct(
        goal,
        control_system(glider),
        guesses=starts,
        n_intervals=n_intervals,
        mesh_tol=mesh_tol,
        length_scale=glider.radius_stf,
        time_scale=glider.time_scale,
        time_limit=time_limit,
    )
