"""`glideplan route`: JSON keys and values, exit codes, one-line errors for bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest

from glideplan.fields.synthetic import copernicus_dataset

T0 = np.datetime64("2026-03-01T00:00", "ns")
TIMES = T0 + np.arange(49) * np.timedelta64(3600, "s")
LAT = np.linspace(44.0, 45.0, 21)
LON = np.linspace(-9.0, -8.0, 21)


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A steady 0.1 m/s eastward current with a land corner (NaN) in the north-east."""
    d = tmp_path_factory.mktemp("cli")
    u = np.full((TIMES.size, 1, LAT.size, LON.size), 0.1)
    u[:, :, -3:, -3:] = np.nan
    path = d / "cur.nc"
    copernicus_dataset(LAT, LON, TIMES, [0.5], u, np.where(np.isnan(u), np.nan, 0.0)).to_netcdf(
        path)
    text = d / "notes.nc"
    text.write_text("hello\n")
    return path, text


def test_json_keys_and_values(files, run_cli, tmp_path):
    """Uniform 0.1 m/s along the route's line (west -> east): t = D / (V + c), closed form."""
    path, _ = files
    png = tmp_path / "route.png"
    code, out, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                             "44.5", "-8.5", "--speed", "0.4", "--depart", "2026-03-01T06:00Z",
                             "--resolution", "1500", "--json", "--plot", str(png))
    assert code == 0, err
    data = json.loads(out)
    for key in ("status", "duration_s", "distance_m", "depart", "arrive", "track",
                "endpoint_error_m", "straight_line_duration_s", "field", "stats"):
        assert key in data
    assert data["status"] == "solved"
    assert data["depart"] == "2026-03-01T06:00:00Z"
    assert set(data["track"]) >= {"t", "lat", "lon"}
    assert data["field"]["file"] == [str(path)]
    assert data["field"]["variables"] == ["uo", "vo"]
    assert {"grid_nodes", "front_s"} <= set(data["stats"])
    from glideplan.routing.sphere import gc_distance

    # On the router's sphere the great circle's bearing stays within 0.15 deg of east here:
    # the cross current is < 3e-4 m/s, so holding it takes D / (V + c) to within 1e-5, and
    # in a uniform current that line is the time-optimal route (to ~(D / R)^2).
    dist = float(gc_distance(44.5, -8.9, 44.5, -8.5))
    t_line = dist / (0.4 + 0.1)
    assert data["straight_line_duration_s"] == pytest.approx(t_line, rel=1e-5)
    assert data["duration_s"] == pytest.approx(t_line, rel=1e-3)
    assert data["land_clearance_m"] > 0 and data["unreachable_reason"] is None
    assert data["endpoint_error_m"] < 10.0
    import matplotlib.image

    assert matplotlib.image.imread(png).ndim == 3  # the figure reads back as an image
    arrive = np.datetime64(data["arrive"].rstrip("Z"))
    assert (arrive - np.datetime64("2026-03-01T06:00")) / np.timedelta64(1, "s") == \
        pytest.approx(data["duration_s"], abs=1.0)


def test_unreachable_exits_1(run_cli):
    code, out, err = run_cli("route", "--example", "double-gyre", "--from", "30.45", "-39.8",
                             "--to", "30.45", "-38.2", "--speed", "0.02", "--resolution", "8000",
                             "--json")
    assert code == 1, err
    data = json.loads(out)
    assert data["status"] == "unreachable" and data["best_distance_m"] > 0


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (("--speed", "0"), "--speed"),
        (("--speed", "-1"), "--speed"),
        (("--speed", "nan"), "--speed"),
        (("--to", "46.0", "-8.5"), "north bound 45"),
        (("--from", "44.5", "-7.5"), "east bound -8"),
        (("--to", "44.95", "-8.05"), "on land"),
        (("--depart", "yesterday"), "--depart"),
        (("--depart", "2026-04-01T00:00"), "after the field's last time"),
        (("--depth-range", "0", "100"), "deepest level"),
        (("--resolution", "-5"), "--resolution"),
    ],
)
def test_bad_input_one_line_exit_2(files, cli_error, args, needle):
    path, _ = files
    base = {"--field": [str(path)], "--from": ["44.5", "-8.9"], "--to": ["44.5", "-8.5"],
            "--speed": ["0.4"]}
    override = {args[0]: list(args[1:])}
    merged = {**base, **override}
    argv = ["route"]
    for k, v in merged.items():
        argv += [k, *v]
    line = cli_error(*argv)
    assert needle in line


def test_bad_files_exit_2(files, tmp_path, cli_error):
    _, text = files
    common = ("--from", "44.5", "-8.9", "--to", "44.5", "-8.5", "--speed", "0.4")
    assert "not a NetCDF or GRIB file" in cli_error("route", "--field", str(text), *common)
    assert "no such file" in cli_error("route", "--field", str(tmp_path / "x.nc"), *common)
    import xarray as xr

    temp = tmp_path / "temp.nc"
    xr.Dataset({"thetao": (("latitude", "longitude"), np.zeros((2, 2)))},
               coords={"latitude": [44.0, 45.0], "longitude": [-9.0, -8.0]}).to_netcdf(temp)
    assert "no eastward/northward velocity pair" in cli_error("route", "--field", str(temp),
                                                              *common)
    assert "--field" in cli_error("route", *common)
    assert "--example" in cli_error("route", "--example", "gyre", *common)


