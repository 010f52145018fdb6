"""`glideplan plan min-altitude` from the command line: JSON fields, units, bad input."""

import json

import pytest

from glideplan.cli.app import main
from glideplan.vehicles import dg1001m

G = dg1001m()


def test_normalized_goal_json(capsys):
    argv = ["plan", "min-altitude", "--goal", "0", "1", "120", "--normalized", "--json"]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["planner"] == "min_altitude" and data["objective"] == "altitude"
    assert (data["family"], data["word"]) == ("BBB", "RLR")
    assert data["cost"] == pytest.approx(19.4289, abs=1e-3)
    assert data["dubins_cost"] == pytest.approx(21.8987, abs=1e-3)
    assert data["improvement"] == pytest.approx(data["dubins_cost"] - data["cost"])
    assert data["length_unit"] == pytest.approx(G.radius_stf)
    assert data["goal"]["y"] == pytest.approx(G.radius_stf)
    assert data["endpoint_error"]["max"] < 1e-6
    prof = data["profile"]
    n = len(prof["t"])
    assert all(len(prof[k]) == n for k in ("s", "x", "y", "heading", "speed", "turn_rate"))
    assert prof["altitude_loss"][0] == 0.0
    assert prof["altitude_loss"][-1] == pytest.approx(data["cost"], rel=1e-9)
    assert min(prof["speed"]) == pytest.approx(G.v_stall)
    assert data["vehicle"]["model"] == "quadratic_polar_glider"
    assert {c["orientation"] for c in data["candidates"]} >= {"RLR"}


def test_metres_polar_start_and_plot(capsys, tmp_path):
    png = tmp_path / "p.png"
    R = G.radius_stf
    argv = ["plan", "min-altitude", "--goal", f"{-3 * R + 10}", f"{4 * R - 5}", "0"]
    argv += ["--start", "10", "-5", "0", "--polar", f"{G.a}", f"{G.b}", f"{G.c}"]
    argv += ["--v-stall", f"{G.v_stall}", "--v-max", f"{G.v_max}", "--u-max", f"{G.u_max}"]
    argv += ["--json", "--plot", str(png)]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["word"] == "LSR" and data["cost"] == pytest.approx(25.8483, abs=1e-3)
    assert data["start"]["x"] == 10.0
    assert png.stat().st_size > 10_000


def test_direct_method_and_table(capsys):
    assert main(["plan", "min-altitude", "--goal", "150", "100", "45", "--method", "direct"]) == 0
    out = capsys.readouterr().out
    assert "min_altitude_direct" in out and "solved" in out


def _polar(a="0.0027", v_stall="21", u_max="0.2"):
    return ["--polar", a, "-0.137", "2.31", "--v-stall", v_stall, "--v-max", "44", "--u-max", u_max]


@pytest.mark.parametrize(
    ("extra", "needle"),
    [
        (["--vehicle", "asw28"], "vehicle"),
        (["--method", "shooting"], "method"),
        (["--polar", "0.0027", "-0.137", "2.31"], "--v-stall"),
        (["--v-stall", "20"], "--v-stall"),
        (["--vehicle", "dg1001m", "--polar", "0.0027", "-0.137", "2.31"], "either"),
        ([*_polar(a="-0.0027")], "Assumption 5.2.1"),
        ([*_polar(v_stall="24.5")], "Assumption 5.2.4"),
        ([*_polar(u_max="0")], "--u-max"),
    ],
)
def test_bad_vehicle_input_exits_2(cli_error, extra, needle):
    line = cli_error("plan", "min-altitude", "--goal", "100", "0", "0", *extra)
    assert needle in line


@pytest.mark.parametrize(
    "goal",
    [["nan", "0", "0"], ["1", "2"], ["a", "b", "c"], ["1", "2", "inf"]],
)
def test_bad_goal_exits_2(cli_error, goal):
    cli_error("plan", "min-altitude", "--goal", *goal)


def test_help_states_units(capsys):
    assert main(["plan", "min-altitude", "--help"]) == 0
    out = capsys.readouterr().out
    for text in ("s/m", "m/s", "rad/s", "R_stf"):
        assert text in out
