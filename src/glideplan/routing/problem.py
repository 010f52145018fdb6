"""The route's problem and what its phases hand on (`RouteProblem`, `RouteGrid`,
`FrontOutcome`, `Candidate`), and the first phase, `setup`: the inputs checked, files read, the
departure, the time limit and its reason fixed (`glideplan.routing.phases`)."""

from __future__ import annotations

import pathlib
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError
from glideplan.fields.field import FlowField, to_seconds
from glideplan.routing.settings import RouteSettings
from glideplan.routing.sphere import gc_distance, unwrap_lon
from glideplan.routing.window import Lattice, Window, WindowCurrents

FloatArray = NDArray[np.float64]


@dataclass(frozen=True, eq=False)
class RouteProblem:
    """What `setup` fixes: the field, start/goal (deg; goal lon unwrapped about the start),
    speed (m/s), departure t0 and limit t_max (s since the field's epoch), why t_max is the
    limit ("time_span" / "max_duration"), the great-circle distance (m), the settings."""

    field_: FlowField
    start: tuple[float, float]
    goal: tuple[float, float]
    speed: float
    t0: float
    t_max: float
    limit_reason: str
    distance_m: float
    settings: RouteSettings
    depart: np.datetime64 | None
    warnings: tuple[str, ...] = ()


@dataclass(eq=False)
class RouteGrid:
    """What `grid` builds: the lattice, the window, the field on it, the clearance (m) and
    the obstacle nodes (land, or within the clearance of land)."""

    lattice: Lattice
    window: Window
    currents: WindowCurrents
    clearance_m: float
    obstacle: NDArray[np.bool_]
    land: NDArray[np.bool_]
    warnings: list[str] = field(default_factory=list)
    coast_xyz: FloatArray = field(default_factory=lambda: np.zeros((0, 3)))
    #: the clearance of the front's obstacles (m): less than clearance_m when the route keeps
    #: the clearance at the land mask's resolution (`routing.coast`)
    front_clearance_m: float | None = None

    @property
    def spacing_m(self) -> float:
        return self.lattice.spacing_m


@dataclass(frozen=True, eq=False)
class FrontOutcome:
    """The front's answer: arrival times (s since epoch, inf never) on the final window, the
    goal's arrival (None if not reached), the stop reason (kernel's) and, when unreachable,
    the route's `unreachable_reason`; the closest approach (m); the kernel's problem (for
    backtracking); steps and window growths."""

    arrival: FloatArray
    goal_time: float | None
    reason: str
    unreachable_reason: str | None
    closest_m: float
    problem: Any
    steps: int
    growths: int
    state: Any = None


@dataclass(frozen=True, eq=False)
class Candidate:
    """A route to verify: vertex times (s since epoch), lat/lon (deg, lon continuous),
    compass headings (rad) of the through-water velocity, held per leg (`hold`) or linear in
    time; its duration (s) and method name."""

    method: str
    t: FloatArray
    lat: FloatArray
    lon: FloatArray
    chi: FloatArray
    hold: bool
    duration: float
    note: str = ""



def _as_field(field_: Any, depth_range: tuple[float, float] | None) -> FlowField:
    if isinstance(field_, FlowField):
        if depth_range is not None:
            raise InvalidParameterError(
                "depth_range", depth_range, "applies when reading files; average the field first"
            )
        return field_
    if isinstance(field_, (str, pathlib.Path)) or (
        isinstance(field_, Sequence) and all(isinstance(p, (str, pathlib.Path)) for p in field_)
    ):
        from glideplan.fields.io import open_field

        return open_field(field_, depth_range=depth_range)
    raise InvalidParameterError("field", type(field_).__name__, "must be a FlowField or file(s)")


def _check_point(fld: FlowField, t: float, point: Any, name: str) -> tuple[float, float]:
    from glideplan.validation import check_finite

    try:
        lat, lon = (check_finite(name, float(point[0])), check_finite(name, float(point[1])))
    except (TypeError, ValueError, IndexError):
        raise InvalidParameterError(name, point, "must be (lat, lon) in degrees") from None
    if abs(lat) > 90.0:
        raise InvalidParameterError(name, point, "latitude must lie in [-90, 90]")
    fld.check_position(lat, lon, name=name)
    if abs(lat) > 85.0:
        raise InvalidParameterError(name, point, "latitude beyond +-85 deg: the router's "
                                    "lat/lon grid does not reach the poles")
    u, v = fld.velocity(t, lat, lon)
    if not (np.all(np.isfinite(u)) and np.all(np.isfinite(v))):
        raise InvalidParameterError(name, (lat, lon), fld.nan_cause(t, lat, lon))
    return lat, lon


def setup(field_: Any, start: Any, goal: Any, speed: float, depart: Any = None,
          depth_range: tuple[float, float] | None = None,
          settings: RouteSettings | None = None) -> RouteProblem:
    """Check the inputs and fix the problem (module docstring). Raises InvalidParameterError."""
    from glideplan.validation import check_physical

    settings = settings or RouteSettings()
    speed = check_physical("speed", speed, "speed")
    fld = _as_field(field_, depth_range)
    if (getattr(fld, "info", None) or {}).get("medium") == "water":  # a current, not a wind
        check_physical("speed", speed, "water_speed")
    if depart is None:
        t0 = fld.time_span[0] if fld.time_span is not None else 0.0
        if fld.time_span is None and fld.time_levels is not None:
            t0 = float(fld.time_levels[0])
        tl = getattr(fld, "times", None)
        if fld.time_span is None and tl is not None and np.size(tl) == 1:
            t0 = float(np.ravel(tl)[0])
    else:
        t0 = float(to_seconds(depart, fld.epoch))
    fld.check_time(t0)
    a = _check_point(fld, t0, start, "from")
    b = _check_point(fld, t0, goal, "to")
    b = (b[0], float(unwrap_lon(b[1], a[1])))
    dist = float(gc_distance(a[0], a[1], b[0], b[1]))
    md = settings.max_duration
    if fld.time_span is not None:
        t_max, reason = fld.time_span[1], "time_span"
        if md is not None and t0 + md < t_max:
            t_max, reason = t0 + md, "max_duration"
    else:
        t_max = t0 + (md if md is not None else max(10.0 * dist / speed, 3600.0))
        reason = "max_duration"
    depart_dt = None if fld.epoch is None else fld.epoch + np.timedelta64(round(t0 * 1e3), "ms")
    return RouteProblem(fld, a, b, float(speed), float(t0), float(t_max), reason, dist,
                        settings, depart_dt, tuple(getattr(fld, "warnings", ())))
