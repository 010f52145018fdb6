"""`glideplan glide reach|turnback` end to end: files in, JSON and files out, one-line errors."""

import json

import numpy as np
import pytest

from glideplan.reach import Landable
from glideplan.reach.landables import write_cup_landables
from glideplan.terrain.geotiff import write_geotiff


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("reach_cli")
    n = 81
    lat = 46.0 + 0.3 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.4 * np.arange(n) / (n - 1)
    z = np.full((n, n), 400.0)
    tif = write_geotiff(d / "dem.tif", lat, lon, z)
    cup = write_cup_landables(d / "fields.cup", [Landable("Near", 46.16, 7.2, 400.0, 4),
                                                 Landable("Far", 46.28, 7.38, 400.0, 3)])
    return d, tif, cup


def test_reach_json_and_files(run_cli, files, polar_file):
    d, tif, cup = files
    code, out, err = run_cli(
        "glide", "reach", "--polar", str(polar_file), "--from", "46.15", "7.2", "900",
        "--terrain", str(tif), "--landables", str(cup), "--wind", "5", "270", "--json",
        "--geojson", str(d / "r.geojson"), "--kml", str(d / "r.kml"), "--plot",
        str(d / "r.png"))
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved"
    near, far = data["points"]
    assert near["name"] == "Near" and near["reachable"] is True
    assert near["arrival_altitude_m"] > 400 + 300
    assert far["reachable"] is False
    assert data["glide"]["wind_ms"] == pytest.approx([5.0, 0.0], abs=1e-12)  # from the west
    for f in ("r.geojson", "r.kml", "r.png"):
        assert (d / f).stat().st_size > 0
    assert json.loads((d / "r.geojson").read_text())["type"] == "FeatureCollection"


def test_reach_table(run_cli, files, polar_file):
    _, tif, cup = files
    code, out, _ = run_cli("glide", "reach", "--polar", str(polar_file), "--from", "46.15",
                           "7.2", "900", "--terrain", str(tif), "--landables", str(cup))
    assert code == 0
    assert "Near" in out and "1 of 2 landable(s) reachable" in out


@pytest.mark.parametrize("args,flag", [
    (["--terrain", "missing.hgt"], "--terrain"),
    (["--mc", "-1"], "--mc"),
    (["--safety-height", "-5"], "--safety-height"),
    (["--resolution", "0"], "--resolution"),
])
def test_reach_bad_input_one_line(cli_error, files, polar_file, args, flag):
    _, tif, _ = files
    base = ["glide", "reach", "--polar", str(polar_file), "--from", "46.15", "7.2", "900"]
    if "--terrain" not in args:
        base += ["--terrain", str(tif)]
    line = cli_error(*base, *args)
    assert flag in line


def test_reach_start_outside_terrain(cli_error, files, polar_file):
    _, tif, _ = files
    line = cli_error("glide", "reach", "--polar", str(polar_file), "--from", "48", "7.2",
                     "900", "--terrain", str(tif))
    assert "--from" in line and "outside the terrain" in line


def test_reach_foreign_terrain_file(cli_error, files, polar_file, tmp_path):
    bad = tmp_path / "N46E007.hgt"
    bad.write_text("not a tile")
    line = cli_error("glide", "reach", "--polar", str(polar_file), "--from", "46.5", "7.2",
                     "900", "--terrain", str(bad))
    assert "--terrain" in line and "1201x1201" in line


def test_turnback_json(run_cli, polar_file):
    code, out, err = run_cli("glide", "turnback", "--polar", str(polar_file), "--from", "46.2",
                             "7.2", "1500", "--course", "90", "--home", "46.2", "7.2", "200",
                             "--json")
    assert code == 0, err
    data = json.loads(out)
    assert data["status"] == "solved" and data["turnback"]["distance_m"] > 10000


def test_turnback_unreachable_exit_1(cli_error, polar_file):
    line = cli_error("glide", "turnback", "--polar", str(polar_file), "--from", "46.2", "7.2",
                     "600", "--course", "90", "--home", "46.6", "7.2", "200", code=1)
    assert "unreachable" in line


