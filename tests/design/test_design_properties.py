"""Hypothesis properties of the design toolkit: inverses and exactness over random inputs."""

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan.design import (
    FX23DV,
    VTUG_BLADDER,
    bladder_moles,
    equilibrium_volume_m3,
    fix_position,
    flow_coefficient,
    gas_flow_scfm,
    number_of_dives,
)

coord = st.floats(-2000.0, 2000.0, allow_nan=False)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.floats(1e-5, 5e-3), st.floats(0.0, 300.0))
def test_equilibrium_volume_inverts_7_5(v, z):
    n = bladder_moles(VTUG_BLADDER, v, z)
    assert abs(equilibrium_volume_m3(VTUG_BLADDER, n, z) - v) < 1e-12


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.floats(0.01, 10.0), st.floats(20.0, 3000.0), st.floats(0.0, 0.999), st.floats(400, 600))
def test_cv_inverts_flow(cv, p1, frac, t):
    p2 = max(p1 * frac, 1e-3)
    q = gas_flow_scfm(cv, p1, p2, t)
    assert np.isclose(flow_coefficient(q, p1, p2, t), cv, rtol=1e-10)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.floats(1e-3, 5e-3), st.floats(0.0, 500.0), st.floats(1.0, 100.0))
def test_deeper_means_fewer_dives(v, z, dz):
    assert number_of_dives(FX23DV, v, z + dz) < number_of_dives(FX23DV, v, z)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(st.lists(st.tuples(coord, coord), min_size=3, max_size=6), st.tuples(coord, coord))
def test_noise_free_fix_is_exact_or_refused(beacons, point):
    b = np.array(beacons)
    centred = b - b.mean(axis=0)
    s = np.linalg.svd(centred, compute_uv=False)
    # well-conditioned networks only: the weakest axis spans at least 50 m and 20 % of the widest
    if s[-1] < max(50.0, 0.2 * s[0]):
        return
    p = np.array(point)
    r = np.linalg.norm(p - b, axis=-1)
    est = fix_position(b, r)
    assert np.linalg.norm(est - p) < 1e-6
