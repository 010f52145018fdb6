"""Geography at the edges: WGS84 lat/lon, compass bearings, and a local metric projection.

Inside glideplan positions are metres in a local plane (x east, y north) and headings are
radians counter-clockwise from +x (east). Outside, positions are WGS84 latitude/longitude in
decimal degrees and headings are compass bearings (degrees clockwise from true north); a wind
is given by the compass direction it blows FROM (converted by `glideplan.units.wind_from_compass`
and `wind_to_compass`). This module is the one place that converts positions and bearings.

The local plane is an azimuthal equidistant projection about an origin (pyproj/PROJ `aeqd`
on the WGS84 ellipsoid): distances and bearings from the origin are exact, and the scale
error elsewhere grows as about (d / R_earth)^2 / 6 with the distance d from the origin
(1e-3 at about 490 km).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError

__all__ = [
    "EARTH_RADIUS_M",
    "MAX_SCALE_DISTORTION",
    "LocalProjection",
    "check_latlon",
    "compass_to_heading",
    "destination",
    "geodesic_distance_bearing",
    "heading_to_compass",
    "rhumb_destination",
]

#: Largest relative scale error of the local projection accepted over a mission's extent.
MAX_SCALE_DISTORTION = 1e-3

#: The one Earth radius of every spherical computation (m): the IUGG mean radius
#: R1 = (2a + b) / 3 of WGS84 (Moritz 2000), used by the router, the fronts, the terrain
#: grids, glide reach and the synthetic fields alike. (Ellipsoidal work uses pyproj.)
EARTH_RADIUS_M = 6_371_008.8


def destination(lat: ArrayLike, lon: ArrayLike, bearing: ArrayLike, dist: ArrayLike) -> tuple[
    NDArray[np.float64], NDArray[np.float64]
]:
    """The point `dist` m from (lat, lon) deg along the GREAT CIRCLE of initial compass
    `bearing` (rad, clockwise from north) on the sphere of radius `EARTH_RADIUS_M`:
    phi2 = asin(sin phi1 cos d + cos phi1 sin d cos b),
    lam2 = lam1 + atan2(sin b sin d cos phi1, cos d - sin phi1 sin phi2), d = dist / R;
    (lat, lon) deg, lon continuous with the input's (not wrapped). Vectorised."""
    p1, l1 = np.radians(lat), np.radians(lon)
    d = np.asarray(dist, dtype=float) / EARTH_RADIUS_M
    b = np.asarray(bearing, dtype=float)
    p2 = np.arcsin(np.clip(np.sin(p1) * np.cos(d) + np.cos(p1) * np.sin(d) * np.cos(b), -1, 1))
    l2 = l1 + np.arctan2(np.sin(b) * np.sin(d) * np.cos(p1), np.cos(d) - np.sin(p1) * np.sin(p2))
    return np.degrees(p2), np.degrees(l2)


def rhumb_destination(lat: float, lon: float, chi: float, s: ArrayLike) -> tuple[
    NDArray[np.float64], NDArray[np.float64]
]:
    """Points `s` m from (lat, lon) deg along the RHUMB LINE (constant compass course, as a
    pilot holds one) of direction `chi` (rad, counter-clockwise from east): phi = phi0 +
    s sin(chi) / R, lam = lam0 + s cos(chi) / (R q) with q = dphi / dpsi from the isometric
    latitude psi = ln tan(pi/4 + phi/2) (q = cos phi0 on a parallel). Vectorised over `s`."""
    s = np.asarray(s, dtype=float)
    p0 = math.radians(lat)
    p = p0 + s * math.sin(chi) / EARTH_RADIUS_M
    dpsi = np.log(np.tan(0.25 * np.pi + 0.5 * p)) - math.log(math.tan(0.25 * math.pi + 0.5 * p0))
    with np.errstate(invalid="ignore", divide="ignore"):
        q = np.where(np.abs(dpsi) > 1e-12, (p - p0) / np.where(dpsi == 0, 1, dpsi), math.cos(p0))
    dl = s * math.cos(chi) / (EARTH_RADIUS_M * q)
    return np.degrees(p), lon + np.degrees(dl)


def compass_to_heading(bearing_deg: ArrayLike) -> NDArray[np.float64] | float:
    """Heading (rad, CCW from east, in (-pi, pi]) of a compass bearing (deg, CW from north).

    heading = pi/2 - radians(bearing)
    """
    h = np.pi / 2 - np.radians(np.asarray(bearing_deg, dtype=float))
    out = np.pi - np.mod(np.pi - h, 2 * np.pi)
    return float(out) if out.ndim == 0 else out


def heading_to_compass(heading_rad: ArrayLike) -> NDArray[np.float64] | float:
    """Compass bearing (deg, CW from north, in [0, 360)) of a heading (rad, CCW from east).

    bearing = degrees(pi/2 - heading) mod 360
    """
    b = np.mod(np.degrees(np.pi / 2 - np.asarray(heading_rad, dtype=float)), 360.0)
    b = np.where(b >= 360.0, 0.0, b)  # -0 and round-off at 360
    return float(b) if b.ndim == 0 else b