# ----- issue 18: routes on the real ocean, from the CLI as a new user runs them ------------


def test_era5_file_across_greenwich_from_the_cli(tmp_path, run_cli):
    """ERA5-style global file (0..359.5 E, descending latitude, valid_time): 50 N 3 W -> 3 E
    at 25 m/s in still air was `unreachable`; now solved, duration = great-circle distance / V
    (the router's sphere; refined to 1e-5, the grid's own time within 1 %)."""
    from glideplan.fields.synthetic import era5_dataset
    from glideplan.routing.sphere import gc_distance

    path = tmp_path / "era5.nc"
    era5_dataset(step_deg=0.5, times=[T0, T0 + np.timedelta64(2, "D")]).to_netcdf(path)
    code, out, err = run_cli("route", "--field", str(path), "--from", "50", "-3", "--to", "50",
                             "3", "--speed", "25", "--resolution", "8000", "--json")
    assert code == 0, err
    data = json.loads(out)
    d = float(gc_distance(50.0, -3.0, 50.0, 3.0))
    assert data["status"] == "solved" and data["unreachable_reason"] is None
    assert data["duration_s"] == pytest.approx(d / 25.0, rel=1e-2)
    assert data["land_clearance_m"] == pytest.approx(8000.0)  # one spacing: no land
    assert min(data["track"]["lon"]) < 0.0 < max(data["track"]["lon"])
    # beyond the old 490 km limit: 40 N 30 W -> 45 N 0 E, ~2,500 km
    code, out, err = run_cli("route", "--field", str(path), "--from", "40", "-30", "--to",
                             "45", "0", "--speed", "25", "--resolution", "40000", "--json")
    assert code == 0, err
    data = json.loads(out)
    d = float(gc_distance(40.0, -30.0, 45.0, 0.0))
    assert d > 2.4e6 and data["status"] == "solved"
    assert data["duration_s"] == pytest.approx(d / 25.0, rel=1e-2)


def test_route_across_180_plots_and_exports_split_lines(tmp_path, run_cli):
    """A -180..180 global file, 10 N 175 E -> 12 N 170 W (was `unreachable`, `--plot`
    crashed near 180): solved; the figure reads back; the GeoJSON line is split at 180
    (RFC 7946 3.1.9: parts meeting at +-180, checked by pygeoif) and fastkml reads the KML."""
    import sys

    sys.path.insert(0, str(__import__("pathlib").Path(__file__).parents[1] / "formats"))
    from geojson_checks import check_geometry

    from glideplan.fields.synthetic import global_dataset

    path = tmp_path / "global.nc"
    global_dataset(step_deg=1.0, lon_convention="-180..180",
                   times=[T0, T0 + np.timedelta64(2, "D")]).to_netcdf(path)
    png, gj, kml_file = tmp_path / "r.png", tmp_path / "r.geojson", tmp_path / "r.kml"
    code, out, err = run_cli("route", "--field", str(path), "--from", "10", "175", "--to",
                             "12", "-170", "--speed", "25", "--resolution", "15000", "--json",
                             "--plot", str(png), "--geojson", str(gj), "--kml", str(kml_file))
    assert code == 0, err
    assert json.loads(out)["status"] == "solved"
    import matplotlib.image

    assert matplotlib.image.imread(png).ndim == 3
    geom = json.loads(gj.read_text())["features"][0]["geometry"]
    check_geometry(geom)
    assert geom["type"] == "MultiLineString"
    a, b = geom["coordinates"][0][-1], geom["coordinates"][1][0]
    assert abs(a[0]) == 180.0 and abs(b[0]) == 180.0 and a[1] == pytest.approx(b[1])
    from fastkml import kml

    doc = kml.KML.from_string(kml_file.read_bytes())
    assert type(doc.features[0].features[0].geometry).__name__ == "MultiLineString"


