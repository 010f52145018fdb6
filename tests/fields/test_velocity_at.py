"""`FlowField.velocity_at` (the integrators' scalar path) equals `velocity` (SciPy's interpolator).

Reference: `GriddedField.velocity`, SciPy's `RegularGridInterpolator` (linear), an independent
implementation of the same trilinear rule; the scalar path must agree to rounding (1e-12
relative), give NaN exactly where it gives NaN (land), and raise the same named error outside.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import AnalyticField, Extent, GriddedField


def _gridded(periodic: bool, nt: int, seed: int = 3) -> GriddedField:
    rng = np.random.default_rng(seed)
    lat = np.linspace(-10.0, 12.0, 12)
    lon = np.arange(0.0, 360.0, 15.0) if periodic else np.linspace(170.0, 200.0, 9)
    u = rng.normal(size=(nt, lat.size, lon.size))
    v = rng.normal(size=(nt, lat.size, lon.size))
    u[:, 4, 3] = np.nan  # a land node
    v[:, 4, 3] = np.nan
    return GriddedField(times=np.arange(nt) * 3600.0, lat=lat, lon=lon, u=u, v=v)


@pytest.mark.parametrize(("periodic", "nt"), [(False, 1), (False, 4), (True, 1), (True, 4)])
def test_scalar_path_equals_the_interpolator(periodic: bool, nt: int) -> None:
    fld = _gridded(periodic, nt)
    rng = np.random.default_rng(11)
    n = 400
    t = rng.uniform(0.0, 3600.0 * max(nt - 1, 1), n)
    lat = rng.uniform(-10.0, 12.0, n)
    lon = rng.uniform(-400.0, 400.0, n) if periodic else rng.uniform(170.0, 200.0, n)
    lon[:5] = fld.lon[0]  # on grid lines and the last node: the clipped cell index
    lat[5:10] = fld.lat[-1]
    u_ref, v_ref = fld.velocity(t, lat, lon)
    for k in range(n):
        u, v = fld.velocity_at(float(t[k]), float(lat[k]), float(lon[k]))
        for got, ref in ((u, u_ref[k]), (v, v_ref[k])):
            if math.isnan(ref):
                assert math.isnan(got), k
            else:
                assert got == pytest.approx(float(ref), rel=1e-12, abs=1e-14), k
    assert np.isnan(u_ref).any()  # the land node is sampled, so NaN agreement was tested


def test_scalar_path_raises_the_same_error_outside() -> None:
    fld = _gridded(False, 4)
    for args in ((0.0, 50.0, 180.0), (0.0, 0.0, 150.0), (1e9, 0.0, 180.0),
                 (0.0, math.nan, 180.0)):
        with pytest.raises(InvalidParameterError) as a:
            fld.velocity(*args)
        with pytest.raises(InvalidParameterError) as b:
            fld.velocity_at(*args)
        assert str(a.value) == str(b.value)


def test_analytic_scalar_path_equals_velocity() -> None:
    fld = AnalyticField(fn=lambda t, la, lo: (np.sin(la) * t, np.cos(lo) + 0 * t),
                        extent=Extent(-5.0, 5.0, 100.0, 120.0), time_span=(0.0, 10.0))
    here = fld.velocity_at(3.0, 1.0, 110.0)
    assert here == tuple(float(x) for x in fld.velocity(3.0, 1.0, 110.0))
    assert fld.velocity_at(3.0, 1.0, 110.0 - 360.0) == pytest.approx(here)
    with pytest.raises(InvalidParameterError, match="outside the field"):
        fld.velocity_at(3.0, 1.0, 130.0)
