"""`glideplan glide reach|turnback --example ridge`: runs with no files; `--write-example DIR`
writes the same case as files (read back by the terrain reader and aerofiles) that give the
same answer; the answer checked against bounds derived from the example's geometry.

Geometry (`glideplan.reach.examples`): a flat floor at FLOOR_M = 500 m; the ridge's crest
runs along the meridian 7.55 E from 46.40 to 46.62 N at 3000 m, above the start altitude
(1500 m), so no glide crosses the crest; its flanks reach the floor FLANK_M from the crest.
Hence, per field behind the ridge (east of 7.55 E), in the example's wind, with the ground
glide ratio per bearing r(chi) (`Glide.ratio`, checked against brute force over the polar in
test_model) and straight (rhumb) legs, which are optimal in a uniform wind when the curve
r(chi) u(chi) bounds a convex set (then 1 / r is a gauge and the triangle inequality holds;
`test_ground_glide_set_is_convex` checks it for the example's wind):

- a LOWER bound on the altitude lost: every path crosses the meridian 7.55 E north of the
  crest (lat >= 46.62) or south of it (lat <= 46.40), at some Q: loss >= min over Q of
  loss(S -> Q) + loss(Q -> field);
- an UPPER bound: a path flown round an end of the ridge by the box S -> P1 -> P2 -> field,
  P1, P2 = the end +- (FLANK_M + 200 m) west/east and beyond it: every leg stays FLANK_M +
  200 m from the crest (longitude and latitude are monotone along a rhumb leg), so the
  bilinear terrain under it is the floor (a 3" cell's diagonal is 113 m < 200 m) and it
  keeps the safety height while its altitude stays >= FLOOR_M + safety.

A field whose lower bound leaves less than the safety height is unreachable by ANY path; one
whose upper bound arrives above it is reachable. A field whose straight line crosses the
crest needs a detour of at least the distance from the line to the crest's end.
"""

import contextlib
import io
import json
import math
import shlex

import numpy as np
import pytest

from glideplan.reach import Glide
from glideplan.reach import examples as E
from glideplan.sailplane import polar_from_file, read_plr
from glideplan.units import wind_from_compass

from .test_reach import R_EARTH, bearing, haversine

BOX_MARGIN_M = 200.0


def _cli_json(*args: str) -> dict:
    """Run the CLI in-process (module fixtures cannot take capsys); its --json output."""
    from glideplan.cli.app import main

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(list(args))
    assert code == 0, err.getvalue()
    return json.loads(out.getvalue())


@pytest.fixture(scope="module")
def ex():
    return E.example("ridge")


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    return tmp_path_factory.mktemp("ridge_exports")


@pytest.fixture(scope="module")
def reach_json(exports):
    return _cli_json("glide", "reach", "--example", "ridge", "--json", "--geojson",
                     str(exports / "ridge.geojson"), "--kml", str(exports / "ridge.kml"))


@pytest.fixture(scope="module")
def turnback_json():
    return _cli_json("glide", "turnback", "--example", "ridge", "--json")


@pytest.fixture(scope="module")
def glide(ex):
    polar = polar_from_file(read_plr(ex.polar_file))
    return Glide(polar, mc=ex.mc, wind=wind_from_compass(ex.wind_speed_ms, ex.wind_from_deg))


def _loss(glide, a, b):
    """Altitude lost (m) on the straight (rhumb) leg a -> b at the ground glide ratio of its
    bearing; a, b = (lat, lon), either may hold arrays."""
    d = np.vectorize(haversine)(a[0], a[1], b[0], b[1])
    chi = np.vectorize(bearing)(a[0], a[1], b[0], b[1])
    return d / glide.ratio(np.atleast_1d(chi)).reshape(np.shape(d))


def _bounds(glide, ex, lat, lon):
    """(lower, upper) bound on the altitude lost from the start to (lat, lon) behind the
    ridge (module docstring)."""
    S = ex.start[:2]
    crest = E.RIDGE_NORTH[1]
    qn = np.arange(E.RIDGE_NORTH[0], 47.0, 1e-4)  # ~11 m apart: the minimum to < 1 cm
    qs = np.arange(46.0, E.RIDGE_SOUTH[0] + 1e-12, 1e-4)
    lower = min(float(np.min(_loss(glide, S, (q, crest)) + _loss(glide, (q, crest), (lat, lon))))
                for q in (qn, qs))
    w = E.FLANK_M + BOX_MARGIN_M
    dla = math.degrees(w / R_EARTH)
    dlo = math.degrees(w / (R_EARTH * math.cos(math.radians(ex.start[0]))))
    upper = math.inf
    for end, side in ((E.RIDGE_NORTH, 1.0), (E.RIDGE_SOUTH, -1.0)):
        p1, p2 = (end[0] + side * dla, crest - dlo), (end[0] + side * dla, crest + dlo)
        upper = min(upper, float(_loss(glide, S, p1) + _loss(glide, p1, p2)
                                 + _loss(glide, p2, (lat, lon))))
    return lower, upper


