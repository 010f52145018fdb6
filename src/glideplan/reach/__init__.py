"""Glide reach over terrain in wind, and the turn-back point (issue 20).

`glide_reach(terrain, start, polar, ...)` -> `ReachResult`: the minimum altitude loss to every
point over paths that keep a safety height above the terrain (a front in altitude,
`glideplan.fronts`), each landable's path verified by flying it through the wind with the
polar. `turnback(...)` -> `TurnbackResult`: how far out along a course the glider can fly and
still glide home. Importing this package imports NumPy only (the front imports numba).
"""

from glideplan.reach.model import Glide, GroundGlide
from glideplan.reach.problem import Landable, ReachProblem
from glideplan.reach.result import ReachPoint, ReachResult
from glideplan.reach.solve import glide_reach
from glideplan.reach.turnback import TurnbackResult, turnback

__all__ = [
    "Glide",
    "GroundGlide",
    "Landable",
    "ReachPoint",
    "ReachProblem",
    "ReachResult",
    "TurnbackResult",
    "glide_reach",
    "turnback",
]
