"""glideplan: optimal paths for gliding vehicles.

After A. Wolek, *Optimal Paths in Gliding Flight*, PhD dissertation, Virginia Tech, 2015.

The public API is what this module exports: `plan()`, poses, vehicle models, paths and
segments, solutions, and the registry of planners.
"""

from glideplan.errors import InvalidParameterError, PlanningError, ResultsFileError
from glideplan.path import Path, PathSamples
from glideplan.planning import PlannerOutput, Problem, plan, register_planner, registered_planners
from glideplan.pose import Pose, mod_2pi, wrap_to_pi
from glideplan.segments import Arc, HeadingSpeedArc, Sampled, Segment, Straight
from glideplan.solution import Candidate, Solution, Status
from glideplan.vehicles import DubinsCar, Vehicle
from glideplan.verify import EndpointError, endpoint_error, integrate_path

__version__ = "0.1.0"

__all__ = [
    "Arc",
    "Candidate",
    "DubinsCar",
    "EndpointError",
    "HeadingSpeedArc",
    "InvalidParameterError",
    "Path",
    "PathSamples",
    "PlannerOutput",
    "PlanningError",
    "Pose",
    "Problem",
    "ResultsFileError",
    "Sampled",
    "Segment",
    "Solution",
    "Status",
    "Straight",
    "Vehicle",
    "__version__",
    "endpoint_error",
    "integrate_path",
    "mod_2pi",
    "plan",
    "register_planner",
    "registered_planners",
    "wrap_to_pi",
]


def _load_planners() -> None:
    from glideplan.planners import load_all

    load_all()


_load_planners()
