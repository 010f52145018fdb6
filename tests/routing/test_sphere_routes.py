"""Routes on the sphere (issue 18): great circles, global files and their seams, coasts.

Every reference is a closed form on the router's sphere (R = 6,371,008.8 m, the front
kernel's): in still water the time-optimal route is the great circle, duration = D / V. The
files are built here with `glideplan.fields.synthetic` (xarray), nothing is downloaded.

Accuracy: the refined (Zermelo-shooting) route is integrated with RK4 through the grid's
bilinear current and stops when it ends within 1 % of a cell h = D / cells of the goal, so in
still water its time is D / V to 0.01 / cells (measured 1e-5 at 40 cells, 7e-10 at 60 over
4,400 km); the grid (front) time is first/second order in h: its measured error is <= 4e-4 at
60-250 cells, the tests allow 1 %.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.fields import AnalyticField, Extent, UniformField, open_field
from glideplan.fields.synthetic import (
    copernicus_dataset,
    copernicus_headland_dataset,
    era5_dataset,
    global_dataset,
)
from glideplan.routing import route
from glideplan.routing.sphere import EARTH_RADIUS_M, gc_distance

T0 = np.datetime64("2026-01-01T00:00", "ns")
HOURLY = T0 + np.arange(13) * np.timedelta64(3600, "s")
TWO_DAYS = [T0, T0 + np.timedelta64(2, "D")]


def _geod_sphere():
    from pyproj import Geod

    return Geod(a=EARTH_RADIUS_M, b=EARTH_RADIUS_M)


def _check_still(r, start, goal, speed, cells=60):
    rel_refined = 1e-2 / cells
    d = float(gc_distance(*start, *goal))
    assert r.status == "solved", r.message
    assert r.grid_duration_s == pytest.approx(d / speed, rel=1e-2)
    if r.method == "zermelo-shooting":
        assert r.duration_s == pytest.approx(d / speed, rel=rel_refined)
    else:
        assert r.duration_s == pytest.approx(d / speed, rel=1e-2)
    assert r.endpoint_error_m <= r.endpoint_tolerance_m
    # continuous track: no jump of 360 deg across 0 or 180
    assert np.all(np.abs(np.diff(r.lon)) < 5.0)


def test_still_water_transect_of_thousands_of_km_is_the_great_circle():
    """4,400 km in still water: duration = great-circle distance / V (pyproj's inverse on
    the same sphere agrees to 1e-9); the WGS84 geodesic differs by the sphere's model error
    (< 0.5 %, stated in `routing.sphere`)."""
    start, goal, speed = (20.0, -60.0), (40.0, -20.0), 1.0
    r = route(UniformField(0.0, 0.0), start, goal, speed, cells=60)
    _check_still(r, start, goal, speed)
    _, _, d_sphere = _geod_sphere().inv(start[1], start[0], goal[1], goal[0])
    assert float(gc_distance(*start, *goal)) == pytest.approx(d_sphere, rel=1e-9)
    from glideplan.geodesy import geodesic_distance_bearing

    d_wgs84, _ = geodesic_distance_bearing(*start, *goal)
    assert r.duration_s * speed == pytest.approx(float(d_wgs84), rel=5e-3)
    assert r.distance_m == pytest.approx(d_sphere, rel=1e-4)
    assert r.stats["window_growths"] >= 0 and r.unreachable_reason is None


@pytest.mark.parametrize("convention", ["0..360", "-180..180"])
def test_global_files_across_0_and_180_in_still_air(tmp_path, convention):
    """Still air in a global 1-degree file (either longitude convention): across Greenwich
    (50 N, 3 W -> 3 E) and across 180 (10 N 175 E -> 12 N 170 W) the route is the great
    circle, solved; a start in the seam of a 0..359 file (359.5 E) is accepted."""
    path = tmp_path / "global.nc"
    global_dataset(step_deg=1.0, lon_convention=convention, times=TWO_DAYS).to_netcdf(path)
    fld = open_field(path)
    for start, goal in (((50.0, -3.0), (50.0, 3.0)), ((10.0, 175.0), (12.0, -170.0)),
                        ((45.0, 359.5), (46.0, 4.0))):
        r = route(fld, start, goal, 25.0, cells=40)
        _check_still(r, start, goal, 25.0, cells=40)
        d = r.to_dict()
        assert all(-180.0 <= x < 180.0 for x in d["track"]["lon"])


def test_era5_file_across_greenwich(tmp_path):
    """An ERA5-style file (valid_time, latitude descending, u10/v10, 0..359.5): still air,
    50 N 3 W -> 3 E at 25 m/s is the great circle."""
    path = tmp_path / "era5.nc"
    era5_dataset(step_deg=0.5, times=TWO_DAYS).to_netcdf(path)
    start, goal = (50.0, -3.0), (50.0, 3.0)
    r = route(open_field(path), start, goal, 25.0, cells=60)
    _check_still(r, start, goal, 25.0)


def test_uniform_tailwind_along_the_equator_across_greenwich(tmp_path):
    """A 10 m/s eastward wind, 25 m/s air speed, 0 N 5 W -> 5 E: the wind field is symmetric
    about the equator and along it, so the optimal route is the equator (the great circle)
    flown straight downwind: duration = D / (V + W) (closed form)."""
    path = tmp_path / "wind.nc"
    global_dataset(step_deg=1.0, u=10.0, times=TWO_DAYS).to_netcdf(path)
    start, goal = (0.0, -5.0), (0.0, 5.0)
    r = route(open_field(path), start, goal, 25.0, cells=60)
    d = float(gc_distance(*start, *goal))
    assert r.status == "solved", r.message
    assert r.duration_s == pytest.approx(d / 35.0, rel=1e-4)
    assert r.grid_duration_s == pytest.approx(d / 35.0, rel=1e-2)
    assert np.max(np.abs(r.lat)) < 0.01


def test_linear_shear_current_matches_the_zermelo_extremal():
    """u = s y (y = R lat, at the equator where the sphere's metric is the plane's to
    ~(y / R)^2 < 1e-5), v = 0: Zermelo's extremals have tan(theta) = tan(theta0) - s t and
    y = y0 + (V / s) (sec theta0 - sec theta) in closed form, x by quadrature; (theta0, T)
    solved with SciPy (Bryson & Ho 1975, sec. 2.7) is the reference; the refined route matches
    it to 1e-4 (measured 7e-7)."""
    from scipy.integrate import quad
    from scipy.optimize import fsolve

    s, speed = 1e-5, 0.3
    R = EARTH_RADIUS_M

    def fn(t, lat, lon):
        return s * R * np.radians(lat), 0.0 * lat

    fld = AnalyticField(fn=fn, extent=Extent(-1.0, 1.0, 9.0, 11.0), name="shear")
    start, goal = (-0.1, 10.0), (0.1, 10.3)
    x_g = R * math.radians(0.3)
    y0, y_g = R * math.radians(-0.1), R * math.radians(0.1)

    def end(p):
        th0, T = p
        th = lambda t: math.atan(math.tan(th0) - s * t)  # noqa: E731
        y = lambda t: y0 + speed / s * (1 / math.cos(th0) - 1 / math.cos(th(t)))  # noqa: E731
        x = quad(lambda t: speed * math.cos(th(t)) + s * y(t), 0.0, T, epsabs=1e-6)[0]
        return [x - x_g, y(T) - y_g]

    th0, T = fsolve(end, [math.atan2(y_g - y0, x_g), x_g / speed], xtol=1e-12)
    assert max(abs(e) for e in end([th0, T])) < 1e-3
    r = route(fld, start, goal, speed, cells=60)
    assert r.status == "solved", r.message
    assert r.duration_s == pytest.approx(T, rel=1e-4)
    # the front's own time: measured +1.1 % at 60 cells, +0.34 % at 120 (order ~1.7)
    assert r.grid_duration_s == pytest.approx(T, rel=2e-2)


def _rounded_rectangle_path(a, b, corners, c):
    """The two ways (m) from a to b round the rectangle with `corners` grown by c (a rounded
    rectangle) along the boundary of the convex hull of a, b and the grown rectangle (its
    corner arcs sampled at 20,000 points): [(length, largest y on the way), ...]."""
    from scipy.spatial import ConvexHull

    th = np.linspace(0.0, 2 * np.pi, 20000, endpoint=False)
    pts = [np.asarray(a), np.asarray(b)]
    for cx, cy in corners:
        pts.append(np.stack([cx + c * np.cos(th), cy + c * np.sin(th)], axis=1))
    allp = np.vstack([np.atleast_2d(p) for p in pts])
    hull = ConvexHull(allp)
    ring = list(hull.vertices)
    ia, ib = ring.index(0), ring.index(1)
    n = len(ring)

    def way(i, j):
        out, k, ymax = 0.0, i, -np.inf
        while k != j:
            p, q = allp[ring[k]], allp[ring[(k + 1) % n]]
            out += float(np.hypot(*(q - p)))
            ymax = max(ymax, float(q[1]))
            k = (k + 1) % n
        return out, ymax

    return [way(ia, ib), way(ib, ia)]


def test_cape_from_the_field_edge_is_rounded_at_its_corners(tmp_path):
    """Still water, a rectangular headland reaching out from the field's south edge (a
    Copernicus-like file, 1/12 deg, depth levels from 0.494 m, `--depth-range 0 5`): the
    route goes round the cape's north corners keeping the clearance c -- the hull of start,
    goal and the land nodes' rectangle grown by c (closed form, in the plane tangent at the
    cape: its scale error over 100 km is < 1e-4). The obstacle's corners are NaN nodes, so
    the reference is exact up to the edges' scallops (depth dx^2 / 8c) and the grid: 0.5 %."""
    path = tmp_path / "cape.nc"
    copernicus_headland_dataset().to_netcdf(path)
    fld = open_field(path, depth_range=(0.0, 5.0))
    assert any("0.494" in w for w in fld.warnings)
    start, goal = (30.2, -40.8), (30.2, -39.7)
    r = route(fld, start, goal, 0.5, cells=100)
    assert r.status == "solved", r.message
    uu, _ = fld.velocity(fld.time_span[0] if fld.time_span else 0.0, r.lat, r.lon)
    assert np.all(np.isfinite(uu)), "a track point is on land"
    # land nodes of the cape: lat 30 .. 30.5833, lon -40.3333 .. -40.1667 (1/12 deg nodes)
    lat_c, lon_c = 30.3, -40.25
    kx = EARTH_RADIUS_M * math.cos(math.radians(lat_c)) * math.pi / 180
    ky = EARTH_RADIUS_M * math.pi / 180

    def xy(la, lo):
        return ((lo - lon_c) * kx, (la - lat_c) * ky)

    top = 30.0 + 7 / 12
    corners = [xy(top, -40.0 - 4 / 12), xy(top, -40.0 - 2 / 12), xy(30.0, -40.0 - 4 / 12),
               xy(30.0, -40.0 - 2 / 12)]
    c = r.land_clearance_m
    ways = _rounded_rectangle_path(xy(*start), xy(*goal), corners, c)
    north = max(ways, key=lambda w: w[1])[0]  # the south way passes below the field's edge
    assert r.duration_s == pytest.approx(north / 0.5, rel=5e-3)
    assert r.to_dict()["land_clearance_m"] == c


