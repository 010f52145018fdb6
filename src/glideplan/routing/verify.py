"""Plane checks through the field itself for the glider-scale path (`routing.glider`).

Routes themselves are verified on the sphere (`routing.sphere.fly_headings`).

`integrate_headings` flies the heading controls h(t) (rad in the local plane, linear between
nodes) through the field with SciPy's `solve_ivp` (RK45, rtol 1e-8):

    dx/dt = V cos h(t) + c_x(x, t),   dy/dt = V sin h(t) + c_y(x, t),

with c the field's (east, north) velocity at the point's latitude/longitude, rotated into the
local plane. The endpoint error is the distance (m) from where that lands to the goal.
(The straight line with a crab angle is `routing.sphere.straight_line_duration`.)
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField
from glideplan.geodesy import LocalProjection
from glideplan.routing.grid import local_rotation, rotate_to_local

__all__ = ["FlownRoute", "integrate_headings", "local_current"]

FloatArray = NDArray[np.float64]


class _OffField(Exception):
    pass


def local_current(field_: FlowField, proj: LocalProjection, t: float, x: Any, y: Any) -> tuple[
    FloatArray, FloatArray
]:
    """Field velocity (m/s) at local points, in local axes; NaN on land; raises off the field."""
    lat, lon = proj.to_geographic(x, y)
    u, v = field_.velocity(t, lat, lon)
    cg, sg = local_rotation(proj, np.atleast_1d(lat), np.atleast_1d(lon))
    cx, cy = rotate_to_local(np.atleast_1d(u), np.atleast_1d(v), cg, sg)
    return cx, cy


@dataclass(frozen=True, eq=False)
class FlownRoute:
    """Where the heading controls take the vehicle through the field."""

    t: FloatArray
    x: FloatArray
    y: FloatArray
    on_land: bool
    left_field: str | None
    endpoint_error_m: float


def integrate_headings(
    field_: FlowField,
    proj: LocalProjection,
    speed: float,
    t: FloatArray,
    heading: FloatArray,
    goal_xy: tuple[float, float],
    samples: int = 400,
    hold: bool = False,
) -> FlownRoute:
    """Fly heading(t) from the start (0, 0) at t[0] until t[-1].

    Headings are linear between nodes, or held from each node to the next with `hold`
    (piecewise-constant controls; the integrator restarts at every node).
    """
    from scipy.integrate import solve_ivp

    hd = np.unwrap(np.asarray(heading, dtype=float))
    tt = np.asarray(t, dtype=float)
    land = [False]

    def rhs(s: float, z: FloatArray) -> FloatArray:
        if hold:
            h = float(hd[min(max(int(np.searchsorted(tt, s, side="right")) - 1, 0), hd.size - 1)])
        else:
            h = float(np.interp(s, tt, hd))
        try:
            cx, cy = local_current(field_, proj, s, z[0], z[1])
        except InvalidParameterError as exc:
            raise _OffField(str(exc)) from None
        if not (np.isfinite(cx[0]) and np.isfinite(cy[0])):
            land[0] = True
            cx, cy = np.zeros(1), np.zeros(1)
        return np.array([speed * math.cos(h) + cx[0], speed * math.sin(h) + cy[0]])

    duration = float(tt[-1] - tt[0])
    pieces = [(tt[0], tt[-1])] if not hold else list(itertools.pairwise(tt))
    z = np.zeros(2)
    ts_out, xs_out, ys_out = [np.array([tt[0]])], [np.zeros(1)], [np.zeros(1)]
    for a, b in pieces:
        if b <= a:
            continue
        n_eval = max(2, int(samples * (b - a) / max(duration, 1e-12)) + 1)
        try:
            sol = solve_ivp(rhs, (a, b), z, method="RK45", rtol=1e-8, atol=1e-3,
                            t_eval=np.linspace(a, b, n_eval),
                            max_step=max(min(duration / 100.0, b - a), 1e-6))
        except _OffField as exc:
            return FlownRoute(tt, np.zeros(1), np.zeros(1), land[0], str(exc), math.inf)
        if not sol.success:
            return FlownRoute(tt, np.zeros(1), np.zeros(1), land[0], sol.message, math.inf)
        z = sol.y[:, -1]
        ts_out.append(sol.t[1:])
        xs_out.append(sol.y[0, 1:])
        ys_out.append(sol.y[1, 1:])
    x, y = np.concatenate(xs_out), np.concatenate(ys_out)
    sol_t = np.concatenate(ts_out)
    err = math.hypot(x[-1] - goal_xy[0], y[-1] - goal_xy[1])
    return FlownRoute(sol_t, x, y, land[0], None, err)

