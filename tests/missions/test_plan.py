"""Multi-leg missions: verified legs, totals, and straight-leg lists within tolerance."""

from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest

from glideplan.missions import Route, plan_mission, straight_leg_list
from glideplan.missions.straight_legs import segment_distances
from glideplan.planners.wind import convected_dubins
from glideplan.units import wind_from_compass


def _route():
    return Route.from_geographic(
        ["A", "B", "C", "D", "E"],
        [41.52, 41.535, 41.515, 41.4950, 41.505],
        [-70.90, -70.865, -70.835, -70.86, -70.89],
        [math.nan, math.nan, 180.0, math.nan, math.nan],
    )


def test_mission_legs_are_verified_and_headings_respected():
    """Each leg is planned by plan() and verified by integration (endpoint error < 1e-6 m);
    the given heading (compass 180) is kept; the totals are the sums over the legs."""
    plan = plan_mission(_route(), speed=0.5, radius=400.0)
    assert plan.ok
    assert plan.headings_deg[2] == pytest.approx(180.0)
    for leg in plan.legs:
        assert leg.solution.endpoint_error.max < 1e-6
    assert plan.total_length_m == pytest.approx(sum(leg.length_m for leg in plan.legs))
    assert plan.total_duration_s == pytest.approx(plan.total_length_m / 0.5)
    # the legs' lengths equal the optimiser's cost for the chosen headings
    assert plan.total_length_m == pytest.approx(plan.heading_plan.total, rel=1e-9)
    d = plan.to_dict()
    assert [leg["from"] for leg in d["legs"]] == ["A", "B", "C", "D"]


def test_straight_leg_list_stays_within_the_deviation():
    """Independent check of the simplification: the track resampled 20x more densely than the
    simplifier's samples lies within the tolerance of the polyline (plus the sagitta bound of
    the simplifier's sampling, 1 % of the tolerance); mission waypoints are in the list."""
    plan = plan_mission(_route(), speed=0.5, radius=400.0)
    tol = 30.0
    legs = straight_leg_list(plan, tol)
    assert legs.max_deviation_m <= tol
    names = [n for n, m in zip(legs.names, legs.mission, strict=True) if m]
    assert names == list(plan.route.names)
    dense = plan.track(legs.sample_spacing_m / 20)
    # distance of every dense sample to the nearest polyline segment
    best = np.full(dense.x.size, np.inf)
    for i in range(len(legs.x) - 1):
        d = segment_distances(dense.x, dense.y, legs.x[i], legs.y[i], legs.x[i + 1],
                              legs.y[i + 1])
        best = np.minimum(best, d)
    assert best.max() <= tol * 1.01
    assert len(legs.names) > plan.route.n  # the turns needed extra points at this tolerance


def test_wind_mission_times_match_the_wind_planner():
    """With a wind of 0.2 m/s from the north, every leg is the convected-Dubins minimum-time
    path (plan() with DubinsCarInWind, verified by integration through the wind) and its
    duration equals the scalar planner's arrival time for the chosen headings."""
    r = Route.from_local(["a", "b", "c"], [0.0, 800.0, 900.0], [0.0, 300.0, -500.0])
    plan = plan_mission(r, speed=1.0, radius=150.0, objective="time", wind=(0.0, -0.2),
                        headings=12)  # (east, north) towards: 0.2 m/s from the north
    assert plan.ok
    for leg in plan.legs:
        assert leg.solution.endpoint_error.max < 1e-6
        h0, h1 = plan.headings[leg.start], plan.headings[leg.end]
        dx, dy = r.x[leg.end] - r.x[leg.start], r.y[leg.end] - r.y[leg.start]
        c, s = math.cos(h0), math.sin(h0)
        local = (c * dx + s * dy, -s * dx + c * dy, h1 - h0)
        wind_local = (c * 0.0 + s * -0.2, -s * 0.0 + c * -0.2)  # (0, -0.2) rotated
        ref = convected_dubins(local, speed=1.0, radius=150.0, wind=wind_local).time
        assert leg.duration_s == pytest.approx(ref, rel=1e-9)
    assert plan.total_duration_s == pytest.approx(plan.heading_plan.total, rel=1e-6)


def test_wind_mission_planned_cost_is_the_flown_time():
    """Regression: in a wind the optimiser's cost of the chosen headings (vectorised times)
    equals the verified legs' total time; a spurious root at a 2 pi jump of a word's length
    once made the refinement report less than the planner then flew."""
    from glideplan.formats import read_route

    data = pathlib.Path(__file__).parents[2] / "src/glideplan/missions/data/buzzards_bay.gpx"
    plan = plan_mission(read_route(data), speed=0.5, radius=300.0, objective="time",
                        wind=wind_from_compass(0.15, 200.0), headings=8)
    assert plan.ok
    assert plan.total_duration_s == pytest.approx(plan.heading_plan.total, rel=1e-6)
