"""Issue 10: direct-method planners stop at a wall-clock limit and say so; the load-factor
planner refuses goals beyond its documented reach instead of running for minutes."""

import math

import pytest

from glideplan import InvalidParameterError, LoadFactorGlider, Pose, Status, VariableSpeedCar, plan
from glideplan.planners.load_factor import MAX_GOAL_DISTANCE


@pytest.mark.parametrize(
    ("vehicle", "goal", "method"),
    [
        (LoadFactorGlider(), Pose(200.0, 0.0, math.pi), None),
        (VariableSpeedCar(0.3, 1.0, 1.0), Pose(0.0, 2.0, 2.0943951023931953), "direct"),
    ],
)
def test_time_limit_reached_is_a_solver_failure_with_its_message(vehicle, goal, method):
    """A limit far below one IPOPT solve: no path, status solver_failed, the stated message."""
    sol = plan(Pose(), goal, vehicle, method=method, time_limit=1e-3)
    assert sol.status is Status.SOLVER_FAILED and sol.path is None
    assert "time limit of 0.001 s reached" in sol.message
    assert sol.stats["time_limit_reached"] is True


def test_time_limit_must_be_positive():
    with pytest.raises(InvalidParameterError, match="time_limit"):
        plan(Pose(), Pose(5.0, 3.0, 1.0), LoadFactorGlider(), time_limit=-1.0)


def test_load_factor_refuses_goals_beyond_its_reach():
    """`plan load-factor --goal 1000 0 180` ran for 590 s; now a one-line refusal naming the
    goal and the documented maximum distance."""
    assert MAX_GOAL_DISTANCE < 1000.0
    with pytest.raises(InvalidParameterError, match=rf"goal=1000.*at most {MAX_GOAL_DISTANCE:g}"):
        plan(Pose(), Pose(1000.0, 0.0, math.pi), LoadFactorGlider())


def test_a_failed_retiming_is_a_warning_of_the_solution(monkeypatch):
    """Issue 10 §3: when re-timing fails, the engine keeps the collocation timing and says so;
    plan() carries the sentence into Solution.warnings (and --json). The failure is forced by
    replacing the re-timing with one that reports no convergence."""
    import glideplan.planners.direct.engine as engine

    def failing_retime(t, speed, turn_rate, target, **kwargs):
        return t, 0.2, False

    monkeypatch.setattr(engine, "retime", failing_retime)
    sol = plan(
        Pose(), Pose(0.0, 2.0, 2.0943951023931953), VariableSpeedCar(0.3, 1.0, 1.0), method="direct"
    )
    assert any("re-timing" in w and "stretch 0.2" in w for w in sol.warnings)
    assert sol.to_dict()["warnings"] == list(sol.warnings)
