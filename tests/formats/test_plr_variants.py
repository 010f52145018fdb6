"""`.plr` polars written with decimal commas, and absurd polars refused (issue 19).

References: the decimal-comma lines are the same numbers as their '.'-decimal twins, so both
must give identical points (exact). The physical ranges are those stated in
`glideplan.sailplane.plr` (glide ratio 1..100, sink >= 0.2 m/s, speed <= 400 km/h, mass
<= 5,000 kg); the absurd cases are far outside them, built by hand (below).
"""

from __future__ import annotations

import pytest

from glideplan.sailplane import PolarFileError, parse_plr, polar_from_file

DOT = "325, 0, 80.0, -0.58, 100.0, -0.70, 150.0, -1.50, 10.5"


@pytest.mark.parametrize("line", [
    "325  0  80,0  -0,58  100,0  -0,70  150,0  -1,50  10,5",
    "325\t0\t80,0\t-0,58\t100,0\t-0,70\t150,0\t-1,50\t10,5",
    "325; 0; 80,0; -0,58; 100,0; -0,70; 150,0; -1,50; 10,5",
    "325, 0, 80,0, -0,58, 100,0, -0,70, 150,0, -1,50, 10,5",  # ', ' separates, ',' decimals
])
def test_decimal_commas_read_as_the_dot_file(line):
    pf = parse_plr(f"* polar for: Test\n{line}  // BestLD40\n", "comma.plr")
    ref = parse_plr(DOT, "dot.plr")
    assert pf.decimal_comma and not ref.decimal_comma
    assert pf.points == ref.points and pf.wing_area_m2 == ref.wing_area_m2 == 10.5
    assert pf.mass_kg == 325.0 and pf.best_ld == 40.0
    assert polar_from_file(pf).a == polar_from_file(ref).a


def test_comma_separated_integers_are_not_decimal_commas():
    """`300,0,90,-1,...` (no spaces, no '.') is the ordinary comma-separated format."""
    pf = parse_plr("300,0,80,-1,100,-1,150,-2\n", "int.plr")
    assert not pf.decimal_comma and pf.points[0] == (80.0, -1.0)


def test_ambiguous_decimal_commas_say_so():
    """Commas everywhere and decimal commas inside: the message names decimal commas and the
    fix, not only the rule the misreading broke."""
    with pytest.raises(PolarFileError) as err:
        parse_plr("325,0,80,0,-0,58,100,0,-0,70,150,0,-1,50\n", "amb.plr")
    msg = str(err.value)
    assert "amb.plr, line 1" in msg and "decimal commas?" in msg and "separate the fields" in msg


@pytest.mark.parametrize(("line", "rule"), [
    # 80 km/h = 22.2 m/s at 0.001 m/s sink: L/D 22,222 (the polar) -> sink too small
    ("300, 0, 80, -0.001, 100, -0.7, 150, -1.5", "too small"),
    # w(v) = 0.012 (v - 25)^2 + 0.001 m/s (v in m/s) through 72, 108, 144 km/h: every point
    # sinks >= 0.3 m/s, but the fitted polar's best glide is ~25 / 0.001 = 25,000 > 100
    ("300, 0, 72, -0.301, 108, -0.301, 144, -2.701", "glide ratio reaches"),
    ("300, 0, 80, -30, 100, -40, 150, -60", "glide ratio falls"),  # L/D 0.74 < 1
    ("300, 0, 80, -0.6, 100, -0.7, 1500, -15", "must be <= 400 km/h"),
    ("1e300, 0, 80, -0.6, 100, -0.7, 150, -1.5", "mass must be <= 5000"),
])
def test_absurd_polars_refused(line, rule):
    with pytest.raises(PolarFileError) as err:
        parse_plr(f"* c\n{line}\n", "absurd.plr")
    msg = str(err.value)
    assert "absurd.plr, line 2" in msg and rule in msg


def test_cli_reads_a_decimal_comma_polar_and_refuses_an_absurd_one(tmp_path, run_cli,
                                                                   cli_error):
    good = tmp_path / "comma.plr"
    good.write_text("* decimal commas\r\n325  0  80,0  -0,58  100,0  -0,70  150,0  -1,50\r\n",
                    encoding="latin-1")
    code, out, err = run_cli("glide", "polar", str(good))
    assert code == 0, err
    dot = tmp_path / "comma_dot.plr"  # the same numbers with '.' decimals: the same report
    dot.write_text("325, 0, 80.0, -0.58, 100.0, -0.70, 150.0, -1.50\n")
    code, out_dot, err = run_cli("glide", "polar", str(dot))
    assert code == 0, err
    assert out.replace("comma:", "comma_dot:", 1) == out_dot
    bad = tmp_path / "absurd.plr"
    bad.write_text("300, 0, 80, -0.001, 100, -0.7, 150, -1.5\n")
    line = cli_error("glide", "polar", str(bad))
    assert "absurd.plr" in line and "line 1" in line and "too small" in line
