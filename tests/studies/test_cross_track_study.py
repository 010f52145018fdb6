"""The cross-track study: resumable store (kill -9 halfway), identical results across
interruptions and backends (local processes, Dask), refused files, CLI, the curves' shape."""

import json
import os
import signal
import sqlite3
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

from glideplan.cli.app import main
from glideplan.errors import InvalidParameterError, ResultsFileError
from glideplan.studies.cross_track import CrossTrackConfig, knee, run_cross_track_study

SMALL = {"eps": (0.25, 0.5), "r_plan": (1.0, 2.0), "samples": 24, "chunk": 3, "seed": 5}


def _rows(directory):
    with sqlite3.connect(directory / "samples.sqlite") as conn:
        return conn.execute(
            "SELECT case_name, eps, r_plan, sample, goal_x, goal_y, error, crossed "
            "FROM results ORDER BY case_name, eps, r_plan, sample"
        ).fetchall()


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """The small study run uninterrupted, in this process."""
    out = tmp_path_factory.mktemp("reference")
    res = run_cross_track_study(out, CrossTrackConfig(**SMALL), processes=1, progress=False)
    return out, res


def test_summary_records(reference):
    out, res = reference
    summary = json.loads((out / "summary.json").read_text())
    assert summary == res.summary
    assert len(summary) == 2 * 2 * 2  # cases x eps x r_plan
    for rec in summary:
        assert set(rec) == {
            "case",
            "eps",
            "r_plan",
            "samples",
            "mean_error",
            "std_error",
            "failures",
        }
        assert rec["samples"] == 24 and rec["mean_error"] > 0.0
    assert len(_rows(out)) == 8 * 24


def test_kill_9_halfway_then_resume_loses_and_repeats_nothing(reference, tmp_path):
    ref_dir, ref = reference
    out = tmp_path / "killed"
    script = textwrap.dedent(
        f"""
        from glideplan.studies.cross_track import CrossTrackConfig, run_cross_track_study
        run_cross_track_study({str(out)!r}, CrossTrackConfig(**{SMALL!r}), processes=2,
                              progress=False)
        """
    )
    proc = subprocess.Popen([sys.executable, "-c", script], start_new_session=True)
    db = out / "samples.sqlite"
    units_total = len(CrossTrackConfig(**SMALL).units())
    done = 0
    try:
        deadline = time.monotonic() + 120
        while time.monotonic() < deadline and proc.poll() is None:
            if db.exists():
                try:
                    with sqlite3.connect(db, timeout=1) as conn:
                        done = conn.execute("SELECT COUNT(*) FROM units").fetchone()[0]
                except sqlite3.OperationalError:
                    done = 0
                if done >= 4:
                    break
            time.sleep(0.05)
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)  # the study and its worker processes
        proc.wait(timeout=30)
    assert 4 <= done < units_total, "the study was not caught halfway"
    with sqlite3.connect(db) as conn:
        partial = conn.execute("SELECT COUNT(*) FROM units").fetchone()[0]
    assert partial < units_total
    res = run_cross_track_study(out, CrossTrackConfig(**SMALL), processes=1, progress=False)
    assert res.report.skipped == partial and res.report.ran == units_total - partial
    assert _rows(out) == _rows(ref_dir)  # nothing lost, nothing repeated, identical values
    assert res.summary == ref.summary


def test_dask_local_cluster_gives_identical_results(reference, tmp_path):
    distributed = pytest.importorskip("distributed")
    ref_dir, ref = reference
    cfg = CrossTrackConfig(**SMALL)
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        res = run_cross_track_study(
            tmp_path / "dask", cfg, scheduler=cluster.scheduler_address, progress=False
        )
    assert res.summary == ref.summary
    assert _rows(tmp_path / "dask") == _rows(ref_dir)


