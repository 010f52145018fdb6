""".cup files as pilots have them: Windows-1252 (SeeYou), UTF-8 with a BOM, empty elevations,
and a minute field >= 60 refused (library and CLI)."""

import codecs

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.reach.landables import read_cup

# names with umlauts, accents and an en dash (Windows-1252 0x96, not in Latin-1)
NAMES = ["Zürich Süd", "Bözberg", "Saint-Étienne", "Grenchen – Ost"]


def _write_aerofiles(path, encoding, elevations=(430.0, 560.0, 400.0, 433.0)):
    """The fields written by aerofiles' SeeYou writer in `encoding` (as SeeYou writes them)."""
    from aerofiles.seeyou import Writer

    bom = encoding == "utf-8-sig"  # (aerofiles' writer would put a BOM on every line)
    with open(path, "wb") as fp:
        if bom:
            fp.write(codecs.BOM_UTF8)
        w = Writer(fp, encoding="utf-8" if bom else encoding)
        for k, (name, elev) in enumerate(zip(NAMES, elevations, strict=True)):
            w.write_waypoint(name, f"F{k}", "CH", 47.1 + 0.01 * k, 8.2 + 0.02 * k, elev,
                             style=3 if k else 4)
    return path


@pytest.mark.parametrize("encoding,expect", [("cp1252", "cp1252"),
                                             ("utf-8-sig", "utf-8 with BOM"),
                                             ("utf-8", "utf-8")])
def test_cup_encodings_read_back_with_the_right_names(tmp_path, encoding, expect):
    """aerofiles reads the file back in its encoding with the names (the independent reader);
    glideplan detects the encoding and gives the same names, positions and elevations."""
    from aerofiles.seeyou import Reader

    p = _write_aerofiles(tmp_path / "fields.cup", encoding)
    if encoding == "cp1252":
        with pytest.raises(UnicodeDecodeError):
            p.read_bytes().decode("utf-8")  # what a UTF-8-only reader met before
    with open(p, encoding=encoding, newline="") as fp:
        ref = Reader().read(fp)["waypoints"]
    assert [w["name"] for w in ref] == NAMES
    got = read_cup(p)
    assert got.encoding == expect
    assert [f.name for f in got.landables] == NAMES
    for f, w in zip(got.landables, ref, strict=True):
        assert (f.lat, f.lon, f.elevation_m) == (w["latitude"], w["longitude"],
                                                w["elevation"]["value"])


def test_latin1_only_bytes_are_read_as_latin1(tmp_path):
    """0x81 is undefined in Windows-1252: such a file is read as Latin-1 (U+0081)."""
    p = tmp_path / "odd.cup"
    p.write_bytes("name,code,country,lat,lon,elev,style,rwdir,rwlen,freq,desc\r\n"
                  "\"Aé\x81\",A,,4706.000N,00812.000E,430m,3,,,,\r\n".encode("latin-1"))
    got = read_cup(p)
    assert got.encoding == "latin-1" and got.landables[0].name == "Aé\x81"


def _cup(path, *lines):
    header = "name,code,country,lat,lon,elev,style,rwdir,rwlen,freq,desc"
    path.write_text("\r\n".join([header, *lines]) + "\r\n", encoding="utf-8")
    return path


