"""Glider with speed and load-factor controls, nondimensional (dissertation 6.2-6.3).

Units: speeds in V_ref (the wings-level minimum-drag speed), times in t_ref = V_ref / g,
lengths in l_ref = V_ref^2 / g, altitude in l_ref. In these units (eqs. 6.8-6.15, 6.22):

- turn rate per unit time   psi_dot = sqrt(n^2 - 1) / v       (6.9),
- curvature per unit length psi'    = sqrt(n^2 - 1) / v^2     (6.15),
- sink per unit length      z'      = p1 (v^2 + n^2 / v^2)    (6.22),
- sink rate per unit time   z_dot   = p1 (v^3 + n^2 / v)      (6.8),

with p1 = 1 / (2 (L/D)_max) and p2 = 1 / v_min^2 (the stall boundary n <= p2 v^2, 6.18).
The path model is flown in time, so a path's (speed, turn_rate) gives the load factor
n = sqrt(1 + (v psi_dot)^2) and the bank angle phi = atan(v psi_dot) (n = sec phi, 6.54).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.units import G0
from glideplan.validation import check_less, check_positive
from glideplan.vehicles.base import Vehicle

__all__ = ["LOAD_FACTOR_LIMITS", "GliderScales", "LoadFactorGlider"]

# Supported nondimensional parameter ranges of `LoadFactorGlider` (inclusive).
LOAD_FACTOR_LIMITS: dict[str, tuple[float, float]] = {
    "l_over_d_max": (1.0, 1000.0),
    "v_min": (1e-3, 1e3),
    "v_max": (1e-3, 1e3),
    "n_max": (1.0, 100.0),
}


@dataclass(frozen=True)
class GliderScales:
    """Reference speed (m/s), time (s) and length (m) of the nondimensional model (6.12)."""

    speed: float
    gravity: float = G0

    def __post_init__(self) -> None:
        object.__setattr__(self, "speed", check_positive("speed", self.speed))
        object.__setattr__(self, "gravity", check_positive("gravity", self.gravity))

    @property
    def time(self) -> float:
        """t_ref = V_ref / g (s)."""
        return self.speed / self.gravity

    @property
    def length(self) -> float:
        """l_ref = V_ref^2 / g (m)."""
        return self.speed**2 / self.gravity

    def to_dimensional(
        self, *, speed: ArrayLike = 0.0, length: ArrayLike = 0.0, time: ArrayLike = 0.0
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Nondimensional speed, length (or altitude) and time to m/s, m and s."""
        return (
            np.asarray(speed, dtype=float) * self.speed,
            np.asarray(length, dtype=float) * self.length,
            np.asarray(time, dtype=float) * self.time,
        )

    def to_nondimensional(
        self, *, speed: ArrayLike = 0.0, length: ArrayLike = 0.0, time: ArrayLike = 0.0
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Speed (m/s), length (m) and time (s) to the nondimensional units."""
        return (
            np.asarray(speed, dtype=float) / self.speed,
            np.asarray(length, dtype=float) / self.length,
            np.asarray(time, dtype=float) / self.time,
        )


@dataclass(frozen=True)
class LoadFactorGlider(Vehicle):
    """Nondimensional glider with speed v and load factor n controls (6.13-6.22).

    Control set (6.20): 1 <= n <= n_max, n <= p2 v^2 (stall), v <= v_max, where
    p2 = 1 / v_min^2. Defaults are the dissertation's example (6.21).

    Supported range (nondimensional, see `LOAD_FACTOR_LIMITS`): (L/D)max in [1, 1000],
    v_min and v_max in [1e-3, 1e3] (units of V_ref) with v_min < v_max, n_max in (1, 100].
    Outside it the direct method's scaling (and any real glider) is left behind.
    """

    l_over_d_max: float = 30.0
    v_min: float = 0.75
    v_max: float = 2.0
    n_max: float = 2.0

    model: ClassVar[str] = "load_factor_glider"
    default_objective: ClassVar[str] = "altitude"

    def __post_init__(self) -> None:
        for name in ("l_over_d_max", "v_min", "v_max", "n_max"):
            object.__setattr__(self, name, check_positive(name, getattr(self, name)))
        if self.n_max <= 1.0:
            raise InvalidParameterError(
                "n_max", self.n_max, "must be > 1 (n = 1 is wings-level flight)"
            )
        for name, (low, high) in LOAD_FACTOR_LIMITS.items():
            value = getattr(self, name)
            if not low <= value <= high:
                raise InvalidParameterError(
                    name, value, f"must lie in [{low:g}, {high:g}] (the supported range)"
                )
        check_less("v_min", self.v_min, "v_max", self.v_max)

    # ----- parameters (6.13-6.22) ----------------------------------------------------------
    @property
    def p1(self) -> float:
        """p1 = 1 / (2 (L/D)_max) = sqrt(K C_D0)."""
        return 0.5 / self.l_over_d_max

    @property
    def p2(self) -> float:
        """p2 = C_L,max / C_L,md = 1 / v_min^2 (> 1 when v_min < 1)."""
        return 1.0 / self.v_min**2

    @property
    def n_limit(self) -> float:
        """The largest attainable load factor: min(n_max, p2 v_max^2)."""
        return min(self.n_max, self.p2 * self.v_max**2)

    @property
    def max_bank(self) -> float:
        """Bank angle at the largest attainable load factor, arccos(1 / n_limit) (rad)."""
        return math.acos(1.0 / self.n_limit)

    @property
    def corner_speed(self) -> float:
        """v_c = sqrt(n_max / p2): stall and maximum load factor both active (6.51)."""
        return math.sqrt(self.n_limit / self.p2)

    @property
    def corner_radius(self) -> float:
        """Smallest turn radius, at the corner: v_c^2 / sqrt(n_max^2 - 1)."""
        return self.corner_speed**2 / math.sqrt(self.n_limit**2 - 1.0)

    @property
    def length_scale(self) -> float:
        return 1.0

    # ----- the model in time (path convention) ---------------------------------------------
    def load_factor(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """n = sqrt(1 + (v psi_dot)^2) (from 6.9)."""
        v, u = np.asarray(speed, dtype=float), np.asarray(turn_rate, dtype=float)
        return np.sqrt(1.0 + (v * u) ** 2)

    def bank_angle(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """phi = atan(v psi_dot) (rad, signed; n = sec phi, 6.54)."""
        v, u = np.asarray(speed, dtype=float), np.asarray(turn_rate, dtype=float)
        return np.arctan(v * u)

    def turn_rate(self, speed: ArrayLike, load_factor: ArrayLike, direction: ArrayLike = 1.0):
        """psi_dot = direction sqrt(n^2 - 1) / v (6.9)."""
        v, n = np.asarray(speed, dtype=float), np.asarray(load_factor, dtype=float)
        return np.asarray(direction, dtype=float) * np.sqrt(np.maximum(n**2 - 1.0, 0.0)) / v

    def sink_rate(self, speed: ArrayLike, turn_rate: ArrayLike) -> np.ndarray:
        """Altitude loss per unit time p1 (v^3 + n^2 / v) with n from the turn rate (6.8)."""
        v, u = np.asarray(speed, dtype=float), np.asarray(turn_rate, dtype=float)
        return self.p1 * (v**3 + (1.0 + (v * u) ** 2) / v)

    def sink_per_length(self, speed: ArrayLike, load_factor: ArrayLike) -> np.ndarray:
        """Altitude loss per unit arc length f0 = p1 (v^2 + n^2 / v^2) (6.22)."""
        v, n = np.asarray(speed, dtype=float), np.asarray(load_factor, dtype=float)
        return self.p1 * (v**2 + n**2 / v**2)

    def admissible(self, speed: ArrayLike, load_factor: ArrayLike, tol: float = 1e-9):
        """Whether (v, n) lies in the control set (6.20)."""
        v, n = np.asarray(speed, dtype=float), np.asarray(load_factor, dtype=float)
        return (
            (n >= 1.0 - tol)
            & (n <= self.n_max + tol)
            & (n <= self.p2 * v**2 + tol)
            & (v <= self.v_max + tol)
        )

    # ----- dimensional units ----------------------------------------------------------------
    @staticmethod
    def reference_speed(wing_loading: float, density: float, cl_md: float) -> float:
        """V_ref = sqrt(2 (W/S) / (rho C_L,md)) (m/s): wings-level minimum-drag speed (6.2).

        `wing_loading` W/S in N/m^2 (or kg/m^2 times g: pass the weight per area),
        `density` rho in kg/m^3, `cl_md` = sqrt(C_D0 / K).
        """
        ws = check_positive("wing_loading", wing_loading)
        rho = check_positive("density", density)
        cl = check_positive("cl_md", cl_md)
        return math.sqrt(2.0 * ws / (rho * cl))

    def scales(
        self,
        *,
        wing_loading: float | None = None,
        density: float | None = None,
        cl_md: float | None = None,
        stall_speed: float | None = None,
        gravity: float = G0,
    ) -> GliderScales:
        """Reference speed, time and length for this glider.

        Give either `stall_speed` (wings-level stall speed, m/s: V_ref = V_stall / v_min) or
        `wing_loading` (N/m^2), `density` (kg/m^3) and `cl_md` (lift coefficient at minimum
        drag). Also C_L,max = p2 C_L,md.
        """
        if stall_speed is not None:
            vs = check_positive("stall_speed", stall_speed)
            return GliderScales(vs / self.v_min, gravity)
        if wing_loading is None or density is None or cl_md is None:
            raise InvalidParameterError(
                "scales", None, "give stall_speed, or wing_loading, density and cl_md"
            )
        return GliderScales(self.reference_speed(wing_loading, density, cl_md), gravity)

    def describe(self) -> dict[str, float]:
        """Derived parameters: p1, p2, corner speed and radius, limiting load factor."""
        return {
            "p1": self.p1,
            "p2": self.p2,
            "corner_speed": self.corner_speed,
            "corner_radius": self.corner_radius,
            "n_limit": self.n_limit,
            "max_bank_deg": math.degrees(self.max_bank),
        }
