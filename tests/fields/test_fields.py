"""Fields from files: layouts (Copernicus, HYCOM, GRIB), interpolation, depth averaging, errors.

Every file is built here with xarray (or eccodes for GRIB) and read back by the product's own
reader (xarray/netCDF4, cfgrib) before glideplan reads it.
"""

from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from glideplan.errors import InvalidParameterError
from glideplan.fields import (
    GriddedField,
    UniformField,
    depth_average,
    double_gyre,
    from_xarray,
    open_field,
)
from glideplan.fields.synthetic import copernicus_dataset, hycom_dataset, write_grib

LAT = np.linspace(29.0, 31.0, 21)
LON = np.linspace(-41.0, -39.0, 21)
TIMES = np.array(["2026-01-01T00", "2026-01-01T06", "2026-01-01T12"], dtype="datetime64[ns]")


def linear_u(t_s, lat, lon):
    """A field linear in time, latitude and longitude: trilinear interpolation is exact."""
    return 0.1 + 1e-6 * t_s + 0.05 * (lat - 30.0) - 0.02 * (lon + 40.0)


def linear_v(t_s, lat, lon):
    return -0.05 + 2e-6 * t_s + 0.03 * (lon + 40.0)


def _linear_arrays():
    ts = (TIMES - TIMES[0]) / np.timedelta64(1, "s")
    T, LA, LO = np.meshgrid(ts, LAT, LON, indexing="ij")
    return linear_u(T, LA, LO)[:, None], linear_v(T, LA, LO)[:, None]


@pytest.fixture
def layouts(tmp_path):
    """The same linear field written in the Copernicus and the HYCOM layout."""
    u, v = _linear_arrays()
    cop = tmp_path / "cmems.nc"
    copernicus_dataset(LAT, LON, TIMES, [0.5], u, v).to_netcdf(cop)
    hyc = tmp_path / "hycom.nc"
    hycom_dataset(LAT, LON, TIMES, [0.0], u, v, descending_lat=True).to_netcdf(hyc)
    return cop, hyc


def test_layouts_read_back_and_agree(layouts):
    """Both layouts (read back by xarray first) give the analytic linear field.

    Reference: the linear function itself (trilinear interpolation reproduces it exactly);
    HYCOM packs to 0.001 m/s, so it agrees to 5e-4.
    """
    cop, hyc = layouts
    with xr.open_dataset(hyc) as raw:
        assert float(raw["lon"].min()) >= 0.0 and float(raw["lon"].max()) > 180.0
        assert raw["lat"].values[0] > raw["lat"].values[-1]
    with xr.open_dataset(cop) as raw:
        assert raw["uo"].attrs["standard_name"] == "eastward_sea_water_velocity"
    fc, fh = open_field(cop), open_field(hyc)
    assert fc.info["variables"] == ["uo", "vo"] and fh.info["variables"] == ["water_u", "water_v"]
    rng = np.random.default_rng(1)
    lat = rng.uniform(29.0, 31.0, 50)
    lon = rng.uniform(-41.0, -39.0, 50)
    t = rng.uniform(0.0, 43200.0, 50)
    for f, tol in ((fc, 1e-6), (fh, 6e-4)):
        assert f.extent.lon_min == pytest.approx(-41.0) and f.extent.lon_max == pytest.approx(-39)
        u, v = f.velocity(t, lat, lon)
        np.testing.assert_allclose(u, linear_u(t, lat, lon), atol=tol)
        np.testing.assert_allclose(v, linear_v(t, lat, lon), atol=tol)
    # Queries in 0..360 land in the same place.
    u1, _ = fc.velocity(t, lat, lon + 360.0)
    np.testing.assert_allclose(u1, linear_u(t, lat, lon), atol=1e-6)


def test_grib_descending_latitude(tmp_path):
    """GRIB (10u/10v, north-to-south scan, 0..360) via cfgrib: the linear field, to float32."""
    path = tmp_path / "wind.grib2"
    lat, lon = np.linspace(29.0, 31.0, 9), np.linspace(-41.0, -39.0, 9)
    ts = (TIMES - TIMES[0]) / np.timedelta64(1, "s")
    T, LA, LO = np.meshgrid(ts, lat, lon, indexing="ij")
    write_grib(path, lat, lon, TIMES, linear_u(T, LA, LO), linear_v(T, LA, LO))
    with xr.open_dataset(path, engine="cfgrib", backend_kwargs={"indexpath": ""}) as raw:
        assert {"u10", "v10"} <= set(raw.data_vars)
        assert raw["latitude"].values[0] > raw["latitude"].values[-1]
    f = open_field(path)
    assert f.info["variables"] == ["u10", "v10"]
    assert str(f.epoch)[:13] == "2026-01-01T00"
    tq, laq, loq = np.array([0.0, 2e4]), np.array([29.3, 30.7]), np.array([-40.6, -39.2])
    u, v = f.velocity(tq, laq, loq)
    np.testing.assert_allclose(u, linear_u(tq, laq, loq), atol=2e-5)
    np.testing.assert_allclose(v, linear_v(tq, laq, loq), atol=2e-5)


