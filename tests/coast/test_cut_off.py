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


def _global(tmp_path, land):
    from glideplan.fields.synthetic import global_dataset

    path = tmp_path / "global.nc"
    global_dataset(0.5, "0..360", kind="current", land=land).to_netcdf(path)
    f = open_field(path)
    assert f.periodic_lon
    return f


def _band_with_strait(strait_cols):
    """Land at 10..20 N all round the globe but for the strait's longitudes."""
    def land(lat, lon):
        band = (lat >= 10.0) & (lat <= 20.0)
        return band & ~np.isin(np.round(np.mod(lon, 360.0), 6), strait_cols)

    return land


def test_a_strait_at_the_seam_of_a_global_file(tmp_path):
    """The check wraps for a global 0.5 deg file, 0..359.5 E (it returned None for any field
    closing the circle). The check's metric (`cutoff` docstring: spacings at the field's mean
    latitude, 0 here): dx = 0.5 deg x 111.2 km = 55.6 km. Strait: the columns 0, 0.5 and
    1 E, land at 359.5 E (across the seam) and 1.5 E. Its middle column lies 2 dx = 111.2 km
    from land on both sides; the column at 0 E lies 1 dx from the land at 359.5 E (3 dx from
    1.5 E: an unwrapped check would call it free at 120 km). A clearance of 80 km leaves the
    middle free (open: None); 120 km closes it ("clearance": water alone joins start and
    goal); a band with no strait separates them ("land")."""
    from glideplan.routing.cutoff import field_cut_off

    f = _global(tmp_path, _band_with_strait([0.0, 0.5, 1.0]))
    start, goal = (5.0, 0.5), (25.0, 0.5)
    assert field_cut_off(f, 0.0, start, goal, 80e3) is None
    assert field_cut_off(f, 0.0, start, goal, 120e3) == "clearance"
    assert field_cut_off(f, 0.0, (5.0, 180.0), (25.0, 359.9), 120e3) == "clearance"
    assert field_cut_off(_global(tmp_path, _band_with_strait([])), 0.0, start, goal,
                         80e3) == "land"


def test_a_sea_across_the_seam_is_one_water(tmp_path):
    """Water only between 355 and 5 E, 10 S..10 N: one sea that the file's seam (0 E) cuts in
    two columns' worth of halves. Start at 357 E, goal at 3 E: the same water at a 100 km
    clearance (None; the sea is 20 deg across); a wall of land along 0 E splits it ("land").
    An unwrapped check would call the two halves two waters ("land") in the first case."""
    from glideplan.routing.cutoff import field_cut_off

    def sea(lat, lon):
        lon = np.mod(lon, 360.0)
        return ~((np.abs(lat) <= 10.0) & ((lon >= 355.0) | (lon <= 5.0)))

    start, goal = (0.0, 357.0), (0.0, 3.0)
    assert field_cut_off(_global(tmp_path, sea), 0.0, start, goal, 100e3) is None

    def split(lat, lon):
        return sea(lat, lon) | (np.isclose(np.mod(lon, 360.0), 0.0) & (np.abs(lat) <= 10.0))

    assert field_cut_off(_global(tmp_path, split), 0.0, start, goal, 10e3) == "land"


def test_a_strait_at_high_latitude_is_measured_in_its_own_metres(tmp_path):
    """Land at 70..80 N all round a global 0.5 deg file but for the columns 0, 0.5 and 1 E.
    At the strait's latitudes dx = 55.6 km x cos(lat): 19.0 km at 70 N, 9.7 km at 80 N, so
    its middle column lies 2 dx = 19.3..38.0 km from land on either side. A 50 km clearance
    closes it ("clearance"); a 15 km one leaves it open (None). The check before measured it
    at the file's mean latitude (the equator: 111 km) and called it open at 50 km."""
    from glideplan.routing.cutoff import field_cut_off

    def land(lat, lon):
        band = (lat >= 70.0) & (lat <= 80.0)
        return band & ~np.isin(np.round(np.mod(lon, 360.0), 6), [0.0, 0.5, 1.0])

    f = _global(tmp_path, land)
    start, goal = (60.0, 0.5), (85.0, 0.5)
    assert field_cut_off(f, 0.0, start, goal, 50e3) == "clearance"
    assert field_cut_off(f, 0.0, start, goal, 15e3) is None
