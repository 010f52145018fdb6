"""Closed-loop path following under disturbances (dissertation §3.4): guidance, disturbances,
the vectorised simulator."""

from glideplan.simulation.closed_loop import FollowerSettings, FollowResult, follow_paths
from glideplan.simulation.disturbances import (
    DrydenTurbulence,
    FieldDisturbance,
    PositionalStream,
    SteadyDisturbance,
    saturate,
)
from glideplan.simulation.guidance import GuidanceCommand, PathArrays, lookahead_guidance

__all__ = [
    "DrydenTurbulence",
    "FieldDisturbance",
    "FollowResult",
    "FollowerSettings",
    "GuidanceCommand",
    "PathArrays",
    "PositionalStream",
    "SteadyDisturbance",
    "follow_paths",
    "lookahead_guidance",
    "saturate",
]