def test_depth_average_trapezoid():
    """Levels 0, 50, ..., 500; 1 m/s at 0 and 50 m, 0 below: (50*1 + 25*1)/500 = 0.15 m/s."""
    z = np.arange(0.0, 501.0, 50.0)
    prof = np.where(z <= 50.0, 1.0, 0.0)
    assert depth_average(prof, z, 0.0, 500.0) == pytest.approx(0.15, rel=1e-12)
    # A partial layer interpolates at its ends: 25..75 m -> (25*1 + 25*(1+0.5)/2) / 50.
    assert depth_average(prof, z, 25.0, 75.0) == pytest.approx((25 + 18.75) / 50, rel=1e-12)
    with pytest.raises(InvalidParameterError, match="depth_range"):
        depth_average(prof, z, 0.0, 600.0)


def test_depth_range_from_file(tmp_path):
    z = np.arange(0.0, 501.0, 50.0)
    u = np.where(z <= 50.0, 1.0, 0.0)[None, :, None, None] * np.ones((1, 1, LAT.size, LON.size))
    path = tmp_path / "cur.nc"
    copernicus_dataset(LAT, LON, TIMES[:1], z, u, 0.0 * u).to_netcdf(path)
    f = open_field(path, depth_range=(0.0, 500.0))
    uu, vv = f.velocity(0.0, 30.0, -40.0)
    assert float(uu) == pytest.approx(0.15, rel=1e-6) and float(vv) == 0.0
    assert float(open_field(path).velocity(0.0, 30.0, -40.0)[0]) == pytest.approx(1.0)


def test_nan_is_land_and_bounds_are_named():
    """A NaN node makes every query whose stencil touches it NaN; outside -> named bound."""
    u = np.zeros((1, 3, 3))
    u[0, 0, 0] = np.nan
    f = GriddedField(np.zeros(1), np.array([0.0, 1.0, 2.0]), np.array([10.0, 11.0, 12.0]),
                     u, np.zeros((1, 3, 3)))
    uu, _ = f.velocity(0.0, [0.5, 0.9, 1.5, 0.5], [10.5, 10.9, 11.5, 11.5])
    assert np.isnan(uu[0]) and np.isnan(uu[1]) and uu[2] == 0.0 and uu[3] == 0.0
    with pytest.raises(InvalidParameterError, match="north bound 2"):
        f.velocity(0.0, 2.5, 11.0)
    with pytest.raises(InvalidParameterError, match="west bound 10"):
        f.velocity(0.0, 1.0, 9.0)


def test_time_outside_span_is_an_error(layouts):
    f = open_field(layouts[0])
    with pytest.raises(InvalidParameterError, match="after the field's last time 2026-01-01T12"):
        f.velocity(43201.0, 30.0, -40.0)
    with pytest.raises(InvalidParameterError, match="before the field's first time"):
        f.velocity(np.datetime64("2025-12-31T23:00"), 30.0, -40.0)