def _crosses_crest(ex, lat, lon):
    """Latitude where the straight line start -> (lat, lon) meets the crest's meridian, and
    whether that lies on the crest."""
    lat0, lon0 = ex.start[:2]
    t = (E.RIDGE_NORTH[1] - lon0) / (lon - lon0)
    lat_c = lat0 + t * (lat - lat0)
    return lat_c, 0 <= t <= 1 and E.RIDGE_SOUTH[0] <= lat_c <= E.RIDGE_NORTH[0]


def _local(lat, lon, lat0, lon0):
    c = math.cos(math.radians(lat0))
    return (R_EARTH * c * np.radians(np.asarray(lon) - lon0),
            R_EARTH * np.radians(np.asarray(lat) - lat0))


def _convex(glide) -> bool:
    """Does r(chi) u(chi), the ground distance per metre of altitude, trace a convex curve
    (cross products of successive edges >= 0, 3600 directions)?"""
    chi = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)
    r = glide.ratio(chi)
    pts = np.stack([r * np.cos(chi), r * np.sin(chi)], axis=-1)
    e = np.roll(pts, -1, axis=0) - pts
    f = np.roll(e, -1, axis=0)
    return bool(np.all(e[:, 0] * f[:, 1] - e[:, 1] * f[:, 0] >= -1e-9 * np.max(r) ** 2))


def test_ground_glide_set_is_convex(glide):
    """The premise of the bounds, in the example's wind."""
    assert _convex(glide)


def test_example_runs_with_no_files(reach_json, ex):
    """Exit 0 (the fixture), the issue's JSON keys, points in the .cup order."""
    d = reach_json
    assert d["status"] == "solved"
    assert d["start"]["altitude_m"] == ex.start[2]
    assert d["glide"]["wind_ms"] == pytest.approx(
        list(wind_from_compass(ex.wind_speed_ms, ex.wind_from_deg)), abs=1e-12)
    keys = {"name", "lat", "lon", "elevation_m", "reachable", "arrival_altitude_m",
            "arrival_margin_m", "distance_m", "detour", "track"}
    assert [p["name"] for p in d["points"]] == [f[0] for f in E.FIELDS]
    for p in d["points"]:
        assert keys <= set(p)


def _inside(lon, lat, ring):
    """Even-odd ray casting: is (lon, lat) inside the closed ring [[lon, lat], ...]?"""
    x, y = np.asarray(ring, dtype=float).T
    x0, y0, x1, y1 = x[:-1], y[:-1], x[1:], y[1:]
    crosses = (y0 > lat) != (y1 > lat)
    with np.errstate(divide="ignore", invalid="ignore"):
        xc = x0 + (lat - y0) * (x1 - x0) / (y1 - y0)
    return bool(np.sum(crosses & (xc > lon)) % 2)


def test_example_exports_read_back(reach_json, exports):
    """GeoJSON (json) and KML (fastkml) of the example: one footprint feature holding every
    reachable field (each arrives >= 98 m above its safety height, i.e. kilometres inside the
    footprint's edge) and not the unreachable one; the fields as points in the .cup order."""
    from fastkml import kml

    data = json.loads((exports / "ridge.geojson").read_text())
    kinds = [f["properties"]["kind"] for f in data["features"]]
    assert kinds.count("footprint") == 1
    foot = data["features"][kinds.index("footprint")]["geometry"]
    polys = [foot["coordinates"]] if foot["type"] == "Polygon" else foot["coordinates"]
    lands = [f for f in data["features"] if f["properties"]["kind"] == "landable"]
    assert [f["properties"]["name"] for f in lands] == [f[0] for f in E.FIELDS]
    for f, p in zip(lands, reach_json["points"], strict=True):
        lon, lat = f["geometry"]["coordinates"]
        inside = any(_inside(lon, lat, poly[0]) and not any(_inside(lon, lat, h)
                                                            for h in poly[1:])
                     for poly in polys)
        assert inside == p["reachable"], p["name"]
    doc = kml.KML.parse(str(exports / "ridge.kml"))
    names = [m.name for m in doc.features[0].features]
    assert all(f[0] in names for f in E.FIELDS) and "start" in names


