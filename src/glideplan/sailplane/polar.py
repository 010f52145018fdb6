"""Compatibility: the sailplane polar lives beside the vehicles.

`glideplan.vehicles.sailplane_polar`, re-exported here so `glideplan.sailplane.polar` keeps
working.
"""

from glideplan.vehicles.sailplane_polar import *  # noqa: F403
from glideplan.vehicles.sailplane_polar import KMH as KMH
from glideplan.vehicles.sailplane_polar import __all__ as __all__
