"""Terrain as people keep it: zipped and gzipped .hgt, folders, globs, projected GeoTIFFs;
clear errors for files that are not terrain."""

import gzip
import math
import zipfile

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.terrain import read_hgt, read_terrain, write_hgt
from glideplan.terrain.grid import EARTH_RADIUS_M

N3 = 1201


def _tile_z(lat0: int, lon0: int) -> np.ndarray:
    """A smooth relief over one SRTM3 tile, continuous across tiles (a function of lat, lon)."""
    lat = lat0 + np.arange(N3) / (N3 - 1)
    lon = lon0 + np.arange(N3) / (N3 - 1)
    return np.round(900 + 500 * np.sin(7 * lat[:, None]) * np.cos(11 * lon[None, :]))


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    """Two adjacent SRTM3 tiles, N46E007 and N46E008, as plain .hgt files."""
    d = tmp_path_factory.mktemp("plain")
    return [write_hgt(d / f"N46E00{k}.hgt", _tile_z(46, k)) for k in (7, 8)]


def test_zip_and_gz_tiles_read_as_the_plain_tile(plain, tmp_path):
    """An SRTM download's zip (N46E007.SRTMGL3.hgt.zip holding N46E007.hgt) and a gzipped
    tile (N46E007.hgt.gz) give the plain tile's nodes and samples exactly."""
    ref = read_hgt(plain[0])
    zp = tmp_path / "N46E007.SRTMGL3.hgt.zip"
    with zipfile.ZipFile(zp, "w", zipfile.ZIP_DEFLATED) as zf:
        zf.write(plain[0], "N46E007.hgt")
    gz = tmp_path / "N46E007.hgt.gz"
    gz.write_bytes(gzip.compress(plain[0].read_bytes(), compresslevel=1))
    for t in (read_terrain([zp]), read_terrain([gz]), read_hgt(zp)):
        np.testing.assert_array_equal(t.lat, ref.lat)
        np.testing.assert_array_equal(t.lon, ref.lon)
        np.testing.assert_array_equal(t.z, ref.z)


def test_a_zip_of_a_folder_of_tiles_and_a_folder_merge_like_the_files(plain, tmp_path):
    """A viewfinderpanoramas-like zip (M32/N46E007.hgt, M32/N46E008.hgt), the tiles' folder and
    a glob pattern each merge to the same 1201 x 2401 grid as the two files given one by one."""
    ref = read_terrain(plain)
    assert ref.shape == (N3, 2 * N3 - 1)
    zp = tmp_path / "M32.zip"
    with zipfile.ZipFile(zp, "w", zipfile.ZIP_STORED) as zf:
        for f in plain:
            zf.write(f, f"M32/{f.name}")
        zf.writestr("M32/readme.txt", "not a tile")
    folder = plain[0].parent
    (folder / "notes.txt").write_text("ignored: not a terrain file")
    for t in (read_terrain([zp]), read_terrain([folder]),
              read_terrain([str(folder / "N46E00*.hgt")]),
              read_terrain([folder, plain[1]])):  # a file named twice is read once
        assert t.shape == ref.shape
        np.testing.assert_array_equal(t.z, ref.z)
        assert len(t.sources) == 2


@pytest.mark.parametrize("kind", ["empty folder", "no tile in zip", "bad name", "foreign",
                                  "not gzip", "glob matches nothing", "not a zip"])
def test_clear_errors_name_the_file(kind, tmp_path):
    """Each refusal names the file (or folder) and what is wrong with it."""
    p = tmp_path / "x"
    expect = ""
    if kind == "empty folder":
        p.mkdir()
        (p / "readme.txt").write_text("no tiles here")
        expect = "holds no terrain file"
    elif kind == "no tile in zip":
        p = tmp_path / "tiles.zip"
        with zipfile.ZipFile(p, "w") as zf:
            zf.writestr("readme.txt", "x")
        expect = "holds no SRTM .hgt tile (it holds readme.txt)"
    elif kind == "bad name":
        p = tmp_path / "tile_46_7.hgt"
        p.write_bytes(b"\0" * 2 * N3 * N3)
        expect = "named by its south-west corner"
    elif kind == "foreign":
        p = tmp_path / "dem.xyz"
        p.write_text("1 2 3")
        expect = "terrain files are SRTM .hgt"
    elif kind == "not gzip":
        p = tmp_path / "N46E007.hgt.gz"
        p.write_bytes(b"plain text")
        expect = "not a gzip file"
    elif kind == "glob matches nothing":
        p = tmp_path / "S9*.hgt"
        expect = "matches no file"
    elif kind == "not a zip":
        p = tmp_path / "N46E007.hgt.zip"
        p.write_bytes(b"not a zip")
        expect = "not a zip archive"
    with pytest.raises(InvalidParameterError) as e:
        read_terrain([p])
    assert str(p) in str(e.value) and expect in str(e.value), str(e.value)


