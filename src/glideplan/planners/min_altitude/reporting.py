"""What the planner reports besides its candidates: the Dubins reference and flight profiles."""

from __future__ import annotations

from typing import Any

import numpy as np

from glideplan.path import Path
from glideplan.planners.dubins import dubins_path
from glideplan.pose import Pose
from glideplan.solution import Candidate, Status
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider

__all__ = ["dubins_reference", "flight_profile"]


def dubins_reference(start: Pose, goal: Pose, glider: QuadraticPolarGlider) -> Candidate | None:
    """The shortest Dubins path flown at v_stf with radius R_stf and its altitude loss (m).

    The comparison of section 5.9 (the dashed paths of Figs. 5.5-5.7); None if no Dubins
    word reaches the goal (never, for distinct poses).
    """
    path = dubins_path(start, goal, glider.radius_stf, glider.v_stf)
    if path is None:
        return None
    path = path.with_vehicle(glider)
    cost = path.duration * glider.w_stf
    return Candidate(path.word, "Dubins", cost, path, Status.FEASIBLE, {"speed": glider.v_stf})


def flight_profile(path: Path, n: int = 201) -> dict[str, Any]:
    """Altitude lost (m) and the control history along `path` (which carries its glider).

    Samples at `n` evenly spaced times plus every segment boundary (where the controls
    switch): time t (s), arc length s (m), x, y (m), heading (rad), speed (m/s), turn rate
    (rad/s) and the cumulative altitude loss (m), as lists for JSON.
    """
    starts = np.concatenate([[0.0], np.cumsum([s.duration for s in path.segments])])
    times = np.unique(np.concatenate([np.linspace(0.0, path.duration, max(2, int(n))), starts]))
    smp = path.sample(times=times, objective="altitude")
    assert smp.cost is not None
    return {
        "t": smp.t.tolist(),
        "s": smp.s.tolist(),
        "x": smp.x.tolist(),
        "y": smp.y.tolist(),
        "heading": smp.heading.tolist(),
        "speed": smp.speed.tolist(),
        "turn_rate": smp.turn_rate.tolist(),
        "altitude_loss": smp.cost.tolist(),
    }
