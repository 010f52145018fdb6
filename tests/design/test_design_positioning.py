"""LBL positioning: exactness, error vs number of beacons, degenerate geometry, survey sim."""

import numpy as np
import pytest

from glideplan.design import (
    LBLConfig,
    check_beacon_geometry,
    dilution_of_precision,
    fix_algebraic,
    fix_least_squares,
    fix_position,
    horizontal_ranges_m,
    lawnmower_track,
    simulate_survey,
)
from glideplan.errors import InvalidParameterError


def _ring(m: int, radius: float = 500.0) -> np.ndarray:
    a = 2 * np.pi * np.arange(m) / m + 0.3
    return radius * np.column_stack([np.cos(a), np.sin(a)])


def _ranges(points: np.ndarray, beacons: np.ndarray) -> np.ndarray:
    return np.linalg.norm(points[..., None, :] - beacons, axis=-1)


@pytest.mark.parametrize("m", [3, 4, 7])
def test_noise_free_fix_is_exact(m):
    rng = np.random.default_rng(1)
    beacons = rng.uniform(-800, 800, (m, 2))
    points = rng.uniform(-1000, 1000, (200, 2))
    r = _ranges(points, beacons)
    for est in (fix_algebraic(beacons, r), fix_least_squares(beacons, r), fix_position(beacons, r)):
        assert np.max(np.linalg.norm(est - points, axis=-1)) < 1e-6


def test_noise_free_fix_from_slant_ranges_with_depths():
    beacons = np.array([[0.0, 0.0], [300.0, 0.0], [100.0, 250.0]])
    p = np.array([120.0, 80.0])
    slant = np.sqrt(_ranges(p, beacons) ** 2 + (1.524 - 4.572) ** 2)
    est = fix_position(beacons, horizontal_ranges_m(slant, 1.524, 4.572), "algebraic")
    assert np.linalg.norm(est - p) < 1e-6


def test_least_squares_error_falls_as_beacons_are_added():
    # fixed seed, 2000 fixes per network, points inside the ring; sigma = 3 m range noise
    rng = np.random.default_rng(2024)
    pts = rng.uniform(-250, 250, (2000, 2))
    mean_err = []
    for m in (3, 4, 6, 8, 12):
        b = _ring(m)
        r = _ranges(pts, b) + rng.normal(0.0, 3.0, (2000, m))
        mean_err.append(np.mean(np.linalg.norm(fix_least_squares(b, r) - pts, axis=-1)))
    assert np.all(np.diff(mean_err) < 0), mean_err
    # evenly spaced beacons: HDOP ~ 2 / sqrt(m), so 12 beacons halve the 3-beacon error
    assert mean_err[-1] < 0.6 * mean_err[0]


def test_least_squares_beats_algebraic_on_average():
    rng = np.random.default_rng(7)
    b = _ring(5)
    pts = rng.uniform(-300, 300, (2000, 2))
    r = _ranges(pts, b) + rng.normal(0.0, 5.0, (2000, 5))
    e_ls = np.linalg.norm(fix_least_squares(b, r) - pts, axis=-1)
    e_al = np.linalg.norm(fix_algebraic(b, r) - pts, axis=-1)
    assert np.sqrt(np.mean(e_ls**2)) < np.sqrt(np.mean(e_al**2))


def test_hdop_matches_evenly_spaced_formula():
    # m beacons evenly on a circle seen from its centre: J^T J = (m/2) I -> HDOP = 2 / sqrt(m)
    for m in (3, 4, 8):
        assert dilution_of_precision(_ring(m), [0.0, 0.0]) == pytest.approx(2 / np.sqrt(m))


def test_collinear_beacons_are_an_error():
    b = np.array([[0.0, 0.0], [100.0, 50.0], [300.0, 150.0]])
    with pytest.raises(InvalidParameterError) as err:
        fix_least_squares(b, [10.0, 20.0, 30.0])
    assert err.value.name == "beacons_m" and "collinear" in str(err.value)
    with pytest.raises(InvalidParameterError):
        LBLConfig(beacons_m=((0.0, 0.0), (1.0, 1.0), (2.0, 2.0)))


def test_fewer_than_three_beacons_is_an_error():
    with pytest.raises(InvalidParameterError) as err:
        check_beacon_geometry([[0.0, 0.0], [100.0, 0.0]])
    assert err.value.name == "beacons_m" and "at least 3" in str(err.value)
    with pytest.raises(InvalidParameterError):
        fix_position([[0.0, 0.0], [100.0, 0.0]], [1.0, 2.0])


def test_dropped_pings_and_collinear_subsets_give_nan_not_a_wrong_fix():
    # beacons 0, 1, 2 collinear on y = 0; beacon 3 off the line
    b = np.array([[0.0, 0.0], [100.0, 0.0], [200.0, 0.0], [100.0, 150.0]])
    p = np.array([60.0, 40.0])
    r = _ranges(p, b)
    rows = np.array([r, r, r, r])
    rows[1, 3] = np.nan  # only the collinear three answered -> ambiguous -> NaN
    rows[2, [0, 1]] = np.nan  # two answers -> NaN
    rows[3, 0] = np.nan  # 1, 2, 3 answered: fine
    est = fix_position(b, rows)
    assert np.linalg.norm(est[0] - p) < 1e-6 and np.linalg.norm(est[3] - p) < 1e-6
    assert np.all(np.isnan(est[1])) and np.all(np.isnan(est[2]))


def test_survey_simulation_statistics_and_seed():
    cfg = LBLConfig(range_noise_std_m=4.0, ping_success_probability=0.75)
    track = lawnmower_track((300.0, 900.0), (500.0, 900.0), 7, 5.0)
    a = simulate_survey(cfg, track, 11)
    b = simulate_survey(cfg, track, np.random.default_rng(11))
    assert np.array_equal(a.errors_m, b.errors_m, equal_nan=True)
    s = a.statistics
    # 3 * 567 pings, binomial sd = sqrt(0.75 * 0.25 / 1701) = 0.0105
    assert s.pings == 3 * len(track)
    assert abs(s.ping_success_fraction - 0.75) < 0.04
    # a fix needs all 3 replies: P = 0.75^3 = 0.42
    assert abs(s.fix_fraction - 0.75**3) < 0.06
    assert 0 < s.median_error_m <= s.p95_error_m <= s.max_error_m


def test_survey_without_noise_is_exact_and_bias_hurts():
    track = lawnmower_track((300.0, 900.0), (500.0, 900.0), 3, 20.0)
    clean = simulate_survey(
        LBLConfig(range_noise_std_m=0.0, ping_success_probability=1.0), track, 0
    )
    assert clean.statistics.fix_fraction == 1.0
    assert clean.statistics.max_error_m < 1e-6
    biased = LBLConfig(
        range_noise_std_m=0.0, ping_success_probability=1.0, sound_speed_true_m_s=1440.0
    )
    assert simulate_survey(biased, track, 0).statistics.mean_error_m > 1.0


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: LBLConfig(range_noise_std_m=-1.0), "range_noise_std_m"),
        (lambda: LBLConfig(ping_success_probability=1.5), "ping_success_probability"),
        (lambda: LBLConfig(method="kalman"), "method"),
        (lambda: fix_algebraic(_ring(3), [1.0, 2.0]), "ranges_m"),
        (lambda: fix_algebraic(_ring(3), [1.0, -2.0, 3.0]), "ranges_m"),
        (lambda: lawnmower_track((1.0, 0.0), (0.0, 1.0), 3, 1.0), "x_range_m"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(InvalidParameterError) as err:
        call()
    assert err.value.name == name