def check_latlon(lat: ArrayLike, lon: ArrayLike, name: str = "position") -> tuple[
    NDArray[np.float64], NDArray[np.float64]
]:
    """Return (lat, lon) as float arrays; latitudes in [-90, 90], longitudes in [-180, 360]."""
    try:
        la = np.asarray(lat, dtype=float)
        lo = np.asarray(lon, dtype=float)
    except (TypeError, ValueError):
        raise InvalidParameterError(
            name, (lat, lon), "latitude/longitude must be numbers"
        ) from None
    if not (np.all(np.isfinite(la)) and np.all(np.isfinite(lo))):
        raise InvalidParameterError(name, (lat, lon), "latitude/longitude must be finite")
    if np.any(np.abs(la) > 90.0):
        bad = float(la.flat[int(np.argmax(np.abs(la)))])
        raise InvalidParameterError(f"{name} latitude", bad, "must be in [-90, 90] degrees")
    if np.any(lo < -180.0) or np.any(lo > 360.0):
        bad = float(lo.flat[int(np.argmax(np.abs(lo)))])
        raise InvalidParameterError(f"{name} longitude", bad, "must be in [-180, 360] degrees")
    return la, lo


def _geod() -> Any:
    from pyproj import Geod

    return Geod(ellps="WGS84")


def geodesic_distance_bearing(
    lat1: ArrayLike, lon1: ArrayLike, lat2: ArrayLike, lon2: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Geodesic distance (m) and initial compass bearing (deg, [0, 360)) on WGS84, vectorised."""
    la1, lo1 = check_latlon(lat1, lon1, "from")
    la2, lo2 = check_latlon(lat2, lon2, "to")
    az, _, dist = _geod().inv(lo1, la1, lo2, la2)
    return np.asarray(dist, dtype=float), np.mod(np.asarray(az, dtype=float), 360.0)


@dataclass(frozen=True)
class LocalProjection:
    """Azimuthal equidistant plane about (lat0, lon0): x east, y north, in metres (WGS84)."""

    lat0: float
    lon0: float

    def __post_init__(self) -> None:
        check_latlon(self.lat0, self.lon0, "projection origin")
        if abs(self.lat0) > 89.9:
            raise InvalidParameterError(
                "projection origin latitude",
                self.lat0,
                "must be within 89.9 degrees of the equator",
            )

    @cached_property
    def _proj(self) -> Any:
        from pyproj import Proj

        return Proj(
            proj="aeqd", lat_0=self.lat0, lon_0=self.lon0, datum="WGS84", units="m"
        )

    def to_local(self, lat: ArrayLike, lon: ArrayLike) -> tuple[NDArray[np.float64], ...]:
        """(x, y) in metres of WGS84 (lat, lon) in degrees; vectorised. Longitudes may be
        unwrapped (a track continuous across 180 deg runs to -540..540)."""
        try:
            lo_in = np.asarray(lon, dtype=float)
        except (TypeError, ValueError):
            lo_in = None  # check_latlon names it
        if lo_in is not None and np.all(np.isfinite(lo_in)) and np.all(np.abs(lo_in) <= 540.0):
            lon = (lo_in + 180.0) % 360.0 - 180.0
        la, lo = check_latlon(lat, lon)
        lo = (lo + 180.0) % 360.0 - 180.0
        x, y = self._proj(lo, la)
        return np.asarray(x, dtype=float), np.asarray(y, dtype=float)

    def to_geographic(self, x: ArrayLike, y: ArrayLike) -> tuple[NDArray[np.float64], ...]:
        """(lat, lon) in degrees (lon in [-180, 180)) of local (x, y) in metres; vectorised."""
        xa = np.asarray(x, dtype=float)
        ya = np.asarray(y, dtype=float)
        if not (np.all(np.isfinite(xa)) and np.all(np.isfinite(ya))):
            raise InvalidParameterError("local position", (x, y), "must be finite")
        lo, la = self._proj(xa, ya, inverse=True)
        lo = (np.asarray(lo, dtype=float) + 180.0) % 360.0 - 180.0
        return np.asarray(la, dtype=float), lo

    def scale_distortion(self, lat: ArrayLike, lon: ArrayLike) -> float:
        """Largest relative scale error |k - 1| (meridian or parallel) at the given points."""
        la, lo = check_latlon(lat, lon)
        lo = (lo + 180.0) % 360.0 - 180.0
        f = self._proj.get_factors(lo.ravel(), la.ravel())
        h = np.asarray(f.meridional_scale, dtype=float)
        k = np.asarray(f.parallel_scale, dtype=float)
        worst = np.nanmax(np.abs(np.concatenate([h - 1.0, k - 1.0])))
        # infinite at the centre's antipode (the projection is singular there), not 0
        return float(worst) if not np.isnan(worst) else 0.0

    def check_extent(
        self, lat: ArrayLike, lon: ArrayLike, max_distortion: float = MAX_SCALE_DISTORTION
    ) -> float:
        """Return the scale distortion over the points; raise if it exceeds `max_distortion`."""
        d = self.scale_distortion(lat, lon)
        if d > max_distortion:
            raise InvalidParameterError(
                "extent",
                f"scale error {d:.2e}",
                f"too large for one local projection (limit {max_distortion:g}, about "
                f"{_extent_km(max_distortion):.0f} km from the first point): split the mission",
            )
        return d


def _extent_km(max_distortion: float) -> float:
    # aeqd on a sphere: k = c / sin c ~ 1 + c^2 / 6, so c = sqrt(6 * distortion).
    return math.sqrt(6.0 * max_distortion) * EARTH_RADIUS_M / 1000.0
