"""Write a planned mission in the requested formats: one call, format -> files."""

from __future__ import annotations

import pathlib
from dataclasses import dataclass

from glideplan.errors import InvalidParameterError
from glideplan.formats.interchange import write_csv, write_geojson, write_gpx, write_kml
from glideplan.formats.vehicle_files import (
    write_qgc_plan,
    write_qgc_wpl,
    write_seaglider_targets,
    write_slocum_goto,
)
from glideplan.missions.field_mission import FieldMission
from glideplan.missions.plan import MissionPlan
from glideplan.missions.straight_legs import StraightLegList, straight_leg_list

__all__ = ["EXPORT_FORMATS", "ExportOptions", "export_mission", "parse_formats",
           "skipped_formats"]

EXPORT_FORMATS = ("geojson", "kml", "gpx", "csv", "qgc-wpl", "qgc-plan", "slocum", "seaglider")
GEOGRAPHIC_ONLY = frozenset(EXPORT_FORMATS) - {"csv"}


@dataclass(frozen=True)
class ExportOptions:
    """Acceptance radius (m), largest deviation of the straight legs from the track (m; default
    half the acceptance radius), QGC altitude above home (m), Slocum file number and size."""

    acceptance_radius: float = 100.0
    max_deviation: float | None = None
    altitude: float = 50.0
    goto_number: int = 10
    max_goto_waypoints: int = 8
    name: str = "mission"

    def __post_init__(self) -> None:
        for label, v in (("acceptance-radius", self.acceptance_radius),
                         ("max-deviation", self.max_deviation)):
            if v is not None and not (v == v and 0.0 < v < float("inf")):
                raise InvalidParameterError(label, v, "must be finite and > 0 (m)")
        if not (self.altitude == self.altitude and abs(self.altitude) < float("inf")):
            raise InvalidParameterError("altitude", self.altitude, "must be finite (m)")
        if not isinstance(self.goto_number, int) or not 0 <= self.goto_number <= 99:
            raise InvalidParameterError("goto-number", self.goto_number, "must be in 0..99")
        if not isinstance(self.max_goto_waypoints, int) or self.max_goto_waypoints < 2:
            raise InvalidParameterError(
                "max-goto-waypoints", self.max_goto_waypoints, "must be an integer >= 2")

    @property
    def deviation(self) -> float:
        return self.max_deviation if self.max_deviation is not None else (
            0.5 * self.acceptance_radius)


def parse_formats(text: str | None, geographic: bool = True) -> tuple[str, ...]:
    """The formats of a comma-separated LIST (default: all that suit the route)."""
    if text is None or text.strip().lower() in ("", "all"):
        return EXPORT_FORMATS if geographic else ("csv",)
    out = []
    for f in (t.strip().lower() for t in text.split(",")):
        if f not in EXPORT_FORMATS:
            raise InvalidParameterError("formats", f, f"must be from {', '.join(EXPORT_FORMATS)}")
        if f in GEOGRAPHIC_ONLY and not geographic:
            raise InvalidParameterError(
                "formats", f, "needs a geographic route (lat/lon); this route is in local metres"
            )
        if f not in out:
            out.append(f)
    return tuple(out)


def skipped_formats(text: str | None, geographic: bool) -> tuple[str, ...]:
    """The formats the default list (`--formats` not given, or 'all') leaves out because
    they need lat/lon and the route is in local metres; () otherwise."""
    if geographic or not (text is None or text.strip().lower() in ("", "all")):
        return ()
    return tuple(f for f in EXPORT_FORMATS if f in GEOGRAPHIC_ONLY)


def skipped_warning(skipped: tuple[str, ...]) -> str:
    """The warning naming the formats `skipped_formats` left out."""
    return (f"not written: {', '.join(skipped)} (they need lat/lon waypoints; this route is "
            "in local x,y metres): only csv")


def export_mission(
    plan: MissionPlan | FieldMission,
    out_dir: pathlib.Path,
    formats: tuple[str, ...],
    options: ExportOptions = ExportOptions(),
) -> tuple[dict[str, str | list[str]], StraightLegList]:
    """Write `formats` into `out_dir`; return format -> path (Slocum: list) and the leg list."""
    out_dir.mkdir(parents=True, exist_ok=True)
    legs = straight_leg_list(plan, options.deviation)
    track = plan.track(legs.sample_spacing_m)
    stem = options.name
    files: dict[str, str | list[str]] = {}
    acc = options.acceptance_radius
    for f in formats:
        if f in GEOGRAPHIC_ONLY and not plan.route.geographic:
            raise InvalidParameterError(
                "formats", f, "needs a geographic route (lat/lon); this route is in local metres"
            )
        if f == "geojson":
            files[f] = str(write_geojson(plan, legs, track, out_dir / f"{stem}.geojson"))
        elif f == "kml":
            files[f] = str(write_kml(plan, legs, track, out_dir / f"{stem}.kml"))
        elif f == "gpx":
            files[f] = str(write_gpx(plan, legs, track, out_dir / f"{stem}.gpx"))
        elif f == "csv":
            files[f] = str(write_csv(plan, legs, out_dir / f"{stem}.csv"))
        elif f == "qgc-wpl":
            files[f] = str(write_qgc_wpl(legs, out_dir / f"{stem}.waypoints",
                                         altitude=options.altitude, acceptance_radius=acc))
        elif f == "qgc-plan":
            files[f] = str(write_qgc_plan(legs, out_dir / f"{stem}.plan",
                                          altitude=options.altitude, acceptance_radius=acc,
                                          cruise_speed=plan.speed,
                                          depart=plan.depart_time))
        elif f == "slocum":
            files[f] = [str(p) for p in write_slocum_goto(
                legs, out_dir, goto_number=options.goto_number,
                max_waypoints=options.max_goto_waypoints, acceptance_radius=acc,
                mission_name=stem, depart=plan.depart_time)]
        elif f == "seaglider":
            files[f] = str(write_seaglider_targets(legs, out_dir / "targets",
                                                   acceptance_radius=acc, mission_name=stem,
                                                   depart=plan.depart_time))
    return files, legs