def test_start_equal_goal_is_solved_in_no_time():
    r = route(UniformField(0.1, 0.0), (30.0, -40.0), (30.0, -40.0), 0.5)
    assert r.ok and r.duration_s == 0.0 and r.distance_m == 0.0
    assert r.to_dict()["status"] == "solved"


def _lake_file(tmp_path):
    """Still water, 30..31 N, 40.5..39.5 W, 0.01 deg, with a ring of land (radius 8-11 km)
    round a lake at (30.5 N, 40 W)."""
    lat = np.arange(30.0, 31.0001, 0.01)
    lon = np.arange(-40.5, -39.4999, 0.01)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    y = (LA - 30.5) * 111_195.0
    x = (LO + 40.0) * 111_195.0 * math.cos(math.radians(30.5))
    r = np.hypot(x, y)
    u = np.where((r > 8000) & (r < 11000), np.nan, 0.0)[None, None]
    path = tmp_path / "lake.nc"
    copernicus_dataset(lat, lon, HOURLY[:1], [0.5], u, u).to_netcdf(path)
    return path


def test_unreachable_reasons(tmp_path):
    """Unreachable only when it is, and why: a goal in a lake ringed by land ->
    "front_stopped"; a field that ends before the still-water time -> "time_span"; a
    uniform current faster than the vehicle away from the goal -> "outside_drift_cone"; one
    out of the field that is not everywhere faster -> "field_extent"."""
    fld = open_field(_lake_file(tmp_path))
    r = route(fld, (30.2, -40.4), (30.5, -40.0), 0.5, cells=40)
    assert r.status == "unreachable" and r.unreachable_reason == "front_stopped"
    assert r.best_distance_m > 8000.0  # outside the ring

    lat = np.linspace(29.5, 30.5, 21)
    lon = np.linspace(-40.5, -39.5, 21)
    u = np.zeros((3, 1, lat.size, lon.size))
    short = tmp_path / "short.nc"
    copernicus_dataset(lat, lon, HOURLY[:3], [0.5], u, u).to_netcdf(short)  # 2 h of field
    r = route(open_field(short), (30.0, -40.2), (30.0, -39.8), 0.3, cells=40)  # needs 36 h
    assert r.status == "unreachable" and r.unreachable_reason == "time_span"

    west = tmp_path / "west.nc"
    copernicus_dataset(lat, lon, HOURLY[:1], [0.5], u[:1] - 0.5, u[:1]).to_netcdf(west)
    r = route(open_field(west), (30.0, -40.0), (30.0, -39.8), 0.3, cells=40)
    # uniform and faster than the vehicle, away from the goal: outside the drift cone
    assert r.status == "unreachable" and r.unreachable_reason == "outside_drift_cone"
    assert r.front is None
    # still water along the north edge: the drift cone (the field's velocity box) no longer
    # excludes the goal, and the front drifts out of the field's west edge first
    slack = u[:1] - 0.5
    slack[..., -1, :] = 0.0
    copernicus_dataset(lat, lon, HOURLY[:1], [0.5], slack, u[:1]).to_netcdf(west)
    r = route(open_field(west), (30.0, -40.0), (30.0, -39.8), 0.3, cells=40)
    assert r.status == "unreachable" and r.unreachable_reason == "field_extent"
    assert r.front is not None and np.isfinite(r.front.arrival).any()


