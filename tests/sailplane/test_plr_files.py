"""Reading `.plr` polar files: the fixtures, malformed files, and the 156-file corpus."""

import math
import pathlib

import pytest

from glideplan.sailplane import PolarFileError, parse_plr, polar_from_file, read_plr

CORPUS = pathlib.Path(__file__).resolve().parents[3] / "shared" / "polars"
needs_corpus = pytest.mark.skipif(
    not CORPUS.is_dir(), reason="../shared/polars (the 156-file polar corpus) is not present"
)

# eq. (5.26) with v in km/h: w = 0.0002093 V^2 - 0.0381 V + 2.3146
DG_KMH = (0.0002093, -0.0381, 2.3146)


@pytest.mark.parametrize("name", ["DG-1001M_ch5.plr", "DG-1001M_tabs_cr.plr"])
def test_fixture_recovers_the_dissertation_polar(fixtures_dir, name):
    """Three points of eq. (5.26) fix it exactly: the fit returns its coefficients (SI here,
    so a = 3.6^2 a_kmh, b = 3.6 b_kmh). The second file has tabs, CR line endings, points out
    of order, a `//` comment and trailing fields."""
    pf = read_plr(fixtures_dir / name)
    p = polar_from_file(pf)
    assert p.a == pytest.approx(DG_KMH[0] * 3.6**2, rel=1e-9)
    assert p.b == pytest.approx(DG_KMH[1] * 3.6, rel=1e-9)
    assert p.c == pytest.approx(DG_KMH[2], rel=1e-9)
    assert pf.mass_kg == 614.0 and pf.wing_area_m2 == 17.53
    assert [v for v, _ in pf.points] == sorted(v for v, _ in pf.points)


def test_comment_best_ld_and_missing_wing_area(fixtures_dir):
    pf = read_plr(fixtures_dir / "DG-1001M_tabs_cr.plr")
    assert pf.best_ld == 47.0 and pf.max_ballast_l == 100.0
    delta = read_plr(fixtures_dir / "Delta_LF.plr")
    assert delta.wing_area_m2 is None and delta.points[0] == (30.0, -1.10)


@pytest.mark.parametrize(
    ("text", "line", "rule"),
    [
        ("* c\n300, 0, 90, -0.6, 120\n", 2, "at least 8"),
        ("* c\n300, 0, 90, -0.6, 120, x, 150, -1.5\n", 2, "w2 must be a number"),
        ("* c\n\n300, 0, 90, 0.6, 120, -0.8, 150, -1.5\n", 3, "sink rates must be negative"),
        ("300, 0, 90, -0.6, 90, -0.8, 150, -1.5\n", 1, "speeds must differ"),
        ("-300, 0, 90, -0.6, 120, -0.8, 150, -1.5\n", 1, "mass must be > 0"),
        ("300, 0, 90, -0.6, 120, -0.8, 150, -1.5, -3\n", 1, "wing area"),
        ("300, 0, 90, -0.6, 120, -0.8, 150, -1.5, nan\n", 1, "wing area must be finite"),
    ],
)
def test_malformed_line_is_named(text, line, rule):
    with pytest.raises(PolarFileError) as err:
        parse_plr(text, "bad.plr")
    msg = str(err.value)
    assert "bad.plr" in msg and f"line {line}" in msg and rule in msg


def test_file_without_data_line():
    with pytest.raises(PolarFileError, match=r"bad\.plr.*no data line"):
        parse_plr("* only\n* comments\n\n", "bad.plr")


@pytest.mark.parametrize(
    ("points", "rule"),
    [
        # concave: the middle point sinks more than the chord (a < 0)
        ("90, -0.6, 120, -1.4, 150, -1.5", "concave"),
        # sink falls across the range: minimum sink beyond v3
        ("90, -2.0, 120, -1.2, 150, -0.9", "not inside the speed range"),
    ],
)
def test_polar_breaking_the_assumptions_is_rejected(points, rule):
    pf = parse_plr(f"300, 0, {points}\n", "odd.plr")
    with pytest.raises(PolarFileError, match=rf"odd\.plr, line 1.*{rule}"):
        polar_from_file(pf)


@needs_corpus
def test_all_156_corpus_files_load():
    """Every real file (spacing, trailing fields, comments, line endings vary) loads and
    gives a convex polar with its minimum sink inside the speed range."""
    files = sorted(CORPUS.glob("*.plr"))
    assert len(files) == 156
    for f in files:
        p = polar_from_file(read_plr(f))
        assert p.a > 0 and p.v_min < p.v_ms < p.v_max and p.w_ms > 0, f.name


@needs_corpus
def test_best_glide_ratio_within_3_percent_of_the_stated_one():
    """The 9 files whose `//` comment states a best L/D (BestLD..): the three-point fit's
    best glide ratio 1 / (2 sqrt(ac) + b) agrees within 3 %."""
    stated = [(f, read_plr(f)) for f in sorted(CORPUS.glob("*.plr"))]
    stated = [(f, pf) for f, pf in stated if pf.best_ld is not None]
    assert len(stated) == 9
    for f, pf in stated:
        p = polar_from_file(pf)
        ld = 1.0 / (2.0 * math.sqrt(p.a * p.c) + p.b)
        assert ld == pytest.approx(p.best_glide_ratio, rel=1e-9)
        assert ld == pytest.approx(pf.best_ld, rel=0.03), f.name
