"""MacCready speed to fly in wind, vectorised over many glides (MacCready 1954; section 5.2).

Along a straight ground track with tailwind component W_t (wind along the track, m/s) and
crosswind component W_c, the glider crabs so that its ground track stays on the line: its
ground speed at airspeed v is g(v) = sqrt(v^2 - W_c^2) + W_t. The speed to fly minimises the
altitude lost (plus MC times the time, MacCready's price of time) per metre of track,

    f(v) = (w(v) + MC) / g(v),   v in [v_lo, v_max].

f is a convex positive function over a concave positive one, hence quasi-convex: its
stationary point (w'(v) g(v) = (w(v) + MC) g'(v)) is found by bisection on that sign. With no
crosswind and a headwind H = -W_t it is the closed form
v = H + sqrt(H^2 + (b H + c + MC) / a). The optimum is clipped to the speed range.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.vehicles.sailplane_polar import SailplanePolar

__all__ = ["ground_speed", "maccready_table", "speed_to_fly"]

_BISECTIONS = 52


def ground_speed(
    speed: ArrayLike, tailwind: ArrayLike = 0.0, crosswind: ArrayLike = 0.0
) -> NDArray[np.float64]:
    """Ground speed along the track, sqrt(v^2 - W_c^2) + W_t (m/s); NaN where |W_c| >= v."""
    v = np.asarray(speed, dtype=float)
    wc = np.asarray(crosswind, dtype=float)
    with np.errstate(invalid="ignore"):
        along = np.sqrt(np.where(v > np.abs(wc), v**2 - wc**2, np.nan))
    return along + np.asarray(tailwind, dtype=float)


def _slope_sign(
    polar: SailplanePolar, v: np.ndarray, mc: np.ndarray, wt: np.ndarray, wc: np.ndarray
) -> np.ndarray:
    """w'(v) g(v) - (w(v) + MC) g'(v): negative where f still decreases."""
    root = np.sqrt(np.maximum(v**2 - wc**2, 1e-300))
    g = root + wt
    dg = v / root
    return (2.0 * polar.a * v + polar.b) * g - (polar.sink(v) + mc) * dg


def speed_to_fly(
    polar: SailplanePolar,
    mc: ArrayLike = 0.0,
    tailwind: ArrayLike = 0.0,
    crosswind: ArrayLike = 0.0,
) -> NDArray[np.float64]:
    """Airspeed (m/s) minimising (w(v) + MC) / ground speed along a straight track.

    Broadcasts over `mc` (m/s), `tailwind` and `crosswind` (m/s, components along and across
    the track). NaN where no airspeed in the range makes progress along the track (wind too
    strong).
    """
    mc_a, wt, wc = np.broadcast_arrays(
        np.asarray(mc, dtype=float),
        np.asarray(tailwind, dtype=float),
        np.asarray(crosswind, dtype=float),
    )
    wind = np.hypot(wt, wc)
    # lowest airspeed that can hold the track and move along it: v > |W_c|, and v > |W| when
    # the wind has a head component (g(v) = 0 at v = |W|)
    lo = np.maximum(polar.v_min, np.where(wt < 0.0, wind, np.abs(wc)) * (1.0 + 1e-12) + 1e-12)
    hi = np.full_like(lo, polar.v_max)
    feasible = lo < hi
    lo = np.where(feasible, lo, hi)
    # closed form without crosswind
    head = -wt
    with np.errstate(invalid="ignore"):
        disc = head**2 + (polar.b * head + polar.c + mc_a) / polar.a
        closed = head + np.sqrt(np.where(disc >= 0.0, disc, np.nan))
    # bisection with crosswind
    a_, b_ = lo.copy(), hi.copy()
    for _ in range(_BISECTIONS):
        mid = 0.5 * (a_ + b_)
        dec = _slope_sign(polar, mid, mc_a, wt, wc) < 0.0
        a_ = np.where(dec, mid, a_)
        b_ = np.where(dec, b_, mid)
    bisected = 0.5 * (a_ + b_)
    v = np.where(wc == 0.0, np.nan_to_num(closed, nan=hi), bisected)
    v = np.clip(v, lo, hi)
    return np.where(feasible, v, np.nan)


def maccready_table(polar: SailplanePolar, mcs: ArrayLike) -> list[dict[str, float]]:
    """Still-air speed to fly, glide ratio and average cross-country speed for each MC
    (`at_top_speed`: the speed to fly was clipped to v_max).

    Cross-country speed (climbing at MC, gliding at the speed to fly v):
    V_xc = v MC / (w(v) + MC) (0 for MC = 0).
    """
    mc = np.asarray(mcs, dtype=float)
    v = speed_to_fly(polar, mc)
    w = polar.sink(v)
    xc = np.where(mc > 0.0, v * mc / (w + mc), 0.0)
    return [
        {
            "mc": float(m),
            "speed_to_fly_kmh": float(vi * 3.6),
            "glide_ratio": float(vi / wi),
            "cross_country_kmh": float(x * 3.6),
            # the quadratic is not extrapolated beyond the polar's top speed
            "at_top_speed": bool(vi >= polar.v_max * (1.0 - 1e-12)),
        }
        for m, vi, wi, x in zip(mc, v, w, xc, strict=True)
    ]
