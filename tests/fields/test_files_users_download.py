"""Field files as users download them: global grids and their seams, ERA5, Copernicus depth
levels from 0.494 m, ROMS curvilinear grids, scalar time coordinates (issue 18).

Every file is built with xarray (`glideplan.fields.synthetic`), written, and read back by
xarray itself before glideplan reads it. References are the closed forms sampled into the
files; tolerances are the interpolation error bounds derived in each test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from glideplan.errors import InvalidParameterError
from glideplan.fields import GriddedField, from_xarray, open_field
from glideplan.fields.synthetic import (
    COPERNICUS_DEPTHS,
    EARTH_RADIUS_M,
    basin_current,
    basin_dataset,
    copernicus_dataset,
    copernicus_headland_dataset,
    era5_dataset,
    global_dataset,
    nemo_datasets,
    roms_dataset,
    write_grib,
)

AMP_U, AMP_V = 3.0, 2.0


def periodic_wind(t_s, lat, lon):
    """u = 5 + 3 sin(lon) cos(lat) + 1e-5 t, v = 2 cos(lon) (m/s): periodic in longitude."""
    lam, phi = np.radians(lon), np.radians(lat)
    return 5.0 + AMP_U * np.sin(lam) * np.cos(phi) + 1e-5 * t_s, AMP_V * np.cos(lam) + 0.0 * phi


def bilinear_bound(step_deg: float) -> float:
    """Bilinear interpolation error of periodic_wind on a step_deg grid (linear in time: exact).

    |e| <= (h_lam^2 / 8) max|f_lam lam| + (h_phi^2 / 8) max|f_phi phi| with h in radians:
    for u both second derivatives are bounded by 3, for v by 2 (and 0), so 2 * 3 h^2 / 8;
    float32 storage adds 1e-6 (values <= 8 m/s, rounding 2^-24 relative).
    """
    h = math.radians(step_deg)
    return 2.0 * max(AMP_U, AMP_V) * h * h / 8.0 + 1e-6


# Longitudes at and across both seams, in every representation a user may type.
SEAM_LON = np.array([359.5, 359.99, 360.0, -3.0, -0.3, 0.0, 3.0, 720.2, 179.5, 180.0, -179.7,
                     -180.0, 540.0, 181.0])


@pytest.mark.parametrize("convention", ["0..360", "-180..180"])
def test_global_field_wraps_at_both_seams(tmp_path, convention):
    """A global 1 deg grid (either convention) is periodic; queries across 0 and 180 deg (the
    wrap gap 359..360 of a 0..359 grid, -3 W) equal the sampled closed form within the
    bilinear bound."""
    path = tmp_path / "global.nc"
    global_dataset(1.0, convention, fn=periodic_wind).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        lon = raw["longitude"].values
        assert lon.size == 360 and lon[0] == (0.0 if convention == "0..360" else -180.0)
    f = open_field(path)
    assert f.periodic_lon and f.extent.periodic
    assert f.extent.lon_max - f.extent.lon_min == pytest.approx(360.0)
    assert f.lon[0] == lon[0]  # the file's own convention is kept
    lat = np.tile([50.0, -33.3, 0.0, 71.0], SEAM_LON.size)
    lo = np.repeat(SEAM_LON, 4)
    t = np.full(lo.size, 3.0 * 86400.0)
    u, v = f.velocity(t, lat, lo)
    ue, ve = periodic_wind(t, lat, lo)
    tol = bilinear_bound(1.0)
    np.testing.assert_allclose(u, ue, rtol=0, atol=tol)
    np.testing.assert_allclose(v, ve, rtol=0, atol=tol)
    # Inside the seam cell the interpolant is the mean of the two wrapped columns.
    uu, _ = f.velocity(0.0, 10.0, lon[-1] + 0.5)
    u0, _ = f.velocity(0.0, 10.0, lon[0])
    u1, _ = f.velocity(0.0, 10.0, lon[-1])
    assert float(uu) == pytest.approx(0.5 * (float(u0) + float(u1)), abs=1e-12)
    # Latitude is still bounded, with the bound named.
    with pytest.raises(InvalidParameterError, match=r"position latitude.*north bound 90"):
        f.velocity(0.0, 90.5, 0.0)


def test_global_field_with_land_and_periodic_flag_rule():
    """Land (NaN) stays an obstacle across the seam; periodic_lon follows |nx dlon - 360| <=
    dlon / 2."""
    ds = global_dataset(2.0, "0..360", u=4.0, land=lambda la, lo: (np.abs(la) < 5.0) & (
        (lo >= 356.0) | (lo <= 2.0)), kind="current")
    f = from_xarray(ds)
    assert f.info["variables"] == ["uo", "vo"] and f.periodic_lon
    u, _ = f.velocity(0.0, [0.0, 0.0, 0.0, 20.0], [-1.0, 359.0, 1.0, 359.0])
    assert np.all(np.isnan(u[:3])) and u[3] == pytest.approx(4.0)
    z = np.zeros((1, 3, 4))
    lat = np.array([0.0, 1.0, 2.0])
    # 4 columns 90 deg apart close the circle; 4 columns 70 deg apart (gap 150) do not.
    assert GriddedField(np.zeros(1), lat, np.array([0.0, 90, 180, 270]), z, z).periodic_lon
    regional = GriddedField(np.zeros(1), lat, np.array([0.0, 70, 140, 210]), z, z)
    assert not regional.periodic_lon and not regional.extent.periodic
    with pytest.raises(InvalidParameterError, match="field longitude"):
        GriddedField(np.zeros(1), lat, np.array([0.0, 120, 240, 360]), z, z)


@pytest.mark.parametrize("first", [-180.0, 0.0])
def test_global_file_with_the_closing_column_repeated(first):
    """Files that repeat the first meridian at the end (-180..180 or 0..360 inclusive, 361
    columns at 1 deg) drop the repeat and wrap; Extent.contains_lon accepts every longitude."""
    lon = first + np.arange(361.0)
    lat = np.array([-10.0, 0.0, 10.0])
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    u, v = periodic_wind(0.0, LA, LO)
    ds = xr.Dataset(
        {"u10": (("latitude", "longitude"), u, {"units": "m s-1"}),
         "v10": (("latitude", "longitude"), v, {"units": "m s-1"})},
        coords={"latitude": lat, "longitude": lon},
    )
    f = from_xarray(ds)
    assert f.lon.size == 360 and f.lon[0] == first and f.periodic_lon
    assert f.extent.contains_lon([-540.0, -3.0, 0.0, 359.99, 1e4]).all()
    q = np.array([179.6, -179.6, 359.6, -0.4])
    np.testing.assert_allclose(f.velocity(0.0, 5.0, q)[0], periodic_wind(0.0, 5.0, q)[0],
                               atol=bilinear_bound(1.0))


def test_regional_fields_across_the_antimeridian(tmp_path):
    """A 170E..190E field (0..360) and the same field as a -180..180 subset (columns 170..179
    and -180..-170, sorted ascending as a subset tool writes them) read as one contiguous
    field 170..190: a query at 180 interpolates between its neighbours, never across the gap,
    and 0 deg is outside (named bound)."""
    lat = np.linspace(-5.0, 5.0, 11)
    lon360 = np.arange(170.0, 190.5, 1.0)
    times = np.array(["2026-01-01T00"], dtype="datetime64[ns]")

    def u_of(lon):  # linear in longitude east of 170 E: bilinear interpolation is exact
        return 0.1 + 0.01 * np.mod(np.asarray(lon) - 170.0, 360.0)

    u = u_of(lon360)[None, None, None, :] * np.ones((1, 1, lat.size, 1))
    lon_pm = (lon360 + 180.0) % 360.0 - 180.0
    order = np.argsort(lon_pm)
    for name, lo, uu in (("a.nc", lon360, u), ("b.nc", lon_pm[order], u[..., order])):
        path = tmp_path / name
        ds = copernicus_dataset(lat, lo, times, [0.494], uu, 0.0 * uu)
        ds = ds.assign_coords(longitude=("longitude", lo, {"units": "degrees_east"}))
        ds.to_netcdf(path)
        with xr.open_dataset(path) as raw:
            np.testing.assert_array_equal(raw["longitude"].values, lo)
        f = open_field(path)
        assert not f.periodic_lon
        np.testing.assert_allclose(f.lon, lon360)
        assert f.extent.contains_lon([-175.0, 185.0, 170.0]).all()
        assert not f.extent.contains_lon([169.0, 0.0, -169.0]).any()
        q = np.array([179.5, 180.0, -179.5, 180.5, 189.0, 170.2])
        np.testing.assert_allclose(f.velocity(0.0, 1.0, q)[0], u_of(q), atol=1e-7)
        with pytest.raises(InvalidParameterError, match="outside the field"):
            f.velocity(0.0, 0.0, 0.0)


def test_era5_netcdf_layout(tmp_path):
    """ERA5 as the CDS writes NetCDF: valid_time, latitude 90..-90, longitude 0..359, u10/v10
    in 'm s**-1', scalar number, expver along time. Read across 0 deg and in time (the field is
    linear in time: exact) within the bilinear bound."""
    path = tmp_path / "era5.nc"
    era5_dataset(1.0, fn=periodic_wind).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert set(raw["u10"].dims) == {"valid_time", "latitude", "longitude"}
        assert raw["latitude"].values[0] == 90.0 and raw["latitude"].values[-1] == -90.0
        assert raw["longitude"].values[-1] == 359.0 and raw["number"].ndim == 0
        assert raw["u10"].attrs["units"] == "m s**-1" and "expver" in raw.coords
    f = open_field(path)
    assert f.info["variables"] == ["u10", "v10"] and f.warnings == ()
    assert str(f.epoch)[:13] == "2026-01-01T00" and f.time_span == (0.0, 10 * 86400.0)
    assert f.periodic_lon and np.all(np.diff(f.lat) > 0)
    lat = np.array([50.0, 50.0, 50.0, 49.7, -12.0])
    lon = np.array([-3.0, 3.0, 359.8, 0.4, 180.3])
    t = np.array([0.0, 3600.0, 2.5 * 86400, 4e5, 8.64e5])
    u, v = f.velocity(t, lat, lon)
    ue, ve = periodic_wind(t, lat, lon)
    np.testing.assert_allclose(u, ue, atol=bilinear_bound(1.0))
    np.testing.assert_allclose(v, ve, atol=bilinear_bound(1.0))


def test_global_grib_across_greenwich(tmp_path):
    """A global GRIB (cfgrib: 10u/10v, 90..-90, 0..355 at 5 deg): -3 W and the wrap gap read."""
    path = tmp_path / "gfs.grib2"
    lat, lon = np.arange(-90.0, 90.1, 5.0), np.arange(0.0, 359.0, 5.0)
    times = np.array(["2026-01-01T00", "2026-01-01T06"], dtype="datetime64[ns]")
    ts = (times - times[0]) / np.timedelta64(1, "s")
    T, LA, LO = np.meshgrid(ts, lat, lon, indexing="ij")
    write_grib(path, lat, lon, times, *periodic_wind(T, LA, LO))
    f = open_field(path)
    assert f.periodic_lon and f.lon[0] == 0.0 and f.lon[-1] == 355.0
    q = np.array([-3.0, 357.5, 359.9, 2.0])
    u, v = f.velocity(1e4, 50.0, q)
    ue, ve = periodic_wind(1e4, 50.0, q)
    np.testing.assert_allclose(u, ue, atol=bilinear_bound(5.0) + 2e-5)  # + GRIB packing
    np.testing.assert_allclose(v, ve, atol=bilinear_bound(5.0) + 2e-5)


def test_era5_old_layout_with_expver_dimension(tmp_path):
    """The old layout (time, expver=[0001, 0005], ...): ERA5 and ERA5T halves merged."""
    path = tmp_path / "era5t.nc"
    times = np.array(["2026-01-01T00", "2026-01-01T06", "2026-01-01T12", "2026-01-01T18"],
                     dtype="datetime64[ns]")
    era5_dataset(2.0, fn=periodic_wind, times=times, expver_dimension=True).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert raw["u10"].dims[:2] == ("time", "expver")
        assert np.isnan(raw["u10"].values[3, 0]).all() and np.isnan(raw["u10"].values[0, 1]).all()
    f = open_field(path)
    assert not np.isnan(f.u).any() and f.time_span == (0.0, 18 * 3600.0)
    t = np.array([1000.0, 30000.0, 60000.0])
    u, _ = f.velocity(t, 45.0, 358.5)
    np.testing.assert_allclose(u, periodic_wind(t, 45.0, 358.5)[0], atol=bilinear_bound(2.0))


def test_depth_range_from_the_surface_in_a_copernicus_file(tmp_path):
    """--depth-range 0 500 on levels 0.494..541 m: the top level holds from 0 to 0.494 m.

    The profile u(z) = u0 (1 - s z) is linear, so the trapezoids (and the interpolation at
    500 m) are exact: 500 ubar = 0.494 u(0.494) + int_0.494^500 u0 (1 - s z) dz (closed form;
    float32 storage: 1e-7 relative)."""
    path = tmp_path / "cmems.nc"
    u0, s = 0.3, 1e-3
    copernicus_headland_dataset(depths=COPERNICUS_DEPTHS, u=u0, shear_per_m=s).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert float(raw["depth"][0]) == pytest.approx(0.494025)
    f = open_field(path, depth_range=(0.0, 500.0))
    z1 = COPERNICUS_DEPTHS[0]
    ref = (z1 * u0 * (1 - s * z1) + u0 * ((500.0 - z1) - 0.5 * s * (500.0**2 - z1**2))) / 500.0
    uu, vv = f.velocity(0.0, 30.9, -39.6)
    assert float(uu) == pytest.approx(ref, rel=1e-6) and float(vv) == 0.0
    assert len(f.warnings) == 1 and "0.494025 m" in f.warnings[0]
    assert "held constant to the surface" in f.warnings[0]
    assert f.describe()["warnings"] == list(f.warnings)
    # The headland (lat 30..30.6, lon -40.35..-40.15) is land at every depth.
    u_land, _ = f.velocity(0.0, [30.3, 30.3, 30.9], [-40.25, -40.6, -40.25])
    assert np.isnan(u_land[0]) and np.isfinite(u_land[1:]).all()
    # A layer inside the levels gives no warning; bad layers name depth_range and the rule.
    assert open_field(path, depth_range=(1.0, 100.0)).warnings == ()
    with pytest.raises(InvalidParameterError, match=r"depth_range.*deepest level 541.089"):
        open_field(path, depth_range=(0.0, 600.0))
    with pytest.raises(InvalidParameterError, match=r"depth_range.*below the surface"):
        open_field(path, depth_range=(-5.0, 100.0))


def _linear_east_north(t_s, lat, lon):
    """A linear field in lat/lon: linear interpolation on any triangle reproduces it."""
    return 0.2 + 0.1 * (lat - 30.0) - 0.05 * (lon + 40.0) + 0.0 * t_s, -0.1 + 0.08 * (lon + 40.0)


def _grid_index(lat, lon, lat0=30.0, lon0=-40.0, nx=41, ny=31, h=2000.0, angle_deg=30.0):
    """Fractional (i, j) of points on roms_dataset's rotated grid (inverse of its map)."""
    a = math.radians(angle_deg)
    east = np.radians(lon - lon0) * EARTH_RADIUS_M * math.cos(math.radians(lat0))
    north = np.radians(lat - lat0) * EARTH_RADIUS_M
    x = east * math.cos(a) + north * math.sin(a)
    y = -east * math.sin(a) + north * math.cos(a)
    return x / h + 0.5 * (nx - 1), y / h + 0.5 * (ny - 1)


