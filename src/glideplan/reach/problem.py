"""What a glide reach asks: terrain, the glider's position and altitude, how it flies, where
it may land, the safety height and the front grid's resolution (`ReachProblem`)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import check_latlon
from glideplan.reach.model import Glide
from glideplan.terrain.grid import Terrain
from glideplan.validation import check_finite, check_nonnegative, check_physical, check_positive

__all__ = ["Landable", "ReachProblem"]


@dataclass(frozen=True)
class Landable:
    """A place to land: name, WGS84 lat/lon (deg), elevation (m MSL), SeeYou style code."""

    name: str
    lat: float
    lon: float
    elevation_m: float
    style: int = 0
    code: str = ""

    def __post_init__(self) -> None:
        check_latlon(self.lat, self.lon, f"landable {self.name!r}")
        check_finite(f"landable {self.name!r} elevation", self.elevation_m)


@dataclass(frozen=True, eq=False)
class ReachProblem:
    """start = (lat, lon, altitude m MSL); safety_height (m) above the terrain all along and
    above a landable on arrival; resolution_m: the front grid's spacing (None: chosen for
    speed, `glideplan.reach.grid`)."""

    terrain: Terrain
    start: tuple[float, float, float]
    glide: Glide
    landables: tuple[Landable, ...] = ()
    safety_height: float = 300.0
    resolution_m: float | None = None

    def __post_init__(self) -> None:
        if len(self.start) != 3:
            raise InvalidParameterError("start", self.start, "must be (lat, lon, altitude_m)")
        lat, lon = (float(v) for v in check_latlon(self.start[0], self.start[1], "start"))
        alt = check_physical("start altitude", self.start[2], "altitude")  # as final_glide
        object.__setattr__(self, "start", (lat, lon, alt))
        object.__setattr__(self, "landables", tuple(self.landables))
        check_nonnegative("safety_height", self.safety_height)
        if self.resolution_m is not None:
            check_positive("resolution", self.resolution_m)
        ground = float(self.terrain.elevation(lat, lon))
        if not math.isfinite(ground):
            s, n, w, e = self.terrain.extent
            raise InvalidParameterError(
                "start", (lat, lon),
                f"lies outside the terrain (lat {s:g}..{n:g}, lon {w:g}..{e:g}) or on no data")
        if alt < ground:
            raise InvalidParameterError(
                "start altitude", alt, f"is below the terrain there ({ground:.0f} m)")

    @property
    def ground_at_start(self) -> float:
        return float(self.terrain.elevation(self.start[0], self.start[1]))
