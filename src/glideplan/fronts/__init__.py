"""Fronts: first-arrival times of reachable sets on a lat/lon grid (numba narrow band).

The machinery routes (time through a current) and glide reach (altitude lost in a wind, over
terrain) share: `LatLonGrid` (nodes and the sphere's metric), `FrontProblem` (the Hamiltonian
max_k (a_k |p| + d_k . p) and obstacles), `start_state`, `propagate` (the level set),
`backtrack` (optimal paths along the characteristics). Importing this package imports numba.
"""

from glideplan.fronts.characteristics import Characteristic, arrival_gradient_at, backtrack
from glideplan.fronts.grid import EARTH_RADIUS_M, LatLonGrid
from glideplan.fronts.solver import (
    DriftLevels,
    FrontProblem,
    FrontResult,
    FrontState,
    propagate,
    start_state,
)

__all__ = [
    "EARTH_RADIUS_M",
    "Characteristic",
    "DriftLevels",
    "FrontProblem",
    "FrontResult",
    "FrontState",
    "LatLonGrid",
    "arrival_gradient_at",
    "backtrack",
    "propagate",
    "start_state",
]
