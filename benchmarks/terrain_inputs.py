"""Benchmark: reading terrain as people keep it (issue 24) -- a projected (UTM) GeoTIFF
reprojected to lat/lon, and a folder of zipped SRTM3 tiles against the same tiles plain.

UTM: a 3000 x 3000, 30 m GeoTIFF in EPSG:32632 (90 km square at 46.5 N 10.4 E, ~1 deg of grid
convergence) sampled from a smooth lat/lon reference z = 800 + A (sin k x + sin k y) (A = 300
m, wavelength 3 km); `read_terrain` reprojects it (PROJ on every 8th node, bilinear between;
bilinear elevations). Reported: wall time, the lat/lon grid, and the largest error against
the reference with its bound (h_x^2 + h_y^2)/8 A k^2 x 1.02 (tests/reach/test_terrain_inputs.py
derives it). Peer (measured in this run): GDAL's warper, `rasterio.warp.reproject` with
bilinear resampling onto the same lat/lon grid (time and error).

Tiles: four SRTM3 tiles (2 x 2 degrees) as .hgt, and as .hgt.zip in a folder: the time to read
and merge each.

Usage: python benchmarks/terrain_inputs.py [--n 3000]
"""

from __future__ import annotations

import argparse
import math
import pathlib
import sys
import tempfile
import time
import zipfile

import numpy as np

from glideplan.terrain import read_terrain, write_hgt

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "tests" / "reach"))
import test_terrain_inputs as ref  # the reference surface and the UTM writer


def _gdal_peer(path: pathlib.Path, lat: np.ndarray, lon: np.ndarray) -> tuple[float, float]:
    """(seconds, max error m) of rasterio.warp.reproject (bilinear) onto the nodes lat, lon."""
    import rasterio
    from affine import Affine
    from rasterio.warp import Resampling, reproject

    dlat, dlon = lat[1] - lat[0], lon[1] - lon[0]
    out = np.full((lat.size, lon.size), np.nan, dtype=np.float32)
    t0 = time.perf_counter()
    with rasterio.open(path) as ds:
        reproject(ds.read(1).astype(np.float32), out, src_transform=ds.transform,
                  src_crs=ds.crs, src_nodata=np.nan, dst_transform=Affine(
                      dlon, 0.0, lon[0] - dlon / 2, 0.0, -dlat, lat[-1] + dlat / 2),
                  dst_crs="EPSG:4326", dst_nodata=np.nan, resampling=Resampling.bilinear)
    dt = time.perf_counter() - t0
    out = out[::-1]
    la, lo = np.meshgrid(lat, lon, indexing="ij")
    ok = np.isfinite(out)
    # compare away from the raster's edge (GDAL fills partly covered nodes there)
    ok[:3], ok[-3:], ok[:, :3], ok[:, -3:] = False, False, False, False
    return dt, float(np.max(np.abs(out[ok] - ref._relief(la[ok], lo[ok]))))


def utm(d: pathlib.Path, n: int) -> None:
    p = ref._write_utm(d / "utm.tif", n=n)
    t0 = time.perf_counter()
    t = read_terrain([p])
    dt = time.perf_counter() - t0
    la, lo = np.meshgrid(t.lat, t.lon, indexing="ij")
    ok = np.isfinite(t.z)
    err = float(np.max(np.abs(t.z[ok] - ref._relief(la[ok], lo[ok]))))
    k = 2 * math.pi / ref.WAVE
    bound = 2 * ref.H**2 / 8 * ref.AMP * k**2 * 1.02
    print(f"UTM {n}x{n} 30 m -> lat/lon {t.shape[0]}x{t.shape[1]}: {dt:.2f} s, max error "
          f"{err:.3f} m (bilinear bound {bound:.3f} m)")
    gdt, gerr = _gdal_peer(p, t.lat, t.lon)
    print(f"  peer rasterio.warp.reproject (bilinear): {gdt:.2f} s, max error {gerr:.3f} m")


def tiles(d: pathlib.Path) -> None:
    plain, zipped = d / "plain", d / "zipped"
    plain.mkdir()
    zipped.mkdir()
    for la in (46, 47):
        for lo in (7, 8):
            name = f"N{la}E00{lo}.hgt"
            lat = la + np.arange(1201) / 1200
            lon = lo + np.arange(1201) / 1200
            z = np.round(900 + 500 * np.sin(7 * lat[:, None]) * np.cos(11 * lon[None, :]))
            f = write_hgt(plain / name, z)
            with zipfile.ZipFile(zipped / f"{name[:-4]}.SRTMGL3.hgt.zip", "w",
                                 zipfile.ZIP_DEFLATED) as zf:
                zf.write(f, name)
    for what, paths in (("4 plain .hgt", sorted(plain.iterdir())),
                        ("folder of 4 .hgt.zip", [zipped])):
        t0 = time.perf_counter()
        t = read_terrain(paths)
        print(f"{what}: {time.perf_counter() - t0:.2f} s -> {t.shape[0]}x{t.shape[1]}")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=3000)
    args = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        d = pathlib.Path(tmp)
        utm(d, args.n)
        tiles(d)


if __name__ == "__main__":
    main()
