"""Time-optimal routing through currents and winds.

Public API (for missions and scripts)::

    from glideplan.routing import route, RouteResult
    res = route(field, start=(lat, lon), goal=(lat, lon), speed=V,
                depart=None, resolution=None, depth_range=None)

`field` is a `glideplan.fields.FlowField` (e.g. `open_field("cur.nc")`, `double_gyre()`,
`UniformField(u, v)`) or NetCDF/GRIB path(s), read with `depth_range=(z0, z1)` (m, positive
down; depth-averaged by the trapezoidal rule). `depart` is a `numpy.datetime64`, seconds since
the field's epoch, or None (the field's first time); `resolution` is the grid spacing in
metres (default: ~200 cells across the start-goal box grown by half the distance each side).

`RouteResult` (frozen): `status` ("solved" / "unreachable"), `duration_s`, `distance_m`,
`depart`, `arrive` (datetime64 or None), track `t` (s after departure), `lat`, `lon`,
`heading_deg` (compass, through the water), `endpoint_error_m` (the heading controls flown
through the field with SciPy, distance to the goal), `straight_line_duration_s` (holding the
straight line with a crab angle; None if impossible), `grid_duration_s`,
`refined_duration_s`, `method`, `best_distance_m` (how close the reachable set came),
`field_info`, `stats` (grid size, seconds per phase); `to_dict()` is the CLI's JSON.

Method: the reachable front, phi_t + V|grad phi| + c.grad phi = 0 (Lolla et al. 2012), on a
grid in a local azimuthal-equidistant plane about the start (`levelset`); backtracking along
grad T of the arrival-time map (`backtrack`); a local refinement (`refine`: Zermelo shooting,
else direct single shooting over headings in open water, else polyline collocation with a
land-clearance constraint) kept only when it converges, stays off land, verifies and is not
slower than the grid time (beyond `GRID_TIME_TOLERANCE`, the grid's own error); verification
through the field (`verify`). Bad input raises
`InvalidParameterError`; an unreachable goal is a result, not an exception.

`glider_path(result, radius, ...)` turns a solved route into a flyable Dubins path with the
feasible radius R0' = R0 (1 + eps)^2 and follows it in closed loop through the same field.
"""

from glideplan.routing.route import GRID_TIME_TOLERANCE, RouteResult, route

__all__ = ["GRID_TIME_TOLERANCE", "RouteResult", "route"]
