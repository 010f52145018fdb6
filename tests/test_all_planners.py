"""Every registered planner honours the contract of `plan()` (parametrised over all of them).

For each planner: the solution is verified, its cost equals the cost the core recomputes from
the path's controls and the cost integrated independently along them, the best candidate is
the cheapest feasible one, and moving start and goal together by a rigid motion changes
nothing (translation only where the vehicle carries a world-fixed wind).
"""

import math

import pytest

import glideplan
from glideplan import Pose, plan
from glideplan.planning import registered_planners
from glideplan.verify import integrate_path


def _examples():
    """(vehicle, goal in the start frame, rotation invariant) for each vehicle model."""
    v = glideplan.vehicles
    out = {
        "DubinsCar": (v.DubinsCar(speed=2.0, turn_radius=1.5), (2.0, 3.0, 2.5), True),
        "DubinsCarInWind": (
            v.DubinsCarInWind(speed=1.0, turn_radius=1.0, wind_speed=0.3, wind_direction=0.5),
            (3.0, 3.0, math.pi / 2),
            False,
        ),
        "VariableSpeedCar": (v.VariableSpeedCar(0.3, 1.0, 1.0), (0.0, 2.0, 2 * math.pi / 3), True),
        "LoadFactorGlider": (v.LoadFactorGlider(), (-2.0, 4.0, 7 * math.pi / 4), True),
    }
    if hasattr(v, "QuadraticPolarGlider"):
        from glideplan.vehicles.quadratic_polar_glider import dg1001m

        g = dg1001m()
        r = g.length_scale
        out["QuadraticPolarGlider"] = (g, (-3.0 * r, 4.0 * r, 0.0), True)
    return out


EXAMPLES = _examples()
# only the package's own planners (tests may register toy planners in the same process)
PACKAGE_SPECS = [s for s in registered_planners() if s.vehicle.__module__.startswith("glideplan.")]
SPECS = [s for s in PACKAGE_SPECS if s.default]


def test_every_planner_has_an_example_vehicle():
    missing = {s.vehicle.__name__ for s in PACKAGE_SPECS} - set(EXAMPLES)
    assert not missing, f"add an example vehicle for {missing} to this test"


@pytest.fixture(scope="module", params=SPECS, ids=lambda s: f"{s.name}-{s.objective}")
def solved(request):
    spec = request.param
    vehicle, goal, rotation_invariant = EXAMPLES[spec.vehicle.__name__]
    start = Pose(0.0, 0.0, 0.0)
    sol = plan(start, Pose(*goal), vehicle, spec.objective)
    return spec, vehicle, goal, rotation_invariant, sol


def test_solution_is_verified(solved):
    spec, vehicle, _, _, sol = solved
    assert sol.ok, sol.message
    scale = max(1.0, vehicle.length_scale)
    assert sol.endpoint_error.position <= 1e-6 * scale
    assert sol.endpoint_error.heading <= 1e-6
    assert sol.planner == spec.name and sol.objective == spec.objective


def test_cost_is_the_cost_of_the_path(solved):
    spec, _, _, _, sol = solved
    assert sol.path.cost(spec.objective) == pytest.approx(sol.cost, rel=1e-6)
    if spec.objective != "time" or not hasattr(sol.path.segments[0], "drift"):
        independent = integrate_path(sol.path, spec.objective).cost
        assert independent == pytest.approx(sol.cost, rel=1e-6)


def test_best_candidate_is_the_cheapest_feasible(solved):
    _, _, _, _, sol = solved
    feasible = [c.cost for c in sol.candidates if c.feasible]
    assert feasible and sol.cost == pytest.approx(min(feasible), rel=1e-12)
    assert feasible == sorted(feasible)


def test_rigid_motion_of_both_poses_changes_nothing(solved):
    spec, vehicle, goal, rotation_invariant, sol = solved
    frame = Pose(17.0, -4.0, 1.1 if rotation_invariant else 0.0)
    start = Pose(0.0, 0.0, 0.0).from_frame(frame)
    moved = plan(start, Pose(*goal).from_frame(frame), vehicle, spec.objective)
    assert moved.ok
    assert moved.cost == pytest.approx(sol.cost, rel=1e-6)
    assert moved.path.start.distance_to(start) < 1e-9
