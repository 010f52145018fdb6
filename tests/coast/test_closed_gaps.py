"""The warning naming a gap open at the land mask's resolution that the front's grid closes
(issue 24, `glideplan.routing.gaps`).

A 2 km thick wall of land (500 m mask) from the field's west edge with a hole one cell wide
at x = 10 km (land nodes 1 km apart: 200 m of water beyond a 400 m clearance), open water
the long way round its east end. The hole is the narrowest gap; a straight coast and a
rectangular cape have none (no saddle of the distance to land)."""

from __future__ import annotations

import pytest

from glideplan.fields import open_field
from glideplan.routing import route

from . import shapes

WALL = (40.0, 30.0, [(0.0, 9.6, 14.0, 16.0), (10.4, 32.0, 14.0, 16.0)], (4.0, 8.0),
        (10.0, 22.0))
COAST = (40.0, 30.0, [(0.0, 40.0, 14.0, 30.0)], (5.0, 8.0), (35.0, 9.0))


def _route(tmp_path, monkeypatch, name, shape, **kw):
    monkeypatch.setitem(shapes.SHAPES, name, shape)
    lat, lon, land = shapes.mask(name, 500.0)
    path = tmp_path / f"{name}.nc"
    shapes.write(path, lat, lon, land)
    _, _, _, start, goal = shape
    return route(open_field(path), shapes.lat_lon(*start), shapes.lat_lon(*goal), 1.0, **kw)


@pytest.mark.parametrize("res", [250.0, 1500.0])
def test_a_one_cell_hole_the_grid_closes_is_named(tmp_path, monkeypatch, res):
    """The warning names a gap 1 km wide between land nodes (the hole: one mask cell of
    water) at a node of the hole (x = 10 km, 14 <= y <= 16 km: the hole's 2 km length;
    the pass nearest a front obstacle is named, not necessarily the middle). At 250 m the
    front's lattice misses the hole's middle and the route goes the long way (> 3 x the
    ~16.4 km through the hole, measured) -- the case the warning is for."""
    r = _route(tmp_path, monkeypatch, "wall", WALL, resolution=res, land_clearance_m=400.0)
    assert r.status == "solved", r.message
    gap = [w for w in r.warnings if "open at the land mask's resolution" in w]
    assert gap and "closes a gap 1 km wide" in gap[0], r.warnings
    where = gap[0].split("near ")[1].split(" that")[0]
    lat, lon = (float(v) for v in where.split(", "))
    y, x = (v * shapes.R / shapes.KM * 3.141592653589793 / 180 for v in (lat, lon))
    assert abs(x - 10.0) <= 0.5 + 1e-6 and 14.0 - 1e-3 <= y <= 16.0 + 1e-3, (x, y)
    if res == 250.0:
        assert r.duration_s > 3 * 16.4e3


@pytest.mark.parametrize("name", ["coast", "cape"])
def test_open_coasts_give_no_gap_warning(tmp_path, monkeypatch, name):
    shape = COAST if name == "coast" else shapes.SHAPES["cape"]
    r = _route(tmp_path, monkeypatch, name, shape, resolution=1500.0)
    assert r.status == "solved", r.message
    assert not any("gap" in w for w in r.warnings), r.warnings
