"""Glide reach against closed forms: flat still air, flat uniform wind, a wall to go round."""

import itertools
import json
import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.reach import Landable, glide_reach
from glideplan.solution import Status
from glideplan.terrain import Terrain

from .conftest import flat_terrain
from .test_model import brute

R_EARTH = 6371008.8


def haversine(lat1, lon1, lat2, lon2):
    """Great-circle distance on the fronts' sphere (an independent distance reference; it
    differs from the rhumb legs flown by < 1 mm at these ranges)."""
    p1, p2 = math.radians(lat1), math.radians(lat2)
    a = (math.sin((p2 - p1) / 2) ** 2
         + math.cos(p1) * math.cos(p2) * math.sin(math.radians(lon2 - lon1) / 2) ** 2)
    return 2 * R_EARTH * math.asin(math.sqrt(a))


def bearing(lat1, lon1, lat2, lon2):
    """Direction (rad CCW from east) of the constant-bearing (rhumb) line, from the Mercator
    projection: tan(theta) = d lon / d psi, psi = ln tan(pi/4 + lat/2)."""
    dpsi = (math.log(math.tan(math.pi / 4 + math.radians(lat2) / 2))
            - math.log(math.tan(math.pi / 4 + math.radians(lat1) / 2)))
    return math.atan2(dpsi, math.radians(lon2 - lon1))


START = (46.3, 7.4)
SAFETY = 300.0


@pytest.fixture(scope="module")
def still(polar):
    E = polar.best_glide_ratio
    alt = SAFETY + 20000.0 / E  # footprint radius 20 km
    pts = [Landable("N8", 46.3 + 8000 / 111195, 7.4, 0.0),
           Landable("SE14", 46.3 - 0.09, 7.4 + 0.13, 0.0),
           Landable("W19", 46.3, 7.4 - 19000 / (111195 * math.cos(math.radians(46.3))), 0.0),
           Landable("E25", 46.3, 7.4 + 25000 / (111195 * math.cos(math.radians(46.3))), 0.0)]
    t = flat_terrain(121)
    return glide_reach(t, (*START, alt), polar, landables=pts, safety_height=SAFETY), alt, E


def test_flat_still_air_arrivals_are_the_best_glide(still):
    """Closed form: arrival = ALT - d / (L/D)max along the straight line (flown exactly)."""
    result, alt, E = still
    assert result.status is Status.SOLVED and result.ok
    for p in result.points[:3]:
        d = haversine(*START, p.landable.lat, p.landable.lon)
        assert p.reachable and p.verified and not p.detour
        assert p.arrival_altitude_m == pytest.approx(alt - d / E, abs=1e-3)
        assert p.arrival_margin_m == pytest.approx(alt - d / E - SAFETY, abs=1e-3)
        assert p.distance_m == pytest.approx(d, abs=0.01)
        assert p.endpoint_error_m < 1e-3
        # the grid's own answer: within two cells of altitude (first-order front)
        assert abs(p.front_arrival_altitude_m - (alt - d / E)) <= 2 * result.resolution_m / E
    far = result.points[3]
    assert not far.reachable  # 25 km > 20 km: below the safety height on arrival
    assert far.arrival_margin_m == pytest.approx(-(5000.0 / E), abs=0.5)


def test_flat_still_air_footprint_is_the_disk(still):
    """Closed form: a disk of radius (ALT - safety) (L/D)max; the contour within one grid
    spacing of it (the grid's stated accuracy)."""
    result, alt, E = still
    radius = (alt - SAFETY) * E
    assert len(result.footprint) == 1 and len(result.footprint[0]) == 1
    ring = result.footprint[0][0]
    x = R_EARTH * math.cos(math.radians(START[0])) * np.radians(ring[:, 0] - START[1])
    y = R_EARTH * np.radians(ring[:, 1] - START[0])
    r = np.hypot(x, y)
    assert np.max(np.abs(r - radius)) <= result.resolution_m
    assert not result.clipped


def test_to_dict_is_the_json_of_the_issue(still):
    result, _, _ = still
    d = json.loads(json.dumps(result.to_dict()))
    assert d["status"] == "solved"
    assert [p["name"] for p in d["points"]] == ["N8", "SE14", "W19", "E25"]
    keys = {"name", "lat", "lon", "elevation_m", "reachable", "arrival_altitude_m",
            "arrival_margin_m", "distance_m", "detour", "track"}
    for p in d["points"]:
        assert keys <= set(p)
    tr = d["points"][0]["track"]
    assert len(tr["lat"]) == len(tr["altitude_m"]) == len(tr["t"])
    assert tr["altitude_m"][0] == pytest.approx(d["start"]["altitude_m"])


