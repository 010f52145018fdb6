"""`mission plan --field` with `--depart`, `--depth-range` and `--radius`: legs chained in time
through a time-varying, depth-layered current, and the flyable track in the vehicle files."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.geodesy import LocalProjection

V = 0.5
R0 = 100.0
DEPTHS = [0.0, 50.0, 100.0, 500.0]
# East current at 0 and 50 m, none from 100 m down: the 0-500 m trapezoidal average is
# (50 * 1 + 25 * 1) / 500 = 0.15 of the surface value (issue 12's example).
LAYER_FACTOR = 0.15
DAY = 86400.0
SURFACE = np.array([1.0, 0.2, -1.0, 1.0])  # surface east current (m/s) at days 0, 1, 2, 3
EPOCH = np.datetime64("2026-01-01T00:00", "ns")
DEPART_S = 6 * 3600.0  # --depart 2026-01-01T06:00Z
WAYPOINTS = [("A", 29.90, -40.20), ("B", 30.02, -40.05), ("C", 29.95, -39.90)]


@pytest.fixture(scope="module")
def layered_file(tmp_path_factory):
    from glideplan.fields.synthetic import copernicus_dataset

    lat = np.linspace(29.7, 30.2, 26)
    lon = np.linspace(-40.4, -39.7, 36)
    times = EPOCH + (np.arange(SURFACE.size) * DAY).astype("timedelta64[s]")
    profile = np.array([1.0, 1.0, 0.0, 0.0])  # x the surface value, per depth level
    u = SURFACE[:, None, None, None] * profile[None, :, None, None] * np.ones(
        (1, 1, lat.size, lon.size))
    path = tmp_path_factory.mktemp("layered") / "layered.nc"
    copernicus_dataset(lat, lon, times, DEPTHS, u, np.zeros_like(u)).to_netcdf(path)
    return path


@pytest.fixture(scope="module")
def route_file(tmp_path_factory):
    path = tmp_path_factory.mktemp("route") / "r.csv"
    path.write_text("name,lat,lon\n" + "".join(f"{n},{a},{b}\n" for n, a, b in WAYPOINTS))
    return path


def _drift(t0: float, t1: float) -> float:
    """Integral of the depth-averaged east current from t0 to t1 (s since the epoch): the
    current is linear between the daily levels, so the trapezoid on the knots is exact."""
    inner = np.arange(1, SURFACE.size) * DAY
    knots = np.concatenate([[t0], inner[(inner > t0) & (inner < t1)], [t1]])
    c = LAYER_FACTOR * np.interp(knots, np.arange(SURFACE.size) * DAY, SURFACE)
    return float(np.sum(0.5 * (c[1:] + c[:-1]) * np.diff(knots)))


def _leg_time(a, b, t0: float) -> float:
    """Issue 12's closed form for a current uniform in space: the reachable set after t is the
    disk of radius V t about the drift, so the leg time is the smallest t with
    |d - (drift(t0, t0 + t), 0)| <= V t (bisection to 1e-9 s), d in the plane of the leg's
    start (aeqd: exact distance and bearing from the start)."""
    x, y = (float(v) for v in LocalProjection(a[1], a[2]).to_local(b[1], b[2]))

    def gap(t: float) -> float:
        return math.hypot(x - _drift(t0, t0 + t), y) - V * t

    lo, hi = 0.0, 1.0
    while gap(hi) > 0:
        hi *= 2.0
    while hi - lo > 1e-9:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if gap(mid) > 0 else (lo, mid)
    return hi


def test_depart_depth_range_and_flyable_track(run_cli, tmp_path, layered_file, route_file):
    import gpxpy

    out = tmp_path / "out"
    code, stdout, err = run_cli(
        "mission", "plan", str(route_file), "--speed", str(V), "--radius", str(R0),
        "--field", str(layered_file), "--depart", "2026-01-01T06:00Z",
        "--depth-range", "0", "500", "--json", "--export", str(out), "--formats", "gpx,slocum")
    assert code == 0, err
    d = json.loads(stdout)
    assert d["status"] == "solved" and d["radius"] == R0
    legs = d["legs"]
    # chained departures: leg 1 at --depart, leg 2 when leg 1 arrives
    assert legs[0]["depart"] == "2026-01-01T06:00:00.000Z"
    assert legs[0]["depart_s"] == pytest.approx(DEPART_S, abs=1e-6)
    assert legs[1]["depart_s"] == pytest.approx(DEPART_S + legs[0]["duration_s"], abs=1e-3)
    assert legs[1]["depart"] == legs[0]["arrive"]
    t = DEPART_S
    for i, leg in enumerate(legs):
        ref = _leg_time(WAYPOINTS[i], WAYPOINTS[i + 1], t)
        # the routing issue's accuracy after its Zermelo refinement: 1e-3 relative
        assert leg["duration_s"] == pytest.approx(ref, rel=1e-3)
        t += ref
        g = leg["glider"]
        # R0' = R0 (1 + eps)^2 with eps = the largest depth-averaged current on the leg / V
        assert 0.0 < g["disturbance_ratio"] <= LAYER_FACTOR * 1.0 / V + 1e-6
        assert g["feasible_radius_m"] == pytest.approx(
            R0 * (1 + g["disturbance_ratio"]) ** 2, rel=1e-12)
        # the closed-loop follower through the field stays on the path (trackable, App. A)
        assert g["status"] == "solved" and g["max_cross_track_m"] < R0
        assert g["final_distance_m"] < R0
    # the departure makes a difference: from the field's first time the legs take other times
    ref0 = _leg_time(WAYPOINTS[0], WAYPOINTS[1], 0.0)
    assert abs(ref0 - legs[0]["duration_s"]) > 10 * 1e-3 * ref0

    # the track is the flyable path: through the waypoints, turns no tighter than R0'
    proj = LocalProjection(WAYPOINTS[0][1], WAYPOINTS[0][2])
    x, y = proj.to_local(np.array(d["track"]["lat"]), np.array(d["track"]["lon"]))
    for _, la, lo in WAYPOINTS:
        wx, wy = proj.to_local(la, lo)
        assert np.min(np.hypot(x - wx, y - wy)) < 1e-3
    r_min = min(leg["glider"]["feasible_radius_m"] for leg in legs)
    ax, ay, bx, by = x[1:-1] - x[:-2], y[1:-1] - y[:-2], x[2:] - x[1:-1], y[2:] - y[1:-1]
    a, b = np.hypot(ax, ay), np.hypot(bx, by)
    c = np.hypot(x[2:] - x[:-2], y[2:] - y[:-2])
    ok = (a > 1.0) & (b > 1.0)
    curvature = 2.0 * np.abs(ax * by - ay * bx)[ok] / (a * b * c)[ok]  # 1 / circumradius
    assert curvature.max() <= 1.0 / r_min * 1.02  # aeqd scale distortion << 2 %
    # the course is continuous at the interior waypoint: no kink in the track there
    headings = np.degrees(np.arctan2(by, bx))
    jumps = np.abs((np.diff(headings) + 180.0) % 360.0 - 180.0)
    assert jumps.max() < 15.0
    # the GPX file carries that dense track (read back with gpxpy)
    with open(out / "r.gpx") as fh:
        gpx = gpxpy.parse(fh)
    pts = [p for trk in gpx.tracks for seg in trk.segments for p in seg.points]
    assert len(pts) == len(d["track"]["lat"])
    assert max(abs(p.latitude - la) for p, la in zip(pts, d["track"]["lat"], strict=True)) < 1e-6
    assert (out / "goto_l10.ma").is_file()
    assert d["stats"]["straight_legs"]["max_deviation_m"] <= 50.0
    # per-waypoint ETAs (issue 26): each waypoint's is its leg's route arrival (the JSON and
    # the GPX waypoints' times, read by gpxpy)
    etas = [w["eta"] for w in d["waypoints"]]
    assert etas[0] == legs[0]["depart"] and etas[1:] == [leg["arrive"] for leg in legs]
    got = [w.time.strftime("%Y-%m-%dT%H:%M:%S.%f")[:-3] + "Z" for w in gpx.waypoints]
    assert got == etas


def test_depart_outside_the_field_names_the_bound(cli_error, route_file, layered_file):
    base = ["mission", "plan", str(route_file), "--speed", str(V), "--radius", str(R0),
            "--field", str(layered_file)]
    line = cli_error(*base, "--depart", "2026-01-05T00:00Z")
    assert "--depart" in line and "after the field's last time 2026-01-04T00:00:00Z" in line
    line = cli_error(*base, "--depart", "2025-12-31T23:00Z")
    assert "--depart" in line and "before the field's first time 2026-01-01T00:00:00Z" in line
    assert "ISO 8601" in cli_error(*base, "--depart", "tomorrow")
    assert "--depth-range" in cli_error(*base, "--depth-range", "100", "50")
    assert "--depth-range" in cli_error(*base, "--depth-range", "-5", "50")
    # --depart without --field gives the waypoints' ETAs as UTC times (issue 26); the depth
    # range still needs a field
    line = cli_error("mission", "plan", str(route_file), "--speed", "1", "--radius", "10",
                     "--depth-range", "0", "50")
    assert "--depth-range" in line and "--field" in line


def test_route_command_shares_the_depart_check(cli_error, layered_file):
    line = cli_error("route", "--field", str(layered_file), "--from", "29.9", "-40.2", "--to",
                     "30.0", "-40.0", "--speed", "0.5", "--depart", "2026-01-09T00:00Z")
    assert "--depart" in line and "after the field's last time" in line
