"""`glideplan route`: JSON keys and values, exit codes, one-line errors for bad input."""

from __future__ import annotations

import json
import math

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
