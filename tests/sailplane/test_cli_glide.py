"""`glideplan glide polar|ardusoar|final`: JSON keys, hand checks, files, one-line errors."""

import json
import math

import pytest

from glideplan.sailplane import polar_from_file, read_plr, straight_final_glide


def test_polar_json(run_cli, dg_file):
    code, out, err = run_cli("glide", "polar", str(dg_file), "--json")
    assert code == 0, err
    d = json.loads(out)
    p = polar_from_file(read_plr(dg_file))
    assert d["a"] == pytest.approx(p.a) and d["b"] == pytest.approx(p.b)
    assert d["c"] == pytest.approx(p.c)
    assert d["best_glide_ratio"] == pytest.approx(1 / (2 * math.sqrt(p.a * p.c) + p.b))
    assert d["best_glide_speed_kmh"] == pytest.approx(3.6 * math.sqrt(p.c / p.a))
    assert d["min_sink_ms"] == pytest.approx(p.c - p.b**2 / (4 * p.a))
    assert d["min_sink_speed_kmh"] == pytest.approx(-3.6 * p.b / (2 * p.a))
    assert d["reference_mass_kg"] == 614.0
    mcs = [row["mc"] for row in d["maccready"]]
    assert mcs == [0.5 * k for k in range(11)]
    assert {"mc", "speed_to_fly_kmh", "glide_ratio", "cross_country_kmh"} <= set(d["maccready"][3])
    # cross-country speed v MC / (w(v) + MC) at the speed to fly (hand formula)
    row = d["maccready"][4]
    v = row["speed_to_fly_kmh"] / 3.6
    w = p.a * v * v + p.b * v + p.c
    assert row["cross_country_kmh"] == pytest.approx(3.6 * v * 2.0 / (w + 2.0))
    assert row["glide_ratio"] == pytest.approx(v / w)
    # MC = 0 flies the best-glide speed; the speed to fly grows with MC
    assert d["maccready"][0]["speed_to_fly_kmh"] == pytest.approx(d["best_glide_speed_kmh"])
    speeds = [row["speed_to_fly_kmh"] for row in d["maccready"]]
    assert speeds == sorted(speeds)


def test_polar_mass_and_bugs(run_cli, fixtures_dir):
    f = str(fixtures_dir / "DG-1001M_tabs_cr.plr")
    _, out0, _ = run_cli("glide", "polar", f, "--json")
    code, out, err = run_cli("glide", "polar", f, "--ballast", "100", "--bugs", "10", "--json")
    assert code == 0, err
    d0, d = json.loads(out0), json.loads(out)
    assert d["mass_kg"] == 714.0
    assert d["best_glide_ratio"] == pytest.approx(0.9 * d0["best_glide_ratio"])
    k = math.sqrt(714.0 / 614.0)
    assert d["best_glide_speed_kmh"] == pytest.approx(k * d0["best_glide_speed_kmh"])


def test_ardusoar_writes_a_parm_file_pymavlink_reads(run_cli, dg_file, tmp_path):
    from pymavlink import mavparm

    out = tmp_path / "soar.parm"
    code, stdout, err = run_cli("glide", "ardusoar", str(dg_file), "--out", str(out), "--json")
    assert code == 0, err
    d = json.loads(stdout)
    parms = mavparm.MAVParmDict()
    parms.load(str(out))
    for name in ("SOAR_POLAR_CD0", "SOAR_POLAR_B", "SOAR_POLAR_K"):
        assert parms[name] == pytest.approx(d[name], rel=1e-7)
    assert 0 < d["max_sink_error_ms"] < 0.1


