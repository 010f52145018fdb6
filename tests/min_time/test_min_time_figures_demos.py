"""Chapter 4 reproductions, demo cases and the goal grid."""

import math

import numpy as np
import pytest

from glideplan import VariableSpeedCar
from glideplan.demos import demo_cases, run_demo_case
from glideplan.figures import get_figure, load_all, run_figure
from glideplan.planners.min_time.grid import best_time, time_optimal_grid


@pytest.mark.parametrize("fid", ["fig4.1", "fig4.2", "fig4.7", "fig4.8"])
def test_quick_figures(tmp_path, fid):
    load_all()
    report = run_figure(get_figure(fid), tmp_path)
    assert report.files
    for f in report.files:
        assert (tmp_path / f).read_bytes()[:4] == b"\x89PNG"
    if fid == "fig4.2":
        assert [r.ours for r in report.rows] == ["S", "B", "C", "C"]
    if fid == "fig4.8":
        assert report.rows[-1].ours == 0  # no CCC path to this goal


@pytest.mark.heavy  # 9 s: the whole table 4.3 reproduction; make validate runs it
def test_table_4_3_report(tmp_path):
    load_all()
    report = run_figure(get_figure("table4.3"), tmp_path)
    rows = {r.quantity: r for r in report.rows}
    assert rows["CBSB LSR: time"].ours == pytest.approx(2.8747, abs=1e-4)
    assert rows["BSB LSR: time (ours: BSB LSL)"].ours == pytest.approx(9.3776, abs=1e-4)
    for name, weak in (("CBSB LSL", 2.8829), ("BCBB LR", 2.8873), ("BTB RLR", 3.2185),
                       ("CBSBC LSL", 3.1761), ("CBSBCB RSR", 11.3595)):  # fmt: skip
        row = rows[f"{name}: minimum of (4.27) in the dissertation's parameterisation"]
        assert row.ours == pytest.approx(weak, abs=1e-4) and row.verdict == "agrees"
        assert "descends to" in rows[f"{name}: a local optimum of the control problem"].note
    assert "descends to 2.874650" in rows["CBSB LSL: a local optimum of the control problem"].note
    assert rows["Dubins at v_max / optimal time"].ours == pytest.approx(2.08, abs=0.01)
    assert (tmp_path / "table4_3.md").read_text().count("\n") >= 15


def test_grid_matches_single_goal_synthesis():
    car = VariableSpeedCar(0.3, 1.0, 1.0)
    xs = np.array([-1.5, 0.0, 1.5])
    grid = time_optimal_grid(car, xs, xs, math.pi, processes=1)
    assert grid.time.shape == (3, 3)
    for i, y in enumerate(xs):
        for j, x in enumerate(xs):
            t, fam, _word = best_time(car, x, y, math.pi)
            assert grid.time[i, j] == pytest.approx(t) and grid.family[i, j] == fam
    assert np.all(grid.ratio[np.isfinite(grid.ratio)] >= 1 - 1e-12)
    assert np.allclose(grid.time, grid.time[::-1, :])  # psi1 = pi: mirror symmetric
    assert best_time(car, 0.0, 0.0, 0.0) == (0.0, "", "")


def test_chapter_4_demo_cases():
    cases = [c for c in demo_cases() if c.name.startswith("Min-time")]
    assert len(cases) == 5
    for case in cases:
        result = run_demo_case(case)
        assert result.solution.ok, case.name
        assert result.solution.cost == pytest.approx(case.reference_cost, abs=5e-4), case.name
        assert result.solution.word == case.reference_word, case.name
        # Speed is measured in benchmarks/min_time.py, not here: a loaded machine must not
        # fail a correctness test.
        assert result.solution.endpoint_error is not None
        assert result.solution.endpoint_error.max <= 1e-6, case.name
