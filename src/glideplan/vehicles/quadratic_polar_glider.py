"""A glider with a quadratic glide polar w(v) = a v^2 + b v + c (dissertation chapter 5).

The sink rate does not depend on the turn rate (the small-bank model of Remark 5.2.1), so the
altitude lost along a path is the time integral of w(v) (eq. 5.4). SI units throughout:
speeds and sink rates in m/s, so `a` is in s/m, `b` is dimensionless and `c` is in m/s.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.units import kmh_to_ms
from glideplan.validation import check_finite, check_positive
from glideplan.vehicles.base import (
    Vehicle,
    check_length,
    check_speed,
    check_speed_ratio,
    check_turn_rate,
)
from glideplan.vehicles.quadratic_polar import (
    best_glide_speed,
    min_sink_speed,
    quadratic_sink,
)

__all__ = ["QuadraticPolarGlider", "dg1001m"]


@dataclass(frozen=True)
class QuadraticPolarGlider(Vehicle):
    """Speed v in [v_stall, v_max] (m/s), turn rate |u| <= u_max (rad/s), sink w(v) (m/s).

    Validated against Assumptions 5.2.1-5.2.4: a > 0 and w(v) > 0 on [v_stall, v_max]
    (5.2.1); the minimum-sink speed v_ms = -b / 2a inside (v_stall, v_max) (5.2.2); the
    speed to fly v_stf = sqrt(c / a) inside (v_stall, v_max) (5.2.3); and
    v_ms > (v_stall + v_stf) / 2 (5.2.4). Supported range (`glideplan.vehicles.base`):
    speeds in [1e-6, 1e6] m/s with v_max / v_stall <= 1e6, u_max in [1e-6, 1e6] rad/s and the
    turn radii v_stall / u_max, v_max / u_max in [1e-6, 1e7] m.

    Args:
        a: quadratic coefficient (s/m).
        b: linear coefficient (dimensionless).
        c: constant term (m/s).
        v_stall: stall (minimum) speed (m/s).
        v_max: maximum speed (m/s).
        u_max: maximum turn rate (rad/s).
    """

    a: float
    b: float
    c: float
    v_stall: float
    v_max: float
    u_max: float

    model: ClassVar[str] = "quadratic_polar_glider"
    default_objective: ClassVar[str] = "altitude"

    def __post_init__(self) -> None:
        for name in ("a", "b", "c"):
            object.__setattr__(self, name, check_finite(name, getattr(self, name)))
        for name in ("v_stall", "v_max"):
            object.__setattr__(self, name, check_speed(name, getattr(self, name)))
        object.__setattr__(self, "u_max", check_turn_rate("u_max", self.u_max))
        a, b, c, lo, hi = self.a, self.b, self.c, self.v_stall, self.v_max
        if a <= 0.0:
            raise InvalidParameterError("a", a, "Assumption 5.2.1 (convex polar) needs a > 0 (s/m)")
        if hi <= lo:
            raise InvalidParameterError(
                "v_max", hi, f"Assumption 5.2.1 needs v_max > v_stall = {lo:.6g} m/s"
            )
        check_speed_ratio("v_max", hi, "v_stall", lo)
        check_length("v_stall/u_max", lo / self.u_max)
        check_length("v_max/u_max", hi / self.u_max)
        v_ms = -b / (2.0 * a)
        w_min = float(self.sink_rate(min(max(v_ms, lo), hi), 0.0))
        if w_min <= 0.0:
            raise InvalidParameterError(
                "c",
                c,
                f"Assumption 5.2.1 needs w(v) > 0 on [v_stall, v_max] = [{lo:.6g}, {hi:.6g}] "
                f"m/s, but its minimum there is {w_min:.6g} m/s",
            )
        if not lo < v_ms < hi:
            raise InvalidParameterError(
                "b",
                b,
                f"Assumption 5.2.2 needs the minimum-sink speed v_ms = -b/(2a) = {v_ms:.6g} m/s "
                f"inside (v_stall, v_max) = ({lo:.6g}, {hi:.6g}) m/s",
            )
        v_stf = math.sqrt(c / a)  # c > 0 follows from w(v_ms) > 0 with b < 0
        if not lo < v_stf < hi:
            raise InvalidParameterError(
                "c",
                c,
                f"Assumption 5.2.3 needs the speed to fly v_stf = sqrt(c/a) = {v_stf:.6g} m/s "
                f"inside (v_stall, v_max) = ({lo:.6g}, {hi:.6g}) m/s",
            )
        if not v_ms > 0.5 * (lo + v_stf):
            raise InvalidParameterError(
                "b",
                b,
                f"Assumption 5.2.4 needs v_ms = {v_ms:.6g} m/s > (v_stall + v_stf)/2 = "
                f"{0.5 * (lo + v_stf):.6g} m/s",
            )

    @classmethod
    def from_kmh_polar(
        cls,
        a_kmh: float,
        b_kmh: float,
        c: float,
        v_stall_kmh: float,
        v_max_kmh: float,
        u_max: float,
    ) -> QuadraticPolarGlider:
        """A glider from a polar fitted with w in m/s and v in km/h (as in eq. 5.26).

        w = a_kmh V^2 + b_kmh V + c with V = 3.6 v, so a = 3.6^2 a_kmh, b = 3.6 b_kmh.
        """
        k = float(kmh_to_ms(1.0))  # m/s per km/h
        return cls(
            a=check_finite("a_kmh", a_kmh) / k**2,
            b=check_finite("b_kmh", b_kmh) / k,
            c=c,
            v_stall=float(kmh_to_ms(check_positive("v_stall_kmh", v_stall_kmh))),
            v_max=float(kmh_to_ms(check_positive("v_max_kmh", v_max_kmh))),
            u_max=u_max,
        )

    def sink_rate(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """w(v) = a v^2 + b v + c (m/s), independent of the turn rate (eq. 5.4)."""
        return quadratic_sink(self.a, self.b, self.c, speed)

    # ----- derived flight conditions (Section 5.2, Table 5.2) ---------------------------
    @property
    def v_ms(self) -> float:
        """Minimum-sink speed -b / 2a (m/s)."""
        return min_sink_speed(self.a, self.b)

    @property
    def v_stf(self) -> float:
        """Speed to fly sqrt(c / a) (m/s): the polar's tangent through the origin."""
        return best_glide_speed(self.a, self.c)

    @property
    def w_ms(self) -> float:
        """Minimum sink rate w(v_ms) (m/s)."""
        return float(self.sink_rate(self.v_ms, 0.0))

    @property
    def w_stf(self) -> float:
        """Sink rate at the speed to fly (m/s)."""
        return float(self.sink_rate(self.v_stf, 0.0))

    @property
    def w_stall(self) -> float:
        """Sink rate at the stall speed (m/s)."""
        return float(self.sink_rate(self.v_stall, 0.0))

    @property
    def glide_ratio(self) -> float:
        """Best glide ratio v_stf / w(v_stf)."""
        return self.v_stf / self.w_stf

    @property
    def radius_stall(self) -> float:
        """Minimum turn radius at the stall speed, v_stall / u_max (m)."""
        return self.v_stall / self.u_max

    @property
    def radius_ms(self) -> float:
        """Minimum turn radius at the minimum-sink speed (m)."""
        return self.v_ms / self.u_max

    @property
    def radius_stf(self) -> float:
        """Minimum turn radius at the speed to fly, R_stf (m): the chapter's length unit."""
        return self.v_stf / self.u_max

    @property
    def length_scale(self) -> float:
        return self.radius_stf

    @property
    def time_scale(self) -> float:
        """Time to turn one radian at the maximum rate, 1 / u_max (s)."""
        return 1.0 / self.u_max

    def to_dict(self) -> dict[str, Any]:
        return {
            **super().to_dict(),
            "v_ms": self.v_ms,
            "v_stf": self.v_stf,
            "w_ms": self.w_ms,
            "w_stf": self.w_stf,
            "w_stall": self.w_stall,
            "radius_stf": self.radius_stf,
        }


def dg1001m(v_max_kmh: float = 160.0) -> QuadraticPolarGlider:
    """The DG-1001M motorglider of section 5.9: polar (5.26), v_stall = 75.6 km/h, u_max = pi/15.

    The dissertation does not state v_max. We take 160 km/h, the upper end of the digitised
    polar of Fig. 5.4 (the quadratic fit is not meaningful far beyond it). It never matters:
    on every extremal the speed stays at or below v_stf = 105.2 km/h (see
    `glideplan.planners.min_altitude`), so any v_max > v_stf gives the same optimal paths.
    """
    return QuadraticPolarGlider.from_kmh_polar(
        0.0002093, -0.0381, 2.3146, 75.6, v_max_kmh, math.pi / 15.0
    )