def test_zip_member_of_wrong_size_is_named_not_inflated(tmp_path):
    p = tmp_path / "N46E007.hgt.zip"
    with zipfile.ZipFile(p, "w") as zf:
        zf.writestr("N46E007.hgt", b"\0" * 1000)
    with pytest.raises(InvalidParameterError) as e:
        read_terrain([p])
    assert f"{p} member N46E007.hgt" in str(e.value) and "1201x1201" in str(e.value)


# ----- a projected (UTM) GeoTIFF --------------------------------------------------------------
LAT0, LON0 = 46.5, 10.4  # UTM zone 32N (central meridian 9 E): the grid is rotated ~1 deg
AMP, WAVE = 300.0, 3000.0  # relief amplitude (m), wavelength (m)
H = 30.0  # UTM pixel (m)


def _relief(lat, lon):
    """The reference terrain, defined in lat/lon: z = 800 + A (sin k y + sin k x) with x, y the
    local east/north metres from (LAT0, LON0), k = 2 pi / wavelength."""
    k = 2 * math.pi / WAVE
    y = EARTH_RADIUS_M * np.radians(np.asarray(lat) - LAT0)
    x = EARTH_RADIUS_M * math.cos(math.radians(LAT0)) * np.radians(np.asarray(lon) - LON0)
    return 800 + AMP * (np.sin(k * y) + np.sin(k * x))


def _write_utm(path, n=200, nodata_block=False):
    """The reference sampled at the pixel centres of an n x n, 30 m UTM 32N (EPSG:32632) grid
    centred on (LAT0, LON0)."""
    import rasterio
    from affine import Affine
    from pyproj import Transformer

    to_utm = Transformer.from_crs("EPSG:4326", "EPSG:32632", always_xy=True)
    e0, n0 = to_utm.transform(LON0, LAT0)
    west, north = round(e0 - n * H / 2), round(n0 + n * H / 2)
    cols, rows = np.meshgrid(np.arange(n) + 0.5, np.arange(n) + 0.5)
    lon, lat = Transformer.from_crs("EPSG:32632", "EPSG:4326", always_xy=True).transform(
        west + H * cols, north - H * rows)
    z = _relief(lat, lon).astype(np.float32)
    if nodata_block:
        z[50:54, 60:70] = -9999.0
    with rasterio.open(path, "w", driver="GTiff", height=n, width=n, count=1, dtype="float32",
                       crs="EPSG:32632", transform=Affine(H, 0, west, 0, -H, north),
                       nodata=-9999.0) as ds:
        ds.write(z, 1)
    return path


