"""plan(): registry dispatch, normalisation to the start frame, verification, statuses."""

import math
from dataclasses import dataclass
from typing import ClassVar

import pytest

from glideplan import (
    Candidate,
    InvalidParameterError,
    Path,
    PlannerOutput,
    PlanningError,
    Pose,
    Status,
    Straight,
    plan,
    register_planner,
)
from glideplan.vehicles.base import Vehicle


@dataclass(frozen=True)
class Rover(Vehicle):
    """A test vehicle that can only drive straight ahead (heading fixed)."""

    model: ClassVar[str] = "test_rover"
    default_objective: ClassVar[str] = "length"
    lie: bool = False  # when True the planner returns a path that misses the goal


seen_goals: list[Pose] = []


@register_planner("test-straight", vehicle=Rover, objective="length")
def _straight(problem, *, slack: float = 0.0):
    g = problem.goal
    seen_goals.append(g)
    if abs(g.y) > 1e-9 or g.x < 0 or abs(g.heading) > 1e-9:
        return PlannerOutput(candidates=(Candidate("S", "S", math.inf, None, "infeasible"),))
    extra = 0.5 if problem.vehicle.lie else 0.0
    path = Path((Straight(problem.start, g.x + extra),))
    return PlannerOutput(candidates=(Candidate("S", "S", g.x + extra + slack, path),))


def test_plan_normalises_to_the_start_frame_and_maps_back():
    start = Pose(1.0, 1.0, math.pi / 4)
    goal = Pose(1.0 + 3.0 / math.sqrt(2), 1.0 + 3.0 / math.sqrt(2), math.pi / 4)
    sol = plan(start, goal, Rover())
    assert sol.ok and sol.status is Status.SOLVED
    # the planner saw the goal 3 m straight ahead of the origin
    assert (seen_goals[-1].x, seen_goals[-1].y) == pytest.approx((3.0, 0.0), abs=1e-12)
    assert sol.cost == pytest.approx(3.0)
    assert sol.path.start == start
    assert sol.endpoint_error.max < 1e-9
    d = sol.to_dict()
    assert d["planner"] == "test-straight" and d["word"] == "S" and d["length"] == pytest.approx(3)


def test_no_path_and_not_verified_statuses():
    sol = plan((0, 0, 0), (0, 1, 0), Rover())
    assert sol.status is Status.NO_PATH and sol.path is None and not sol.ok
    with pytest.raises(PlanningError, match="no_path"):
        sol.raise_for_status()
    lying = plan((0, 0, 0), (2, 0, 0), Rover(lie=True))
    assert lying.status is Status.NOT_VERIFIED and lying.path is None


def test_unknown_option_objective_and_method_are_errors():
    with pytest.raises(InvalidParameterError, match="slak"):
        plan((0, 0, 0), (1, 0, 0), Rover(), slak=1.0)
    with pytest.raises(InvalidParameterError, match="objective"):
        plan((0, 0, 0), (1, 0, 0), Rover(), objective="time")
    with pytest.raises(InvalidParameterError, match="method"):
        plan((0, 0, 0), (1, 0, 0), Rover(), method="magic")
    assert plan((0, 0, 0), (1, 0, 0), Rover(), slack=0.25).cost == pytest.approx(1.25)


@pytest.mark.parametrize("bad", [(0, 0), (math.nan, 0, 0), (0, math.inf, 0)])
def test_bad_poses_are_errors(bad):
    with pytest.raises(InvalidParameterError, match="goal"):
        plan((0, 0, 0), bad, Rover())
