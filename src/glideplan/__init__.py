"""glideplan: optimal paths for gliding vehicles.

After A. Wolek, *Optimal Paths in Gliding Flight*, PhD dissertation, Virginia Tech, 2015.

The public API is what this module exports:

- planning: `plan()` (one path between two poses, verified by integration) and the registry
  of planners; poses, paths and segments;
- products above `plan()`: `route()` through a current or wind field (`FlowField`,
  `open_field`), `plan_mission()` over waypoints, `final_glide()` for a sailplane
  (`Sailplane`, `SailplanePolar`), `glide_reach()` and `turnback()` (`glideplan.reach`);
- results: every one is an `Outcome` (status, ok, message, warnings, `to_dict()`, `plot()`)
  with one `Status` vocabulary, and tracks are one `Track` type;
- vehicle models.

`import glideplan` stays light (no SciPy integrators, Matplotlib, xarray, pyproj, CasADi,
Numba or Dask): the products are imported on first use (`__getattr__` below).
"""

from typing import TYPE_CHECKING, Any

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

if TYPE_CHECKING:
    from glideplan.fields import FlowField, open_field
    from glideplan.missions import plan_mission
    from glideplan.reach import glide_reach, turnback
    from glideplan.results import Outcome
    from glideplan.routing import route
    from glideplan.sailplane.request import final_glide
    from glideplan.track import Track
    from glideplan.vehicles.sailplane import Sailplane
    from glideplan.vehicles.sailplane_polar import SailplanePolar

__version__ = "0.1.0"

# Public names imported on first use: name -> module holding it.
_LAZY = {
    "route": "glideplan.routing",
    "plan_mission": "glideplan.missions",
    "final_glide": "glideplan.sailplane.request",
    "glide_reach": "glideplan.reach",
    "turnback": "glideplan.reach",
    "FlowField": "glideplan.fields",
    "open_field": "glideplan.fields",
    "Sailplane": "glideplan.vehicles.sailplane",
    "SailplanePolar": "glideplan.vehicles.sailplane_polar",
    "Track": "glideplan.track",
    "Outcome": "glideplan.results",
}


def __getattr__(name: str) -> Any:
    """Import a product (`route`, `plan_mission`, `final_glide`, `Sailplane`, ...) on first
    use."""
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module 'glideplan' has no attribute {name!r}")
    import importlib

    try:
        value = getattr(importlib.import_module(module), name)
    except (ImportError, AttributeError) as exc:
        raise ImportError(
            f"glideplan.{name} comes from {module}, which cannot provide it: {exc}"
        ) from exc
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(_LAZY))


__all__ = [
    "Arc",
    "Candidate",
    "DriftingStraight",
    "DubinsCar",
    "DubinsCarInWind",
    "EndpointError",
    "FlowField",
    "HeadingSpeedArc",
    "InvalidParameterError",
    "LoadFactorGlider",
    "Outcome",
    "Path",
    "PathSamples",
    "PlannerOutput",
    "PlanningError",
    "Pose",
    "Problem",
    "QuadraticPolarGlider",
    "ResultsFileError",
    "Sailplane",
    "SailplanePolar",
    "Sampled",
    "Segment",
    "Solution",
    "Status",
    "Straight",
    "Track",
    "TrochoidArc",
    "VariableSpeedCar",
    "Vehicle",
    "__version__",
    "dubins_path",
    "dubins_shortest",
    "endpoint_error",
    "feasible_radius",
    "final_glide",
    "glide_reach",
    "integrate_path",
    "mod_2pi",
    "open_field",
    "plan",
    "plan_mission",
    "register_planner",
    "registered_planners",
    "route",
    "run_batch",
    "turnback",
    "wrap_to_pi",
]