def test_the_window_grows_to_the_whole_circle():
    """Still water, 0 N 0 E -> 0 N 170 E (18,900 km): the window starts about start and goal
    and grows with the front until it closes the circle of longitude (periodic); the route is
    the equator, D / V."""
    start, goal = (0.0, 0.0), (0.0, 170.0)
    r = route(UniformField(0.0, 0.0), start, goal, 10.0, cells=60)
    assert r.stats["periodic"] and r.stats["window_growths"] >= 1
    _check_still(r, start, goal, 10.0)


def test_phases_run_alone():
    """setup -> grid -> front -> backtrack -> verify, each called on its own (still water,
    70 km): the front's arrival at the goal is D / V to 1 %, the grid route's controls end
    within a cell."""
    from glideplan.routing import phases
    from glideplan.routing.settings import RouteSettings

    problem = phases.setup(UniformField(0.0, 0.0), (30.0, -40.0), (30.5, -39.5), 1.0,
                           settings=RouteSettings(cells=60))
    assert problem.limit_reason == "max_duration"
    rg = phases.grid(problem)
    assert rg.window.fixed_sides() == set() and not rg.obstacle.any()
    fo, rg = phases.front(problem, rg)
    assert fo.reason == "goal"
    assert fo.goal_time - problem.t0 == pytest.approx(problem.distance_m, rel=1e-2)
    cand = phases.backtrack(problem, rg, fo)
    assert cand.duration == pytest.approx(problem.distance_m, rel=1e-2)
    flown = phases.verify(problem, rg, cand)
    assert phases.flown_ok(flown, rg.spacing_m) and not flown.on_land