def test_fields_in_the_valley_are_the_straight_glide(reach_json, ex, glide):
    """Closed form: the straight line to a valley field stays over the floor (west of the
    ridge's flank, east of the west range's), so arrival = ALT - d / r(bearing), flown."""
    lat0, lon0, alt = ex.start
    for p in reach_json["points"]:
        if p["lon"] > E.RIDGE_NORTH[1]:
            continue
        flank_deg = math.degrees(E.FLANK_M / (R_EARTH * math.cos(math.radians(lat0))))
        assert E.WEST_CREST_LON + flank_deg < min(lon0, p["lon"])
        assert max(lon0, p["lon"]) < E.RIDGE_NORTH[1] - flank_deg
        ref = alt - float(_loss(glide, (lat0, lon0), (p["lat"], p["lon"])))
        assert p["reachable"] and not p["detour"]
        assert p["arrival_altitude_m"] == pytest.approx(ref, abs=1e-3)


def _check_behind_the_ridge(points, h, glide, ex):
    """The bounds of the module docstring decide each field behind the ridge; the flown
    arrival must lie between them (the upper bound on the loss less the front's accuracy of
    two grid cells h of glide, as in test_reach); a field whose straight line crosses the
    crest must be reported with a detour, its path leaving the line by at least the line's
    distance from the crest's end. Returns (a reachable detour seen, an unreachable seen)."""
    assert _convex(glide)  # the bounds' premise
    lat0, lon0, alt = ex.start
    floor_needed = E.FLOOR_M + ex.safety_height
    r_min = float(np.min(glide.ratio(np.linspace(0, 2 * np.pi, 360))))
    seen_detour_reachable = seen_unreachable = False
    for p in points:
        if p["lon"] <= E.RIDGE_NORTH[1]:
            continue
        lower, upper = _bounds(glide, ex, p["lat"], p["lon"])
        _, blocked = _crosses_crest(ex, p["lat"], p["lon"])
        if alt - lower < floor_needed:  # no path whatever reaches it
            assert p["reachable"] is False, p["name"]
            seen_unreachable = True
            continue
        if alt - upper >= floor_needed:  # the box path reaches it: so must the solver
            assert p["reachable"] is True, p["name"]
            assert alt - upper - 2 * h / r_min <= p["arrival_altitude_m"] <= alt - lower + 1e-6
            x, y = _local(p["track"]["lat"], p["track"]["lon"], lat0, lon0)
            gx, gy = _local(p["lat"], p["lon"], lat0, lon0)
            offset = np.max(np.abs(x * gy - y * gx)) / math.hypot(gx, gy)
            if blocked:  # the path passes beyond one of the crest's ends
                ends = [_local(e[0], e[1], lat0, lon0) for e in (E.RIDGE_NORTH, E.RIDGE_SOUTH)]
                need = min(abs(float(ex_) * gy - float(ey_) * gx) / math.hypot(gx, gy)
                           for ex_, ey_ in ends)
                assert need > h  # a detour the grid resolves
                assert p["detour"] is True and offset >= need
                seen_detour_reachable = True
    return seen_detour_reachable, seen_unreachable


def test_behind_the_ridge_detour_reachable_and_unreachable(reach_json, ex, glide):
    """`_check_behind_the_ridge` on the example as it ships; it is built to show both a
    reachable field with a detour and an unreachable one (a failure of the last assertion
    means the example changed)."""
    seen = _check_behind_the_ridge(reach_json["points"], reach_json["grid"]["resolution_m"],
                                   glide, ex)
    assert seen == (True, True)


def test_behind_the_ridge_in_a_stronger_wind_at_mc_1(ex):
    """The same bounds with the README's override (wind 10 m/s from 250 deg, MC 1): Behind
    North is reachable round the ridge's north end (the box path arrives 15 m above its
    safety height) although the front's characteristic cuts the end's corner there; the
    fallback down the reached nodes (`solve.descend_reached`) finds the flown path (it was
    reported unreachable before)."""
    from glideplan.reach import glide_reach

    polar = polar_from_file(read_plr(ex.polar_file))
    wind = wind_from_compass(10.0, 250.0)
    glide = Glide(polar, mc=1.0, wind=wind)
    r = glide_reach(ex.terrain, ex.start, polar, landables=ex.landables, mc=1.0, wind=wind,
                    safety_height=ex.safety_height, resolution_m=ex.resolution_m)
    seen = _check_behind_the_ridge(r.to_dict()["points"], r.resolution_m, glide, ex)
    assert seen == (True, True)
    assert r.points[2].landable.name == "Behind North" and r.points[2].reachable