def test_mismatched_and_corrupt_files_are_refused(reference, tmp_path, capsys):
    ref_dir, _ = reference
    other = dict(SMALL, seed=6)
    with pytest.raises(ResultsFileError, match="seed"):
        run_cross_track_study(ref_dir, CrossTrackConfig(**other), processes=1, progress=False)
    bad = tmp_path / "corrupt"
    bad.mkdir()
    (bad / "samples.sqlite").write_bytes(b"not a database at all" * 100)
    with pytest.raises(ResultsFileError):
        run_cross_track_study(bad, CrossTrackConfig(**SMALL), processes=1, progress=False)
    # a valid SQLite file that is not a study
    alien = tmp_path / "alien"
    alien.mkdir()
    with sqlite3.connect(alien / "samples.sqlite") as conn:
        conn.execute("CREATE TABLE t (x)")
    with pytest.raises(ResultsFileError):
        run_cross_track_study(alien, CrossTrackConfig(**SMALL), processes=1, progress=False)
    args = [
        "study",
        "cross-track",
        "--eps",
        "0.25,0.5",
        "--r-plan",
        "1,2",
        "--samples",
        "24",
        "--chunk",
        "3",
        "--seed",
        "6",
        "--processes",
        "1",
        "--no-progress",
    ]
    assert main([*args, "--out", str(ref_dir)]) == 2
    assert main([*args, "--out", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and all(e.startswith("glideplan: error:") for e in err)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"eps": (1.0,)},
        {"eps": (-0.1,)},
        {"r_plan": (0.0,)},
        {"samples": 0},
        {"cases": ("windy",)},
        {"seed": -1},
        {"follower": {"dt": -0.05}},
        {"follower": {"no_such_gain": 1.0}},
    ],
)
def test_bad_config(kwargs):
    with pytest.raises(InvalidParameterError):
        CrossTrackConfig(**kwargs)


def test_cli_small_study_and_bad_input(tmp_path, capsys, cli_error):
    out = tmp_path / "cli"
    code = main(
        [
            "study",
            "cross-track",
            "--eps",
            "0.5",
            "--r-plan",
            "1:2:0.5",
            "--samples",
            "6",
            "--case",
            "steady",
            "--processes",
            "1",
            "--no-progress",
            "--json",
            "--out",
            str(out),
        ]
    )
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert [r["r_plan"] for r in data["summary"]] == [1.0, 1.5, 2.0]
    assert (out / "summary.json").exists() and (out / "samples.sqlite").exists()
    for bad in (
        ["--eps", "1.0"],
        ["--eps", "abc"],
        ["--case", "gusty"],
        ["--samples", "0"],
        ["--r-plan", "1:2:0"],
    ):
        cli_error("study", "cross-track", *bad, "--out", str(tmp_path / "x"))


def test_knee_on_synthetic_curves():
    r = np.round(np.arange(1.0, 4.01, 0.1), 10)
    e = np.maximum(0.05, 0.5 - 0.6 * (r - 1.0))  # linear drop to a plateau at r = 1.75
    assert knee(r, e) == pytest.approx(1.7)
    assert knee(r, np.full(r.size, 0.1)) == pytest.approx(1.0)


def test_steady_curve_decreases_to_a_plateau_with_knee_near_feasible_radius(tmp_path):
    cfg = CrossTrackConfig(
        eps=(0.25, 0.5),
        r_plan=tuple(np.round(np.arange(1, 3.01, 0.25), 4)),
        samples=60,
        chunk=60,
        cases=("steady",),
        seed=1,
    )
    res = run_cross_track_study(tmp_path / "shape", cfg, processes=1, progress=False)
    for eps in cfg.eps:
        pts = [s for s in res.summary if s["eps"] == eps]
        errors = [p["mean_error"] for p in pts]
        rf = (1 + eps) ** 2
        at_rf = min(pts, key=lambda p: abs(p["r_plan"] - rf))["mean_error"]
        assert errors[0] > 4 * at_rf  # large gain up to R0'
        assert at_rf < 2.0 * min(errors) + 0.01  # R0' is already near the plateau
        assert abs(res.knees["steady"][eps] - rf) <= 0.5
