"""`glideplan plan time-optimal` from the command line."""

import json
import math

import pytest

from glideplan.cli.app import main

BASE = ["plan", "time-optimal", "--goal", "0", "2", "120", "--v-min", "0.3", "--v-max", "1",
        "--u-max", "1"]  # fmt: skip


def test_json_has_common_fields_and_control_history(capsys):
    assert main([*BASE, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("planner", "objective", "status", "cost", "word", "family", "length",
                "duration", "endpoint_error", "segments", "candidates", "stats"):  # fmt: skip
        assert key in data
    assert data["objective"] == "time" and data["status"] == "solved"
    assert data["cost"] == pytest.approx(2.874650, abs=1e-6)
    assert data["cost"] == pytest.approx(data["duration"])
    assert (data["family"], data["word"]) == ("CBSB", "LSR")
    assert data["bang_radius"] == 1.0 and data["corner_radius"] == pytest.approx(0.3)
    ctl = data["controls"]
    assert len(ctl["t"]) == len(ctl["speed"]) == len(ctl["turn_rate"]) == 8
    assert ctl["t"][-1] == pytest.approx(data["cost"])
    assert set(ctl["speed"]) == {0.3, 1.0}
    assert set(ctl["turn_rate"]) == {1.0, 0.0, -1.0}
    assert data["candidates"][0]["type"] == "CBSB LSR"
    assert data["segments"][0]["label"] == "C"


def test_start_units_plot_and_table(capsys, tmp_path):
    png = tmp_path / "path.png"
    argv = ["plan", "time-optimal", "--goal", "10", "5", "90", "--start", "2", "-3", "45",
            "--v-min", "0.5", "--v-max", "2", "--u-max", "0.25", "--plot", str(png)]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "family" in out and "solved" in out
    assert png.stat().st_size > 1000
    assert main([*argv[:-2], "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["start"]["heading"] == pytest.approx(math.pi / 4)
    assert data["bang_radius"] == pytest.approx(8.0) and data["corner_radius"] == pytest.approx(2.0)


def test_direct_method(capsys):
    assert main([*BASE, "--method", "direct", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["planner"] == "time-optimal-direct"
    assert data["cost"] == pytest.approx(2.874650, rel=1e-4)
    assert len(data["controls"]["t"]) > 20


@pytest.mark.parametrize(
    ("flag", "value", "text"),
    [
        ("--v-min", "0", "--v-min"),
        ("--v-min", "-1", "--v-min"),
        ("--v-min", "2", "--v-min"),
        ("--v-min", "nan", "--v-min"),
        ("--v-max", "inf", "--v-max"),
        ("--u-max", "0", "--u-max"),
        ("--method", "shooting", "method"),
    ],
)
def test_bad_input_one_line_exit_2(capsys, flag, value, text):
    argv = list(BASE)
    if flag in argv:
        argv[argv.index(flag) + 1] = value
    else:
        argv += [flag, value]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("glideplan: error:") and text in err[0]


def test_missing_speed_is_a_usage_error(capsys):
    assert main(["plan", "time-optimal", "--goal", "0", "2", "120", "--v-max", "1"]) == 2
    assert "glideplan: error:" in capsys.readouterr().err
