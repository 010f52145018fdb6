"""The synthesis against the independent direct method (method="direct")."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError, Pose, VariableSpeedCar, plan
from glideplan.planners.min_time.direct import classify_controls

# 12 goals: the example, two special ones, and random goals in [-3, 3]^2 for r/R = 0.3, 0.5
_RNG = np.random.default_rng(2024)
GOALS = [(0.0, 2.0, 2 * math.pi / 3, 0.3), (-2.0, 0.0, math.pi, 0.3), (0.6, 0.9, math.pi, 0.5)]
GOALS += [(0.148, 0.7861, 2.3468, 0.5)]  # optimum C B T B C, a type (4.26) leaves out
GOALS += [
    (float(x), float(y), float(h), rho)
    for rho in (0.3, 0.5)
    for x, y, h in zip(_RNG.uniform(-3, 3, 5), _RNG.uniform(-3, 3, 5),
                       _RNG.uniform(-math.pi, math.pi, 5), strict=True)
]  # fmt: skip


@pytest.mark.parametrize("goal", GOALS, ids=lambda g: f"{g[0]:.2f},{g[1]:.2f},{g[2]:.2f},r{g[3]}")
def test_synthesis_never_above_direct(goal):
    x, y, h, rho = goal
    car = VariableSpeedCar(rho, 1.0, 1.0)
    syn = plan(Pose(), Pose(x, y, h), car)
    # direct collocation started from Dubins paths only: independent of the synthesis
    direct = plan(Pose(), Pose(x, y, h), car, method="direct", synthesis_starts=0)
    assert syn.ok and direct.ok
    assert direct.endpoint_error.max < 1e-6
    assert syn.cost <= direct.cost * (1 + 1e-4)
    # collocation smears the switches, so it lands slightly above the exact optimum
    assert direct.cost <= syn.cost * (1 + 1e-3) or direct.family != syn.family


def test_direct_from_synthesis_starts_matches_table_4_3():
    car = VariableSpeedCar(0.3, 1.0, 1.0)
    d = plan(Pose(), Pose(0.0, 2.0, 2 * math.pi / 3), car, method="direct")
    assert d.ok and d.planner == "time-optimal-direct"
    assert d.cost == pytest.approx(2.874650, rel=1e-4)
    assert (d.family, d.word) == ("CBSB", "LSR")
    assert d.stats["starts_tried"] >= 3


def test_direct_options_are_checked():
    car = VariableSpeedCar(0.3, 1.0, 1.0)
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1, 1, 0), car, method="direct", n_intervals=2)
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1, 1, 0), car, method="direct", synthesis_starts=-1)
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1, 1, 0), car, method="direct", bogus=1)
    with pytest.raises(InvalidParameterError):
        plan(Pose(), Pose(1, 1, 0), car, method="shooting")


def test_classify_controls():
    car = VariableSpeedCar(0.3, 1.0, 1.0)
    t = np.linspace(0.0, 4.0, 401)
    v = np.where(t < 1.0, 0.3, 1.0)
    u = np.where(t < 2.0, 1.0, np.where(t < 3.0, 0.0, -1.0))
    assert classify_controls(car, t, v, u) == ("CBSB", "LSR")
