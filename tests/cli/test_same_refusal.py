"""Issue 26, one range table: the same physical input gets the same refusal in every command
and in Python — the rule of its row of `validation.PHYSICAL_RANGES` (range, unit, reason),
under the user's own name for the input (exit 2, one error line on the command line;
`InvalidParameterError` in Python).

Reference: the table's own `PhysicalRange.rule()` text, which every refusal must contain.
"""

from __future__ import annotations

import pathlib

import pytest

from glideplan.errors import InvalidParameterError
from glideplan.validation import PHYSICAL_RANGES

DATA = pathlib.Path(__file__).parents[1] / "data"
POLAR = str(DATA / "polars" / "DG-1001M_ch5.plr")
GPX = str(pathlib.Path(__file__).parents[2] / "src/glideplan/missions/data/buzzards_bay.gpx")
FINAL = ("glide", "final", "--polar", POLAR, "--from", "47.0", "8.0", "1500", "--to", "47.2",
         "8.1", "450")
REACH = ("glide", "reach", "--example", "ridge")
TURNBACK = ("glide", "turnback", "--example", "ridge")
ROUTE = ("route", "--example", "double-gyre", "--from", "30.45", "-39.8", "--to", "30.45",
         "-39.5", "--speed", "0.5")


def _polar():
    from glideplan.sailplane import polar_from_file, read_plr

    return polar_from_file(read_plr(POLAR))


def _rule(kind: str) -> str:
    return PHYSICAL_RANGES[kind].rule()


# (row of the table, [command lines], [Python calls]); every one must be refused by that row
CASES = {
    "turn radius 5e5 m": ("turn_radius", [
        ("plan", "dubins", "--goal", "4", "3", "90", "--radius", "5e5"),
        ("plan", "wind", "--goal", "4", "3", "90", "--speed", "1", "--radius", "5e5",
         "--wind", "0.1", "270"),
        ("mission", "plan", GPX, "--speed", "0.3", "--radius", "5e5"),
        (*ROUTE, "--radius", "5e5"),
    ], [
        lambda: __import__("glideplan").DubinsCar(speed=1.0, turn_radius=5e5),
        lambda: __import__("glideplan").DubinsCarInWind(1.0, 5e5, (0.1, 0.0)),
    ]),
    "MacCready 20 m/s": ("mc", [
        (*FINAL, "--mc", "20"), (*REACH, "--mc", "20"), (*TURNBACK, "--mc", "20"),
    ], [
        lambda: __import__("glideplan").final_glide(_polar(), (47.0, 8.0, 1500.0),
                                                    (47.2, 8.1, 450.0), mc=20.0),
        lambda: __import__("glideplan.reach", fromlist=["Glide"]).Glide(_polar(), mc=20.0),
    ]),
    "altitude 30,000 m": ("altitude", [
        ("glide", "final", "--polar", POLAR, "--from", "47.0", "8.0", "30000", "--to", "47.2",
         "8.1", "450"),
        (*REACH, "--from", "46.5", "7.4", "30000"),
        (*TURNBACK, "--from", "46.5", "7.4", "30000"),
    ], [
        lambda: __import__("glideplan").final_glide(_polar(), (47.0, 8.0, 30000.0),
                                                    (47.2, 8.1, 450.0)),
    ]),
    "safety height 6,000 m": ("height", [
        (*FINAL, "--safety-height", "6000"), (*REACH, "--safety-height", "6000"),
        (*TURNBACK, "--safety-height", "6000"), (*REACH, "--arrival-height", "6000"),
    ], [
        lambda: __import__("glideplan").final_glide(_polar(), (47.0, 8.0, 1500.0),
                                                    (47.2, 8.1, 450.0), safety_height=6000.0),
        lambda: __import__("glideplan.reach.solve", fromlist=["two_heights"]).two_heights(
            None, 6000.0, None),
    ]),
    "mass 10 kg": ("mass_ratio", [
        (*FINAL, "--mass", "10"), (*REACH, "--mass", "10"), (*TURNBACK, "--mass", "10"),
        ("glide", "polar", POLAR, "--mass", "10"),
    ], [
        lambda: __import__("glideplan.sailplane", fromlist=["x"]).polar_from_file(
            __import__("glideplan.sailplane", fromlist=["x"]).read_plr(POLAR), mass_kg=10.0),
    ]),
    "wind 200 m/s": ("wind_speed", [
        ("plan", "wind", "--goal", "4", "3", "90", "--speed", "1", "--radius", "1", "--wind",
         "200", "270"),
        ("mission", "plan", GPX, "--speed", "0.3", "--radius", "150", "--wind", "200", "270"),
        (*FINAL, "--wind", "200", "270"), (*REACH, "--wind", "200", "270"),
        (*TURNBACK, "--wind", "200", "270"),
    ], [
        lambda: __import__("glideplan.units", fromlist=["x"]).wind_from_compass(200.0, 270.0),
        lambda: __import__("glideplan").DubinsCarInWind(1.0, 1.0, (200.0, 0.0)),
    ]),
}