@pytest.mark.parametrize("mc", [0.0, 1.5])
def test_flat_uniform_wind_arrivals_follow_the_ground_glide_per_bearing(polar, mc):
    """Reference: per bearing, the best ground glide ratio (MC 0) or the MacCready speed to
    fly's (MC > 0), brute force over the polar's speeds with the crab angle (test_model)."""
    wind = (3.0, -7.0)
    pts = [Landable(f"B{k}", START[0] + 0.1 * math.sin(a), START[1] + 0.14 * math.cos(a), 0.0)
           for k, a in enumerate(np.radians(np.arange(0, 360, 45)))]
    t = flat_terrain(101)
    result = glide_reach(t, (*START, 600.0), polar, landables=pts, wind=wind, mc=mc,
                         safety_height=SAFETY)
    n_reach = 0
    for p in result.points:
        la, lo = p.landable.lat, p.landable.lon
        d = haversine(*START, la, lo)
        ref = 600.0 - d / brute(polar, wind, bearing(*START, la, lo), mc)
        # the great-circle distance differs from the rhumb leg flown by < 1 mm here
        assert p.arrival_altitude_m == pytest.approx(ref, abs=1e-3)
        assert p.reachable == (ref - SAFETY >= 0)
        n_reach += p.reachable
    assert 0 < n_reach < len(pts)  # the wind splits them: a real test of the anisotropy
    # the footprint: along every bearing the (ALT - safety) x the ground glide ratio of that
    # bearing (brute force), within one grid spacing (the grid's stated accuracy)
    assert len(result.footprint) == 1
    ring = result.footprint[0][0][:-1]
    x = R_EARTH * math.cos(math.radians(START[0])) * np.radians(ring[::7, 0] - START[1])
    y = R_EARTH * np.radians(ring[::7, 1] - START[0])
    for xi, yi in zip(x, y, strict=True):
        ref = (600.0 - SAFETY) * brute(polar, wind, math.atan2(yi, xi), mc, n=20001)
        assert abs(math.hypot(xi, yi) - ref) <= result.resolution_m


def _wall_case():
    """Flat ground at 0 m with a 3000 m wall two samples thick between start and landable."""
    n = 161
    lat = 46.0 + 0.4 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.5 * np.arange(n) / (n - 1)
    z = np.zeros((n, n), np.float32)
    i0, i1, jw = 30, 110, 80
    z[i0:i1 + 1, jw:jw + 2] = 3000.0
    return Terrain(lat, lon, z), (lat, lon, i0, i1, jw)


def _legs(pts):
    return sum(haversine(*a, *b) for a, b in itertools.pairwise(pts))


def test_wall_path_goes_round_its_end(polar):
    """Closed form: straight legs start -> the wall's end corners -> landable. The bilinear
    terrain ramps from the wall's last sample to 0 over one sample, so the true corners lie
    between the last wall samples (shortest, L_lo) and one sample beyond them (L_hi): the
    flown path's length lies in [L_lo, L_hi + h/4] (its corners are string-pulled points of
    the front's path, which passes the obstacle within a grid cell h: a quarter cell of length
    covers the residual), and arrival = ALT - length / E (still air, flown exactly)."""
    terrain, (lat, lon, _, i1, jw) = _wall_case()
    E = polar.best_glide_ratio
    start = (46.22, 7.15)
    behind = Landable("behind", 46.22, 7.38, 0.0)
    dla, dlo = lat[1] - lat[0], lon[1] - lon[0]
    l_lo = _legs([start, (lat[i1], lon[jw]), (lat[i1], lon[jw + 1]), (behind.lat, behind.lon)])
    l_hi = _legs([start, (lat[i1] + dla, lon[jw] - dlo), (lat[i1] + dla, lon[jw + 1] + dlo),
                  (behind.lat, behind.lon)])
    alt = SAFETY + l_hi / E + 60.0
    beyond = Landable("beyond", 46.22, 7.47, 0.0)
    l_beyond = _legs([start, (lat[i1], lon[jw]), (lat[i1], lon[jw + 1]), (beyond.lat, beyond.lon)])
    assert alt - SAFETY < l_beyond / E  # beyond reach even by the shortest way round
    result = glide_reach(terrain, (*start, alt), polar, landables=[behind, beyond],
                         safety_height=SAFETY)
    p, q = result.points
    assert p.reachable and p.detour and p.verified
    h = result.resolution_m
    assert l_lo - 1e-6 <= p.distance_m <= l_hi + h / 4
    assert p.arrival_altitude_m == pytest.approx(alt - p.distance_m / E, abs=1e-6)
    assert p.min_clearance_m >= SAFETY - 1e-6
    # it went round the north end (the nearer), not through
    assert np.max(p.path.waypoints_lat) >= lat[i1]
    assert not q.reachable
    # the straight glide (what a per-ray computer draws) runs into the wall
    from glideplan.reach.flight import fly

    straight = fly(result.glide, terrain, SAFETY, np.array([start[0], behind.lat]),
                   np.array([start[1], behind.lon]), alt)
    assert not straight.clear and straight.min_clearance_m < 0


