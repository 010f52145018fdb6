"""`routing.local_sampler`: the current sampled once on a grid answers one point at a time.

Reference: a current linear in x, y and t is reproduced exactly by trilinear interpolation
of its samples (to rounding); outside the box or the span the exact function answers.
"""

from __future__ import annotations

import numpy as np
import pytest

from glideplan.routing.local_sampler import sampled_velocity


def _exact(t, x, y):
    x, y = np.atleast_1d(x), np.atleast_1d(y)
    return 0.1 + 1e-5 * x - 2e-5 * y + 1e-6 * t, -0.05 + 3e-5 * x + 1e-7 * t + 0 * y


def _levels(times, x, y):
    pairs = [_exact(float(t), x, y) for t in times]
    return np.array([p[0] for p in pairs]), np.array([p[1] for p in pairs])


def test_linear_current_reproduced_and_outside_falls_back():
    calls = []

    def exact(t, x, y):
        calls.append(1)
        return _exact(t, x, y)

    fn = sampled_velocity(exact, (-1000.0, 2000.0, -500.0, 1500.0), np.array([0.0, 3600.0,
                                                                              7200.0]),
                          100.0, _levels)
    rng = np.random.default_rng(0)
    for _ in range(50):
        t = rng.uniform(0, 7200)
        x, y = rng.uniform(-1000, 2000), rng.uniform(-500, 1500)
        u, v = fn(t, np.array([x]), np.array([y]))
        ue, ve = _exact(t, x, y)
        assert u[0] == pytest.approx(ue[0], abs=1e-12) and v[0] == pytest.approx(ve[0],
                                                                                 abs=1e-12)
    assert not calls
    fn(100.0, np.array([5000.0]), np.array([0.0]))  # outside the box
    fn(9000.0, np.array([0.0]), np.array([0.0]))  # after the span
    assert len(calls) == 2
