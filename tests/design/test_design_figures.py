"""Chapter 7 `reproduce` figures: each writes its PNG and compares with the dissertation."""

import pytest

from glideplan.figures import get_figure, load_all, run_figure

IDS = ["fig7.3", "fig7.4", "fig7.6", "fig7.7", "fig7.8", "fig7.17", "fig7.27"]


@pytest.fixture(scope="module")
def reports(tmp_path_factory):
    load_all()
    out = tmp_path_factory.mktemp("ch7")
    return out, {fid: run_figure(get_figure(fid), out) for fid in IDS}


@pytest.mark.parametrize("fid", IDS)
def test_figure_written_with_comparisons(reports, fid):
    out, reps = reports
    rep = reps[fid]
    assert rep.files and all((out / f).stat().st_size > 1000 for f in rep.files)
    assert rep.rows and all(r.ours and r.dissertation for r in rep.rows)


def test_fig7_3_reports_thirteen_dives_and_flags_31_mol(reports):
    rep = reports[1]["fig7.3"]
    # p_t V_t / (p_amb V) = 71,167.5 / 5,411.6 = 13.15 -> 13 full dives, as reported
    assert int(rep.data["dives_5L_100m"]) == 13
    row = next(r for r in rep.rows if "31.1" in r.dissertation)
    assert "275" in row.note  # 31.1 mol implies about 275 K


def test_fig7_17_top_speed_within_ten_percent(reports):
    assert abs(reports[1]["fig7.17"].data["top_speed_m_s"] - 1.75) < 0.175
