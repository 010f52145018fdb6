"""Glide reach at the DEM's own resolution (issue 24): passes stay open, the footprint agrees
with an independent reference search on the native grid (tests/reach/native_reference.py),
fields over the antimeridian, two safety heights, `short_by_m`, `terrain_missing`."""

import math

import numpy as np
import pytest

from glideplan.reach import Landable, glide_reach
from glideplan.terrain import Terrain

from .conftest import flat_terrain
from .native_reference import reference_error, reference_loss

LAT0, LON0 = 46.0, 7.0
DLAT = 3 / 3600  # 92.6 m
DLON = DLAT / math.cos(math.radians(LAT0))  # 92.6 m east too
KM_LAT = 1000 / (6371008.8 * math.radians(1))
ALT = 1450.0
WIND = (5.0, 0.0)  # from the west
COLS = ((-6.0, 0.3), (0.0, 1.0), (7.0, 3.0))  # (x km, flat col floor width km)
FIELDS = {"behind 300 m col": (-9.0, 5.0), "behind 1 km col": (3.0, 5.0),
          "behind 3 km col": (9.5, 5.0)}


def _xy_to_latlon(x_km, y_km):
    return LAT0 + y_km * KM_LAT, LON0 + x_km * KM_LAT / math.cos(math.radians(LAT0))


def ridge_terrain():
    """A valley floor at 500 m (gently rough), an east-west ridge (crest 1400 m, 0.8 km
    plateau, 1.2 km flanks) at y = 0 with three cols down to 900 m, 92.6 m sampling."""
    y = np.arange(-7.0, 7.0 + 1e-9, DLAT / KM_LAT)
    x = np.arange(-11.0, 11.0 + 1e-9, DLAT / KM_LAT)
    Y, X = np.meshgrid(y, x, indexing="ij")
    crest = np.full(X.shape, 1400.0)
    for xc, w in COLS:
        d = np.abs(X - xc) - 0.5 * w  # < 0 on the col's floor; 0.3 km to the crest
        crest = np.minimum(crest, 900.0 + 500.0 * np.clip(d / 0.3, 0.0, 1.0))
    across = np.clip(1.0 - (np.abs(Y) - 0.4) / 1.2, 0.0, 1.0)
    rough = 60.0 * np.sin(1.3 * X) * np.sin(1.1 * Y + 0.4) + 40.0 * np.cos(2.3 * X + 0.7 * Y)
    z = np.maximum(500.0 + rough * (1 - across) + (crest - 500.0) * across, 300.0)
    lat, lon = _xy_to_latlon(0.0, y)[0], _xy_to_latlon(x, 0.0)[1]
    return Terrain(lat, lon, z.astype(np.float32))


@pytest.fixture(scope="module")
def case(polar):
    t = ridge_terrain()
    start = (*_xy_to_latlon(0.0, -5.0), ALT)
    fields = []
    for name, (x, y) in FIELDS.items():
        la, lo = _xy_to_latlon(x, y)
        # fields on nodes: the reference's answer is the node's
        i = round((la - t.lat[0]) / t.dlat)
        j = round((lo - t.lon[0]) / t.dlon)
        fields.append(Landable(name, float(t.lat[i]), float(t.lon[j]),
                               float(t.z[i, j]), 3))
    i, j = round(12.0 / (DLAT / KM_LAT)), round(11.0 / (DLAT / KM_LAT))  # (0, +5) km
    high = Landable("high field", float(t.lat[i]), float(t.lon[j]), float(t.z[i, j]) + 600, 3)
    fields.append(high)
    r = glide_reach(t, start, polar, landables=fields, wind=WIND, terrain_clearance=150.0,
                    arrival_height=300.0)
    from glideplan.reach import Glide

    ref = reference_loss(t, start, Glide(polar, 0.0, WIND), 150.0)
    return t, start, fields, r, ref


@pytest.fixture(scope="module")
def ref_error(polar):
    """The reference's own overestimate in this wind (`reference_error`)."""
    from glideplan.reach import Glide

    return reference_error(Glide(polar, 0.0, WIND))