@pytest.mark.parametrize("staggered", [True, False])
def test_roms_curvilinear_grid_is_regridded(tmp_path, staggered):
    """ROMS (grid rotated 30 deg; staggered grid-relative u/v with `angle`, or u_eastward/
    v_northward on rho points) regridded to a regular grid at the native spacing (2 km =
    0.01799 deg). The field is linear in lat/lon, so the interpolation in the grid's own
    triangles and the rotation by the exact angle reproduce it to float32 (1e-6); NaN outside
    the grid and at the land (mask 0) box; the top s-level is used; a warning says so."""
    path = tmp_path / "roms.nc"

    def land(lat, lon):
        return (np.abs(lat - 30.0) < 0.03) & (np.abs(lon + 40.0) < 0.03)

    roms_dataset(fn=_linear_east_north, staggered=staggered, land=land).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert raw["lat_rho"].ndim == 2
        if staggered:
            assert raw["u"].dims == ("ocean_time", "s_rho", "eta_u", "xi_u")
            assert "lat_u" in raw["u"].coords and float(raw["angle"][0, 0]) == pytest.approx(
                math.radians(30.0))
    f = open_field(path)
    assert len(f.warnings) == 1 and f.warnings[0].startswith("regridded the curvilinear")
    assert ("rotated" in f.warnings[0]) == staggered
    assert "top s_rho level" in f.info["level"]
    d = math.degrees(2000.0 / EARTH_RADIUS_M)
    assert f.lat[1] - f.lat[0] == pytest.approx(d, rel=1e-6)
    LA, LO = np.meshgrid(f.lat, f.lon, indexing="ij")
    u, v = f.u[1], f.v[1]  # the regridded nodes (queries between them: test_fields)
    ue, ve = _linear_east_north(0.0, LA, LO)
    i, j = _grid_index(LA, LO)
    m = 0.5 if staggered else 0.0  # u and v points cover i, j in [m, n - 1 - m]
    inside = (i > m + 1e-6) & (i < 40 - m - 1e-6) & (j > m + 1e-6) & (j < 30 - m - 1e-6)
    near_land = (np.abs(LA - 30.0) < 0.03 + 2 * d) & (np.abs(LO + 40.0) < 0.03 + 3 * d)
    sea = inside & ~near_land
    assert sea.sum() > 500
    np.testing.assert_allclose(u[sea], ue[sea], atol=1e-6)
    np.testing.assert_allclose(v[sea], ve[sea], atol=1e-6)
    outside = (i < -0.01) | (i > 40.01) | (j < -0.01) | (j > 30.01)
    assert outside.sum() > 500 and np.isnan(u[outside]).all() and np.isnan(v[outside]).all()
    assert np.isnan(f.velocity(0.0, 30.0, -40.0)[0])  # the land box


