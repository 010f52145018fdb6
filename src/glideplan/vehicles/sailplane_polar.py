"""The quadratic glide polar of a sailplane (chapter 5), from three points, mass, bugs and bank.

A leaf beside the vehicle models (`glideplan.vehicles.sailplane` uses it); the `.plr` reader is
`glideplan.sailplane.plr` (imported only by `polar_from_file`, for its error type).

Sink rate w(v) = a v^2 + b v + c (w positive down, m/s; v airspeed, m/s), Assumption 5.2.1.
Three points fix it exactly (a `.plr` file gives three). Conventions, stated once:

* Mass and ballast: at all-up weight W against the file's reference W0 (its "MassDryGross"),
  speeds and sink rates scale by k = sqrt(W/W0) (same lift coefficient, same glide ratio):
  w_W(v) = k w_W0(v / k), i.e. a -> a / k, b -> b, c -> c k. Water ballast weighs 1 kg/L.
* Bugs: BUGS percent reduce the glide ratio at every speed by that percentage (XCSoar's
  convention): w_bugs(v) = w(v) / (1 - BUGS/100); speeds do not change. 0 <= BUGS <= 50.
* Speed range: v_max is the highest speed of the file (the quadratic is not extrapolated
  beyond its data); `.plr` files carry no stall speed, so the lowest speed flown is
  v_min = min(v1, 0.85 v_ms) (sailplanes stall at roughly 0.8-0.9 of their minimum-sink
  speed), both scaled by k. The polar is rejected when a <= 0 (not convex) or when its
  minimum sink v_ms = -b / 2a is not inside (0, v_max) or w(v_ms) <= 0.
* Turning flight at bank phi (load factor n = 1 / cos phi): the level polar scaled,
  w_phi(V) = n^{3/2} w(V / sqrt n) = a sqrt(n) V^2 + b n V + n^{3/2} c, and the turn rate is
  g tan(phi) / V; the stall speed rises to v_min sqrt(n).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from glideplan.errors import InvalidParameterError
from glideplan.units import G0
from glideplan.validation import check_fields, check_finite, check_nonnegative, check_positive
from glideplan.vehicles.quadratic_polar import (
    best_glide_speed,
    min_sink_rate,
    min_sink_speed,
    quadratic_sink,
)

if TYPE_CHECKING:
    from glideplan.sailplane.plr import PolarFile

__all__ = [
    "GRAVITY",
    "MAX_BUGS_PCT",
    "STALL_FRACTION",
    "SailplanePolar",
    "fit_three_points",
    "load_polar",
    "polar_from_file",
]

GRAVITY = G0  # standard gravity, m/s^2 (glideplan.units)
STALL_FRACTION = 0.85  # v_min = min(v1, STALL_FRACTION * v_ms) when the file gives no stall speed
MAX_BUGS_PCT = 50.0
KMH = 1.0 / 3.6  # m/s per km/h


def fit_three_points(speeds: ArrayLike, sinks: ArrayLike) -> tuple[float, float, float]:
    """(a, b, c) of the parabola w = a v^2 + b v + c through three (v, w) points (exact)."""
    v = np.asarray(speeds, dtype=float).reshape(3)
    w = np.asarray(sinks, dtype=float).reshape(3)
    a, b, c = np.linalg.solve(np.vander(v, 3), w)
    return float(a), float(b), float(c)


@dataclass(frozen=True)
class SailplanePolar:
    """A quadratic polar in SI: w(v) = a v^2 + b v + c (m/s) on v in [v_min, v_max] (m/s).

    `mass_kg` is the all-up mass it holds for, `reference_mass_kg` the mass of the source
    data, `bugs_pct` the bug degradation already applied, `wing_area_m2` None if unknown.
    """

    a: float
    b: float
    c: float
    v_min: float
    v_max: float
    mass_kg: float
    reference_mass_kg: float
    wing_area_m2: float | None = None
    name: str = ""
    bugs_pct: float = 0.0
    max_ballast_l: float = 0.0

    def __post_init__(self) -> None:
        check_fields(self, check_finite, ("a", "b", "c"))
        check_fields(self, check_positive, ("v_min", "v_max", "mass_kg", "reference_mass_kg"))
        if self.a <= 0.0:
            raise InvalidParameterError(
                "a", self.a, "the polar must be convex, a > 0 (Assumption 5.2.1)"
            )
        if not self.v_min < self.v_max:
            raise InvalidParameterError(
                "v_max", self.v_max, f"must exceed v_min = {self.v_min:.6g} m/s"
            )
        if not self.v_min < self.v_ms < self.v_max:
            raise InvalidParameterError(
                "b",
                self.b,
                f"the minimum sink v_ms = -b/2a = {self.v_ms:.4g} m/s must lie inside the speed "
                f"range ({self.v_min:.4g}, {self.v_max:.4g}) m/s (Assumption 5.2.2)",
            )
        if self.w_ms <= 0.0:
            raise InvalidParameterError(
                "c", self.c, f"the minimum sink rate must be > 0, got {self.w_ms:.4g} m/s"
            )

    # ----- level flight -----------------------------------------------------------------
    def sink(self, speed: ArrayLike) -> NDArray[np.float64]:
        """w(v) = a v^2 + b v + c (m/s, positive down) at airspeed v (m/s)."""
        return quadratic_sink(self.a, self.b, self.c, speed)

    @property
    def v_ms(self) -> float:
        """Minimum-sink speed -b / 2a (m/s)."""
        return min_sink_speed(self.a, self.b)

    @property
    def w_ms(self) -> float:
        """Minimum sink rate c - b^2 / 4a (m/s)."""
        return min_sink_rate(self.a, self.b, self.c)

    @property
    def v_best_glide(self) -> float:
        """Best-glide speed sqrt(c / a) (m/s), clipped to [v_min, v_max]."""
        return min(max(best_glide_speed(self.a, self.c), self.v_min), self.v_max)

    @property
    def best_glide_ratio(self) -> float:
        """max v / w(v): 1 / (2 sqrt(ac) + b) when sqrt(c/a) lies in the speed range."""
        v = self.v_best_glide
        return v / float(self.sink(v))

    # ----- turning flight ---------------------------------------------------------------
    def sink_turning(self, speed: ArrayLike, bank: ArrayLike) -> NDArray[np.float64]:
        """w_phi(V) = n^{3/2} w(V / sqrt n), n = 1 / cos(phi) (bank phi in rad)."""
        n = 1.0 / np.cos(np.asarray(bank, dtype=float))
        return self.sink_at_load_factor(speed, n)

    def sink_at_turn_rate(self, speed: ArrayLike, turn_rate: ArrayLike) -> NDArray[np.float64]:
        """Sink rate (m/s) at airspeed V and turn rate u: bank tan(phi) = u V / g."""
        v = np.asarray(speed, dtype=float)
        n = np.sqrt(1.0 + (np.asarray(turn_rate, dtype=float) * v / GRAVITY) ** 2)
        return self.sink_at_load_factor(v, n)

    def sink_at_load_factor(self, speed: ArrayLike, n: ArrayLike) -> NDArray[np.float64]:
        """n^{3/2} w(V / sqrt n) = a sqrt(n) V^2 + b n V + n^{3/2} c (m/s) at load factor n."""
        v = np.asarray(speed, dtype=float)
        n = np.asarray(n, dtype=float)
        return self.a * np.sqrt(n) * v**2 + self.b * n * v + n**1.5 * self.c

    @staticmethod
    def turn_rate(speed: ArrayLike, bank: ArrayLike) -> NDArray[np.float64]:
        """g tan(phi) / V (rad/s)."""
        return GRAVITY * np.tan(np.asarray(bank, dtype=float)) / np.asarray(speed, dtype=float)

    def stall_speed(self, bank: ArrayLike = 0.0) -> NDArray[np.float64]:
        """Lowest airspeed at bank phi: v_min sqrt(n) (m/s)."""
        return self.v_min / np.sqrt(np.cos(np.asarray(bank, dtype=float)))

    # ----- changes of configuration -----------------------------------------------------
    def at_mass(self, mass_kg: float) -> SailplanePolar:
        """The polar at another all-up mass (speeds and sinks scale by sqrt(W/W_now))."""
        m = check_positive("mass", mass_kg)
        k = math.sqrt(m / self.mass_kg)
        return replace(
            self,
            a=self.a / k,
            c=self.c * k,
            v_min=self.v_min * k,
            v_max=self.v_max * k,
            mass_kg=m,
        )

    def with_bugs(self, bugs_pct: float) -> SailplanePolar:
        """The polar with `bugs_pct` percent less glide ratio at every speed (on top of any)."""
        p = check_nonnegative("bugs", bugs_pct)
        total = 100.0 * (1.0 - (1.0 - self.bugs_pct / 100.0) * (1.0 - p / 100.0))
        if total > MAX_BUGS_PCT:
            raise InvalidParameterError(
                "bugs", bugs_pct, f"must leave a degradation <= {MAX_BUGS_PCT:g} % in total"
            )
        f = 1.0 / (1.0 - p / 100.0)
        return replace(self, a=self.a * f, b=self.b * f, c=self.c * f, bugs_pct=total)

    def to_dict(self) -> dict[str, Any]:
        return {
            "name": self.name,
            "a": self.a,
            "b": self.b,
            "c": self.c,
            "v_min": self.v_min,
            "v_max": self.v_max,
            "mass_kg": self.mass_kg,
            "reference_mass_kg": self.reference_mass_kg,
            "wing_area_m2": self.wing_area_m2,
            "bugs_pct": self.bugs_pct,
        }


def _check_mass_ratio(shown: float, total: float, reference: float) -> None:
    """The all-up mass `total` (kg) within `PHYSICAL_RANGES["mass_ratio"]` times the polar's
    reference mass, else refuse `mass` = `shown` naming the range in kg."""
    from glideplan.validation import PHYSICAL_RANGES

    r = PHYSICAL_RANGES["mass_ratio"]
    if not r.low <= total / reference <= r.high:
        raise InvalidParameterError(
            "mass", shown,
            f"with the ballast must lie in [{r.low * reference:g}, {r.high * reference:g}] kg, "
            f"{r.low:g} to {r.high:g} times the polar's reference mass {reference:g} kg "
            f"({r.reason})")


def polar_from_file(
    pf: PolarFile,
    *,
    mass_kg: float | None = None,
    ballast_l: float = 0.0,
    bugs_pct: float = 0.0,
) -> SailplanePolar:
    """The SI polar of a `.plr` file at all-up mass `mass_kg` (default: the file's reference
    mass) plus `ballast_l` litres of water, degraded by `bugs_pct` percent.

    Raises `PolarFileError` (naming the file and its data line) when the three points give
    a polar that breaks the model's assumptions.
    """
    from glideplan.sailplane.plr import PolarFileError  # the reader's error, named by file

    speeds = [v * KMH for v, _ in pf.points]
    sinks = [-w for _, w in pf.points]
    a, b, c = fit_three_points(speeds, sinks)
    line = ", ".join(f"{v:g}, {w:g}" for v, w in pf.points)
    if not a > 0.0:
        raise PolarFileError(
            pf.source,
            pf.line_no,
            line,
            f"the three points give a concave polar (a = {a:.4g} s/m <= 0): no minimum sink",
        )
    v_ms = -b / (2.0 * a)
    v3 = speeds[2]
    if not 0.0 < v_ms < v3:
        raise PolarFileError(
            pf.source,
            pf.line_no,
            line,
            f"the fitted minimum-sink speed {v_ms * 3.6:.4g} km/h is not inside the speed range "
            f"(0, {v3 * 3.6:.4g}] km/h",
        )
    if c - b * b / (4.0 * a) <= 0.0:
        raise PolarFileError(
            pf.source, pf.line_no, line, "the fitted minimum sink rate is <= 0 (a climb)"
        )
    base = SailplanePolar(
        a=a,
        b=b,
        c=c,
        v_min=min(speeds[0], STALL_FRACTION * v_ms),
        v_max=v3,
        mass_kg=pf.mass_kg,
        reference_mass_kg=pf.mass_kg,
        wing_area_m2=pf.wing_area_m2,
        name=pf.name,
        max_ballast_l=pf.max_ballast_l,
    )
    ballast = check_nonnegative("ballast", ballast_l)
    if ballast > pf.max_ballast_l:
        raise InvalidParameterError(
            "ballast", ballast_l, f"must be <= the glider's maximum {pf.max_ballast_l:g} L"
        )
    mass = pf.mass_kg if mass_kg is None else check_positive("mass", mass_kg)
    _check_mass_ratio(mass_kg if mass_kg is not None else mass + ballast, mass + ballast,
                      pf.mass_kg)
    polar = base.at_mass(mass + ballast) if mass + ballast != pf.mass_kg else base
    return polar.with_bugs(bugs_pct) if bugs_pct else polar


def load_polar(path: Any, *, mass_kg: float | None = None, ballast_l: float = 0.0,
               bugs_pct: float = 0.0) -> SailplanePolar:
    """The SI polar of the `.plr` file at `path` (`read_plr`, then `polar_from_file` with the
    same mass, ballast and bugs): what `glideplan glide ... --polar FILE` and the explorer
    read. The mass is checked against `PHYSICAL_RANGES["mass"]` and `["mass_ratio"]`."""
    from glideplan.sailplane.plr import read_plr
    from glideplan.validation import check_physical

    if mass_kg is not None:
        check_physical("mass", mass_kg, "mass")
    return polar_from_file(read_plr(path), mass_kg=mass_kg, ballast_l=ballast_l,
                           bugs_pct=bugs_pct)
