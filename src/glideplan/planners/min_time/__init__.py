"""Minimum-time paths with variable speed (dissertation chapter 4 and appendix B).

`VariableSpeedCar(v_min, v_max, u_max)` with objective "time": the synthesis over the 72
candidate types of (4.26) (`method="synthesis"`, the default) and an independent direct
collocation solve (`method="direct"`).

>>> from glideplan import Pose, VariableSpeedCar, plan
>>> sol = plan(Pose(), Pose(0.0, 2.0, 2.0943951023931953), VariableSpeedCar(0.3, 1.0, 1.0))
>>> sol.family, sol.word, round(sol.cost, 6)
('CBSB', 'LSR', 2.87465)
"""

from glideplan.planners.min_time.direct import (
    plan_time_optimal_direct,
    solve_time_optimal_direct,
)
from glideplan.planners.min_time.synthesis import (
    SynthesisResult,
    extremal_path,
    plan_time_optimal,
    synthesize,
)
from glideplan.planners.min_time.table import CANDIDATE_TYPES, CandidateType, alpha_subopt

__all__ = [
    "CANDIDATE_TYPES",
    "CandidateType",
    "SynthesisResult",
    "alpha_subopt",
    "extremal_path",
    "plan_time_optimal",
    "plan_time_optimal_direct",
    "solve_time_optimal_direct",
    "synthesize",
]