def test_roms_angle_from_coordinates_and_refusals(tmp_path):
    """Without `angle` the grid angle comes from the coordinates, atan2(dlat, cos(lat) dlon).
    The builder places longitudes with cos(30 deg), so the angle from cos(lat) differs by at
    most tan(lat0) |dlat| sin(a) cos(a) ~ 0.577 * 0.0063 rad * 0.43 = 1.6e-3 rad over the grid:
    error <= 0.3 m/s * 1.6e-3 ~ 5e-4 m/s (asserted 1e-3). Depth averaging on s-levels and a
    degenerate grid are refused, naming the parameter and what to do."""
    ds = roms_dataset(fn=_linear_east_north).drop_vars("angle")
    f = from_xarray(ds)
    assert "from its coordinates" in f.warnings[0]
    LA, LO = np.meshgrid(f.lat, f.lon, indexing="ij")
    u, v = f.u[0], f.v[0]
    ue, ve = _linear_east_north(0.0, LA, LO)
    ok = np.isfinite(u)
    assert ok.sum() > 500
    np.testing.assert_allclose(u[ok], ue[ok], atol=1e-3)
    np.testing.assert_allclose(v[ok], ve[ok], atol=1e-3)
    with pytest.raises(InvalidParameterError, match=r"depth_range.*terrain-following"):
        from_xarray(roms_dataset(), depth_range=(0.0, 50.0))
    wide = roms_dataset(staggered=False, lat0=0.0, nx=5, ny=2, spacing_m=9.0e6, angle_deg=1.0)
    with pytest.raises(InvalidParameterError, match=r"field grid.*global \(tripolar\) grid"):
        from_xarray(wide)
    flat = roms_dataset(staggered=False)
    flat["lat_rho"] = flat["lat_rho"] * 0.0 + 30.0  # every node on one parallel: no area
    with pytest.raises(InvalidParameterError, match=r"field grid.*regrid it to a regular"):
        from_xarray(flat)


