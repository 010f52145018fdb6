"""The warning naming the pass a coarser `resolution_m` grid closes (issue 24,
`glideplan.reach.passes`): the ridge of test_native with one 1 km col (floor at x = 0, y =
0; crest plateau |y| < 0.4 km), searched on a 1 km max-pooled grid (the col closes; the
native search keeps it open); flat terrain has no pass."""

import math

import pytest

from glideplan.reach import Landable, glide_reach

from . import test_native as tn
from .conftest import flat_terrain


def _xy_km(lat, lon):
    return ((lon - tn.LON0) * math.cos(math.radians(tn.LAT0)) / tn.KM_LAT,
            (lat - tn.LAT0) / tn.KM_LAT)


def test_a_closed_col_is_named(polar, monkeypatch):
    """The warning says the 1019 m grid closes a pass within 1 km of the col's middle
    (measured 0.84 km: the native path crosses the col's east shoulder) and names the
    field behind the col (reached natively through it, as test_native shows)."""
    monkeypatch.setattr(tn, "COLS", ((0.0, 1.0),))
    t = tn.ridge_terrain()
    start = (*tn._xy_to_latlon(0.0, -5.0), tn.ALT)
    la, lo = tn._xy_to_latlon(3.0, 5.0)
    i, j = round((la - t.lat[0]) / t.dlat), round((lo - t.lon[0]) / t.dlon)
    field = Landable("behind 1 km col", float(t.lat[i]), float(t.lon[j]), float(t.z[i, j]), 3)
    r = glide_reach(t, start, polar, landables=[field], wind=tn.WIND, terrain_clearance=150,
                    arrival_height=300, resolution_m=1000.0)
    assert r.pooling == 11
    warn = [w for w in r.warnings if w.startswith("the --resolution")]
    assert len(warn) == 1 and "grid closes a pass near" in warn[0], r.warnings
    lat, lon = (float(v) for v in warn[0].split("near ")[1].split(" that")[0].split(", "))
    x, y = _xy_km(lat, lon)
    assert math.hypot(x, y) <= 1.0, (x, y)
    assert "behind 1 km col" in warn[0]


@pytest.mark.parametrize("res", [600.0, 1200.0])
def test_flat_terrain_names_no_pass(polar, res):
    t = flat_terrain(121, span_lat=0.3, span_lon=0.4)
    r = glide_reach(t, (46.15, 7.2, 1500.0), polar, wind=(5.0, 0.0), resolution_m=res)
    assert r.pooling > 1
    assert not any(w.startswith("the --resolution") for w in r.warnings), r.warnings
