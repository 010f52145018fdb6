"""`mission plan --field`: each leg routed through a current field (glideplan.routing)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import LocalProjection

V = 0.5
C = (0.15, -0.05)  # steady uniform current, east and north (m/s)
WAYPOINTS = [("A", 29.90, -40.20), ("B", 30.02, -40.05), ("C", 29.95, -39.90)]


@pytest.fixture(scope="module")
def current_file(tmp_path_factory):
    from glideplan.fields.synthetic import copernicus_dataset

    lat = np.linspace(29.7, 30.2, 26)
    lon = np.linspace(-40.4, -39.7, 36)
    times = np.datetime64("2026-01-01T00:00", "ns") + np.arange(3) * np.timedelta64(86400, "s")
    shape = (3, 1, lat.size, lon.size)
    path = tmp_path_factory.mktemp("field") / "current.nc"
    copernicus_dataset(lat, lon, times, [0.5], np.full(shape, C[0]),
                       np.full(shape, C[1])).to_netcdf(path)
    return path


def _leg_time(a, b):
    """Closed form in a steady uniform current: |d - c t| = V t (a straight ground track),
    t = (-(d.c) + sqrt((d.c)^2 + (V^2 - |c|^2)|d|^2)) / (V^2 - |c|^2), in the plane of the
    leg's start (aeqd: exact distances and bearings from the start)."""
    x, y = LocalProjection(a[1], a[2]).to_local(b[1], b[2])
    dc = float(x) * C[0] + float(y) * C[1]
    d2 = float(x) ** 2 + float(y) ** 2
    k = V * V - C[0] ** 2 - C[1] ** 2
    return (-dc + math.sqrt(dc * dc + k * d2)) / k


def test_field_mission_matches_closed_form(run_cli, tmp_path, current_file):
    route = tmp_path / "r.csv"
    route.write_text("name,lat,lon\n" + "".join(f"{n},{a},{b}\n" for n, a, b in WAYPOINTS))
    out = tmp_path / "out"
    code, stdout, err = run_cli("mission", "plan", str(route), "--speed", str(V), "--radius",
                                "100", "--field", str(current_file), "--json", "--export",
                                str(out), "--formats", "slocum,gpx")
    assert code == 0, err
    d = json.loads(stdout)
    assert d["status"] == "solved" and len(d["legs"]) == 2
    refs = [_leg_time(WAYPOINTS[i], WAYPOINTS[i + 1]) for i in range(2)]
    for leg, ref in zip(d["legs"], refs, strict=True):
        # the routing issue's accuracy after its Zermelo refinement: 1e-3 relative
        assert leg["duration_s"] == pytest.approx(ref, rel=1e-3)
        assert leg["endpoint_error"]["position"] < 50.0
    assert d["total_duration_s"] == pytest.approx(sum(refs), rel=1e-3)
    assert set(d["track"]) == {"lat", "lon"}
    assert (out / "goto_l10.ma").is_file() and (out / "r.gpx").is_file()


def test_field_needs_time_and_no_wind(cli_error, tmp_path, current_file):
    route = tmp_path / "r.csv"
    route.write_text("name,lat,lon\nA,29.9,-40.2\nB,30.0,-40.1\n")
    base = ["mission", "plan", str(route), "--speed", "1", "--radius", "10", "--field",
            str(current_file)]
    assert "--wind" in cli_error(*base, "--wind", "0.1", "0")
    assert "--objective" in cli_error(*base, "--objective", "length")
    far = tmp_path / "far.csv"
    far.write_text("name,lat,lon\nA,10,10\nB,10.1,10.1\n")
    line = cli_error("mission", "plan", str(far), "--speed", "1", "--radius", "10", "--field",
                     str(current_file))
    assert "glideplan: error:" in line


def test_basin_scale_mission_through_a_field(tmp_path):
    """A 3-waypoint mission of ~2,700 km (far beyond one local plane's ~490 km) through a
    global still-water file: read without the one-plane limit and routed on the sphere, each
    leg takes its great-circle distance / V (pyproj Geod on the routing sphere; tolerance
    2e-3, the front's stated accuracy at the default grid, well below one cell per leg)."""
    import pyproj

    from glideplan.fields.io import open_field
    from glideplan.fields.synthetic import global_dataset
    from glideplan.formats import read_route
    from glideplan.fronts import EARTH_RADIUS_M
    from glideplan.missions.field_mission import plan_mission_in_field

    path = tmp_path / "still.nc"
    global_dataset(step_deg=1.0, lon_convention="0..360", kind="current").to_netcdf(path)
    csv = tmp_path / "route.csv"
    csv.write_text("name,lat,lon\nA,10.0,-40.0\nB,14.0,-28.0\nC,20.0,-18.0\n")
    with pytest.raises(InvalidParameterError, match="too large for one local projection"):
        read_route(csv)
    route = read_route(csv, check_extent=False)
    mission = plan_mission_in_field(route, open_field(path), speed=5.0, resolution=20_000.0)
    assert mission.ok, mission.message
    geod = pyproj.Geod(a=EARTH_RADIUS_M, b=EARTH_RADIUS_M)
    lats, lons = [10.0, 14.0, 20.0], [-40.0, -28.0, -18.0]
    for i, leg in enumerate(mission.legs):
        _, _, d = geod.inv(lons[i], lats[i], lons[i + 1], lats[i + 1])
        assert leg.duration_s == pytest.approx(d / 5.0, rel=2e-3)
