"""`glideplan plan dubins` and `glideplan map ...` from the command line."""

import json
import math
import re

import numpy as np
import pytest

from glideplan.cli.app import main


def test_plan_dubins_json_fields(capsys):
    # Goal (0, 8, 180 deg) with R = 2 is the (0, 4, pi) case at twice the scale: LSL 2 (2 + pi).
    assert main(["plan", "dubins", "--goal", "0", "8", "180", "--radius", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    for key in ("planner", "objective", "cost", "word", "length", "duration", "endpoint_error"):
        assert key in data
    assert data["planner"] == "dubins" and data["objective"] == "length"
    assert data["word"] == "LSL"
    assert data["cost"] == pytest.approx(2 * (2 + math.pi))
    assert data["endpoint_error"]["max"] < 1e-9
    seg = data["segments"][0]
    assert seg["kind"] == "arc" and seg["direction"] == "L"
    assert seg["angle"] == pytest.approx(math.pi / 2) and seg["speed"] == 1.0
    assert set(seg["start"]) == {"x", "y", "heading"}
    assert data["segments"][1]["kind"] == "straight"
    assert data["segments"][1]["length"] == pytest.approx(4.0)
    words = {c["word"]: c["cost"] for c in data["candidates"]}
    assert set(words) == {"LSL", "LSR", "RSL", "RSR", "RLR", "LRL"}
    assert words["RLR"] is None  # infeasible: circle centres 12 > 8 apart
    assert data["radius"] == 2.0


def test_negative_numbers_start_speed_eps_and_plot(capsys, tmp_path):
    png = tmp_path / "p.png"
    argv = ["plan", "dubins", "--goal", "-2", "4", "315", "--start", "-1", "-1", "-90"]
    argv += ["--radius", "1.5", "--speed", "3", "--eps", "0.25", "--time", "--json"]
    argv += ["--plot", str(png)]
    assert main(argv) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["objective"] == "time"
    assert data["goal"]["x"] == -2.0 and data["goal"]["heading"] == pytest.approx(math.radians(315))
    assert data["start"]["heading"] == pytest.approx(-math.pi / 2)
    assert data["radius"] == pytest.approx(1.5 * 1.25**2)
    assert data["cost"] == pytest.approx(data["length"] / 3.0)
    assert png.stat().st_size > 1000


def test_table_output(capsys):
    """A straight goal: the word drops the two zero-length arcs of its LSL type (issue 11)."""
    assert main(["plan", "dubins", "--goal", "5", "0", "0", "--radius", "1"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"word\s*│\s*S\s*│", out) and "LSL" not in out and "solved" in out


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["--goal", "1", "2", "0", "--radius", "-1"], "radius"),
        (["--goal", "1", "2", "0", "--radius", "0"], "radius"),
        (["--goal", "1", "2", "0", "--radius", "inf"], "radius"),
        (["--goal", "nan", "2", "0", "--radius", "1"], "goal"),
        (["--goal", "1", "2", "0", "--radius", "1", "--eps", "1"], "--eps"),
        (["--goal", "1", "2", "0", "--radius", "1", "--eps", "-0.5"], "--eps"),
        (["--goal", "1", "2", "0", "--radius", "1", "--speed", "0"], "speed"),
        (["--goal", "1", "2", "--radius", "1"], "goal"),
        (["--radius", "1"], "goal"),
        (["--goal", "1", "2", "0"], "radius"),
        (["--goal", "a", "2", "0", "--radius", "1"], "goal"),
    ],
)
def test_plan_dubins_bad_input(cli_error, argv, needle):
    line = cli_error("plan", "dubins", *argv)
    assert needle in line


def test_map_partition_writes_figure_and_csv(capsys, tmp_path):
    png, csv = tmp_path / "p.png", tmp_path / "p.csv"
    argv = ["map", "partition", "--heading", "180", "--n", "41", "--out", str(png)]
    assert main([*argv, "--data", str(csv)]) == 0
    out = capsys.readouterr().out
    assert "LSL" in out and "RLR" in out
    assert png.stat().st_size > 1000
    rows = [r for r in csv.read_text().splitlines() if not r.startswith("#")]
    assert rows[0].split(",")[:3] == ["x", "y", "label"]
    assert len(rows) == 1 + 41 * 41


def test_map_tradespace_writes_npz(capsys, tmp_path):
    npz = tmp_path / "t.npz"
    argv = ["map", "tradespace", "--heading", "-90", "--eps", "0.5", "--n", "31"]
    assert main([*argv, "--extent", "4", "--data", str(npz), "--processes", "1"]) == 0
    data = np.load(npz)
    assert data["ratio"].shape == (31 * 31,)
    assert np.nanmin(data["ratio"]) >= 1.0 - 1e-12
    assert float(data["eps"]) == 0.5 and float(data["extent"]) == 4.0


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["partition", "--heading", "nan"], "heading"),
        (["partition", "--heading", "0", "--eps", "1"], "eps"),
        (["partition", "--heading", "0", "--n", "1"], "n="),
        (["partition", "--heading", "0", "--extent", "-2"], "extent"),
        (["partition", "--heading", "0", "--data", "x.txt"], "data"),
        (["tradespace", "--heading", "0", "--eps", "-0.1"], "eps"),
        (["tradespace", "--heading", "0", "--processes", "0"], "processes"),
        (["tradespace"], "heading"),
    ],
)
def test_map_bad_input(cli_error, argv, needle):
    line = cli_error("map", *argv)
    assert needle in line


def test_map_on_a_dask_cluster(capsys, tmp_path):
    distributed = pytest.importorskip("distributed")
    csv = tmp_path / "p.csv"
    with distributed.LocalCluster(
        n_workers=1, processes=False, threads_per_worker=1, dashboard_address=None
    ) as cluster:
        argv = ["map", "partition", "--heading", "120", "--n", "21", "--data", str(csv)]
        assert main([*argv, "--scheduler", cluster.scheduler_address]) == 0
    assert "LSL" in capsys.readouterr().out
    assert len([r for r in csv.read_text().splitlines() if not r.startswith("#")]) == 1 + 21 * 21


def test_map_bad_scheduler_is_one_line(cli_error):
    line = cli_error(
        "map", "partition", "--heading", "0", "--n", "5", "--scheduler", "nonsense::address"
    )
    assert "scheduler" in line
