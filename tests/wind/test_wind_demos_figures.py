"""Chapter 3 demo cases and Fig 3.3 (closed-loop following with R0 and R0')."""


import pytest

from glideplan.demos import demo_cases, run_demo_case
from glideplan.figures.registry import get_figure, run_figure


def test_wind_demo_cases_match_their_references():
    cases = [c for c in demo_cases() if c.name.startswith("Wind")]
    assert len(cases) >= 4
    for case in cases:
        result = run_demo_case(case)
        assert result.solution.ok, case.name
        assert result.seconds < 5.0
        if case.reference_cost is not None:
            assert result.solution.cost == pytest.approx(case.reference_cost, abs=1e-5)
            assert result.solution.word == case.reference_word


def test_fig3_3_feasible_radius_is_followed_more_closely(tmp_path):
    from glideplan.figures.ch3_following import _follow_examples

    for data in _follow_examples().values():
        err = data["result"].error
        assert data["result"].crossed.all()
        assert err[1] < 0.6 * err[0]  # planned with R0' vs with R0
    report = run_figure(get_figure("fig3.3"), tmp_path)
    assert all((tmp_path / f).exists() for f in report.files)
    better = [r for r in report.rows if "followed more closely" in r.quantity]
    assert len(better) == 2 and all(r.ours == "yes" == r.dissertation for r in better)
