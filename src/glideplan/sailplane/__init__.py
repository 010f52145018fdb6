"""Sailplanes: real polars (`.plr`), MacCready, straight final glide in wind, ArduSoar, tasks.

The chapter 5 quadratic polar w(v) = a v^2 + b v + c fitted to the three points pilots' polar
files give (`plr`, `polar`), scaled for mass, ballast and bugs, extended to turning flight;
MacCready's speed to fly with head-, tail- and crosswind (`maccready`); the straight final
glide vectorised over many goals (`straight`); ArduPilot's soaring polar parameters
(`ardusoar`); SeeYou / XCSoar task export (`tasks`); the final-glide service
`final_glide()` (`request`, also `glideplan.final_glide`) returning a `FinalGlide` result. The
polar itself is a leaf beside the vehicles (`glideplan.vehicles.sailplane_polar`, re-exported
here and by `sailplane.polar`); the final glide to an arrival heading is the planner
`glideplan.planners.final_glide`.
"""

from glideplan.sailplane.ardusoar import ArduSoarFit, ardusoar_sink, fit_ardusoar, write_parm
from glideplan.sailplane.maccready import ground_speed, maccready_table, speed_to_fly
from glideplan.sailplane.plr import PolarFile, PolarFileError, parse_plr, read_plr
from glideplan.sailplane.request import FinalGlide, final_glide
from glideplan.sailplane.straight import StraightGlide, straight_final_glide
from glideplan.sailplane.tasks import TaskPoint, write_cup_task, write_tsk_task
from glideplan.vehicles.sailplane_polar import (
    GRAVITY,
    STALL_FRACTION,
    SailplanePolar,
    fit_three_points,
    load_polar,
    polar_from_file,
)

__all__ = [
    "GRAVITY",
    "STALL_FRACTION",
    "ArduSoarFit",
    "FinalGlide",
    "PolarFile",
    "PolarFileError",
    "SailplanePolar",
    "StraightGlide",
    "TaskPoint",
    "ardusoar_sink",
    "final_glide",
    "fit_ardusoar",
    "fit_three_points",
    "ground_speed",
    "load_polar",
    "maccready_table",
    "parse_plr",
    "polar_from_file",
    "read_plr",
    "speed_to_fly",
    "straight_final_glide",
    "write_cup_task",
    "write_parm",
    "write_tsk_task",
]
