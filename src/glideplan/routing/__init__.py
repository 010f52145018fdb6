"""Time-optimal routing through currents and winds, on the sphere.

Public API (for missions and scripts)::

    from glideplan.routing import route, RouteResult, RouteSettings
    res = route(field, start=(lat, lon), goal=(lat, lon), speed=V,
                depart=None, resolution=None, depth_range=None,
                settings=RouteSettings(land_clearance_m=2000.0))

`field` is a `glideplan.fields.FlowField` (e.g. `open_field("cur.nc")`, `double_gyre()`,
`UniformField(u, v)`) or NetCDF/GRIB path(s), read with `depth_range=(z0, z1)` (m, positive
down; depth-averaged). `depart` is a `numpy.datetime64`, seconds since the field's epoch, or
None (the field's first time); `resolution` is the grid spacing in metres (default: the
start-goal distance over ~250 cells).

`RouteResult` (frozen, `glideplan.results.Outcome`): `status` (SOLVED / UNREACHABLE /
NOT_VERIFIED), `ok`, `message`, `warnings`, `duration_s`, `distance_m`, `track` (a
`glideplan.track.Track`, lat/lon continuous across 180 deg), `endpoint_error_m` (the heading
controls flown through the field with SciPy, distance to the goal), `unreachable_reason`,
`best_distance_m`, `land_clearance_m`, `front` (the arrival-time map), `to_dict()` (the
CLI's JSON), `plot()`.

Method (`phases`): the reachable front, phi_t + V|grad phi| + c.grad phi = 0 (Lolla et al.
2012), on a lat/lon grid with the sphere's metric (`glideplan.fronts`), in a window about
start and goal that grows with the front and wraps in longitude for global fields
(`window`); land and a clearance around it are obstacles; backtracking along the kernel's
characteristic, each leg held with its crab angle; Zermelo shooting on the sphere
(`zermelo`) where it converges; verification through the field (`sphere.fly_headings`).

`glider_path(result, radius, ...)` turns a solved route into a flyable Dubins path with the
feasible radius R0' = R0 (1 + eps)^2 and follows it in closed loop through the same field.
"""

from glideplan.routing.result import RouteResult
from glideplan.routing.route import GRID_TIME_TOLERANCE, route
from glideplan.routing.settings import RouteSettings

__all__ = ["GRID_TIME_TOLERANCE", "RouteResult", "RouteSettings", "route"]
