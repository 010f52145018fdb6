"""Terrain: SRTM .hgt and GeoTIFF readers, voids, merging, bilinear sampling, max pooling."""

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.terrain import Terrain, merge_tiles, read_hgt, read_terrain, write_hgt
from glideplan.terrain.geotiff import read_geotiff, write_geotiff


def _relief(lat, lon):
    return np.round(800 + 600 * np.sin(9 * lat[:, None]) * np.cos(13 * lon[None, :]))


def test_hgt_and_geotiff_of_the_same_terrain_agree(tmp_path):
    """The same samples written as an SRTM3 tile and as a GeoTIFF whose pixel centres are the
    tile's nodes: both readers give the same nodes and elevations (bilinear, anywhere)."""
    n = 1201
    lat = 46 + np.arange(n) / (n - 1)
    lon = 7 + np.arange(n) / (n - 1)
    z = _relief(lat, lon)
    a = read_hgt(write_hgt(tmp_path / "N46E007.hgt", z))
    b = read_geotiff(write_geotiff(tmp_path / "tile.tif", lat, lon, z))
    assert a.shape == b.shape == (n, n)
    np.testing.assert_allclose(a.lat, b.lat, atol=1e-9)
    np.testing.assert_allclose(a.lon, b.lon, atol=1e-9)
    rng = np.random.default_rng(1)
    pla, plo = rng.uniform(46, 47, 500), rng.uniform(7, 8, 500)
    np.testing.assert_allclose(a.elevation(pla, plo), b.elevation(pla, plo), atol=1e-3)
    # a node is its sample: row 0 of the file is the north edge
    assert a.elevation(47.0, 7.0) == pytest.approx(z[-1, 0])
    assert a.elevation(46.0, 8.0) == pytest.approx(z[0, -1])


def test_hgt_corner_from_the_name_southern_western(tmp_path):
    z = np.zeros((1201, 1201))
    t = read_hgt(write_hgt(tmp_path / "S12W077.hgt", z))
    assert t.extent == pytest.approx((-12.0, -11.0, -77.0, -76.0))


@pytest.mark.parametrize("name,size", [("N46E007.hgt", 1000), ("tile.hgt", 2 * 1201**2)])
def test_hgt_refuses_wrong_size_or_name(tmp_path, name, size):
    p = tmp_path / name
    p.write_bytes(b"\0" * size)
    with pytest.raises(InvalidParameterError) as e:
        read_hgt(p)
    assert name in str(e.value)


def test_hgt_voids_refused_or_filled(tmp_path):
    n = 1201
    lat = 46 + np.arange(n) / (n - 1)
    lon = 7 + np.arange(n) / (n - 1)
    z = 500.0 + 0.0 * _relief(lat, lon) + 100 * lat[:, None] + 50 * lon[None, :]  # a plane
    holed = z.copy()
    holed[600:610, 300:330] = np.nan
    p = write_hgt(tmp_path / "N46E007.hgt", holed)
    with pytest.raises(InvalidParameterError, match="voids"):
        read_hgt(p)
    near = read_hgt(p, voids="nearest")
    lin = read_hgt(p, voids="linear")
    assert any("filled 300 void" in w for w in near.warnings)
    # linear interpolation reproduces a plane (to the file's 1 m rounding)
    assert np.max(np.abs(lin.z[600:610, 300:330] - z[600:610, 300:330])) <= 1.0
    # nearest takes a neighbour's value: within one sample step of the plane's slope
    assert np.max(np.abs(near.z[600:610, 300:330] - z[600:610, 300:330])) <= 100 * 15 / 1200 + 1


def test_merge_adjacent_tiles(tmp_path):
    n = 1201
    t1 = 46 + np.arange(n) / (n - 1)
    z = np.zeros((n, 2 * n - 1))
    lon = 7 + np.arange(2 * n - 1) / (n - 1)
    z[:] = _relief(t1, lon)
    write_hgt(tmp_path / "N46E007.hgt", z[:, :n])
    write_hgt(tmp_path / "N46E008.hgt", z[:, n - 1:])
    m = read_terrain([tmp_path / "N46E007.hgt", tmp_path / "N46E008.hgt"])
    assert m.shape == (n, 2 * n - 1)
    assert m.extent == pytest.approx((46, 47, 7, 9))
    assert not m.warnings  # the shared edge column agrees
    np.testing.assert_allclose(m.z, z, atol=0.5)


def test_merge_refuses_mixed_resolutions():
    a = Terrain(np.linspace(46, 47, 11), np.linspace(7, 8, 11), np.zeros((11, 11)))
    b = Terrain(np.linspace(46, 47, 21), np.linspace(8, 9, 21), np.zeros((21, 21)))
    with pytest.raises(InvalidParameterError, match="one sample step"):
        merge_tiles([a, b])


def test_geotiff_in_web_mercator_is_reprojected(tmp_path):
    """A raster not in WGS84 lat/lon is reprojected (tests/reach/test_terrain_inputs.py checks
    the accuracy on a UTM tile); it says so in the warnings."""
    import rasterio
    from affine import Affine

    p = tmp_path / "merc.tif"
    with rasterio.open(p, "w", driver="GTiff", height=4, width=4, count=1, dtype="float32",
                       crs="EPSG:3857", transform=Affine(100.0, 0.0, 0.0, 0.0, -100.0, 0.0)) as ds:
        ds.write(np.full((4, 4), 250.0, np.float32), 1)
    t = read_geotiff(p)
    assert "reprojected from EPSG:3857" in t.warnings[0]
    assert np.nanmax(np.abs(t.z - 250.0)) == 0.0 and np.isfinite(t.z).any()


def test_pooled_max_never_understates_the_terrain():
    """Property: the bilinear terrain anywhere in a coarse node's cell is <= that node's
    pooled value (reference: the definition; random points, several factors)."""
    rng = np.random.default_rng(3)
    n = 97
    t = Terrain(np.linspace(46, 46.5, n), np.linspace(7, 7.5, n),
                rng.uniform(0, 3000, (n, n)).astype(np.float32))
    for f in (1, 2, 3, 4):
        lat, lon, z = t.pooled_max(f)
        dla, dlo = lat[1] - lat[0], lon[1] - lon[0]
        pla = rng.uniform(lat[0], lat[-1], 4000)
        plo = rng.uniform(lon[0], lon[-1], 4000)
        i = np.round((pla - lat[0]) / dla).astype(int)
        j = np.round((plo - lon[0]) / dlo).astype(int)
        assert np.all(t.elevation(pla, plo) <= z[i, j] + 1e-3)
