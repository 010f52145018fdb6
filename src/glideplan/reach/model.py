"""The glide a reach front propagates: speeds flown, ground glide per direction, front terms.

"Time" is altitude lost (m); velocities are ground metres per metre of altitude. The glider
flies airspeed V (m/s) at air heading e (unit vector) through a steady wind W (east, north,
m/s, the direction the air moves TO) and sinks at w(V) (m/s), so

    dx/dh = (V e + W) / w(V).

Sink: the polar w(V) = a V^2 + b V + c on [v_min, v_max]; with a safety glide ratio R the
still-air glide ratio at every speed is capped at R, w_R(V) = max(w(V), V / R) (min(polar
L/D, R) at each speed; in still air the best glide becomes min((L/D)max, R)).

Along a straight ground track of direction chi (unit u, crosswind W_c = W . u_perp, tailwind
W_t = W . u) the glider crabs, e . u_perp = -W_c / V, and makes good g(V) = sqrt(V^2 - W_c^2)
+ W_t. The speed flown for the direction of travel minimises MacCready's cost

    J(V) = (w_R(V) + MC) / g(V)    (MC = 0: the best ground glide for that direction),

and the ground glide ratio of the direction is r(chi) = g / w_R at that speed (`Glide.along`).

What the front computes (its Hamiltonian H(p) = max_k a_k |p| + b_k . p, support function
F(n) = max_k a_k + b_k . n of the set of ground velocities per metre of altitude):

* MC = 0: every airspeed may be flown, so the set is the union over V of the disks centred
  W / w_R(V) of radius V / w_R(V); the terms are K disks, a_k = V_k / w_R(V_k),
  b_k = W / w_R(V_k), at K speeds spanning the speeds that are best for some direction
  (one speed in still air: the best glide, exact). Sampling the speeds costs at most
  ~ F'' (dV/2)^2 / 2 of the support function (dV the speed step; < 0.05 % with K = 16).
* MC > 0: one speed per direction (the speed to fly for it), so the set is the curve
  C = {r(chi) u(chi)}, not the union: the terms are points, a_j = 0, b_j = r(chi_j) u(chi_j),
  at N directions of travel (in still air one disk of radius V_mc / w_R(V_mc), exact). The
  front's velocity set is their convex hull, i.e. the minimum altitude loss over polygonal
  paths each leg of which is flown at the speed to fly for its own direction (where C is not
  convex, a zig-zag of two such legs); the inscribed polygon understates F by at most
  1 - cos(pi / N) of r (1.2e-3 with N = 64). MC > 0 never reaches farther than MC = 0: C lies
  inside the MC = 0 set.

The flown path (verification) uses `along` exactly at each leg's direction, not the terms.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.sailplane.polar import SailplanePolar
from glideplan.validation import check_finite, check_physical, check_positive

__all__ = ["Glide", "GroundGlide"]

FloatArray = NDArray[np.float64]

_DENSE = 241  # speeds sampled before the golden-section refinement
_GOLDEN = 48  # golden-section iterations (bracket shrinks by 0.618^48 ~ 1e-10)
MC0_SPEEDS = 16  # K disks for MC = 0 in wind
MC_DIRECTIONS = 64  # N points for MC > 0 in wind


@dataclass(frozen=True, eq=False)
class GroundGlide:
    """Per direction of travel chi (rad, CCW from east): airspeed `speed` (m/s), air
    `heading` (rad CCW from east), ground speed `ground_speed` (m/s), `sink` (m/s) and
    `ratio` = ground_speed / sink (ground m per m of altitude); NaN where the wind allows no
    progress along chi."""

    chi: FloatArray
    speed: FloatArray
    heading: FloatArray
    ground_speed: FloatArray
    sink: FloatArray
    ratio: FloatArray


@dataclass(frozen=True)
class Glide:
    """How the glider flies: polar, MacCready setting `mc` (m/s), wind (east, north) m/s
    (towards), optional safety glide ratio (module docstring)."""

    polar: SailplanePolar
    mc: float = 0.0
    wind: tuple[float, float] = (0.0, 0.0)
    safety_glide_ratio: float | None = None

    def __post_init__(self) -> None:
        check_physical("mc", self.mc, "mc")  # validation.PHYSICAL_RANGES, as final_glide
        if len(self.wind) != 2:
            raise InvalidParameterError("wind", self.wind, "must be (east, north) m/s")
        w = (check_finite("wind east", self.wind[0]), check_finite("wind north", self.wind[1]))
        object.__setattr__(self, "wind", w)
        if self.safety_glide_ratio is not None:
            check_positive("safety_glide_ratio", self.safety_glide_ratio)
        if math.hypot(*w) >= self.polar.v_max:
            raise InvalidParameterError(
                "wind", math.hypot(*w),
                f"must be slower than the polar's top speed {self.polar.v_max:.1f} m/s")

    # ----- the polar as flown ----------------------------------------------------------------
    def sink(self, speed: ArrayLike) -> FloatArray:
        """w_R(V) = max(w(V), V / R) (m/s; w(V) without a safety glide ratio)."""
        v = np.asarray(speed, dtype=float)
        w = np.asarray(self.polar.sink(v), dtype=float)
        if self.safety_glide_ratio is None:
            return w
        return np.maximum(w, v / self.safety_glide_ratio)

    @property
    def still_air_ratio(self) -> float:
        """Still-air glide ratio at the speed flown (MC speed to fly; MC 0: best glide)."""
        return float(self.along(np.zeros(1), still=True).ratio[0])

    def _cost(self, v: FloatArray, wt: FloatArray, wc: FloatArray) -> FloatArray:
        with np.errstate(invalid="ignore", divide="ignore"):
            g = np.sqrt(np.where(v > np.abs(wc), v * v - wc * wc, np.nan)) + wt
            j = (self.sink(v) + self.mc) / g
        return np.where(np.isfinite(j) & (g > 0), j, np.inf)

    def along(self, chi: ArrayLike, *, still: bool = False) -> GroundGlide:
        """The flight along ground directions chi (rad CCW from east): module docstring."""
        c = np.atleast_1d(np.asarray(chi, dtype=float))
        u = np.stack([np.cos(c), np.sin(c)], axis=-1)
        wx, wy = (0.0, 0.0) if still else self.wind
        wt = u[:, 0] * wx + u[:, 1] * wy
        wc = -u[:, 1] * wx + u[:, 0] * wy
        p = self.polar
        dense = np.linspace(p.v_min, p.v_max, _DENSE)
        j = self._cost(dense[None, :], wt[:, None], wc[:, None])
        best = np.argmin(j, axis=1)
        ok = np.isfinite(j[np.arange(c.size), best])
        lo = dense[np.maximum(best - 1, 0)]
        hi = dense[np.minimum(best + 1, _DENSE - 1)]
        gr = 0.5 * (math.sqrt(5.0) - 1.0)
        x1, x2 = hi - gr * (hi - lo), lo + gr * (hi - lo)
        f1, f2 = self._cost(x1, wt, wc), self._cost(x2, wt, wc)
        for _ in range(_GOLDEN):
            left = f1 <= f2
            hi = np.where(left, x2, hi)
            lo = np.where(left, lo, x1)
            x1, x2 = hi - gr * (hi - lo), lo + gr * (hi - lo)
            f1, f2 = self._cost(x1, wt, wc), self._cost(x2, wt, wc)
        v = 0.5 * (lo + hi)
        # the dense optimum may sit on a bound: keep whichever of v, the sample is better
        vb = dense[best]
        v = np.where(self._cost(v, wt, wc) <= self._cost(vb, wt, wc), v, vb)
        v = np.where(ok, v, np.nan)
        with np.errstate(invalid="ignore"):
            g = np.sqrt(v * v - wc * wc) + wt
            w = self.sink(v)
            heading = c - np.arcsin(wc / v)
        return GroundGlide(c, v, heading, g, w, g / w)

    def ratio(self, chi: ArrayLike) -> FloatArray:
        """Ground glide ratio r(chi) (ground m per m of altitude; NaN: no progress)."""
        return self.along(chi).ratio

    @cached_property
    def _ratio_table(self) -> tuple[FloatArray, FloatArray]:
        chi = np.linspace(0.0, 2 * np.pi, 3601)
        return chi, self.along(chi).ratio

    def ratio_fast(self, chi: ArrayLike) -> FloatArray:
        """r(chi) interpolated in a table at 0.1 deg (relative error ~1e-7; for searches --
        flights use `along`)."""
        c = np.mod(np.asarray(chi, dtype=float), 2 * np.pi)
        tc, tr = self._ratio_table
        return np.asarray(np.interp(c, tc, tr), dtype=float)

    # ----- the front's terms ---------------------------------------------------------------
    def front_terms(self) -> tuple[FloatArray, FloatArray]:
        """(a (K,), b (K, 2)) of H(p) = max_k a_k |p| + b_k . p (module docstring)."""
        wind = np.asarray(self.wind, dtype=float)
        calm = not np.any(wind)
        chi = np.linspace(0.0, 2 * np.pi, MC_DIRECTIONS, endpoint=False)
        gg = self.along(chi)
        ok = np.isfinite(gg.ratio) & (gg.ratio > 0)
        if not ok.any():
            raise InvalidParameterError("wind", float(np.hypot(*wind)),
                                        "leaves no direction in which the glider makes progress")
        if self.mc == 0.0 or calm:
            speeds = gg.speed[ok]
            lo, hi = float(speeds.min()), float(speeds.max())
            if calm or hi - lo < 1e-6 * hi:
                v = np.array([0.5 * (lo + hi)])
            else:
                v = np.linspace(lo, hi, MC0_SPEEDS)
            w = self.sink(v)
            return v / w, wind[None, :] / w[:, None]
        pts = gg.ratio[ok, None] * np.stack([np.cos(chi[ok]), np.sin(chi[ok])], axis=-1)
        return np.zeros(pts.shape[0]), pts

    def support(self, n: ArrayLike) -> FloatArray:
        """F(n) = max_k a_k + b_k . n for unit vectors n (..., 2): the front's normal speed."""
        a, b = self.front_terms()
        nn = np.asarray(n, dtype=float)
        return np.max(a + nn @ b.T, axis=-1)

    @property
    def max_ratio(self) -> float:
        """Largest ground glide ratio over all directions (for sizing the domain)."""
        a, b = self.front_terms()
        return float(np.max(a + np.hypot(b[:, 0], b[:, 1])))

    def to_dict(self) -> dict[str, Any]:
        return {"mc_ms": self.mc, "wind_ms": list(self.wind),
                "safety_glide_ratio": self.safety_glide_ratio,
                "still_air_glide_ratio": self.still_air_ratio}
