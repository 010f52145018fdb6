"""Export a final glide's start and goal as a SeeYou `.cup` task and an XCSoar `.tsk` task.

Both are written with `aerofiles` (its SeeYou and XCSoar writers); the `.cup` file holds the
two waypoints and a task line "start, start, goal, goal" (SeeYou repeats the takeoff and
landing points), the `.tsk` file a two-point task (start, finish) with cylinder zones.
"""

from __future__ import annotations

import pathlib
from dataclasses import dataclass

from glideplan.geodesy import check_latlon

__all__ = ["TaskPoint", "write_cup_task", "write_tsk_task"]


@dataclass(frozen=True)
class TaskPoint:
    """A named WGS84 point (degrees) with an elevation (m)."""

    name: str
    lat: float
    lon: float
    elevation: float = 0.0

    def __post_init__(self) -> None:
        check_latlon(self.lat, self.lon, self.name)


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
            writer.write_waypoint(p.name, _code(p.name), "", p.lat, p.lon, p.elevation)
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
                    writer.write_waypoint(
                        name=p.name, latitude=p.lat, longitude=p.lon, altitude=p.elevation
                    )
                    writer.write_observation_zone(
                        type=ObservationZoneType.CYLINDER, radius=radius_m
                    )
