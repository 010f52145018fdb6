"""Flow fields (ocean currents, winds) for routing: uniform, analytic, gridded from files.

`FlowField.velocity(t, lat, lon) -> (u_east, v_north)` (m/s), vectorised; t in seconds since
the field's `epoch` (or datetime64). `open_field(paths, depth_range)` reads NetCDF (CF) and
GRIB; `from_xarray(ds)` converts a dataset; `double_gyre()` is the built-in example.
NaN = land/missing = obstacle. Queries outside the extent or time span raise naming the bound.

Global files wrap in longitude (`GriddedField.periodic_lon`, `Extent.periodic`): queries at any
longitude interpolate across the seam. ERA5 (`valid_time`, descending latitude), curvilinear
ROMS/NEMO grids (regridded to regular lat/lon), depth layers from the surface and single time
steps are read; what the reader changed or assumed is in `field.warnings` (and `describe()`).
"""

from glideplan.fields.io import pyproj_before_eccodes

pyproj_before_eccodes()  # before any cfgrib/eccodes load (see fields.io): avoids an exit crash

from glideplan.fields.examples import double_gyre  # noqa: E402
from glideplan.fields.field import (  # noqa: E402
    AnalyticField,
    Extent,
    FlowField,
    GriddedField,
    UniformField,
    parse_utc,
    to_seconds,
)
from glideplan.fields.io import depth_average, from_xarray, open_field  # noqa: E402

__all__ = [
    "AnalyticField",
    "Extent",
    "FlowField",
    "GriddedField",
    "UniformField",
    "depth_average",
    "double_gyre",
    "from_xarray",
    "open_field",
    "parse_utc",
    "to_seconds",
]
