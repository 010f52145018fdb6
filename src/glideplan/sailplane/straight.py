"""Straight final glide in a steady wind, vectorised over many goals (a glide computer's core).

Along the straight ground track of length D with heading chi (rad, CCW from east), a wind
(wx, wy) (m/s, the direction it blows TO) has tailwind component W_t = wx cos chi + wy sin chi
and crosswind component W_c = -wx sin chi + wy cos chi (from the right when positive: it
pushes left). At the speed to fly v (`maccready.speed_to_fly`) the glider crabs by
delta = -asin(W_c / v) (air heading chi + delta) and makes good g = sqrt(v^2 - W_c^2) + W_t:

    altitude loss      = D w(v) / g
    altitude required  = goal elevation + safety height + loss
    arrival margin     = start altitude - altitude required
    glide ratio needed = D / (start altitude - goal elevation - safety height)
    duration           = D / g
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.sailplane.maccready import ground_speed, speed_to_fly
from glideplan.vehicles.sailplane_polar import SailplanePolar

__all__ = ["StraightGlide", "straight_final_glide"]


@dataclass(frozen=True, eq=False)
class StraightGlide:
    """Arrays (one entry per goal) of a straight final glide; SI units.

    `speed` is the airspeed to fly (NaN where the wind makes the goal unreachable), `crab`
    the air heading minus the track (rad), `altitude_loss`/`altitude_required`/
    `arrival_margin` (m; inf/-inf when unreachable), `glide_ratio_required` (inf when the
    start is not above goal elevation + safety height), `duration` (s).
    """

    distance: NDArray[np.float64]
    track: NDArray[np.float64]
    speed: NDArray[np.float64]
    ground_speed: NDArray[np.float64]
    tailwind: NDArray[np.float64]
    crosswind: NDArray[np.float64]
    crab: NDArray[np.float64]
    altitude_loss: NDArray[np.float64]
    altitude_required: NDArray[np.float64]
    arrival_margin: NDArray[np.float64]
    glide_ratio_required: NDArray[np.float64]
    duration: NDArray[np.float64]

    @property
    def reachable(self) -> NDArray[np.bool_]:
        """Arrival margin >= 0 (and the wind allows progress)."""
        return np.isfinite(self.altitude_loss) & (self.arrival_margin >= 0.0)

    def row(self, i: int = 0) -> dict[str, Any]:
        """One goal as plain floats (for JSON)."""
        return {
            k: float(np.ravel(getattr(self, k))[i])
            for k in (
                "distance",
                "track",
                "speed",
                "ground_speed",
                "tailwind",
                "crosswind",
                "crab",
                "altitude_loss",
                "altitude_required",
                "arrival_margin",
                "glide_ratio_required",
                "duration",
            )
        }


def straight_final_glide(
    polar: SailplanePolar,
    distance: ArrayLike,
    track: ArrayLike,
    *,
    wind: tuple[float, float] = (0.0, 0.0),
    mc: ArrayLike = 0.0,
    start_altitude: ArrayLike = 0.0,
    goal_elevation: ArrayLike = 0.0,
    safety_height: ArrayLike = 300.0,
) -> StraightGlide:
    """Straight final glides over `distance` (m) along `track` (rad, CCW from east).

    Everything broadcasts: one call evaluates every airfield in range. `wind` (wx, wy) is the
    air's velocity (m/s) in the same east/north frame; `mc` the MacCready setting (m/s).
    """
    d = np.asarray(distance, dtype=float)
    chi = np.asarray(track, dtype=float)
    wx, wy = float(wind[0]), float(wind[1])
    c, s = np.cos(chi), np.sin(chi)
    wt = wx * c + wy * s
    wc = -wx * s + wy * c
    v = speed_to_fly(polar, mc, wt, wc)
    ok = np.isfinite(v)
    v_safe = np.where(ok, v, polar.v_max)
    g = ground_speed(v_safe, wt, wc)
    ok &= np.isfinite(g) & (g > 0.0)
    g_safe = np.where(ok, g, 1.0)
    loss = np.where(ok, d * polar.sink(v_safe) / g_safe, np.inf)
    floor = np.asarray(goal_elevation, dtype=float) + np.asarray(safety_height, dtype=float)
    required = floor + loss
    margin = np.asarray(start_altitude, dtype=float) - required
    height = np.asarray(start_altitude, dtype=float) - floor
    ratio = np.where(height > 0.0, d / np.where(height > 0.0, height, 1.0), np.inf)
    crab = np.where(ok, -np.arcsin(np.clip(wc / v_safe, -1.0, 1.0)), np.nan)
    d_b, chi_b = np.broadcast_arrays(d, chi)
    return StraightGlide(
        distance=np.asarray(d_b, dtype=float),
        track=np.asarray(chi_b, dtype=float),
        speed=np.where(ok, v_safe, np.nan),
        ground_speed=np.where(ok, g_safe, np.nan),
        tailwind=wt,
        crosswind=wc,
        crab=crab,
        altitude_loss=loss,
        altitude_required=required,
        arrival_margin=margin,
        glide_ratio_required=ratio,
        duration=np.where(ok, d / g_safe, np.inf),
    )