def test_nemo_grid_u_and_grid_v_files(tmp_path):
    """NEMO's two files (grid_U, grid_V), each with its own nav_lat/nav_lon of the same name,
    combine with each component on its own points; the angle comes from the coordinates
    (grid at 20 deg: tan(30 deg) |dlat| sin(a) cos(a) <= 0.577 * 0.0066 * 0.32 = 1.2e-3 rad,
    error <= 0.3 m/s * 1.2e-3 ~ 4e-4 m/s; asserted 1e-3). The surface level (0.494 m) is used."""
    grid_u, grid_v = nemo_datasets(fn=_linear_east_north)
    pu, pv = tmp_path / "grid_U.nc", tmp_path / "grid_V.nc"
    grid_u.to_netcdf(pu)
    grid_v.to_netcdf(pv)
    with xr.open_dataset(pu) as a, xr.open_dataset(pv) as b:
        assert a["nav_lat"].shape == b["nav_lat"].shape
        assert not np.array_equal(a["nav_lat"].values, b["nav_lat"].values)
    f = open_field([pu, pv])
    assert f.info["variables"] == ["vozocrtx", "vomecrty"] and f.info["depth_m"] == 0.494025
    assert "regridded the curvilinear 31x41 grid" in f.warnings[0] and "rotated" in f.warnings[0]
    LA, LO = np.meshgrid(f.lat, f.lon, indexing="ij")
    ue, ve = _linear_east_north(0.0, LA, LO)
    ok = np.isfinite(f.u[0])
    assert ok.sum() > 500
    np.testing.assert_allclose(f.u[0][ok], ue[ok], atol=1e-3)
    np.testing.assert_allclose(f.v[0][ok], ve[ok], atol=1e-3)