def _rule_text(kind: str) -> str:
    # the mass row is said in kg of the polar's reference mass (its rule names the reason)
    return PHYSICAL_RANGES[kind].reason if kind == "mass_ratio" else _rule(kind)


@pytest.mark.parametrize("case", sorted(CASES))
def test_same_refusal_on_every_command_line(case, run_cli):
    kind, commands, _ = CASES[case]
    for args in commands:
        code, _, err = run_cli(*args)
        last = err.strip().splitlines()[-1]
        assert code == 2, (args, err)
        assert last.startswith("glideplan: error: --"), (args, err)  # the user's flag
        assert _rule_text(kind) in last, (args, last)
        assert "Traceback" not in err


@pytest.mark.parametrize("case", sorted(CASES))
def test_same_refusal_in_python(case):
    kind, _, calls = CASES[case]
    for call in calls:
        with pytest.raises(InvalidParameterError) as info:
            call()
        assert _rule_text(kind) in info.value.rule, info.value


def test_water_speed_is_a_water_vehicles_range(tmp_path):
    """Through a sea-water field (`uo`/`vo`) the vehicle's speed is a water vehicle's
    (`PHYSICAL_RANGES["water_speed"]`: 343 m/s is refused); a field whose current reaches
    20 m/s (cm/s labelled m/s) is warned about, naming its variables."""
    import numpy as np
    import xarray as xr

    from glideplan.fields import open_field
    from glideplan.routing import route

    lat, lon = np.linspace(40.0, 41.0, 11), np.linspace(-40.0, -39.0, 11)
    u = np.full((1, 11, 11), 0.2)
    u[0, 5, 5] = 20.0  # one cell of a 20 "m/s" current: 20 cm/s read as m/s
    ds = xr.Dataset(
        {"uo": (("time", "lat", "lon"), u, {"units": "m s-1"}),
         "vo": (("time", "lat", "lon"), np.zeros_like(u), {"units": "m s-1"})},
        coords={"time": np.array(["2026-01-01T00:00"], dtype="datetime64[ns]"),
                "lat": ("lat", lat, {"units": "degrees_north"}),
                "lon": ("lon", lon, {"units": "degrees_east"})})
    path = tmp_path / "c.nc"
    ds.to_netcdf(path)
    fld = open_field([path])
    assert fld.info["medium"] == "water"
    warned = [w for w in fld.warnings if "uo/vo" in w]
    assert len(warned) == 1 and "20 m/s" in warned[0] and "cm/s" in warned[0]
    with pytest.raises(InvalidParameterError) as info:
        route(fld, (40.2, -39.8), (40.8, -39.2), 343.0)
    assert info.value.name == "speed" and _rule("water_speed") in info.value.rule
