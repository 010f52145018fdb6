"""Messages that name the real cause of a NaN current (issue 26), each on its own input.

Before, each of these said "is on land (no current data: NaN)". References are the inputs'
own construction: which nodes were made NaN, where the rotated grid's edges are (its closed
form placement), which level is below the floor.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.fields import open_field
from glideplan.fields.synthetic import copernicus_dataset, roms_dataset

T0 = np.datetime64("2026-03-01T00:00", "ns")
TIMES = T0 + np.arange(25) * np.timedelta64(3600, "s")
LAT = np.linspace(44.0, 45.0, 11)
LON = np.linspace(-9.0, -8.0, 11)


def _file(tmp_path, u, depth=(0.5,), name="cur.nc"):
    path = tmp_path / name
    copernicus_dataset(LAT, LON, TIMES, list(depth), u, np.where(np.isnan(u), np.nan, 0.0)
                       ).to_netcdf(path)
    return path


def test_all_nan_file_is_refused_by_name(tmp_path, run_cli):
    path = _file(tmp_path, np.full((TIMES.size, 1, LAT.size, LON.size), np.nan))
    with pytest.raises(InvalidParameterError, match="every current value in the file is NaN"):
        open_field(path)
    code, _, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                           "44.5", "-8.5", "--speed", "0.5")
    assert code == 2
    assert "--field" in err and "every current value in the file is NaN" in err
    assert "is on land" not in err


def test_depth_range_below_the_shelf_floor(tmp_path, run_cli):
    """Levels 0.5, 100, 300 m; west of -8.5 the floor is above 300 m (NaN there): a layer
    0..200 m is defined only east of it (the 100..300 interpolation needs 300 m)."""
    u = np.full((TIMES.size, 3, LAT.size, LON.size), 0.1)
    u[:, 2, :, LON < -8.45] = np.nan
    path = _file(tmp_path, u, depth=(0.5, 100.0, 300.0))
    f = open_field(path, depth_range=(0.0, 200.0))
    assert "sea floor there is shallower than 200 m" in f.nan_cause(0.0, 44.5, -8.9)
    code, _, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                           "44.5", "-8.2", "--speed", "0.5", "--depth-range", "0", "200")
    assert code == 2
    assert "--from" in err and "shallower than 200 m" in err and "is on land" not in err
    # the whole file shallower than the range: refused at reading, naming the range
    u[:, 2] = np.nan
    with pytest.raises(InvalidParameterError, match="below the sea floor at every node"):
        open_field(_file(tmp_path, u, depth=(0.5, 100.0, 300.0), name="s.nc"),
                   depth_range=(0.0, 200.0))


def test_depth_range_below_the_floor_of_a_curvilinear_grid(tmp_path):
    """NEMO-like grid_U/grid_V files (`nemo_datasets`: 41 x 31 nodes, 2 km, rotated 20 deg
    about (30, -40); levels 0.494 and 1.54 m) whose second level is NaN on the western half
    of the grid (x index < 20): a layer 0..1.5 m needs the 1.54 m level, so west of the
    centre the floor is above the layer and east of it the layer is defined. The point 20 km
    west of the centre, 10 km north (y = +20 sin 20 + ... inside the 30 km half-height) is
    below the floor, not land; the point 20 km east has water."""
    from glideplan.fields.synthetic import nemo_datasets

    grid_u, grid_v = nemo_datasets(u=0.1)
    paths = []
    for ds, var, name in ((grid_u, "vozocrtx", "grid_U.nc"), (grid_v, "vomecrty",
                                                               "grid_V.nc")):
        vals = ds[var].values.copy()
        vals[:, 1, :, :20] = np.nan
        ds[var].values = vals
        ds.to_netcdf(tmp_path / name)
        paths.append(tmp_path / name)
    f = open_field(paths, depth_range=(0.0, 1.5))
    dlat = math.degrees(10e3 / 6371e3)
    dlon = math.degrees(20e3 / (6371e3 * math.cos(math.radians(30.0))))
    assert "sea floor there is shallower than 1.5 m" in f.nan_cause(0.0, 30.0 + dlat,
                                                                    -40.0 - dlon)
    assert np.isfinite(f.velocity(0.0, 30.0 - dlat, -40.0 + dlon)[0])
    # the surface level alone (no depth range): the same points have water
    g = open_field(paths)
    assert np.isfinite(g.velocity(0.0, 30.0 + dlat, -40.0 - dlon)[0])


def test_point_outside_a_rotated_roms_grid(tmp_path, run_cli):
    """roms_dataset: 41 x 31 nodes, 2 km, xi axis 30 deg CCW from east, about (30, -40). The
    point 45 km east and 40 km south of the centre lies inside the lat/lon box (half-widths
    49.6 and 46.0 km) but at y = -45 sin 30 - 40 cos 30 = -57 km on the grid's axes, beyond
    its half-height of 30 km: outside the grid, not land."""
    path = tmp_path / "roms.nc"
    roms_dataset(u=0.1).to_netcdf(path)
    lat = 30.0 + math.degrees(-40e3 / 6371e3)
    lon = -40.0 + math.degrees(45e3 / (6371e3 * math.cos(math.radians(30.0))))
    f = open_field(path)
    assert "outside the file's curvilinear grid" in f.nan_cause(0.0, lat, lon)
    assert np.isfinite(f.velocity(0.0, 30.0, -40.0)[0])
    code, _, err = run_cli("route", "--field", str(path), "--from", f"{lat}", f"{lon}", "--to",
                           "30", "-40", "--speed", "0.5")
    assert code == 2
    assert "outside the file's curvilinear grid" in err and "is on land" not in err


def test_land_is_still_land(tmp_path):
    u = np.full((TIMES.size, 1, LAT.size, LON.size), 0.1)
    u[:, :, -3:, -3:] = np.nan
    f = open_field(_file(tmp_path, u))
    assert f.nan_cause(0.0, 44.95, -8.05) == "is on land (no current data: NaN)"


def test_all_nan_forecast_day_is_named(tmp_path, run_cli):
    """Hourly steps, 0.1 m/s east, every value NaN from 24 h to 47 h (a forecast day with no
    data). 64 km at 0.5 + 0.1 m/s takes 30 h: the front meets the gap at 24 h. Was
    `field_extent`/`front_stopped`; now `missing_data` naming the step's time."""
    import json

    times = T0 + np.arange(73) * np.timedelta64(3600, "s")
    u = np.full((times.size, 1, LAT.size, LON.size), 0.1)
    u[24:48] = np.nan
    path = tmp_path / "gap.nc"
    copernicus_dataset(LAT, LON, times, [0.5], u, np.where(np.isnan(u), np.nan, 0.0)
                       ).to_netcdf(path)
    code, out, _ = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                           "44.5", "-8.1", "--speed", "0.5", "--json")
    data = json.loads(out)
    assert code == 1
    assert data["unreachable_reason"] == "missing_data"
    assert "no data at 2026-03-02T00:00:00Z" in data["message"]
    # departing inside the gap: the start's error names the empty step, not land
    code, _, err = run_cli("route", "--field", str(path), "--from", "44.5", "-8.9", "--to",
                           "44.5", "-8.1", "--speed", "0.5", "--depart", "2026-03-02T06:00Z")
    assert code == 2 and "is all NaN (no data at that time)" in err


def test_mission_waypoint_on_land_named_by_name_and_line(tmp_path, run_cli):
    """A route file whose third line's waypoint B lies in the land corner (NaN nodes): the
    error names B and its line (was `to=(44.95, -8.05)`), before any leg is routed."""
    u = np.full((TIMES.size, 1, LAT.size, LON.size), 0.1)
    u[:, :, -3:, -3:] = np.nan
    field = _file(tmp_path, u)
    src = tmp_path / "wp.csv"
    src.write_text("name,lat,lon\nA,44.5,-8.9\nB,44.95,-8.05\nC,44.2,-8.5\n")
    code, _, err = run_cli("mission", "plan", str(src), "--speed", "0.5", "--radius", "100",
                           "--field", str(field))
    assert code == 2
    assert "line 3 (B)" in err and "is on land" in err