def test_written_files_give_the_same_answer(run_cli, reach_json, ex, tmp_path):
    """--write-example: the .hgt read back by the terrain reader is the example's terrain
    sample for sample (both int16 metres); the .cup read back by aerofiles holds the fields
    in order at the same positions (they sit on whole 0.001', a .cup's resolution) -- the
    same inputs, so the printed command gives the same answer to 1e-6 m."""
    from glideplan.reach.landables import read_cup_landables
    from glideplan.terrain import read_terrain

    code, out, err = run_cli("glide", "reach", "--example", "ridge", "--write-example",
                             str(tmp_path))
    assert code == 0, err
    t = read_terrain([tmp_path / E.TILE])
    np.testing.assert_array_equal(t.z, ex.terrain.z)
    np.testing.assert_array_equal(t.lat, ex.terrain.lat)
    np.testing.assert_array_equal(t.lon, ex.terrain.lon)
    fields, skipped = read_cup_landables(tmp_path / "fields.cup")
    assert skipped == 0
    assert [f.name for f in fields] == [p["name"] for p in reach_json["points"]]
    for f, g in zip(fields, ex.landables, strict=True):
        assert (f.lat, f.lon, f.elevation_m) == pytest.approx((g.lat, g.lon, g.elevation_m),
                                                              abs=1e-12)
    line = out.strip().splitlines()[-1]
    args = shlex.split(line)
    assert args[:3] == ["glideplan", "glide", "reach"] and "--example" not in args
    code, out, err = run_cli(*args[1:], "--json")
    assert code == 0, err
    d = json.loads(out)
    for p, q in zip(d["points"], reach_json["points"], strict=True):
        assert p["name"] == q["name"] and p["reachable"] == q["reachable"]
        assert p["detour"] == q["detour"]
        if q["arrival_altitude_m"] is None:
            assert p["arrival_altitude_m"] is None
        else:
            assert p["arrival_altitude_m"] == pytest.approx(q["arrival_altitude_m"], abs=1e-6)


def test_turnback_example_and_its_files(run_cli, turnback_json, ex, glide, tmp_path):
    """The course runs up the valley and the return stays over the floor, so the turn-back
    distance s solves the closed form ALT - s / r(course) - loss(P(s) -> home) = FLOOR_M +
    safety (bisection here; the solver refines to 1 m); the written files give the same."""
    from glideplan.geodesy import rhumb_destination as destination

    d = turnback_json
    assert d["status"] == "solved" and d["limited_by"] == "glide home"
    lat0, lon0, alt = ex.start
    chi = math.radians(90.0 - ex.course_deg)
    r_out = float(glide.ratio(np.array([chi]))[0])
    home = (ex.home.lat, ex.home.lon)

    def left(s):
        la, lo = destination(lat0, lon0, chi, np.array([s]))
        return alt - s / r_out - float(_loss(glide, (float(la[0]), float(lo[0])), home)) \
            - (E.FLOOR_M + ex.safety_height)

    a, b = 0.0, 60e3
    assert left(a) > 0 > left(b)
    for _ in range(60):
        m = 0.5 * (a + b)
        a, b = (m, b) if left(m) > 0 else (a, m)
    assert d["turnback"]["distance_m"] == pytest.approx(a, abs=2.0)
    # the premise: the turn-back point (and so both straight legs) lies over the floor
    assert d["turnback"]["lon"] < E.RIDGE_NORTH[1] - math.degrees(
        E.FLANK_M / (R_EARTH * math.cos(math.radians(d["turnback"]["lat"]))))
    code, out, err = run_cli("glide", "turnback", "--example", "ridge", "--write-example",
                             str(tmp_path))
    assert code == 0, err
    args = shlex.split(out.strip().splitlines()[-1])
    assert args[:3] == ["glideplan", "glide", "turnback"]
    code, out, err = run_cli(*args[1:], "--json")
    assert code == 0, err
    assert json.loads(out)["turnback"]["distance_m"] == pytest.approx(
        d["turnback"]["distance_m"], abs=1e-6)


def test_explicit_options_override_the_example(run_cli):
    """--wind and --mc given with --example win over the example's; the JSON says so."""
    code, out, err = run_cli("glide", "turnback", "--example", "ridge", "--wind", "10", "250",
                             "--mc", "1", "--json")
    assert code == 0, err
    g = json.loads(out)["glide"]
    assert g["wind_ms"] == pytest.approx(list(wind_from_compass(10.0, 250.0)), abs=1e-12)
    assert g["mc_ms"] == pytest.approx(1.0)


@pytest.mark.parametrize("args,flag", [
    (["--example", "alps"], "--example"),
    (["--write-example", "somewhere"], "--write-example"),
    ([], "--polar"),
])
def test_example_bad_input_one_line(cli_error, args, flag):
    line = cli_error("glide", "reach", *args)
    assert flag in line