def test_landable_outside_the_terrain_and_clipping(polar):
    t = flat_terrain(61, span_lat=0.3, span_lon=0.4)
    out = Landable("far away", 48.0, 9.0, 100.0)
    r = glide_reach(t, (46.15, 7.2, 1500.0), polar, landables=[out], safety_height=SAFETY)
    assert not r.points[0].reachable and "outside the terrain" in r.points[0].note
    # reach ~ 50 km > the 33 km x 31 km terrain: clipped on all sides, and it says so
    assert set(r.clipped) == {"south", "north", "west", "east"}
    assert any("clipped to the terrain's extent" in w for w in r.warnings)
    assert "clipped" in r.message


@pytest.mark.parametrize("start,kw,name", [
    ((45.0, 7.2, 1500.0), {}, "start"),
    ((46.15, 7.2, -10.0), {}, "start altitude"),
    ((46.15, 7.2, 1500.0), {"safety_height": -1.0}, "safety_height"),
    ((46.15, 7.2, 1500.0), {"resolution_m": 0.0}, "resolution"),
    ((46.15, 7.2, float("nan")), {}, "start altitude"),
])
def test_bad_input_names_the_parameter(polar, start, kw, name):
    t = flat_terrain(61, span_lat=0.3, span_lon=0.4)
    with pytest.raises(InvalidParameterError) as e:
        glide_reach(t, start, polar, **kw)
    assert e.value.name == name


def test_cup_landables_in_file_order_non_landables_skipped(polar, tmp_path):
    """SeeYou .cup written by aerofiles' writer, read by its reader."""
    from aerofiles.seeyou import Writer

    p = tmp_path / "fields.cup"
    with open(p, "wb") as fp:
        w = Writer(fp)
        w.write_waypoint("Zulu", "Z", "CH", 46.2, 7.2, 1640.0, style=2)  # no unit: metres
        w.write_waypoint("Turnpoint", "T", "CH", 46.1, 7.1, 900.0, style=1)
        w.write_waypoint("Alpha", "A", "CH", 46.1, 7.3, 100.0, style=4)
    t = flat_terrain(61, span_lat=0.3, span_lon=0.4)
    r = glide_reach(t, (46.15, 7.2, 1200.0), polar, landables=p, safety_height=SAFETY)
    assert [q.landable.name for q in r.points] == ["Zulu", "Alpha"]
    assert r.points[0].landable.elevation_m == pytest.approx(1640.0)
    assert not r.points[0].reachable  # above the glider
    assert r.points[1].reachable
    assert any("not landable" in w for w in r.warnings)


def test_safety_glide_ratio_on_flat_ground(polar):
    """Closed form: with a safety glide ratio R below (L/D)max the still-air glide is R:
    arrival = ALT - d / R."""
    R = 25.0
    t = flat_terrain(61, span_lat=0.3, span_lon=0.4)
    lnd = Landable("L", 46.2, 7.3, 0.0)
    r = glide_reach(t, (46.15, 7.2, 1200.0), polar, landables=[lnd], safety_height=SAFETY,
                    safety_glide_ratio=R)
    d = haversine(46.15, 7.2, lnd.lat, lnd.lon)
    assert r.points[0].arrival_altitude_m == pytest.approx(1200.0 - d / R, abs=1e-3)
    assert r.to_dict()["glide"]["still_air_glide_ratio"] == pytest.approx(R)


def test_smooth_ridge_landable_behind_is_reached_round_it(polar):
    """A smooth ridge (3100 m crest, 1.5 km flanks) higher than any glide over it, oblique to
    the way: the straight glide meets it, the front goes round its end; the path flown keeps
    the safety height next to the steep flank (the string pulling's margin, flight.py)."""
    n = 161
    lat = 46.4 + 0.4 * np.arange(n) / (n - 1)
    lon = 7.3 + 0.5 * np.arange(n) / (n - 1)
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    c = math.cos(math.radians(46.6))
    (a_la, a_lo), (b_la, b_lo) = (46.56, 7.60), (46.70, 7.48)
    bx, by = (b_lo - a_lo) * 111.2 * c, (b_la - a_la) * 111.2
    px, py = (lo - a_lo) * 111.2 * c, (la - a_la) * 111.2
    s = np.clip((px * bx + py * by) / (bx * bx + by * by), 0, 1)
    d = np.hypot(px - s * bx, py - s * by)
    z = np.maximum(500.0, 3100.0 * np.clip(1.5 - d, 0, 1.5) / 1.5).astype(np.float32)
    t = Terrain(lat, lon, z)
    lnd = Landable("behind", 46.68, 7.62, 500.0)
    r = glide_reach(t, (46.5, 7.5, 2400.0), polar, landables=[lnd], safety_height=SAFETY,
                    wind=(5.0, -3.0))
    p = r.points[0]
    assert p.reachable and p.verified and p.detour
    assert p.min_clearance_m >= SAFETY - 1e-6
    from glideplan.reach.flight import fly

    straight = fly(r.glide, t, SAFETY, np.array([46.5, lnd.lat]), np.array([7.5, lnd.lon]),
                   2400.0)
    assert straight.min_clearance_m < 0
