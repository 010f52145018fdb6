"""Export a final glide's start and goal as a SeeYou `.cup` task and an XCSoar `.tsk` task.

Both are written with `aerofiles` (its SeeYou and XCSoar writers); the `.cup` file holds the
two waypoints and a task line "start, start, goal, goal" (SeeYou repeats the takeoff and
landing points), the `.tsk` file a two-point task (start, finish) with cylinder zones.

Elevations are those of the ground at the point, as both formats define them (SeeYou CUP
format, field 6 `elev`: the waypoint's elevation with a unit, here "m"; XCSoar reads the
`altitude` attribute of a task `Waypoint` into the waypoint's elevation). A final glide's
goal is a field on the ground: its elevation is ELEV_M. Its start is where the glider is,
airborne: the ground elevation there is not known, so the start is written with an empty
`elev` (SeeYou) and no `altitude` attribute (XCSoar), never with the glider's altitude; the
altitude goes into the waypoint's description (`desc` / `comment`) instead.
"""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import check_latlon

__all__ = ["TaskPoint", "write_cup_task", "write_tsk_task"]


@dataclass(frozen=True)
class TaskPoint:
    """A named WGS84 point (degrees) with the ground elevation there (m; None: unknown, e.g.
    an airborne start) and a free-text description (written as the waypoint's description)."""

    name: str
    lat: float
    lon: float
    elevation: float | None = None
    description: str = ""

    def __post_init__(self) -> None:
        check_latlon(self.lat, self.lon, self.name)
        if self.elevation is not None and not math.isfinite(self.elevation):
            raise InvalidParameterError(
                f"{self.name} elevation", self.elevation, "must be finite (m) or None (unknown)"
            )


def _code(name: str) -> str:
    return "".join(ch for ch in name.upper() if ch.isalnum())[:6] or "WP"


def write_cup_task(
    path: str | pathlib.Path, start: TaskPoint, goal: TaskPoint, *, description: str = ""
) -> None:
    """SeeYou `.cup`: the two waypoints and one task (aerofiles.seeyou.Writer)."""
    from aerofiles.seeyou import Writer

    with open(path, "wb") as fp:
        writer = Writer(fp)
        for p in (start, goal):
            elevation = "" if p.elevation is None else float(p.elevation)  # "" = unknown
            writer.write_waypoint(
                p.name, _code(p.name), "", p.lat, p.lon, elevation, description=p.description
            )
        writer.write_task(
            description or "final glide", [start.name, start.name, goal.name, goal.name]
        )


def write_tsk_task(
    path: str | pathlib.Path, start: TaskPoint, goal: TaskPoint, *, radius_m: float = 500.0
) -> None:
    """XCSoar `.tsk`: a racing task start -> finish (aerofiles.xcsoar.Writer)."""
    from aerofiles.xcsoar import ObservationZoneType, PointType, TaskType, Writer

    with open(path, "wb") as fp:
        writer = Writer(fp)
        with writer.write_task(type=TaskType.RACING):
            for kind, p in ((PointType.START, start), (PointType.FINISH, goal)):
                with writer.write_point(type=kind):
                    extra: dict[str, object] = {}
                    if p.elevation is not None:
                        extra["altitude"] = float(p.elevation)
                    if p.description:
                        extra["comment"] = p.description
                    writer.write_waypoint(name=p.name, latitude=p.lat, longitude=p.lon, **extra)
                    writer.write_observation_zone(
                        type=ObservationZoneType.CYLINDER, radius=radius_m
                    )