def test_scalar_time_coordinate_is_one_time_step(tmp_path):
    """A single time as a 0-d coordinate (Copernicus `time`, ERA5 `valid_time`, GRIB with one
    step) reads as one time step, held constant (with a warning), never an internal error."""
    times = np.array(["2026-03-01T12"], dtype="datetime64[ns]")
    path = tmp_path / "one.nc"
    u = np.full((1, 1, 2, 2), 0.4)
    copernicus_dataset([0.0, 1.0], [0.0, 1.0], times, [0.494], u, -u).isel(time=0).to_netcdf(path)
    with xr.open_dataset(path) as raw:
        assert raw["time"].ndim == 0 and "time" not in raw["uo"].dims
    f = open_field(path)
    assert str(f.epoch)[:13] == "2026-03-01T12" and f.time_span is None
    assert any("held constant" in w for w in f.warnings)
    assert tuple(map(float, f.velocity(5e6, 0.5, 0.5))) == pytest.approx((0.4, -0.4))
    era = from_xarray(era5_dataset(2.0, u=7.0).isel(valid_time=0))
    assert str(era.epoch)[:10] == "2026-01-01" and "held constant" in era.warnings[0]
    grib = tmp_path / "one.grib2"
    write_grib(grib, [0.0, 1.0], [0.0, 1.0], times, np.full((1, 2, 2), 2.0), np.zeros((1, 2, 2)))
    g = open_field(grib)
    assert str(g.epoch)[:13] == "2026-03-01T12" and "held constant" in g.warnings[0]


