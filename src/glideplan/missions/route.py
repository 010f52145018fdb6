"""Routes: ordered waypoints with optional headings, geographic or local.

A `Route` holds the waypoints in the mission's local plane (x east, y north, metres) and, for
a geographic route, the WGS84 latitude/longitude they came from and the `LocalProjection`
(azimuthal equidistant about the first waypoint, `glideplan.geodesy`) that maps between them.
Headings are radians CCW from +x inside; NaN marks a free heading that the planner chooses.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.geodesy import LocalProjection, check_latlon, compass_to_heading

__all__ = ["Route"]


@dataclass(frozen=True, eq=False)
class Route:
    """Ordered waypoints: names, local (x, y) in m, headings in rad (NaN = free).

    `lat`, `lon` (degrees) and `projection` are set for a geographic route, None for a local
    one; `source` names the file the route came from (for error messages); `warnings` what
    its reader read despite a flaw (e.g. a GeoJSON feature without geometry, skipped).
    """

    names: tuple[str, ...]
    x: NDArray[np.float64]
    y: NDArray[np.float64]
    headings: NDArray[np.float64]
    lat: NDArray[np.float64] | None = None
    lon: NDArray[np.float64] | None = None
    projection: LocalProjection | None = None
    distortion: float = 0.0
    roundtrip_error_deg: float = 0.0
    source: str = "route"
    labels: tuple[str, ...] = field(default=())
    warnings: tuple[str, ...] = field(default=())  # what the file reader read despite a flaw

    def __post_init__(self) -> None:
        n = len(self.names)
        if n < 2:
            raise InvalidParameterError(
                self.source, f"{n} waypoint(s)", "a route needs at least two waypoints"
            )
        for arr, name in ((self.x, "x"), (self.y, "y")):
            if arr.shape != (n,) or not np.all(np.isfinite(arr)):
                raise InvalidParameterError(f"{self.source} {name}", arr, "must be finite")
        if self.headings.shape != (n,) or np.any(np.isinf(self.headings)):
            raise InvalidParameterError(
                f"{self.source} headings", self.headings, "must be finite or free (empty)"
            )
        labels = self.labels or tuple(f"waypoint {i + 1}" for i in range(n))
        object.__setattr__(self, "labels", labels)
        scale = max(1.0, float(np.max(np.hypot(self.x - self.x[0], self.y - self.y[0]))))
        for i in range(n - 1):
            same = math.hypot(self.x[i + 1] - self.x[i], self.y[i + 1] - self.y[i]) <= (
                1e-9 * scale
            )
            free = math.isnan(self.headings[i]) or math.isnan(self.headings[i + 1])
            if same and free:
                raise InvalidParameterError(
                    f"{self.source}: {labels[i + 1]}",
                    self.names[i + 1],
                    f"is identical to the previous waypoint {self.names[i]!r} while a heading "
                    "is free (the heading there would be arbitrary): remove one or give both "
                    "headings",
                )

    @property
    def n(self) -> int:
        """Number of waypoints."""
        return len(self.names)

    @property
    def geographic(self) -> bool:
        """True for a route given in latitude/longitude."""
        return self.projection is not None

    @property
    def points(self) -> NDArray[np.float64]:
        """(n, 2) local positions (m)."""
        return np.stack([self.x, self.y], axis=-1)

    @property
    def free(self) -> NDArray[np.bool_]:
        """Which headings the planner chooses."""
        return np.isnan(self.headings)

    @classmethod
    def from_local(
        cls,
        names: Sequence[str],
        x: ArrayLike,
        y: ArrayLike,
        headings_rad: ArrayLike | None = None,
        *,
        source: str = "route",
        labels: Sequence[str] = (),
    ) -> Route:
        """A route in local metres; headings in rad CCW from +x (NaN or None = free)."""
        xa = np.asarray(x, dtype=float)
        ya = np.asarray(y, dtype=float)
        h = (
            np.full(xa.shape, np.nan)
            if headings_rad is None
            else np.asarray(headings_rad, dtype=float)
        )
        return cls(tuple(names), xa, ya, h, source=source, labels=tuple(labels))

    @classmethod
    def from_geographic(
        cls,
        names: Sequence[str],
        lat: ArrayLike,
        lon: ArrayLike,
        bearings_deg: ArrayLike | None = None,
        *,
        source: str = "route",
        labels: Sequence[str] = (),
        check_extent: bool = True,
    ) -> Route:
        """A route in WGS84 degrees; headings as compass bearings (deg; NaN or None = free).

        The local plane is the azimuthal equidistant projection about the first waypoint; its
        scale distortion over the waypoints is checked (`LocalProjection.check_extent`) and
        stored, with the worst lat/lon -> local -> lat/lon round-trip error (deg).
        check_extent=False keeps a route of any size (missions through a field route every
        leg on the sphere; the plane then only places the local track, distortion stored).
        """
        la, lo = check_latlon(lat, lon, source)
        if la.ndim != 1 or la.size < 2:
            raise InvalidParameterError(
                source, f"{la.size} waypoint(s)", "a route needs at least two waypoints"
            )
        proj = LocalProjection(float(la[0]), float(lo[0]))
        distortion = proj.check_extent(la, lo) if check_extent else proj.scale_distortion(
            la, lo)
        x, y = proj.to_local(la, lo)
        la2, lo2 = proj.to_geographic(x, y)
        dlon = np.abs((lo2 - lo + 180.0) % 360.0 - 180.0)
        rt = float(max(np.max(np.abs(la2 - la)), np.max(dlon)))
        if bearings_deg is None:
            h = np.full(la.shape, np.nan)
        else:
            b = np.asarray(bearings_deg, dtype=float)
            h = np.where(np.isnan(b), np.nan, compass_to_heading(np.nan_to_num(b)))
        return cls(
            tuple(names),
            np.asarray(x, dtype=float),
            np.asarray(y, dtype=float),
            np.asarray(h, dtype=float),
            lat=la,
            lon=(lo + 180.0) % 360.0 - 180.0,
            projection=proj,
            distortion=distortion,
            roundtrip_error_deg=rt,
            source=source,
            labels=tuple(labels),
        )