def test_final_straight_json_and_hand_check(run_cli, dg_file, tmp_path):
    """No wind, MC = 0: loss = D (2 sqrt(ac) + b), D the geodesic distance."""
    from glideplan.geodesy import geodesic_distance_bearing

    code, out, err = run_cli(
        "glide",
        "final",
        "--polar",
        str(dg_file),
        "--from",
        "47.0",
        "8.0",
        "1500",
        "--to",
        "47.15",
        "8.05",
        "420",
        "--json",
        "--plot",
        str(tmp_path / "g.png"),
        "--cup",
        str(tmp_path / "g.cup"),
        "--tsk",
        str(tmp_path / "g.tsk"),
    )
    assert code == 0, err
    d = json.loads(out)
    p = polar_from_file(read_plr(dg_file))
    dist = float(geodesic_distance_bearing(47.0, 8.0, 47.15, 8.05)[0])
    assert d["distance_m"] == pytest.approx(dist, rel=1e-9)
    loss = dist * (2 * math.sqrt(p.a * p.c) + p.b)
    assert d["altitude_loss_m"] == pytest.approx(loss, rel=1e-9)
    assert d["altitude_required_m"] == pytest.approx(420 + 300 + loss, rel=1e-9)
    assert d["arrival_margin_m"] == pytest.approx(1500 - 720 - loss, rel=1e-9)
    assert d["glide_ratio_required"] == pytest.approx(dist / (1500 - 720))
    assert d["status"] == ("solved" if 1500 - 720 - loss >= 0 else "below_glide")
    for key in ("speed_to_fly_kmh", "duration_s"):
        assert d[key] > 0
    assert (tmp_path / "g.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert (tmp_path / "g.cup").stat().st_size > 0 and (tmp_path / "g.tsk").stat().st_size > 0


def test_final_wind_from_the_goal_is_a_headwind(run_cli, dg_file):
    """A wind FROM the goal's bearing (compass) is a pure headwind: the JSON equals the
    library's straight glide with tailwind -W along the track."""
    args = [
        "glide",
        "final",
        "--polar",
        str(dg_file),
        "--from",
        "47.0",
        "8.0",
        "1200",
        "--to",
        "47.2",
        "8.0",
        "400",
        "--mc",
        "1",
        "--safety-height",
        "250",
        "--json",
    ]
    code, out, err = run_cli(*args, "--wind", "10", "0")  # from the north, goal due north
    assert code == 1, err  # below_glide is not solved: exit 1 like every other outcome
    d = json.loads(out)
    p = polar_from_file(read_plr(dg_file))
    g = straight_final_glide(p, d["distance_m"], math.pi / 2, wind=(0.0, -10.0), mc=1.0)
    assert d["headwind_ms"] == pytest.approx(10.0)
    assert d["altitude_loss_m"] == pytest.approx(float(g.altitude_loss), rel=1e-6)
    assert d["status"] == "below_glide" and d["arrival_margin_m"] < 0


def test_final_arrival_heading(run_cli, dg_file, tmp_path):
    code, out, err = run_cli(
        "glide",
        "final",
        "--polar",
        str(dg_file),
        "--from",
        "47.0",
        "8.0",
        "1500",
        "--to",
        "47.05",
        "8.02",
        "420",
        "--wind",
        "6",
        "250",
        "--arrival-heading",
        "200",
        "--json",
        "--plot",
        str(tmp_path / "a.png"),
    )
    assert code == 0, err
    d = json.loads(out)
    for key in (
        "status",
        "distance_m",
        "altitude_loss_m",
        "altitude_required_m",
        "arrival_margin_m",
        "glide_ratio_required",
        "speed_to_fly_kmh",
        "duration_s",
        "word",
        "track",
        "endpoint_error",
    ):
        assert key in d, key
    assert d["endpoint_error"]["position"] < 1e-3
    track = d["track"]
    assert len(track["lat"]) == len(track["lon"]) == len(track["alt"]) > 10
    assert track["lat"][0] == pytest.approx(47.0) and track["lat"][-1] == pytest.approx(47.05)
    assert track["lon"][-1] == pytest.approx(8.02)
    assert track["alt"][0] == pytest.approx(1500.0)
    assert track["alt"][-1] == pytest.approx(1500.0 - d["altitude_loss_m"], rel=1e-6)
    # turning to arrive on a heading costs at least the straight glide
    assert d["altitude_loss_m"] >= d["straight"]["altitude_loss_m"] - 1e-6
    assert (tmp_path / "a.png").stat().st_size > 1000


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["--from", "95", "8", "1500", "--to", "47", "8", "400"], "latitude"),
        (["--from", "47", "8", "nan", "--to", "47.1", "8", "400"], "altitude"),
        (["--from", "47", "8", "1500", "--to", "47.1", "8", "400", "--bugs", "80"], "bugs"),
        (["--from", "47", "8", "1500", "--to", "47.1", "8", "400", "--mc", "-1"], "--mc"),
        (
            ["--from", "47", "8", "1500", "--to", "47.1", "8", "400", "--start-heading", "10"],
            "--start-heading",
        ),
        (
            [
                "--from",
                "47",
                "8",
                "1500",
                "--to",
                "47.1",
                "8",
                "400",
                "--arrival-heading",
                "10",
                "--bank-max",
                "95",
            ],
            "--bank-max",
        ),
    ],
)
def test_final_bad_input_is_one_line(cli_error, dg_file, args, needle):
    line = cli_error("glide", "final", "--polar", str(dg_file), *args)
    assert needle in line


def test_malformed_polar_file_is_one_line_naming_file_and_line(cli_error, tmp_path):
    bad = tmp_path / "broken.plr"
    bad.write_text("* a comment\r\n350, 0, 90, -0.6, 120, oops, 150, -1.5\r\n")
    line = cli_error("glide", "polar", str(bad))
    assert "broken.plr" in line and "line 2" in line and "w2 must be a number" in line
    line = cli_error("glide", "ardusoar", str(tmp_path / "missing.plr"), "--out", "x.parm")
    assert "FILE=" in line and "missing.plr" in line and "no such file" in line


def test_ardusoar_needs_a_wing_area(cli_error, fixtures_dir, tmp_path):
    line = cli_error(
        "glide", "ardusoar", str(fixtures_dir / "Delta_LF.plr"), "--out", str(tmp_path / "p")
    )
    assert "--wing-area" in line


def test_wind_stronger_than_the_glider_is_unreachable(run_cli, dg_file):
    """A 45 m/s headwind beats the polar's top speed (150 km/h): no airspeed makes progress,
    so the goal is "unreachable" at any altitude (straight or with an arrival heading): exit 1
    (no path), the JSON still printed, one error line saying why."""
    base = ["glide", "final", "--polar", str(dg_file), "--from", "47.0", "8.0", "1500"]
    for extra in ([], ["--arrival-heading", "0"]):
        code, out, err = run_cli(
            *base, "--to", "47.3", "8.0", "420", "--wind", "45", "0", "--json", *extra
        )
        assert code == 1, err
        d = json.loads(out)
        assert d["status"] == "unreachable"
        assert d["altitude_loss_m"] is None and "wind" in d["message"]
        assert "headwind 45.0 m/s" in d["message"] and "150 km/h" in d["message"]
        assert err.strip() == f"glideplan: error: final glide: unreachable: {d['message']}"


def test_final_goal_beyond_one_local_plane_names_to(cli_error, dg_file):
    """A goal half the Earth away is refused under --to (was "extent='scale error ...': ...
    split the mission", a mission's words for a final glide)."""
    line = cli_error("glide", "final", "--polar", str(dg_file), "--from", "47", "8", "1500",
                     "--to", "-47", "-172", "400")
    assert "--to=" in line and "km from the start" in line and "mission" not in line