def test_fields_behind_cols_match_the_reference(case, ref_error):
    """Reachability and arrival of every field as the native reference (+-1 % of the
    altitude lost, widened by the reference's own overestimate, <= 1.3 %); the cols are
    flown through (detour); the crest is too high for the straight glide."""
    t, _start, fields, r, ref = case
    assert r.pooling == 1 and r.resolution_m < 100
    for lnd, pt in zip(fields, r.points, strict=True):
        i = round((lnd.lat - t.lat[0]) / t.dlat)
        j = round((lnd.lon - t.lon[0]) / t.dlon)
        ref_loss = ref[i, j]
        ref_ok = ALT - ref_loss >= lnd.elevation_m + 300.0
        assert pt.reachable == ref_ok, lnd.name
        if lnd.name == "high field":
            assert not pt.reachable and pt.short_by_m is not None
            ref_short = lnd.elevation_m + 300.0 - (ALT - ref_loss)
            assert pt.short_by_m == pytest.approx(ref_short, abs=0.01 * ref_loss
                                                  + ref_error * ref_loss)
            continue
        loss = ALT - pt.arrival_altitude_m
        assert ref_loss / (1 + ref_error) - 0.01 * ref_loss <= loss <= ref_loss * 1.01
        assert pt.detour and pt.verified and pt.min_clearance_m >= 150.0 - 1e-6
        assert pt.short_by_m is None and not pt.terrain_missing
        straight = pt.path.waypoints_lat.size == 2
        assert not straight


def test_a_coarse_grid_is_conservative_and_says_so(polar, case):
    """At a 460 m grid (max-pooled) the cols narrower than ~2 cells close: the fields behind
    them arrive no higher than at the native grid (conservative; the path flown over the true
    DEM), and the warning says passes may close."""
    t, start, fields, r_native, _ = case
    r = glide_reach(t, start, polar, landables=fields, wind=WIND, terrain_clearance=150,
                    arrival_height=300, resolution_m=460.0)
    assert r.pooling == 5
    for p, q in zip(r.points, r_native.points, strict=True):
        if p.arrival_altitude_m is not None and p.verified:
            assert p.arrival_altitude_m <= q.arrival_altitude_m + 1e-6
            assert p.min_clearance_m >= 150 - 1e-6
    assert any("pass or gap narrower" in w for w in r.warnings)


def test_footprint_within_3_percent_of_the_reference_and_never_beyond(case, ref_error):
    """Nodes in the footprint (margin >= 0) against the reference's: area within 3 %; no node
    of the footprint is one the reference cannot reach even with its loss deflated by its
    own overestimate (ref_error); every reachable field inside the drawn polygon."""
    from matplotlib.path import Path

    t, _start, _fields, r, ref = case
    z = np.asarray(t.z, dtype=float)
    assert r.margin.shape == ref.shape
    ours = r.margin >= 0
    theirs = ALT - ref - z - 300.0 >= 0
    assert abs(ours.sum() - theirs.sum()) <= 0.03 * theirs.sum()
    generous = ALT - ref / (1 + ref_error) - z - 300.0 >= 0
    assert not np.any(ours & ~generous)
    for pt in r.points:
        if pt.reachable:
            inside = any(Path(poly[0]).contains_point((pt.landable.lon, pt.landable.lat))
                         for poly in r.footprint)
            assert inside, pt.landable.name


def test_two_heights_and_the_old_single_height(polar):
    """--safety-height sets both heights; the clearance en route and the arrival height act
    separately: on flat ground at 0 m a field 20 km away with arrival 300 m needs
    300 + 20000 / r; a clearance of 400 m en route (> the arrival height) blocks it."""

    from glideplan.reach import Glide

    t = flat_terrain(121, span_lat=0.6, span_lon=0.8)
    g = Glide(polar)
    r_still = float(g.ratio(np.array([0.0]))[0])
    lat0, lon0 = 46.3, 7.1
    dlon = 20000 / (6371008.8 * math.cos(math.radians(lat0))) * 180 / math.pi
    fld = Landable("F", lat0, lon0 + dlon, 0.0)
    alt = 300.0 + 20000 / r_still + 50.0
    r = glide_reach(t, (lat0, lon0, alt), polar, landables=[fld])
    assert r.terrain_clearance == 150 and r.arrival_height == 300
    assert r.points[0].reachable
    assert r.points[0].arrival_margin_m == pytest.approx(50.0, abs=1.0)
    r = glide_reach(t, (lat0, lon0, alt), polar, landables=[fld], safety_height=400.0)
    assert r.terrain_clearance == 400 and r.arrival_height == 400
    assert not r.points[0].reachable
    assert r.points[0].short_by_m == pytest.approx(50.0, abs=1.0)
    assert "short by 50 m" in r.points[0].note


