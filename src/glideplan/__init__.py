"""glideplan: optimal paths for gliding vehicles.

After A. Wolek, *Optimal Paths in Gliding Flight*, PhD dissertation, Virginia Tech, 2015.

The public API is what this module exports: `plan()`, poses, vehicle models, paths and
segments, solutions, and the registry of planners.
"""

from glideplan.batch import run_batch
from glideplan.errors import InvalidParameterError, PlanningError, ResultsFileError
from glideplan.path import Path, PathSamples
from glideplan.planners.dubins import dubins_path, dubins_shortest, feasible_radius
from glideplan.planning import PlannerOutput, Problem, plan, register_planner, registered_planners
from glideplan.pose import Pose, mod_2pi, wrap_to_pi
from glideplan.segments import (
    Arc,
    DriftingStraight,
    HeadingSpeedArc,
    Sampled,
    Segment,
    Straight,
    TrochoidArc,
)
from glideplan.solution import Candidate, Solution, Status
from glideplan.vehicles import DubinsCar, Vehicle
from glideplan.vehicles.dubins_car_in_wind import DubinsCarInWind
from glideplan.vehicles.load_factor_glider import LoadFactorGlider
from glideplan.vehicles.quadratic_polar_glider import QuadraticPolarGlider
from glideplan.vehicles.variable_speed_car import VariableSpeedCar
from glideplan.verify import EndpointError, endpoint_error, integrate_path

__version__ = "0.1.0"

__all__ = [
    "Arc",
    "Candidate",
    "DriftingStraight",
    "DubinsCar",
    "DubinsCarInWind",
    "EndpointError",
    "HeadingSpeedArc",
    "InvalidParameterError",
    "LoadFactorGlider",
    "Path",
    "PathSamples",
    "PlannerOutput",
    "PlanningError",
    "Pose",
    "Problem",
    "QuadraticPolarGlider",
    "ResultsFileError",
    "Sampled",
    "Segment",
    "Solution",
    "Status",
    "Straight",
    "TrochoidArc",
    "VariableSpeedCar",
    "Vehicle",
    "__version__",
    "dubins_path",
    "dubins_shortest",
    "endpoint_error",
    "feasible_radius",
    "integrate_path",
    "mod_2pi",
    "plan",
    "register_planner",
    "registered_planners",
    "run_batch",
    "wrap_to_pi",
]
