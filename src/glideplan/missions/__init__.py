"""Missions on the Earth: routes of waypoints, multi-leg plans with optimised headings."""

from glideplan.missions.field_mission import FieldLeg, FieldMission, plan_mission_in_field
from glideplan.missions.headings import (
    HeadingPlan,
    StillAirCost,
    WindCost,
    alternating_headings,
    bisector_headings,
    headings_cost,
    optimise_headings,
    point_at_next_headings,
)
from glideplan.missions.leg_costs import dubins_length_matrix
from glideplan.missions.plan import MissionLeg, MissionPlan, Track, plan_mission
from glideplan.missions.route import Route
from glideplan.missions.straight_legs import StraightLegList, straight_leg_list

__all__ = [
    "FieldLeg",
    "FieldMission",
    "HeadingPlan",
    "MissionLeg",
    "MissionPlan",
    "Route",
    "StillAirCost",
    "StraightLegList",
    "Track",
    "WindCost",
    "alternating_headings",
    "bisector_headings",
    "dubins_length_matrix",
    "headings_cost",
    "optimise_headings",
    "plan_mission",
    "plan_mission_in_field",
    "point_at_next_headings",
    "straight_leg_list",
]
