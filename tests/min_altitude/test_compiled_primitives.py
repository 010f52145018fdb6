"""The compiled heading primitives of the clipped B arc against the NumPy kernel.

Reference: `Kernel.primitives` on NumPy (checked against numerical integration of
(5.1)-(5.4) in test_extremals). The compiled kernel evaluates the same closed forms per
heading, so the values agree to rounding, over stall-clipped, v_max-clipped and free bands and
over headings beyond one period.
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan.planners.min_altitude import extremals
from glideplan.vehicles import dg1001m

pytest.importorskip("numba")


@settings(max_examples=20, deadline=None)
@given(st.lists(st.tuples(st.floats(-20.0, 20.0), st.just(0.0) | st.floats(1e-3, 60.0)),
                min_size=1, max_size=50))
def test_compiled_primitives_equal_numpy(rows):
    kern = extremals.Kernel.of(dg1001m())
    phi = np.array([r[0] for r in rows])
    lam = np.array([r[1] for r in rows])
    got = kern._compiled(phi, lam, phi.shape)
    extremals.COMPILED = False
    try:
        ref = kern.primitives(phi, lam)
    finally:
        extremals.COMPILED = True
    scale = 1.0 + np.abs(ref[0])
    np.testing.assert_allclose(np.abs(got[0] - ref[0]) / scale, 0.0, atol=1e-12)
    for g, r in zip(got[1:], ref[1:], strict=True):
        np.testing.assert_allclose(g, r, rtol=1e-12, atol=1e-9)