def test_headland_in_a_copernicus_file_with_the_readme_depth_range(tmp_path, run_cli):
    """A Copernicus-like file (levels from 0.494 m) with a rectangular headland between start
    and goal, `--depth-range 0 500` (the README's example): solved round the cape (was
    `unverified` at every resolution), the land clearance reported, no track point on land,
    and the depth warning printed."""
    from glideplan.fields import open_field
    from glideplan.fields.synthetic import COPERNICUS_DEPTHS, copernicus_headland_dataset

    path = tmp_path / "cape.nc"
    copernicus_headland_dataset(depths=COPERNICUS_DEPTHS, u=0.05).to_netcdf(path)
    args = ("route", "--field", str(path), "--from", "30.2", "-40.8", "--to", "30.2",
            "-39.7", "--speed", "0.5", "--depth-range", "0", "500", "--resolution", "1500")
    code, out, err = run_cli(*args, "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved", data["message"]
    assert data["land_clearance_m"] > 1500.0
    fld = open_field(path, depth_range=(0.0, 500.0))
    u, _ = fld.velocity(fld.time_span[0], data["track"]["lat"], data["track"]["lon"])
    assert np.all(np.isfinite(u))
    assert max(data["track"]["lat"]) > 30.6  # round the cape's north end
    code, out, err = run_cli(*args)
    assert code == 0 and "warning" in err and "0.494" in err


@pytest.mark.parametrize("clearance", [None, "600"])
def test_island_in_still_water_from_the_cli(tmp_path, run_cli, clearance):
    """Still water with a circular island (NaN) between start and goal (was `unverified`):
    solved, the shortest way round keeping the reported clearance c (tangent, arc of radius
    R_n + c, tangent; closed form within 1 %, see `test_route.test_island_tangent_arc_tangent`
    for the accuracy), no track point on land -- at the default clearance and at a tighter
    one the user asks for (its few-leg taut route is held leg by leg; a heading interpolated
    between legs once missed by 670 m round an island like this one)."""
    import math

    from glideplan.fields import open_field
    from glideplan.geodesy import LocalProjection

    centre = LocalProjection(30.0, -40.0)
    lat = np.arange(29.7, 30.3001, 0.0025)
    lon = np.arange(-40.35, -39.6499, 0.0029)
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    x, y = centre.to_local(LA, LO)
    u = np.where(np.hypot(x, y) < 8000.0, np.nan, 0.0)[None, None]
    path = tmp_path / "island.nc"
    copernicus_dataset(lat, lon, TIMES[:1], [0.5], u, u).to_netcdf(path)
    (a_lat, a_lon), (b_lat, b_lon) = (centre.to_geographic(-20000.0, 0.0),
                                      centre.to_geographic(20000.0, 0.0))
    code, out, err = run_cli("route", "--field", str(path), "--from", str(float(a_lat)),
                             str(float(a_lon)), "--to", str(float(b_lat)), str(float(b_lon)),
                             "--speed", "0.3", "--resolution", "400", "--json",
                             *(("--land-clearance", clearance) if clearance else ()))
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved", data["message"]
    if clearance:
        assert data["land_clearance_m"] == float(clearance)
    r = 8000.0 + data["land_clearance_m"]
    ref = (2 * math.sqrt(20000.0**2 - r * r) + r * (math.pi - 2 * math.acos(r / 20000.0))) / 0.3
    assert data["duration_s"] == pytest.approx(ref, rel=1e-2)
    uu, _ = open_field(path).velocity(0.0, data["track"]["lat"], data["track"]["lon"])
    assert np.all(np.isfinite(uu))


def test_absurd_speed_is_refused_and_start_equal_goal_is_solved(files, run_cli, cli_error):
    path, _ = files
    line = cli_error("route", "--field", str(path), "--from", "44.5", "-8.9", "--to", "44.5",
                     "-8.5", "--speed", "1e9")
    assert "--speed" in line and "343" in line
    code, out, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                             "44.5", "-8.9", "--speed", "0.4", "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved" and data["duration_s"] == 0.0


def test_unreachable_states_its_reason_and_draws_the_furthest_reach(files, run_cli, tmp_path):
    """0.05 m/s upstream against the 0.1 m/s current: never reachable (the current, faster
    than the vehicle, sets it away from the goal everywhere in the field: outside the drift
    cone, found without a front): exit 1, reason "outside_drift_cone", the figure drawn."""
    path, _ = files
    png = tmp_path / "u.png"
    code, out, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.5", "--to",
                             "44.5", "-8.9", "--speed", "0.05", "--resolution", "2000",
                             "--json", "--plot", str(png))
    assert code == 1, err
    data = json.loads(out)
    assert data["status"] == "unreachable"
    assert data["unreachable_reason"] == "outside_drift_cone"
    assert data["best_distance_m"] > 0 and "front_s" not in data["stats"]
    import matplotlib.image

    assert matplotlib.image.imread(png).ndim == 3


def test_route_centred_on_180_plots(tmp_path, run_cli):
    """40 S 178 E -> 39 S 178 W: the figure's frame is centred on 180 itself (the scale was
    once computed at -180.05 deg and refused): solved, the figure written and read back."""
    from glideplan.fields.synthetic import global_dataset

    path = tmp_path / "global.nc"
    global_dataset(step_deg=1.0, lon_convention="-180..180",
                   times=[T0, T0 + np.timedelta64(2, "D")]).to_netcdf(path)
    png = tmp_path / "am.png"
    code, out, err = run_cli("route", "--field", str(path), "--from", "-40", "178", "--to",
                             "-39", "-178", "--speed", "25", "--resolution", "10000", "--json",
                             "--plot", str(png))
    assert code == 0, err
    assert json.loads(out)["status"] == "solved"
    import matplotlib.image

    assert matplotlib.image.imread(png).ndim == 3
