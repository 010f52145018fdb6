"""The six Dubins words in closed form: hand-derived values, degenerate cases, batching."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError, Pose
from glideplan.planners.dubins import (
    WORDS,
    dubins_distance,
    dubins_path,
    dubins_segment_lengths,
    dubins_shortest,
    dubins_word_lengths,
    feasible_radius,
    word_directions,
)

PI = math.pi
ORIGIN = np.zeros(3)


def _lengths(goal, radius=1.0, start=ORIGIN):
    return dubins_segment_lengths(np.asarray(start, float), np.asarray(goal, float), radius)


def test_words_table_order_and_directions():
    assert WORDS == ("LSL", "LSR", "RSL", "RSR", "RLR", "LRL")
    assert word_directions("lsr") == (1, 0, -1)
    assert word_directions("RLR") == (-1, 1, -1)
    with pytest.raises(InvalidParameterError, match="word"):
        word_directions("SSS")


def test_six_words_goal_0_4_pi_by_hand():
    # Goal (0, 4, pi), R = 1. Start circles: left (0, 1), right (0, -1); goal circles:
    # left (x - sin psi, y + cos psi) = (0, 3), right (x + sin psi, y - cos psi) = (0, 5).
    # LSL: centres 2 apart straight up: quarter turn, straight 2, quarter turn -> pi/2, 2, pi/2.
    # RSR: centres 6 apart: right turn of 3pi/2 (heading -> pi/2), straight 6, 3pi/2 again.
    # LSR: centre distance 4, straight sqrt(16 - 4) = 2 sqrt 3, straight heading
    #      pi/2 + atan(2 / (2 sqrt 3)) = pi/2 + pi/6 = 2pi/3 -> t = 2pi/3, q = 2pi/3 - pi + 2pi.
    # RSL: mirror-like: heading pi/2 - pi/6 = pi/3 -> t = 2pi - pi/3, q = pi - pi/3.
    # RLR: right circles 6 > 4 apart: infeasible.
    # LRL: left circles 2 apart, middle arc 2pi - acos(1 - 4/8) = 5pi/3,
    #      t = pi/2 + 5pi/6 = 4pi/3, q = pi - 4pi/3 + 5pi/3 = 4pi/3.
    table = _lengths([0.0, 4.0, PI])
    s3 = 2.0 * math.sqrt(3.0)
    expected = np.array(
        [
            [PI / 2, 2.0, PI / 2],
            [2 * PI / 3, s3, 5 * PI / 3],
            [5 * PI / 3, s3, 2 * PI / 3],
            [3 * PI / 2, 6.0, 3 * PI / 2],
            [np.nan, np.nan, np.nan],
            [4 * PI / 3, 5 * PI / 3, 4 * PI / 3],
        ]
    )
    np.testing.assert_allclose(table, expected, rtol=0, atol=1e-12)
    best = dubins_shortest(ORIGIN, np.array([0.0, 4.0, PI]), 1.0)
    assert WORDS[int(best.word_index)] == "LSL"
    assert float(best.length) == pytest.approx(2.0 + PI, abs=1e-12)


def test_mirror_case_swaps_left_and_right():
    # Reflecting the goal (0, 4, pi) in the x-axis gives (0, -4, -pi): L and R swap.
    table = _lengths([0.0, -4.0, -PI])
    mirror = _lengths([0.0, 4.0, PI])[[3, 2, 1, 0, 5, 4]]
    np.testing.assert_allclose(table, mirror, atol=1e-12)


def test_turning_around_in_place_is_a_ccc_path_of_7pi_over_3():
    # Goal (0, 0, pi): LSR/RSL need circle centres >= 2 apart but theirs coincide -> infeasible.
    # RLR: right circles (0, -1), (0, 1), 2 apart: middle arc 5pi/3, outer arcs pi/3 each,
    # total 7pi/3; LRL the same by symmetry. LSL / RSR: 3pi/2 + 2 + 3pi/2 = 2 + 3pi.
    totals = dubins_word_lengths(ORIGIN, np.array([0.0, 0.0, PI]), 1.0)
    np.testing.assert_allclose(
        totals, [2 + 3 * PI, np.nan, np.nan, 2 + 3 * PI, 7 * PI / 3, 7 * PI / 3], atol=1e-12
    )
    assert float(dubins_distance(ORIGIN, np.array([0.0, 0.0, PI]))) == pytest.approx(7 * PI / 3)


@pytest.mark.parametrize("radius", [0.5, 1.0, 7.0])
def test_straight_ahead_is_the_distance(radius):
    # Goal on the start heading: every CSC word degenerates to the straight line (t = q = 0).
    goal = np.array([10.0, 0.0, 0.0])
    table = _lengths(goal, radius)
    for k in range(4):
        np.testing.assert_allclose(table[k], [0.0, 10.0, 0.0], atol=1e-12)
    assert float(dubins_distance(ORIGIN, goal, radius)) == pytest.approx(10.0, abs=1e-12)


@pytest.mark.parametrize("angle", [0.3, PI / 2, 2.5, 3 * PI / 2])
@pytest.mark.parametrize("radius", [1.0, 2.5])
def test_pure_turns(angle, radius):
    # A left turn of `angle` on a circle of radius R ends at (R sin a, R (1 - cos a), a):
    # length R a; the right turn is its mirror image.
    left = np.array([radius * math.sin(angle), radius * (1 - math.cos(angle)), angle])
    best = dubins_shortest(ORIGIN, left, radius)
    assert float(best.length) == pytest.approx(radius * angle, abs=1e-12)
    right = left * [1, -1, -1]
    best_r = dubins_shortest(ORIGIN, right, radius)
    assert float(best_r.length) == pytest.approx(radius * angle, abs=1e-12)
    # Only the turn itself has length: the other pieces are exactly zero.
    assert dubins_path(Pose(), Pose(*left), radius).word == "L"
    path_r = dubins_path(Pose(), Pose(*right), radius)
    assert [s.letter for s in path_r.segments if s.length > 1e-7] == ["R"]


def test_goal_equal_to_start_has_length_zero():
    start = np.array([3.0, -2.0, 1.234])
    assert float(dubins_distance(start, start, 1.0)) == 0.0
    best = dubins_shortest(start, start, 1.0)
    assert float(best.length) == 0.0
    np.testing.assert_array_equal(best.segment_lengths, [0.0, 0.0, 0.0])
    path = dubins_path(Pose(*start), Pose(*start), 1.0)
    assert path is not None and path.length == 0.0


@pytest.mark.parametrize("turns", [1, -1, 3])
def test_headings_differing_by_multiples_of_2pi(turns):
    # psi1 = psi0 + 2 pi k is the same pose: goal = start gives 0, a goal ahead gives the distance.
    start = np.array([1.0, 1.0, 0.7])
    same = start + np.array([0.0, 0.0, 2 * PI * turns])
    assert float(dubins_distance(start, same, 1.0)) == 0.0
    ahead = np.array([1.0 + 4 * math.cos(0.7), 1.0 + 4 * math.sin(0.7), 0.7 + 2 * PI * turns])
    assert float(dubins_distance(start, ahead, 1.0)) == pytest.approx(4.0, abs=1e-12)


def test_collinear_goal_behind():
    # Goal 5 behind with the same heading: half turn (pi), straight 5, half turn (pi);
    # LSL and RSR tie at 5 + 2 pi; CCC infeasible (circle centres 5 apart > 4).
    totals = dubins_word_lengths(ORIGIN, np.array([-5.0, 0.0, 0.0]), 1.0)
    assert totals[0] == pytest.approx(5 + 2 * PI, abs=1e-12)
    assert totals[3] == pytest.approx(5 + 2 * PI, abs=1e-12)
    assert np.isnan(totals[4]) and np.isnan(totals[5])


def test_every_feasible_word_path_reaches_its_goal():
    rng = np.random.default_rng(7)
    for _ in range(40):
        start = Pose(*rng.uniform(-5, 5, 2), rng.uniform(-PI, PI))
        goal = Pose(*rng.uniform(-5, 5, 2), rng.uniform(-PI, PI))
        radius = float(rng.uniform(0.3, 3.0))
        for word in WORDS:
            path = dubins_path(start, goal, radius, speed=2.0, word=word)
            if path is None:
                continue
            gap, dh = path.endpoint_gap(goal)
            assert gap < 1e-9 and dh < 1e-9, (word, gap, dh)
            assert path.duration == pytest.approx(path.length / 2.0)


def test_batch_shapes_and_broadcasting():
    rng = np.random.default_rng(3)
    goals = np.concatenate([rng.uniform(-4, 4, (5, 4, 2)), rng.uniform(-PI, PI, (5, 4, 1))], -1)
    radius = rng.uniform(0.5, 2.0, (5, 4))
    table = dubins_segment_lengths(ORIGIN, goals, radius)
    assert table.shape == (5, 4, 6, 3)
    best = dubins_shortest(ORIGIN, goals, radius)
    assert best.length.shape == (5, 4) and best.segment_lengths.shape == (5, 4, 3)
    assert best.words.shape == (5, 4)
    np.testing.assert_allclose(best.segment_lengths.sum(-1), best.length, atol=1e-12)
    fast, index = dubins_distance(ORIGIN, goals, radius, return_index=True)
    np.testing.assert_allclose(fast, best.length, rtol=1e-12, atol=1e-12)
    np.testing.assert_array_equal(index, best.word_index)
    np.testing.assert_allclose(
        dubins_word_lengths(ORIGIN, goals, radius), np.nansum(table, axis=-1) + 0 * table[..., 0]
    )
    for i in range(5):
        for j in range(4):
            one = dubins_shortest(ORIGIN, goals[i, j], radius[i, j])
            assert float(one.length) == pytest.approx(best.length[i, j], abs=1e-12)


def test_fast_path_agrees_with_table_on_many_queries():
    rng = np.random.default_rng(11)
    n = 20_000  # more than two internal chunks
    starts = np.c_[rng.uniform(-6, 6, (n, 2)), rng.uniform(-10, 10, n)]
    goals = np.c_[rng.uniform(-6, 6, (n, 2)), rng.uniform(-10, 10, n)]
    table = dubins_segment_lengths(starts, goals, 1.3)
    totals = np.where(np.isnan(table[..., 0]), np.inf, table.sum(-1))
    fast = dubins_distance(starts, goals, 1.3)
    np.testing.assert_allclose(fast, totals.min(-1), rtol=0, atol=1e-11)


def test_agrees_with_ompl():
    ob = pytest.importorskip("ompl.base")
    rng = np.random.default_rng(5)
    n = 3000
    starts = np.c_[rng.uniform(-8, 8, (n, 2)), rng.uniform(-PI, PI, n)]
    goals = np.c_[rng.uniform(-8, 8, (n, 2)), rng.uniform(-PI, PI, n)]
    space = ob.DubinsStateSpace(1.7)
    a, b = space.allocState(), space.allocState()
    ref = np.empty(n)
    for i in range(n):
        a.setX(starts[i, 0])
        a.setY(starts[i, 1])
        a.setYaw(starts[i, 2])
        b.setX(goals[i, 0])
        b.setY(goals[i, 1])
        b.setYaw(goals[i, 2])
        ref[i] = space.distance(a, b)
    np.testing.assert_allclose(dubins_distance(starts, goals, 1.7), ref, rtol=0, atol=1e-9)


def test_feasible_radius():
    # R0' = R0 (1 + eps)^2: eps = 0.25 -> 1.5625 R0; eps = 0 -> R0.
    assert feasible_radius(2.0, 0.25) == pytest.approx(3.125)
    assert feasible_radius(2.0, 0.0) == 2.0
    np.testing.assert_allclose(feasible_radius(1.0, np.array([0.5, 0.75])), [2.25, 3.0625])


@pytest.mark.parametrize("eps", [1.0, 1.5, -0.1, math.nan, math.inf])
def test_feasible_radius_rejects_bad_eps(eps):
    with pytest.raises(InvalidParameterError, match="disturbance_ratio"):
        feasible_radius(1.0, eps)


@pytest.mark.parametrize("radius", [0.0, -1.0, math.nan, math.inf])
def test_bad_radius(radius):
    with pytest.raises(InvalidParameterError, match="radius"):
        dubins_distance(ORIGIN, np.array([1.0, 2.0, 0.0]), radius)
    with pytest.raises(InvalidParameterError, match="radius"):
        dubins_path(Pose(), Pose(1, 2, 0), radius)


@pytest.mark.parametrize("bad", [[1.0, math.nan, 0.0], [math.inf, 0.0, 0.0], [1.0, 2.0]])
def test_bad_poses(bad):
    with pytest.raises(InvalidParameterError, match="goal"):
        dubins_segment_lengths(ORIGIN, np.array(bad), 1.0)
    with pytest.raises(InvalidParameterError, match="start"):
        dubins_shortest(np.array(bad), ORIGIN, 1.0)


def test_dubins_path_word_choice_and_labels():
    path = dubins_path(Pose(), Pose(0, 4, PI), 1.0, word="LRL", label_turn="C")
    assert path is not None and path.word == "LRL" and path.family == "CCC"
    assert dubins_path(Pose(), Pose(0, 4, PI), 1.0, word="RLR") is None
    best = dubins_path(Pose(), Pose(0, 4, PI), 1.0)
    assert best is not None and best.word == "LSL" and best.family == "BSB"
    with pytest.raises(InvalidParameterError, match="word"):
        dubins_path(Pose(), Pose(0, 4, PI), 1.0, word="LLL")


def test_empty_and_scalar_batches():
    empty = np.zeros((0, 3))
    assert dubins_distance(ORIGIN, empty).shape == (0,)
    assert dubins_word_lengths(ORIGIN, empty, 1.0).shape == (0, 6)
    assert dubins_shortest(ORIGIN, empty).length.shape == (0,)
    length, index = dubins_distance(ORIGIN, np.array([0.0, 4.0, PI]), return_index=True)
    assert length.shape == () and WORDS[int(index)] == "LSL"


def test_dubins_path_accepts_tuples_and_rejects_garbage():
    path = dubins_path((0.0, 0.0, 0.0), (0.0, 4.0, PI), 1.0)
    assert path is not None and path.length == pytest.approx(2 + PI)
    with pytest.raises(InvalidParameterError, match="goal"):
        dubins_path(Pose(), (1.0, math.nan, 0.0), 1.0)
    with pytest.raises(InvalidParameterError, match="start"):
        dubins_path("origin", Pose(), 1.0)


def test_independent_direct_method_value():
    # REFERENCE_NOTES 4.2: a CasADi/IPOPT minimum-time solve to (4, 3, pi/2) with unit speed and
    # radius gave T* = 5.17635, the LSL length.
    length, index = dubins_distance(ORIGIN, np.array([4.0, 3.0, PI / 2]), return_index=True)
    assert float(length) == pytest.approx(5.17635, abs=5e-6)
    assert WORDS[int(index)] == "LSL"
