"""`glideplan design ...` via the real entry point: output, --params, exit 2 on bad input."""

import json
import re

import pytest


def test_dives_json_matches_hand_value(run_cli):
    # 5 L at 100 m: N = 71,167.5 / 5,411.6 = 13.15 (dissertation: 13)
    code, out, _ = run_cli("design", "dives", "--volume-l", "5", "--depth-m", "100", "--json")
    assert code == 0
    (row,) = json.loads(out)
    assert row["dives"] == pytest.approx(13.151, abs=2e-3)


def test_tank_table(run_cli):
    code, out, _ = run_cli("design", "tank")
    assert code == 0
    assert "FX23DV" in out and "29.2" in out


@pytest.mark.parametrize(
    "args",
    [
        ["valve", "--json"],
        ["valve", "--volume-l", "1.5", "--json"],
        ["trim", "--json"],
        ["glide", "--volume-l", "2.5", "--json"],
        ["lbl", "--swaths", "3", "--step-m", "20", "--json"],
    ],
)
def test_commands_emit_json(run_cli, args):
    code, out, _ = run_cli("design", *args)
    assert code == 0
    assert json.loads(out)


def test_init_then_params_round_trip(run_cli, tmp_path):
    f = tmp_path / "glider.toml"
    code, _, _ = run_cli("design", "init", str(f))
    assert code == 0 and f.exists()
    # a second init refuses to overwrite
    code, _, err = run_cli("design", "init", str(f))
    assert code == 2 and "--force" in err
    # a 6 L tank instead of 2.998833 L: N = 13.151 * 6 / 2.998833 = 26.312
    f.write_text(re.sub(r"internal_volume_m3 = .*", "internal_volume_m3 = 0.006", f.read_text()))
    code, out, _ = run_cli(
        "design", "dives", "--volume-l", "5", "--depth-m", "100", "--params", str(f), "--json"
    )
    assert code == 0
    assert json.loads(out)[0]["dives"] == pytest.approx(26.312, abs=3e-3)


@pytest.mark.parametrize(
    ("args", "name"),
    [
        (["dives", "--volume-l", "-5"], "--volume-l"),
        (["dives", "--depth-m", "3000"], "--depth-m"),
        (["valve", "--depth-m", "-1"], "--depth-m"),
        (["trim", "--bladder-l", "-1"], "--bladder-l"),
        (["lbl", "--success", "1.5"], "--success"),
        (["glide", "--volume-l", "0"], "--volume-l"),
    ],
)
def test_bad_input_one_line_exit_2(run_cli, error_line, args, name):
    code, out, err = run_cli("design", *args)
    assert code == 2 and out == ""
    line = error_line(err)
    assert line.startswith("glideplan: error: ")
    assert name in line


def test_malformed_params_file(run_cli, tmp_path):
    f = tmp_path / "bad.toml"
    f.write_text("[tank]\nmax_pressure_pa = \n")
    code, _, err = run_cli("design", "tank", "--params", str(f))
    assert code == 2 and "not valid TOML" in err and len(err.strip().splitlines()) == 1
    f.write_text("[hull]\ndiameter_m = -0.2\n")
    code, _, err = run_cli("design", "tank", "--params", str(f))
    assert code == 2 and "hull.diameter_m" in err
