"""Dryden gusts: RMS, autocorrelation, saturation, reproducibility; steady disturbances."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError
from glideplan.simulation import DrydenTurbulence, SteadyDisturbance, saturate


def test_rms_and_correlation_match_the_model():
    model = DrydenTurbulence(sigma=10.0, scale_length=100.0, airspeed=20.0)  # L/V = 5 s
    g = model.sample(steps=1500, rows=400, dt=0.5, rng=np.random.default_rng(1))
    sigma_c = 10.0 / math.sqrt(2.0)
    # ~400 x 750 s / (2 x 5 s) = 30,000 independent samples per component: RMS within 2%
    assert np.sqrt(np.mean(g**2, axis=(0, 1))) == pytest.approx([sigma_c, sigma_c], rel=0.02)
    assert np.sqrt(np.mean(np.sum(g**2, axis=-1))) == pytest.approx(10.0, rel=0.02)
    for lag_steps in (2, 10, 20):  # lags of 1, 5, 10 s
        c = np.mean(g[lag_steps:] * g[:-lag_steps], axis=(0, 1))
        expect = model.autocorrelation(lag_steps * 0.5)
        assert c == pytest.approx([expect, expect], abs=0.04 * sigma_c**2)
    assert expect == pytest.approx(sigma_c**2 * math.exp(-2.0))
    # the two components are independent
    assert abs(np.mean(g[..., 0] * g[..., 1])) < 0.03 * sigma_c**2


def test_saturation_is_respected():
    model = DrydenTurbulence(sigma=15.0, scale_length=263.0, airspeed=20.0, saturation=15.0)
    g = model.sample(steps=400, rows=500, dt=0.25, rng=np.random.default_rng(2))
    mag = np.hypot(g[..., 0], g[..., 1])
    assert mag.max() <= 15.0 * (1 + 1e-12)
    # Rayleigh magnitude with RMS sigma clipped at sigma: P(clipped) = 1/e, RMS 0.795 sigma
    assert np.mean(mag >= 15.0 * (1 - 1e-12)) == pytest.approx(math.exp(-1), abs=0.02)
    assert np.sqrt(np.mean(mag**2)) / 15.0 == pytest.approx(math.sqrt(1 - math.exp(-1)), rel=0.02)


def test_seeded_and_independent_of_time_step_statistics():
    model = DrydenTurbulence(sigma=4.0)
    a = model.sample(50, 3, 0.05, np.random.default_rng(9))
    b = model.sample(50, 3, 0.05, np.random.default_rng(9))
    np.testing.assert_array_equal(a, b)
    assert not np.array_equal(a, model.sample(50, 3, 0.05, np.random.default_rng(10)))


def test_steady_and_saturate():
    s = SteadyDisturbance([[1.0, 0.0], [0.0, 2.0]]).stream(2, 0.1)
    np.testing.assert_allclose(s.next(), [[1.0, 0.0], [0.0, 2.0]], atol=1e-15)
    np.testing.assert_allclose(SteadyDisturbance((-3.0, 0.0)).velocity(4)[:, 0], -3.0)
    v = saturate(np.array([[3.0, 4.0], [0.3, 0.4], [0.0, 0.0]]), 1.0)
    np.testing.assert_allclose(v, [[0.6, 0.8], [0.3, 0.4], [0.0, 0.0]])


@pytest.mark.parametrize(
    "kwargs",
    [
        {"sigma": -1.0},
        {"sigma": math.nan},
        {"sigma": 1.0, "scale_length": 0.0},
        {"sigma": 1.0, "saturation": -2.0},
    ],
)
def test_bad_dryden_input(kwargs):
    with pytest.raises(InvalidParameterError):
        DrydenTurbulence(**kwargs)


def test_bad_stream_input():
    with pytest.raises(InvalidParameterError):
        DrydenTurbulence(1.0).stream(3, 0.0, np.random.default_rng(0))
    for bad in (None, -1, 1.5):  # a Generator or a seed: never global random state
        with pytest.raises(InvalidParameterError):
            DrydenTurbulence(1.0).stream(3, 0.1, bad)
    np.testing.assert_array_equal(
        DrydenTurbulence(1.0).sample(5, 2, 0.1, 42),
        DrydenTurbulence(1.0).sample(5, 2, 0.1, np.random.default_rng(42)),
    )
    with pytest.raises(InvalidParameterError):
        SteadyDisturbance([[1.0, 0.0], [2.0, 0.0]]).velocity(3)