def test_bad_files(tmp_path):
    text = tmp_path / "notes.nc"
    text.write_text("not a netcdf file\n")
    with pytest.raises(InvalidParameterError, match="not a NetCDF or GRIB file"):
        open_field(text)
    with pytest.raises(InvalidParameterError, match="no such file"):
        open_field(tmp_path / "missing.nc")
    temp = tmp_path / "temp.nc"
    xr.Dataset({"thetao": (("latitude", "longitude"), np.zeros((2, 2)))},
               coords={"latitude": [0.0, 1.0], "longitude": [0.0, 1.0]}).to_netcdf(temp)
    with pytest.raises(InvalidParameterError, match="no eastward/northward velocity pair"):
        open_field(temp)
    good = tmp_path / "good.nc"
    u, v = _linear_arrays()
    copernicus_dataset(LAT, LON, TIMES, [0.5], u, v).to_netcdf(good)
    trunc = tmp_path / "trunc.nc"
    trunc.write_bytes(good.read_bytes()[: good.stat().st_size // 2])
    with pytest.raises(InvalidParameterError, match="cannot read"):
        open_field(trunc)


def test_one_row_of_latitudes_is_named_as_such():
    """A file with a single latitude (a 1-row subset) says so; it said "no latitude
    coordinate found" while listing 'latitude' among the coordinates."""
    ds = copernicus_dataset([30.0], [0.0, 0.5, 1.0], TIMES, [0.5], np.zeros((TIMES.size, 1, 1, 3)),
                            np.zeros((TIMES.size, 1, 1, 3)))
    with pytest.raises(InvalidParameterError, match=r"latitude.*has one value.*at least two"):
        from_xarray(ds)


def test_files_of_different_areas_do_not_merge_into_fake_land(tmp_path):
    """Two files of different areas or grids are refused naming the files: two boxes apart
    (the merged grid interpolated across the gap), a 1/4 deg and a 1/12 deg grid (nodes in no
    file, filled with NaN by the outer join: read as land; `route --field a.nc --field b.nc`
    answered "solved" with a 16.8 km land clearance). Adjacent boxes of one lattice merge."""
    lat, lon = np.arange(40.0, 41.01, 0.25), np.arange(-10.0, -8.99, 0.25)
    times = TIMES[:2]
    zero = np.zeros((2, 1, lat.size, lon.size))
    copernicus_dataset(lat, lon, times, [0.5], zero + 0.1, zero).to_netcdf(tmp_path / "a.nc")
    copernicus_dataset(lat + 3, lon, times, [0.5], zero + 0.1, zero).to_netcdf(tmp_path / "b.nc")
    with pytest.raises(InvalidParameterError, match=r"field=.*: a gap between the files' "
                       r"latitudes 41 and 43 \(their own spacing at most 0\.25\)"):
        open_field([tmp_path / "a.nc", tmp_path / "b.nc"])
    fine = np.arange(40.0, 41.01, 1 / 12)
    z = np.zeros((2, 1, fine.size, fine.size))
    copernicus_dataset(fine, fine - 50.0, times, [0.5], z, z).to_netcdf(tmp_path / "c.nc")
    with pytest.raises(InvalidParameterError, match="in no file"):
        open_field([tmp_path / "a.nc", tmp_path / "c.nc"])
    copernicus_dataset(lat + 1.25, lon, times, [0.5], zero + 0.1, zero).to_netcdf(
        tmp_path / "north.nc")  # the next box north on the same 0.25 deg lattice
    f = open_field([tmp_path / "a.nc", tmp_path / "north.nc"])
    assert f.lat.size == 2 * lat.size and np.isfinite(f.u).all()


def test_standard_names_found_under_other_names():
    """Components are found by standard_name whatever the variable names (cf-xarray)."""
    ds = xr.Dataset(
        {"a": (("lat", "lon"), np.full((2, 2), 3.0), {"standard_name": "eastward_wind"}),
         "b": (("lat", "lon"), np.full((2, 2), -1.0), {"standard_name": "northward_wind"})},
        coords={"lat": ("lat", [0.0, 1.0], {"units": "degrees_north"}),
                "lon": ("lon", [0.0, 1.0], {"units": "degrees_east"})},
    )
    f = from_xarray(ds)
    assert f.info["variables"] == ["a", "b"]
    assert f.time_span is None
    assert tuple(map(float, f.velocity(0.0, 0.5, 0.5))) == (3.0, -1.0)


def test_uniform_and_double_gyre():
    u, v = UniformField(0.2, -0.1).velocity([0.0, 1.0], [10.0, 11.0], [5.0, 6.0])
    assert np.all(u == 0.2) and np.all(v == -0.1)
    g = double_gyre(max_speed=0.3)
    lat = np.linspace(g.extent.lat_min, g.extent.lat_max, 41)
    lon = np.linspace(g.extent.lon_min, g.extent.lon_max, 81)
    LA, LO = np.meshgrid(lat, lon)
    uu, vv = g.velocity(0.0, LA, LO)
    # At t = 0 the gyre is steady-shaped: max speed pi A (scaled to 0.3 m/s) at the centres'
    # edges; the walls y = 0 and y = L carry no normal flow.
    assert np.max(np.hypot(uu, vv)) == pytest.approx(0.3, rel=1e-2)
    np.testing.assert_allclose(vv[:, 0], 0.0, atol=1e-12)


def test_several_files_merge_along_time(tmp_path):
    """Two files holding consecutive time chunks read as one field spanning both."""
    u, v = _linear_arrays()
    first, second = tmp_path / "a.nc", tmp_path / "b.nc"
    copernicus_dataset(LAT, LON, TIMES[:2], [0.5], u[:2], v[:2]).to_netcdf(first)
    copernicus_dataset(LAT, LON, TIMES[2:], [0.5], u[2:], v[2:]).to_netcdf(second)
    f = open_field([first, second])
    assert f.time_span == (0.0, 43200.0)
    uu, vv = f.velocity(40000.0, 30.2, -40.3)
    assert float(uu) == pytest.approx(linear_u(40000.0, 30.2, -40.3), abs=1e-6)
    assert float(vv) == pytest.approx(linear_v(40000.0, 30.2, -40.3), abs=1e-6)