def test_an_empty_elevation_takes_the_terrains(tmp_path):
    """A landable with an empty elev field gets the terrain's bilinear elevation at its
    position, with a note naming the file, line and field; one outside the terrain is skipped
    with a note; without terrain it is refused."""
    from glideplan.terrain import Terrain

    lat = 47.0 + 0.2 * np.arange(21) / 20
    lon = 8.0 + 0.4 * np.arange(21) / 20
    z = 400.0 + 1000.0 * (lat[:, None] - 47.0) + 0.0 * lon[None, :]  # bilinear is exact
    terrain = Terrain(lat, lon, z)
    p = _cup(tmp_path / "f.cup",
             '"Feld A",FA,CH,4706.000N,00812.000E,,3,,,,',
             '"Feld B",FB,CH,4706.000N,00812.000E,1500ft,3,,,,',
             '"Far away",FF,CH,4806.000N,00812.000E,,3,,,,')
    got = read_cup(p, terrain)
    a, b = got.landables
    assert a.elevation_m == pytest.approx(400.0 + 1000.0 * 0.1, abs=1e-6)  # 47 deg 06'
    assert b.elevation_m == pytest.approx(1500 * 0.3048)
    assert f"{p} line 2 (Feld A): no elevation in the file; the terrain's 500 m" in got.notes[0]
    assert f"{p} line 4 (Far away)" in got.notes[1] and "skipped" in got.notes[1]
    with pytest.raises(InvalidParameterError) as e:
        read_cup(p)
    assert f"{p} line 2 (Feld A) elevation" in str(e.value)


@pytest.mark.parametrize("lat,lon,what,minutes", [
    ("4675.000N", "00812.000E", "latitude", "75.000"),
    ("4706.000N", "00860.000E", "longitude", "60.000")])
def test_a_minute_field_of_60_or_more_is_refused(tmp_path, lat, lon, what, minutes):
    p = _cup(tmp_path / "f.cup", '"Ok",OK,CH,4706.000N,00812.000E,430m,3,,,,',
             f'"Bad",BD,CH,{lat},{lon},430m,3,,,,')
    with pytest.raises(InvalidParameterError) as e:
        read_cup(p)
    msg = str(e.value)
    assert f"{p} line 3 {what}" in msg and f"minute field {minutes} must be below 60" in msg


def test_cli_refuses_minutes_over_60_in_one_line(cli_error, polar_file, tmp_path):
    """Exit 2, one line naming --landables, the file, the line and the rule."""
    from glideplan.terrain.geotiff import write_geotiff

    n = 41
    lat = 47.0 + 0.2 * np.arange(n) / (n - 1)
    lon = 8.0 + 0.3 * np.arange(n) / (n - 1)
    tif = write_geotiff(tmp_path / "dem.tif", lat, lon, np.full((n, n), 400.0))
    cup = _cup(tmp_path / "f.cup", '"Bad",BD,CH,4675.000N,00812.000E,430m,3,,,,')
    line = cli_error("glide", "reach", "--polar", str(polar_file), "--from", "47.1", "8.15",
                     "900", "--terrain", str(tif), "--landables", str(cup))
    assert line.startswith(f"glideplan: error: --landables {cup} line 2 latitude")
    assert "must be below 60" in line


def test_cli_empty_elevation_from_terrain_with_a_warning(run_cli, polar_file, tmp_path):
    """End to end: the table lists the field, stderr says its elevation came from the terrain."""
    import json

    from glideplan.terrain.geotiff import write_geotiff

    n = 41
    lat = 47.0 + 0.2 * np.arange(n) / (n - 1)
    lon = 8.0 + 0.3 * np.arange(n) / (n - 1)
    tif = write_geotiff(tmp_path / "dem.tif", lat, lon, np.full((n, n), 400.0))
    cup = tmp_path / "f.cup"
    cup.write_bytes(codecs.BOM_UTF8 + _cup(tmp_path / "x.cup",
                                           '"Wiese Müller",WM,CH,4706.000N,00812.000E,,3,,,,'
                                           ).read_bytes())
    code, out, err = run_cli("glide", "reach", "--polar", str(polar_file), "--from", "47.1",
                             "8.15", "900", "--terrain", str(tif), "--landables", str(cup),
                             "--json")
    assert code == 0, err
    assert "Wiese Müller): no elevation in the file; the terrain's 400 m is used" in err
    data = json.loads(out)
    pt = data["points"][0]
    assert pt["name"] == "Wiese Müller" and pt["elevation_m"] == pytest.approx(400.0)
    assert any("Wiese Müller): no elevation in the file" in w for w in data["warnings"])
