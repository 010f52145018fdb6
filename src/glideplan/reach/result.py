"""`ReachPoint` (one landable's answer) and `ReachResult` (the glide reach's outcome)."""

from __future__ import annotations

import math
import pathlib
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from glideplan.reach.flight import FlownPath
from glideplan.reach.footprint import Polygon
from glideplan.reach.model import Glide
from glideplan.reach.problem import Landable
from glideplan.results import Outcome
from glideplan.terrain.grid import Terrain
from glideplan.track import Track

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["ReachPoint", "ReachResult"]

FloatArray = NDArray[np.float64]


def _num(x: float | None) -> float | None:
    return None if x is None or not math.isfinite(x) else float(x)


def flown_track(path: FlownPath, lat0: float, lon0: float) -> Track:
    """The one track type: t (s), x/y (m, east/north of (lat0, lon0), equirectangular),
    air heading (rad CCW from east), lat, lon."""
    from glideplan.terrain.grid import EARTH_RADIUS_M as R

    x = R * math.cos(math.radians(lat0)) * np.radians(path.lon - lon0)
    y = R * np.radians(path.lat - lat0)
    return Track(path.t, x, y, path.heading, path.lat, path.lon)


@dataclass(frozen=True, eq=False)
class ReachPoint:
    """One landable: reachable (verified arrival >= elevation + safety height, clearance >=
    safety all along), arrival altitude (m MSL, verified) and margin above elevation +
    safety, distance along the path (m), detour (the path leaves the straight line by more
    than the grid's resolution), the flown path (None when none was found), `verified`
    (a path was flown and kept its clearance), front_arrival_altitude_m (the grid's answer),
    `note` (why unreachable)."""

    landable: Landable
    reachable: bool
    arrival_altitude_m: float | None
    arrival_margin_m: float | None
    distance_m: float | None
    detour: bool
    path: FlownPath | None
    verified: bool
    front_arrival_altitude_m: float | None
    min_clearance_m: float | None
    endpoint_error_m: float | None
    max_offset_m: float | None
    note: str
    track: Track | None = None
    #: altitude (m) missing to reach the field (None when reachable or unknown)
    short_by_m: float | None = None
    #: the field lies on missing terrain (void or no tile): not judged
    terrain_missing: bool = False

    def to_dict(self) -> dict[str, Any]:
        p = self.landable
        track = None
        if self.track is not None and self.path is not None:
            track = self.track.to_dict() | {
                "altitude_m": self.path.altitude.tolist(),
                "airspeed_kmh": (self.path.speed * 3.6).tolist(),
            }
        return {
            "name": p.name, "lat": p.lat, "lon": p.lon, "elevation_m": p.elevation_m,
            "reachable": self.reachable,
            "arrival_altitude_m": _num(self.arrival_altitude_m),
            "arrival_margin_m": _num(self.arrival_margin_m),
            "distance_m": _num(self.distance_m),
            "detour": self.detour,
            "verified": self.verified,
            "min_clearance_m": _num(self.min_clearance_m),
            "front_arrival_altitude_m": _num(self.front_arrival_altitude_m),
            "endpoint_error_m": _num(self.endpoint_error_m),
            "note": self.note,
            "short_by_m": _num(self.short_by_m),
            "terrain_missing": self.terrain_missing,
            "track": track,
        }


@dataclass(frozen=True, eq=False, kw_only=True)
class ReachResult(Outcome):
    """The glide reach (`glideplan.reach.glide_reach`): status SOLVED when the solve ran;
    points in the landables' order; footprint polygons (lon, lat rings); the front grid
    (lat, lon, altitude lost `arrival`, pooled terrain `z`, clearance `margin`); clipped:
    the terrain's sides the footprint reaches (it is cut there)."""

    start: tuple[float, float, float]
    safety_height: float
    glide: Glide
    points: tuple[ReachPoint, ...]
    footprint: list[Polygon]
    lat: FloatArray
    lon: FloatArray
    arrival: FloatArray
    margin: FloatArray
    z: FloatArray
    terrain: Terrain
    clipped: tuple[str, ...]
    resolution_m: float
    pooling: int
    stop_reason: str
    front_steps: int = 0
    timings: dict[str, float] = field(default_factory=dict)
    #: en-route terrain clearance (m) and arrival height above a field (m); None: both are
    #: `safety_height` (results built before the two heights existed)
    terrain_clearance: float | None = None
    arrival_height: float | None = None

    @property
    def nodes(self) -> int:
        return int(self.arrival.size)

    def to_dict(self) -> dict[str, Any]:
        lat, lon, alt = self.start
        return {
            **super().to_dict(),
            "start": {"lat": lat, "lon": lon, "altitude_m": alt,
                      "ground_m": _num(float(self.terrain.elevation(lat, lon)))},
            "safety_height_m": self.safety_height,
            "terrain_clearance_m": (self.safety_height if self.terrain_clearance is None
                                    else self.terrain_clearance),
            "arrival_height_m": (self.safety_height if self.arrival_height is None
                                 else self.arrival_height),
            "glide": self.glide.to_dict(),
            "polar": self.glide.polar.name,
            "grid": {"resolution_m": self.resolution_m, "pooling": self.pooling,
                     "shape": list(self.arrival.shape), "stop_reason": self.stop_reason,
                     "front_steps": self.front_steps},
            "footprint": {"polygons": self.footprint_coordinates(),
                          "count": len(self.footprint), "clipped": list(self.clipped),
                          "area_km2": self.footprint_area_km2()},
            "points": [p.to_dict() for p in self.points],
            "timings_s": dict(self.timings),
        }

    def footprint_coordinates(self) -> list[list[list[list[float]]]]:
        """The footprint as GeoJSON MultiPolygon coordinates: polygons of closed rings of
        [lon, lat] (deg, 1e-7), exterior first, split at the antimeridian (RFC 7946 3.1.9)."""
        from glideplan.formats.antimeridian import split_polygon_at_antimeridian

        return [[[[round(float(x), 7), round(float(y), 7)] for x, y in ring] for ring in part]
                for poly in self.footprint for part in split_polygon_at_antimeridian(poly)]

    def footprint_area_km2(self) -> float:
        """Area of the footprint (km^2), from the clearance on the grid (cells with m >= 0)."""
        from glideplan.terrain.grid import EARTH_RADIUS_M as R

        dlat = math.radians(float(self.lat[1] - self.lat[0]))
        dlon = math.radians(float(self.lon[1] - self.lon[0]))
        cell = (R * dlat) * R * np.cos(np.radians(self.lat)) * dlon
        return float(np.sum((self.margin >= 0) * cell[:, None]) / 1e6)

    def plot(self, ax: Any = None, **kwargs: Any) -> Figure:
        """Hillshade, footprint, landables coloured by margin, paths, wind (`reach.plot`)."""
        from glideplan.reach.plot import plot_reach
        from glideplan.results import as_figure

        return as_figure(plot_reach(self, ax=ax, **kwargs))

    def to_geojson(self) -> dict[str, Any]:
        from glideplan.reach.export import reach_geojson

        return reach_geojson(self)

    def write_geojson(self, path: str | pathlib.Path) -> pathlib.Path:
        from glideplan.reach.export import write_geojson

        return write_geojson(self, path)

    def write_kml(self, path: str | pathlib.Path) -> pathlib.Path:
        from glideplan.reach.export import write_kml

        return write_kml(self, path)