def test_utm_geotiff_reprojected_within_the_bilinear_bound(tmp_path):
    """A UTM 32N GeoTIFF sampled from a lat/lon reference reads back (rasterio.warp, bilinear)
    onto lat/lon nodes within the bilinear interpolation bound of its 30 m grid.

    Bilinear interpolation on an h_x x h_y cell errs by at most (h_x^2 + h_y^2)/8 max|f_ss|
    (f_ss: second derivative along a grid axis). For f = A (sin k x + sin k y), along any
    unit direction u, f_uu = -A k^2 (u_x^2 sin k x + u_y^2 sin k y), so |f_uu| <= A k^2; the
    UTM metre differs from the local metre by < 1 % here (scale 0.9996, cos(lat) over 6 km),
    which the factor 1.02 covers (on k^2). Float32 storage adds < 1e-3 m."""
    t = read_terrain([_write_utm(tmp_path / "utm.tif")])
    assert any("reprojected from EPSG:32632" in w for w in t.warnings)
    k = 2 * math.pi / WAVE
    bound = (2 * H**2) / 8 * AMP * k**2 * 1.02 + 1e-3
    lat, lon = np.meshgrid(t.lat, t.lon, indexing="ij")
    ok = np.isfinite(t.z)
    err = np.abs(t.z[ok] - _relief(lat[ok], lon[ok]))
    assert err.max() <= bound, (err.max(), bound)
    assert err.max() > 0.02 * bound  # the comparison sees the interpolation, not nothing
    # the source's ground spacing is kept: 30 m north and east (to the rounding to a whole
    # number of samples per degree)
    east_m, north_m = t.spacing_m
    assert east_m == pytest.approx(H, rel=2e-3) and north_m == pytest.approx(H, rel=2e-3)
    # the 6 km square (rotated ~1 deg) covers most of its lat/lon bounding box; nodes outside
    # it are NaN (outside the terrain), never extrapolated
    assert 0.9 < ok.mean() < 1.0
    assert not np.isfinite(t.elevation(LAT0 + 0.06, LON0)).any()


def test_utm_geotiff_voids_refused_or_filled_in_its_own_grid(tmp_path):
    p = _write_utm(tmp_path / "utm.tif", n=120, nodata_block=True)
    with pytest.raises(InvalidParameterError) as e:
        read_terrain([p])
    assert str(p) in str(e.value) and "40 void(s)" in str(e.value)
    t = read_terrain([p], voids="linear")
    assert any("filled 40 void sample(s)" in w for w in t.warnings)
    assert np.isfinite(t.z).mean() > 0.8


def test_a_tiff_without_georeferencing_is_refused(tmp_path):
    import rasterio
    from rasterio.errors import NotGeoreferencedWarning

    p = tmp_path / "photo.tif"
    with pytest.warns(NotGeoreferencedWarning), rasterio.open(
            p, "w", driver="GTiff", height=4, width=4, count=1, dtype="uint8") as ds:
        ds.write(np.zeros((4, 4), np.uint8), 1)
    with pytest.raises(InvalidParameterError) as e:
        read_terrain([p])
    assert str(p) in str(e.value) and "coordinate reference system" in str(e.value)


# ----- from the command line ------------------------------------------------------------------
def test_cli_terrain_folder_end_to_end(run_cli, polar_file, tmp_path):
    """--terrain FOLDER (a GeoTIFF and a stray text file in it): read and solved."""
    import json

    from glideplan.terrain.geotiff import write_geotiff

    n = 41
    lat = 46.0 + 0.2 * np.arange(n) / (n - 1)
    lon = 7.0 + 0.3 * np.arange(n) / (n - 1)
    d = tmp_path / "dem"
    d.mkdir()
    write_geotiff(d / "dem.tif", lat, lon, np.full((n, n), 400.0))
    (d / "readme.txt").write_text("source: synthetic")
    base = ("glide", "reach", "--polar", str(polar_file), "--from", "46.1", "7.15", "700",
            "--json")
    code, out, err = run_cli(*base, "--terrain", str(d))
    assert code == 0, err
    a = json.loads(out)
    assert a["status"] == "solved" and a["start"]["ground_m"] == pytest.approx(400.0)


@pytest.mark.parametrize("kind", ["empty", "bad name"])
def test_cli_terrain_folder_errors_in_one_line(cli_error, polar_file, tmp_path, kind):
    d = tmp_path / "tiles"
    d.mkdir()
    if kind == "bad name":
        (d / "tile7.hgt").write_bytes(b"\0" * 2 * N3 * N3)
    line = cli_error("glide", "reach", "--polar", str(polar_file), "--from", "46.1", "7.15",
                     "700", "--terrain", str(d))
    expect = (f"--terrain {d}/tile7.hgt='tile7.hgt': an SRTM tile must be named by its "
              "south-west corner" if kind == "bad name" else
              f"--terrain='{d}': the folder holds no terrain file")  # the folder named once
    assert expect in line, line
