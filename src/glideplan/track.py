"""`Track`: the one track type: times, positions and headings along a planned or flown path.

Local tracks carry x, y (m, in a plane) and heading (rad, counter-clockwise from +x);
geographic tracks also carry lat, lon (WGS84 degrees, longitudes unwrapped so the track is
continuous across 180 deg) and report headings as compass bearings at the edges (`to_dict`).
Optional: `alt` (altitude, m, e.g. a glide's profile) and `leg` (the index of the mission leg
each sample belongs to).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from glideplan.errors import InvalidParameterError

__all__ = ["Track", "iso_times"]

FloatArray = NDArray[np.float64]


def iso_times(depart: np.datetime64 | None, t_s: Any) -> list[str | None]:
    """ISO 8601 UTC (ms, 'Z') of depart + t for each t (s); None each without a departure,
    and None for a t that is not finite (a waypoint the mission never reaches)."""
    t = np.atleast_1d(np.asarray(t_s, dtype=float))
    if depart is None:
        return [None] * t.size
    fin = np.isfinite(t)
    ms = np.round(np.where(fin, t, 0.0) * 1e3).astype(np.int64).astype("timedelta64[ms]")
    when = np.asarray(depart).astype("datetime64[ms]") + ms
    return [str(v) + "Z" if ok else None for v, ok in zip(when, fin, strict=True)]


def _empty() -> FloatArray:
    return np.zeros(0)


@dataclass(frozen=True, eq=False)
class Track:
    """Samples along a path: t (s), x, y (m), heading (rad); optional lat, lon (deg), alt (m)
    and leg (int index).

    All arrays have one length. `lat`/`lon` (`alt`, `leg`) are empty when not given.
    """

    t: FloatArray
    x: FloatArray
    y: FloatArray
    heading: FloatArray
    lat: FloatArray = None  # type: ignore[assignment]
    lon: FloatArray = None  # type: ignore[assignment]
    alt: FloatArray = None  # type: ignore[assignment]
    leg: NDArray[np.intp] = None  # type: ignore[assignment]

    def __post_init__(self) -> None:
        for name in ("t", "x", "y", "heading", "lat", "lon", "alt"):
            val = getattr(self, name)
            arr = _empty() if val is None else np.asarray(val, dtype=float)
            object.__setattr__(self, name, arr)
        leg = np.zeros(0, dtype=np.intp) if self.leg is None else np.asarray(self.leg, np.intp)
        object.__setattr__(self, "leg", leg)
        n = self.t.size
        for name in ("x", "y", "heading"):
            if getattr(self, name).size != n:
                raise InvalidParameterError(f"track {name}", getattr(self, name).size,
                                            f"must have {n} samples like t")
        if (self.lat.size or self.lon.size) and not (self.lat.size == self.lon.size == n):
            raise InvalidParameterError("track lat/lon", (self.lat.size, self.lon.size),
                                        f"must both have {n} samples like t")
        for name in ("alt", "leg"):
            size = getattr(self, name).size
            if size and size != n:
                raise InvalidParameterError(f"track {name}", size,
                                            f"must have {n} samples like t (or none)")

    @property
    def size(self) -> int:
        return int(self.t.size)

    @property
    def geographic(self) -> bool:
        return self.lat.size > 0

    @property
    def heading_deg(self) -> FloatArray:
        """Compass bearings (deg clockwise from north) of the headings."""
        from glideplan.geodesy import heading_to_compass

        return np.asarray(heading_to_compass(self.heading), dtype=float)

    def to_dict(self) -> dict[str, Any]:
        """JSON: t, and lat/lon/heading_deg (geographic) or x/y/heading (plane); alt and leg
        when the track has them."""
        out: dict[str, Any]
        if self.geographic:
            lon = (self.lon + 180.0) % 360.0 - 180.0  # the edge: -180..180 as files expect
            out = {"t": self.t.tolist(), "lat": self.lat.tolist(), "lon": lon.tolist(),
                   "heading_deg": self.heading_deg.tolist()}
        else:
            out = {"t": self.t.tolist(), "x": self.x.tolist(), "y": self.y.tolist(),
                   "heading": self.heading.tolist()}
        if self.alt.size:
            out["alt"] = self.alt.tolist()
        if self.leg.size:
            out["leg"] = self.leg.tolist()
        return out

    @classmethod
    def empty(cls) -> Track:
        return cls(_empty(), _empty(), _empty(), _empty())
