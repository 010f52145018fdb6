"""A land clearance that closes the only strait is named as such, not as the field's time
span running out (issue 26). Input: the `shapes` strait (land nodes 4 km apart across a 3 km
strait, coasts filling the field's width), still water over an 11 h time span: at 1 m/s the
straight line (38.8 km, 10.8 h) fits in it (inside the drift cone) but the front cannot fill
the 60 x 18 km water south of the coasts (its far corner 41.8 km away, 11.6 h), so it stops
on time; at a 2.1 km clearance (> half of 4 km) no water joins start and goal at all.
"""

from __future__ import annotations

import numpy as np

from glideplan.fields import open_field
from glideplan.fields.synthetic import copernicus_dataset
from glideplan.routing import route

from . import shapes


def _field(tmp_path):
    lat, lon, land = shapes.mask("strait", 1000.0)
    u = np.where(land, np.nan, 0.0)[None, None].repeat(2, axis=0)
    times = [np.datetime64("2026-01-01T00:00"), np.datetime64("2026-01-01T11:00")]
    path = tmp_path / "strait11h.nc"
    copernicus_dataset(lat, lon, times, [0.5], u, u).to_netcdf(path)
    return open_field(path)


def test_clearance_closing_the_strait_is_named(tmp_path):
    f = _field(tmp_path)
    _, _, _, start, goal = shapes.SHAPES["strait"]
    r = route(f, shapes.lat_lon(*start), shapes.lat_lon(*goal), 1.0, cells=40,
              land_clearance_m=2100.0)
    assert r.status == "unreachable"
    assert r.unreachable_reason == "front_stopped", r.message  # was time_span
    assert "land clearance (2100 m) closes every passage" in r.message


def test_time_span_stays_time_span_when_the_way_is_open(tmp_path):
    """The same strait at a 1.5 km clearance (1 km of water between the disks): open, and
    11 h is too short for the ~40.6 km way through it (11.3 h): the answer stays time_span."""
    f = _field(tmp_path)
    _, _, _, start, goal = shapes.SHAPES["strait"]
    r = route(f, shapes.lat_lon(*start), shapes.lat_lon(*goal), 1.0, cells=40,
              land_clearance_m=1500.0)
    assert r.status == "unreachable" and r.unreachable_reason == "time_span", r.message
