"""Closed-loop path following under disturbances (dissertation §3.4): guidance, disturbances,
the vectorised simulator."""

from glideplan.simulation.closed_loop import FollowerSettings, FollowResult, follow_paths
from glideplan.simulation.disturbances import DrydenTurbulence, SteadyDisturbance, saturate
from glideplan.simulation.guidance import GuidanceCommand, PathArrays, lookahead_guidance

__all__ = [
    "DrydenTurbulence",
    "FollowResult",
    "FollowerSettings",
    "GuidanceCommand",
    "PathArrays",
    "SteadyDisturbance",
    "follow_paths",
    "lookahead_guidance",
    "saturate",
]
