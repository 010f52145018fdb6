"""The chapter 4 synthesis: Table 4.3, special goals, random goals, properties."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan import Pose, VariableSpeedCar, plan
from glideplan.planners.dubins import dubins_path
from glideplan.planners.min_time import CANDIDATE_TYPES, synthesize
from glideplan.planners.min_time.geometry import compose
from glideplan.planners.min_time.solvers import piece_moves, solve_type, trig_roots
from glideplan.verify import endpoint_error, integrate_path

CAR = VariableSpeedCar(0.3, 1.0, 1.0)
GOAL_4_3 = Pose(0.0, 2.0, 2 * math.pi / 3)


@pytest.fixture(scope="module")
def table_4_3():
    return plan(Pose(), GOAL_4_3, CAR)


def test_table_4_3_best_path(table_4_3):
    sol = table_4_3
    assert sol.ok
    assert (sol.family, sol.word) == ("CBSB", "LSR")
    # two independent solvers (this closed form and SLSQP on the 4-parameter problem) agree;
    # the SLSQP value is printed to 10 decimals (+-5e-11) and converged to ~1e-10
    assert sol.cost == pytest.approx(2.874650, abs=5e-7)  # 6 decimals
    assert sol.cost == pytest.approx(2.8746504152, abs=1e-9)
    assert sol.endpoint_error.max < 1e-9
    integrated = integrate_path(sol.path, "time")
    assert integrated.cost == pytest.approx(sol.cost, rel=1e-9)
    # the extremal structure: C arc at v_min, B arc of exactly pi/2 next to S at v_max
    c, b, s, b2 = sol.path.segments
    assert (c.label, c.speed, c.radius) == ("C", 0.3, 0.3)
    assert (b.label, b.speed, b.radius, b.direction) == ("B", 1.0, 1.0, 1)
    assert b.angle == pytest.approx(math.pi / 2, abs=1e-12)
    assert s.label == "S" and b2.direction == -1


# rows of Table 4.3 that are extremals (type as we name it, dissertation's cost)
FOUND = [
    ("CBSB LSR", 2.875),
    ("BBB RLR", 5.980),
    ("BCBSB RSL", 6.615),
    ("BSB RSL", 8.015),  # printed "BBB RSL": an RSL word is a BSB path
    ("CBBCB LL", 8.378),  # fixed turn rate: heading change 2pi/3 + 2pi
    ("BSB LSL", 9.378),  # printed "BSB LSR": LSR does not exist for this goal
    ("BCBSBCB RSR", 11.278),
    ("BSB RSR", 14.078),
]


@pytest.mark.parametrize(("name", "value"), FOUND)
def test_table_4_3_rows_found(table_4_3, name, value):
    costs = {c.info["type"]: c.cost for c in table_4_3.candidates if c.feasible}
    assert costs[name] == pytest.approx(value, abs=5e-4)  # printed to 3 decimals


def test_table_4_3_non_extremal_rows_absent(table_4_3):
    # (4.27) boundary minima in the dissertation's parameterisation, not extremals
    types = {c.info["type"] for c in table_4_3.candidates}
    for name in ("CBSB LSL", "CBSBC LSL", "BCBB LR", "BTB RLR", "CBSBCB RSR"):
        assert name not in types
    assert table_4_3.candidates[0].info["type"] == "CBSB LSR"
    umax = next(c for c in table_4_3.candidates if c.info["type"] == "CBBCB LL")
    assert umax.cost == pytest.approx(2 * math.pi / 3 + 2 * math.pi, abs=1e-9)
    assert set(umax.family) == {"B", "C"} and umax.word == "L"


def test_dubins_ratio_about_two(table_4_3):
    dub = min(
        p.duration
        for w in ("LSL", "LSR", "RSL", "RSR", "LRL", "RLR")
        if (p := dubins_path(Pose(), GOAL_4_3, 1.0, 1.0, word=w)) is not None
    )
    assert dub / table_4_3.cost == pytest.approx(2.08, abs=0.01)


def test_rigid_sequence_left_out_by_b4_is_sometimes_optimal():
    # B.4 / (4.24) drop C B T B C; for this goal it is optimal (the direct method agrees,
    # tests/min_time/test_min_time_direct.py), 10.6 % faster than the best type of (4.26)
    car = VariableSpeedCar(0.5, 1.0, 1.0)
    goal = np.array([0.148, 0.7861, 2.3468])
    only = synthesize(goal, 0.5, supplementary=False).best
    assert only.ctype.name == "CCC RLR" and only.cost == pytest.approx(6.10798, abs=1e-5)
    sol = plan(Pose(), Pose(*goal), car)
    best = sol.candidates[0]
    assert best.info["type"] == "CBTBC RLR" and best.info["in_dissertation"] is False
    assert "4.24" in best.info["violates"]
    assert sol.cost == pytest.approx(5.462384, abs=1e-6)
    assert sol.endpoint_error.max < 1e-9


def test_goal_next_to_start():
    sol = plan(Pose(), Pose(0.09, 0.16, 0.22), CAR)
    assert sol.ok and sol.endpoint_error.max < 1e-9
    assert sol.word == "R"  # one right turn at u_max through 2 pi - 0.22
    assert sol.cost == pytest.approx(2 * math.pi - 0.22, abs=1e-9)


@pytest.mark.parametrize(
    ("goal", "turn"),
    [
        ((0.5, 0.5, math.pi / 2), math.pi / 2),
        ((0.3, 0.7, 2.0), 2.0),
        ((0.2, -0.1, -0.3), 2 * math.pi - 0.3),  # a left turn through 2 pi - 0.3
    ],
)
def test_single_turn_goals_cost_the_heading_change(goal, turn):
    sol = plan(Pose(), Pose(*goal), CAR)
    assert sol.ok and len(sol.word) == 1
    assert sol.cost == pytest.approx(turn, abs=1e-9)  # = |heading change| / u_max
    assert {s.label for s in sol.path.segments} <= {"B", "C"}


def test_single_turn_built_from_a_bcb_turn():
    # B^0.4 C^1.1 B^0.7: every speed profile of the same heading change takes 2.2 s
    p, h = compose([("B", 1, 0.4), ("C", 1, 1.1), ("B", 1, 0.7)], 0.3, ())
    sol = plan(Pose(), Pose(float(p[0]), float(p[1]), float(h)), CAR)
    assert sol.cost == pytest.approx(2.2, abs=1e-9)


def test_trivial_and_straight_goals():
    sol = plan(Pose(), Pose(), CAR)
    assert sol.ok and sol.cost == 0.0
    sol = plan(Pose(), Pose(2.5, 0.0, 0.0), CAR)
    assert sol.cost == pytest.approx(2.5) and sol.word == "S"


def test_scale_invariance_and_world_frame():
    car = VariableSpeedCar(v_min=0.15, v_max=0.5, u_max=0.1)  # R = 5 m, r = 1.5 m
    sol = plan(Pose(), Pose(0.0, 10.0, 2 * math.pi / 3), car)
    assert sol.cost == pytest.approx(28.746504152, abs=1e-6)
    start = Pose(3.0, -1.0, 0.7)
    goal = Pose(0.0, 10.0, 2 * math.pi / 3).from_frame(start)
    moved = plan(start, goal, car)
    assert moved.cost == pytest.approx(sol.cost, rel=1e-12)
    assert endpoint_error(moved.path, goal).max < 1e-6


def test_equal_speeds_reduce_to_dubins():
    car = VariableSpeedCar(1.0, 1.0, 0.5)  # R = 2
    goal = Pose(1.0, 3.0, 2.0)
    sol = plan(Pose(), goal, car)
    dub = min(
        p.length
        for w in ("LSL", "LSR", "RSL", "RSR", "LRL", "RLR")
        if (p := dubins_path(Pose(), goal, 2.0, word=w)) is not None
    )
    assert sol.cost == pytest.approx(dub / 1.0, rel=1e-12)
    assert {c.info["group"] for c in sol.candidates} == {"Dubins"}


def _random_goals(n, seed):
    rng = np.random.default_rng(seed)
    return [
        (float(x), float(y), float(h))
        for x, y, h in zip(
            rng.uniform(-3, 3, n), rng.uniform(-3, 3, n), rng.uniform(-math.pi, math.pi, n),
            strict=True,
        )
    ]  # fmt: skip


@pytest.mark.parametrize("rho", [0.3, 0.5])
def test_random_goals_bounds_mirror_and_endpoint(rho):
    car = VariableSpeedCar(rho, 1.0, 1.0)
    # 20 goals per ratio here; benchmarks/min_time_vs_direct.py checks the same bounds, the
    # mirror and the endpoint on 200 per ratio (`make validate`)
    for x, y, h in _random_goals(20, seed=int(10 * rho)):
        goal = Pose(x, y, h)
        sol = plan(Pose(), goal, car)
        assert sol.ok
        assert sol.endpoint_error.max < 1e-6
        # never above Dubins at v_max (radius R) nor CCC at v_min (radius r), by time
        for radius, speed, words in ((1.0, 1.0, ("LSL", "LSR", "RSL", "RSR", "LRL", "RLR")),
                                     (rho, rho, ("LRL", "RLR"))):  # fmt: skip
            for w in words:
                p = dubins_path(Pose(), goal, radius, speed, word=w)
                if p is not None:
                    assert sol.cost <= p.duration * (1 + 1e-12)
        mirror = plan(Pose(), Pose(x, -y, -h), car)
        assert mirror.cost == pytest.approx(sol.cost, rel=1e-9)
        # every candidate path is a real path to the goal with the stated time
        for c in sol.candidates:
            assert c.path.endpoint_gap(goal)[0] < 1e-7
            assert c.path.duration == pytest.approx(c.cost, rel=1e-12)


def _random_extremal(ctype, rng):
    a = math.pi / 2 if ctype.group == "TST" else rng.uniform(0.02, 1.55)
    first, last = ctype.branches[rng.integers(len(ctype.branches))]
    u1 = rng.uniform(0, math.pi if first == "CB" else a)
    u2 = rng.uniform(0, math.pi if last == "BC" else a)
    d1, d2 = ctype.directions[0], ctype.directions[-1]
    middle = [("S", 0, rng.uniform(0, 3))] if ctype.straight else []
    d = -d1
    for _ in range(ctype.interior):
        middle += piece_moves("T", "interior", d, None, a)
        d = -d
    return piece_moves(first, "first", d1, u1, a) + middle + piece_moves(last, "last", d2, u2, a)


@pytest.mark.parametrize("ctype", [t for t in CANDIDATE_TYPES if t.group in ("TST", "TTTT")],
                         ids=lambda t: t.name.replace(" ", "-"))  # fmt: skip
def test_every_type_recovers_its_own_extremals(ctype):
    rng = np.random.default_rng(abs(hash(ctype.name)) % 2**32)
    for _ in range(4):
        moves = _random_extremal(ctype, rng)
        p, h = compose(moves, 0.3, ())
        goal = np.array([p[0], p[1], h])
        cost = sum(m[2] for m in moves)
        found = solve_type(ctype, goal, 0.3)
        assert any(abs(e.cost - cost) < 1e-7 for e in found)
        assert synthesize(goal, 0.3).best.cost <= cost + 1e-9


def test_trig_roots_finds_all_roots_including_double():
    a = np.arange(16) * (2 * math.pi / 16)
    f = np.cos(2 * a) - 0.3 * np.sin(a) + 0.1  # four simple roots
    roots = trig_roots(f)
    assert roots.size == 4
    assert np.allclose(np.cos(2 * roots) - 0.3 * np.sin(roots) + 0.1, 0.0, atol=1e-12)
    tangent = trig_roots(1.0 - np.cos(a - 1.0))  # double root at a = 1
    assert tangent.size >= 1 and np.allclose(tangent, 1.0, atol=1e-6)


def test_deterministic_and_all_groups_reported(table_4_3):
    again = plan(Pose(), GOAL_4_3, CAR)
    assert [c.cost for c in again.candidates] == [c.cost for c in table_4_3.candidates]
    stats = table_4_3.stats
    assert stats["candidate_types"] == 72 and stats["supplementary_types"] == 42
    assert set(stats["seconds_by_group"]) == {"TTTT", "TST", "umax", "Dubins", "supplementary"}


@settings(max_examples=40, deadline=None)
@given(
    x=st.floats(-3, 3), y=st.floats(-3, 3), h=st.floats(-math.pi, math.pi),
    rho=st.sampled_from([0.2, 0.3, 0.5, 0.8]),
)  # fmt: skip
def test_property_mirror_and_reversal_bounds(x, y, h, rho):
    car = VariableSpeedCar(rho, 1.0, 1.0)
    sol = plan(Pose(), Pose(x, y, h), car, verify=False)
    assert sol.ok
    mirror = plan(Pose(), Pose(x, -y, -h), car, verify=False)
    assert mirror.cost == pytest.approx(sol.cost, rel=1e-9, abs=1e-12)
    # time is at least the straight-line distance at v_max and the net turn at u_max
    assert sol.cost >= math.hypot(x, y) - 1e-9
    assert sol.cost >= abs(math.remainder(h, 2 * math.pi)) - 1e-9
    # reversibility: the reversed path (goal -> start, headings + pi) takes the same time
    back = Pose(0.0, 0.0, math.pi).relative_to(Pose(x, y, h + math.pi))
    assert plan(Pose(), back, car, verify=False).cost == pytest.approx(
        sol.cost, rel=1e-9, abs=1e-12
    )
