"""A general direct-method engine: collocation + IPOPT for the planar gliding vehicles.

The chapter 4, 5 and 6 planners, and their independent cross-checks, describe a vehicle by
a `ControlSystem` (its controls, bounds, kinematics and cost rate) and call `solve_direct`
with analytic initial-guess paths. Minimum-time Dubins car to (4, 3, pi/2) (T* = LSL length):

>>> import math, casadi
>>> from glideplan import Arc, Path, Pose, Straight
>>> from glideplan.planners.direct import ControlSystem, solve_direct
>>> car = ControlSystem(
...     name="dubins-time", control_names=("u",), lower=(-1.0,), upper=(1.0,),
...     kinematics=lambda c: (1.0 + 0 * c[0], c[0]), cost_rate=lambda c: 1.0 + 0 * c[0],
...     controls_from=lambda v, u: u[:, None])
>>> guess = Path((Straight(Pose(), 4.0), Arc(Pose(4.0, 0.0, 0.0), math.pi / 2, 3.0, 1)))
>>> result = solve_direct(Pose(4.0, 3.0, math.pi / 2), car, guesses=[guess])
>>> print(result.status, round(result.cost, 3))
solved 5.176

Start is always the origin; the heading at the goal is matched modulo 2 pi (the guess's final
heading picks the branch); the final time is free. Each guess is one start; the best is kept
after mesh refinement. Failures come back as `status=Status.FAILED` with `path=None`.

For SI models pass `length_scale` and `time_scale` (e.g. R_stf and R_stf / v_stf for the
chapter 5 glider) so the NLP is well scaled; `DirectResult.cost` is the collocation cost on the
final mesh, `path.cost(objective)` the cost of the returned sampled controls (they agree to
about 1e-6 relative).

Endpoint accuracy: the returned `Sampled` path carries the collocation control history at
`output_density` nodes per mesh interval; flown exactly, such a history misses the goal by
1e-5 to 1e-3 (stats "raw_endpoint_error"; more near control switches). `retime` then stretches
the time between nodes (by less than 0.5% in the chapter 4-6 examples, stats
"retime_stretch") without changing any control value, so every control stays admissible and
the path ends at the goal to ~1e-12 by our integrator and ~1e-8 by `plan()`'s DOP853
verification, well inside its default tolerance of 1e-6 (times the vehicle's length scale).
"""

from glideplan.planners.direct.collocation import SCHEMES, Transcription, build_transcription
from glideplan.planners.direct.engine import (
    DirectResult,
    StartResult,
    fly_controls,
    retime,
    solve_direct,
)
from glideplan.planners.direct.system import ControlSystem

__all__ = [
    "SCHEMES",
    "ControlSystem",
    "DirectResult",
    "StartResult",
    "Transcription",
    "build_transcription",
    "fly_controls",
    "retime",
    "solve_direct",
]
