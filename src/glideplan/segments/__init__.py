"""Path segment kinds: straight, constant-speed arc, heading-dependent-speed arc, sampled, and
the same arc and straight drifting in a steady wind.

Every segment implements the `Segment` protocol (`segments/base.py`): start pose, length,
duration, end, turn direction and word, controls and states at local times, drift, arc length
to time, breakpoints, rigid transforms and `to_dict`. Each kind integrates the planar
kinematics x' = v cos psi + wx, y' = v sin psi + wy, psi' = u (dissertation eqs. 2.1, 4.1,
5.1-5.3, A.4) for its own control law, in closed form where one exists.
"""

from glideplan.segments.base import RateFunction, Segment, direction_letter
from glideplan.segments.constant import Arc, Straight
from glideplan.segments.drifting import DriftingStraight, TrochoidArc
from glideplan.segments.heading_speed import HeadingSpeedArc
from glideplan.segments.sampled import Sampled

__all__ = [
    "Arc",
    "DriftingStraight",
    "HeadingSpeedArc",
    "RateFunction",
    "Sampled",
    "Segment",
    "Straight",
    "TrochoidArc",
    "direction_letter",
]