def test_bad_layouts_name_the_parameter():
    """An ensemble dimension, several forecast runs, and undecodable times are refused."""
    ds = era5_dataset(2.0, u=1.0)
    ens = xr.concat([ds, ds], dim="number")
    with pytest.raises(InvalidParameterError, match="dimension 'number' of size 2"):
        from_xarray(ens)
    runs = ds.expand_dims(run=2).assign_coords(
        valid_time=(("run", "valid_time"), np.stack([ds["valid_time"].values] * 2)))
    with pytest.raises(InvalidParameterError, match=r"field time.*select one forecast"):
        from_xarray(runs)
    raw = ds.assign_coords(valid_time=("valid_time", [0.0, 6.0]))
    with pytest.raises(InvalidParameterError, match=r"field time.*must decode to dates"):
        from_xarray(raw)


def test_basin_field_for_the_routing_benchmark():
    """The basin-scale 1/12 deg field: 260 x 500 x 13, speeds <= 0.48 m/s (the bound in
    basin_current's docstring), read back equal to basin_current at its time levels within
    the bilinear bound h^2/8 max|f''|: jet U 2/L^2 (U = 0.25, L = 60 km) and waves s K^2 at
    h = 9.3 km: 1.5e-3 + 4e-4 m/s (asserted 2e-3)."""
    ds = basin_dataset()
    assert ds["uo"].shape == (13, 1, 260, 500)
    assert float(ds["longitude"][1] - ds["longitude"][0]) == pytest.approx(1.0 / 12.0)
    speed = np.hypot(ds["uo"].values, ds["vo"].values)
    assert 0.3 < float(speed.max()) <= 0.48 and float(np.median(speed)) > 0.03
    f = from_xarray(ds)
    rng = np.random.default_rng(7)
    lat = rng.uniform(21.0, 41.0, 400)
    lon = rng.uniform(-69.0, -29.0, 400)
    t = f.times[rng.integers(0, 13, 400)]
    u, v = f.velocity(t, lat, lon)
    ue, ve = basin_current(t, lat, lon)
    np.testing.assert_allclose(u, ue, atol=2e-3)
    np.testing.assert_allclose(v, ve, atol=2e-3)