@pytest.mark.parametrize("home,fragment", [
    (("46.2", "7.2", "nan"), "--home elevation=nan: must be finite"),
    (("nan", "7.2", "200"), "--home"),
])
def test_turnback_bad_home_names_the_flag(cli_error, polar_file, home, fragment):
    """A bad --home value is reported under --home (was "landable 'HOME' elevation=nan")."""
    line = cli_error("glide", "turnback", "--polar", str(polar_file), "--from", "46.2", "7.2",
                     "1500", "--course", "90", "--home", *home)
    assert fragment in line and "HOME" not in line


def test_reach_hgt_voids_refused_then_filled(run_cli, cli_error, polar_file, tmp_path):
    """An SRTM3 tile with a void: refused naming --terrain; --fill-voids fills it and warns."""
    from glideplan.terrain import write_hgt

    z = np.full((1201, 1201), 500.0)
    z[700:705, 600:610] = np.nan
    tile = write_hgt(tmp_path / "N46E007.hgt", z)
    base = ["glide", "reach", "--polar", str(polar_file), "--from", "46.5", "7.5", "900",
            "--terrain", str(tile)]
    line = cli_error(*base)
    assert "--terrain" in line and "voids" in line
    code, out, err = run_cli(*base, "--fill-voids", "nearest", "--json")
    assert code == 0, err
    assert "filled 50 void sample(s)" in err
    assert json.loads(out)["status"] == "solved"


def test_turnback_two_heights(run_cli, polar, polar_file):
    """`glide turnback --terrain-clearance --arrival-height`: still air, flat ground (no
    terrain), d = (ALT - ELEV - arrival height) E / 2 (closed form); --safety-height alone
    sets both (the same answer as the two given equal); defaults 150 / 300."""
    base = ["glide", "turnback", "--polar", str(polar_file), "--from", "46.2", "7.2", "1500",
            "--course", "90", "--home", "46.2", "7.2", "200", "--json"]
    E = polar.best_glide_ratio

    def run(*args):
        code, out, err = run_cli(*base, *args)
        assert code == 0, err
        return json.loads(out)

    d = run("--terrain-clearance", "100", "--arrival-height", "250")
    assert (d["terrain_clearance_m"], d["arrival_height_m"]) == (100, 250)
    assert d["turnback"]["distance_m"] == pytest.approx((1500 - 200 - 250) * E / 2, abs=1.0)
    d = run()
    assert (d["terrain_clearance_m"], d["arrival_height_m"]) == (150, 300)
    one = run("--safety-height", "250")
    assert (one["terrain_clearance_m"], one["arrival_height_m"]) == (250, 250)
    both = run("--terrain-clearance", "250", "--arrival-height", "250")
    assert one["turnback"]["distance_m"] == both["turnback"]["distance_m"]


@pytest.mark.parametrize("flag", ["--terrain-clearance", "--arrival-height", "--safety-height"])
def test_turnback_heights_range_checked(cli_error, polar_file, flag):
    line = cli_error("glide", "turnback", "--polar", str(polar_file), "--from", "46.2", "7.2",
                     "1500", "--course", "90", "--home", "46.2", "7.2", "200", flag, "-5")
    assert flag in line


@pytest.mark.parametrize("command", ["reach", "turnback"])
def test_safety_height_help_tells_the_defaults(run_cli, command):
    """--help of --safety-height: it sets both heights; without it the clearance is 150 m
    (the JSON's terrain_clearance_m); it said "Default 300" for a height kept all along."""
    code, out, _ = run_cli("glide", command, "--help")
    assert code == 0
    row = out.split("│ --safety-height", 1)[1].split("│ --terrain-clearance", 1)[0]
    text = " ".join(row.replace("│", " ").split())
    assert "Sets both" in text and "150 and 300" in text and "Default 300" not in text


def test_terrain_folder_or_pattern_named_once(cli_error, files, polar_file, tmp_path):
    """An empty folder or a pattern matching nothing: `--terrain='X': ...` (it read
    `--terrain X='X': ...`, the path twice)."""
    _, _, cup = files
    empty = tmp_path / "empty"
    empty.mkdir()
    for terrain, rule in ((str(empty), "the folder holds no terrain file"),
                          (str(tmp_path / "N9*.hgt"), "the pattern matches no file")):
        line = cli_error("glide", "reach", "--polar", str(polar_file), "--from", "46.15",
                         "7.2", "900", "--terrain", terrain, "--landables", str(cup))
        assert line.startswith(f"glideplan: error: --terrain='{terrain}': {rule}")
