"""Compatibility: the sailplane polar lives beside the vehicles.

`glideplan.vehicles.sailplane_polar`, re-exported here so `glideplan.sailplane.polar` keeps
working.
"""

from glideplan.vehicles.sailplane_polar import (
    GRAVITY,
    KMH,
    MAX_BUGS_PCT,
    STALL_FRACTION,
    SailplanePolar,
    fit_three_points,
    polar_from_file,
)

__all__ = [
    "GRAVITY",
    "KMH",
    "MAX_BUGS_PCT",
    "STALL_FRACTION",
    "SailplanePolar",
    "fit_three_points",
    "polar_from_file",
]