def test_two_dimensional_coordinates_of_a_regular_grid_are_not_regridded():
    """2-D nav_lat/nav_lon that are a product of 1-D axes (either dimension order) read as the
    regular grid itself: no regridding, values exact (a field linear in lat and lon)."""
    lat, lon = np.array([0.0, 1.0, 2.0]), np.array([10.0, 11.0, 12.0, 13.0])
    LA, LO = np.meshgrid(lat, lon, indexing="ij")
    ds = xr.Dataset(
        {"uo": (("y", "x"), 0.01 * LO, {"standard_name": "eastward_sea_water_velocity"}),
         "vo": (("y", "x"), 0.1 * LA, {"standard_name": "northward_sea_water_velocity"})},
        coords={"nav_lat": (("y", "x"), LA), "nav_lon": (("y", "x"), LO)},
    )
    for d in (ds, ds.transpose("x", "y")):
        f = from_xarray(d)
        assert not any("regridded" in w for w in f.warnings)
        np.testing.assert_array_equal(f.lat, lat)
        np.testing.assert_array_equal(f.lon, lon)
        u, v = f.velocity(0.0, 1.5, 11.25)
        assert (float(u), float(v)) == pytest.approx((0.1125, 0.15), abs=1e-12)


def test_regrid_keeps_a_concave_grid_concave():
    """A curved (polar) grid around three quarters of an annulus, r 20..60 km: nodes inside its
    cells get the linear field exactly (linear on every triangle), nodes in the hole and in the
    missing quarter stay NaN (a Delaunay triangulation of the points would bridge both)."""
    from glideplan.fields.regrid import CurvilinearSource, regrid_curvilinear

    r, th = np.meshgrid(np.linspace(20e3, 60e3, 21), np.radians(np.linspace(0, 270, 136)),
                        indexing="ij")
    k_lon = EARTH_RADIUS_M * math.cos(math.radians(30.0))
    lat = 30.0 + np.degrees(r * np.sin(th) / EARTH_RADIUS_M)
    lon = -40.0 + np.degrees(r * np.cos(th) / k_lon)
    ue, ve = _linear_east_north(0.0, lat, lon)
    g = regrid_curvilinear(CurvilinearSource(ue[None], lat, lon),
                           CurvilinearSource(ve[None], lat, lon))
    LA, LO = np.meshgrid(g.lat, g.lon, indexing="ij")
    x, y = np.radians(LO + 40.0) * k_lon, np.radians(LA - 30.0) * EARTH_RADIUS_M
    rr, tt = np.hypot(x, y), np.degrees(np.mod(np.arctan2(y, x), 2 * np.pi))
    # Chords of the 2 deg arcs lie within r (1 - cos 1 deg) = 9 m of the circles: 0.5 km margins.
    inside = (rr > 20.5e3) & (rr < 59.5e3) & (tt > 1.0) & (tt < 269.0)
    hole = (rr < 19.5e3) | ((tt > 271.0) & (tt < 359.0))
    assert inside.sum() > 1000 and hole.sum() > 500
    np.testing.assert_allclose(g.u[0][inside], _linear_east_north(0.0, LA, LO)[0][inside],
                               atol=1e-12)
    assert np.isnan(g.u[0][hole]).all() and np.isnan(g.v[0][hole]).all()