@pytest.mark.parametrize(("name", "value"), [("cfl", 0.0), ("cells", 2), ("resolution", -1.0),
                                             ("land_clearance_m", float("nan"))])
def test_bad_settings_are_refused(name, value):
    from glideplan.errors import InvalidParameterError
    from glideplan.routing import RouteSettings

    with pytest.raises(InvalidParameterError, match=name):
        RouteSettings(**{name: value})


def test_zero_clearance_hugs_the_coast_without_entering_land_cells(tmp_path):
    """`land_clearance_m=0` next to the cape: the route may run where the file's interpolation
    stencil touches land (no data): verification fills the current there from the nearest
    water node and says so; the track never enters a land cell (its nearest field node is
    land); it is shorter than the route that keeps the default clearance."""
    from glideplan.routing import phases

    path = tmp_path / "cape.nc"
    copernicus_headland_dataset().to_netcdf(path)
    fld = open_field(path)
    start, goal = (30.2, -40.8), (30.2, -39.7)
    r0 = route(fld, start, goal, 0.5, resolution=1500.0, land_clearance_m=0.0)
    assert r0.status == "solved", r0.message
    assert r0.land_clearance_m == 0.0
    in_land = phases._field_land_cells(fld)
    assert not any(in_land(a, b) for a, b in zip(r0.lat, r0.lon, strict=True))
    r1 = route(fld, start, goal, 0.5, resolution=1500.0)
    assert r1.ok and r0.duration_s < r1.duration_s