def test_field_on_missing_terrain_is_marked(polar):
    t = flat_terrain(61, span_lat=0.3, span_lon=0.4)
    z = np.array(t.z)
    z[40:, 40:] = np.nan
    t = Terrain(t.lat, t.lon, z)
    fld = Landable("in the void", float(t.lat[50]), float(t.lon[50]), 0.0)
    r = glide_reach(t, (46.1, 7.1, 1500.0), polar, landables=[fld])
    p = r.points[0]
    assert p.terrain_missing and not p.reachable and p.short_by_m is None
    assert p.to_dict()["terrain_missing"] is True
    assert "missing terrain" in r.clipped


def test_field_over_the_antimeridian(polar, tmp_path):
    """Tiles S17E179 and S17W180 (flat, sea level) merged; a field 28 km east over 180 deg
    whose straight glide arrives 90 m above the arrival height is reachable (+90 m)."""
    from glideplan.reach import Glide
    from glideplan.terrain import read_terrain, write_hgt

    n = 1201
    paths = []
    for name in ("S17E179.hgt", "S17W180.hgt"):
        p = tmp_path / name
        write_hgt(p, np.zeros((n, n), dtype=np.int16))
        paths.append(p)
    t = read_terrain(paths)
    assert t.lon[0] == pytest.approx(179.0) and t.lon[-1] == pytest.approx(181.0)
    lat0, lon0 = -16.5, 179.9
    dlon = math.degrees(28000 / (6371008.8 * math.cos(math.radians(lat0))))
    fld = Landable("over 180", lat0, lon0 + dlon - 360.0, 0.0)
    r_east = float(Glide(polar).ratio(np.array([0.0]))[0])
    alt = 300.0 + 90.0 + 28000 / r_east
    r = glide_reach(t, (lat0, lon0, alt), polar, landables=[fld])
    p = r.points[0]
    assert p.reachable and p.arrival_margin_m == pytest.approx(90.0, abs=1.0)
    assert p.landable.lon == fld.lon  # reported as given


def test_turnback_at_the_dem_resolution_matches_an_independent_bisection(polar):
    """Home south of the ridge, the course east along its north side: the way home runs
    through a col. The turn-back point (one backward search, the course walked, verified by
    flights) against an independent search: bisection on the distance out with, at each
    probe, the forward glide reach from that point (`glide_reach`, home as its landable) --
    within one DEM cell (92.6 m)."""
    from glideplan.geodesy import rhumb_destination as destination
    from glideplan.reach import Glide, turnback

    t = ridge_terrain()
    la_h, lo_h = _xy_to_latlon(0.0, -5.0)
    i = round((la_h - t.lat[0]) / t.dlat)
    j = round((lo_h - t.lon[0]) / t.dlon)
    home = Landable("HOME", float(t.lat[i]), float(t.lon[j]), float(t.z[i, j]))
    la0, lo0 = _xy_to_latlon(-3.0, 4.0)
    alt = 1350.0
    r = turnback((la0, lo0, alt), 90.0, home, polar, terrain=t, safety_height=300.0)
    assert r.ok and r.back is not None and r.back.min_clearance_m >= 300.0 - 1e-6
    assert r.limited_by != "search budget"
    r_out = float(Glide(polar).ratio(np.array([0.0]))[0])

    def reachable(s):
        la, lo = destination(la0, lo0, 0.0, np.array(s))
        res = glide_reach(t, (float(la), float(lo), alt - s / r_out), polar, landables=[home],
                          terrain_clearance=300.0, arrival_height=300.0)
        return res.points[0].reachable

    a, b = 0.0, 6000.0
    assert reachable(a) and not reachable(b)
    while b - a > 46.0:
        mid = 0.5 * (a + b)
        a, b = (mid, b) if reachable(mid) else (a, mid)
    assert r.distance_m == pytest.approx(0.5 * (a + b), abs=92.6)


def test_field_beyond_the_longest_glide_is_out_of_reach_not_missing(polar):
    """On the terrain but outside the searched crop (farther than the longest glide over the
    lowest terrain): out of reach, not terrain_missing, short by the flat-ground straight
    glide's deficit (closed form: elevation + arrival + d / r - ALT)."""
    from glideplan.reach import Glide

    t = flat_terrain(121, span_lat=0.6, span_lon=0.8)
    lat0, lon0 = 46.3, 7.1
    dlon = math.degrees(50000 / (6371008.8 * math.cos(math.radians(lat0))))
    fld = Landable("far", lat0, lon0 + dlon, 0.0)
    r = glide_reach(t, (lat0, lon0, 600.0), polar, landables=[fld])
    p = r.points[0]
    assert not p.reachable and not p.terrain_missing
    ratio = float(Glide(polar).ratio(np.array([0.0]))[0])
    assert p.short_by_m == pytest.approx(300.0 + 50000 / ratio - 600.0, rel=1e-3)
