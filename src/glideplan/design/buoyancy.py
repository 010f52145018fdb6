"""Pneumatic buoyancy engine: dives, net weight, bladder equilibrium, air exchange (7.1-7.7)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.design.gas import (
    FRESH_WATER,
    R_GAS_J_PER_MOL_K,
    Environment,
    Tank,
)
from glideplan.errors import InvalidParameterError
from glideplan.units import inch_to_m, psi_to_pa
from glideplan.validation import check_fields, check_nonnegative, check_positive, scalar_or_array
from glideplan.validation import check_finite_array as finite_array
from glideplan.validation import check_nonnegative_array as nonnegative_array
from glideplan.validation import check_positive_array as positive_array

__all__ = [
    "DEFAULT_ELASTIC_COEFFICIENTS_PA",
    "VTUG_BLADDER",
    "VTUG_HULL",
    "Bladder",
    "Hull",
    "air_exchange_rate_mol_s",
    "bladder_moles",
    "equilibrium_volume_m3",
    "exchange_rate_sweep",
    "lung_volume_m3",
    "moles_per_cycle",
    "net_weight_n",
    "number_of_dives",
    "terminal_depth_rate_m_s",
]

# p_blad = sum_k c_k (V / V_max)^k, k = 1..4, in psi: 1.5 x - 2.5 x^2 + 1.5 x^3 + 0.5 x^4.
# ILLUSTRATIVE: the dissertation's fourth-order fit (Fig 7.5b) is not published; this curve is
# monotone, passes through the origin and reaches 1 psi at full displacement (cf. the 0-5 psid
# bladder pressures of Figs 7.23-7.24, which were measured with a fabric jacket).
DEFAULT_ELASTIC_COEFFICIENTS_PA: tuple[float, ...] = tuple(
    float(psi_to_pa(c)) for c in (1.5, -2.5, 1.5, 0.5)
)


@dataclass(frozen=True)
class Bladder:
    """Elastomeric bladder: maximum and neutral displacement, elastic pressure curve p_blad(V).

    `elastic_coefficients_pa` are c_1..c_k of p_blad(V) = sum_k c_k (V / V_max)^k (Pa), a
    polynomial through the origin as in Fig 7.5b.
    """

    max_volume_m3: float = 5.0e-3
    neutral_volume_m3: float = 2.5e-3
    elastic_coefficients_pa: tuple[float, ...] = DEFAULT_ELASTIC_COEFFICIENTS_PA

    def __post_init__(self) -> None:
        vmax = check_positive("max_volume_m3", self.max_volume_m3)
        vn = check_nonnegative("neutral_volume_m3", self.neutral_volume_m3)
        if vn > vmax:
            raise InvalidParameterError(
                "neutral_volume_m3", vn, f"must be <= max_volume_m3={vmax:g}"
            )
        raw = finite_array("elastic_coefficients_pa", self.elastic_coefficients_pa)
        coeffs = tuple(float(c) for c in raw.ravel())
        object.__setattr__(self, "max_volume_m3", vmax)
        object.__setattr__(self, "neutral_volume_m3", vn)
        object.__setattr__(self, "elastic_coefficients_pa", coeffs)
        x = np.linspace(0.0, 1.0, 201)
        p = self._poly(x)
        if np.any(p < -1e-9 * max(1.0, float(np.max(np.abs(p))))):
            raise InvalidParameterError(
                "elastic_coefficients_pa", coeffs, "p_blad(V) must be >= 0 on [0, max_volume_m3]"
            )
        # (7.5) has one root in V only if V (p_amb + p_blad(V)) increases with V; checked
        # with p_amb = half an atmosphere, below any ambient pressure met in water.
        dp = self._poly_derivative(x)
        if np.any(FRESH_WATER.atmospheric_pressure_pa * 0.5 + p + x * dp <= 0.0):
            raise InvalidParameterError(
                "elastic_coefficients_pa",
                coeffs,
                "V (p_amb + p_blad(V)) must increase with V so that (7.5) has one root",
            )

    def _poly(self, x: np.ndarray) -> np.ndarray:
        out = np.zeros_like(x)
        for k, c in enumerate(self.elastic_coefficients_pa, start=1):
            out = out + c * x**k
        return out

    def _poly_derivative(self, x: np.ndarray) -> np.ndarray:
        # d p_blad / d x with x = V / V_max
        out = np.zeros_like(x)
        for k, c in enumerate(self.elastic_coefficients_pa, start=1):
            out = out + k * c * x ** (k - 1)
        return out

    @property
    def lung_volume_m3(self) -> float:
        """Displacement above neutral available for ascents, V_max - V_neutral (m^3)."""
        return self.max_volume_m3 - self.neutral_volume_m3

    def elastic_pressure_pa(self, volume_m3: ArrayLike) -> np.ndarray | float:
        """Elastic pressure p_blad(V) of the stretched bladder (Pa, used in 7.2 and 7.5)."""
        v = self._volume(volume_m3)
        return scalar_or_array(self._poly(v / self.max_volume_m3))

    def net_weight_n(
        self, volume_m3: ArrayLike, environment: Environment = FRESH_WATER
    ) -> np.ndarray | float:
        """Net weight B - W = rho g (V - V_neutral) at bladder volume V (N, positive = buoyant)."""
        v = self._volume(volume_m3)
        return scalar_or_array(environment.specific_weight_n_m3 * (v - self.neutral_volume_m3))

    def _volume(self, volume_m3: ArrayLike) -> np.ndarray:
        v = nonnegative_array("volume_m3", volume_m3)
        if np.any(v > self.max_volume_m3 * (1.0 + 1e-12)):
            raise InvalidParameterError(
                "volume_m3", float(np.max(v)), f"must be <= max_volume_m3={self.max_volume_m3:g}"
            )
        return v


@dataclass(frozen=True)
class Hull:
    """Hull for buoyancy engine sizing: dry mass, diameter and drag coefficient (7.7)."""

    dry_mass_kg: float = 50.0
    diameter_m: float = 0.2286
    drag_coefficient: float = 0.1

    def __post_init__(self) -> None:
        check_fields(self, check_positive, ("dry_mass_kg", "diameter_m", "drag_coefficient"))

    @property
    def cross_section_m2(self) -> float:
        """Frontal area pi d^2 / 4 (m^2), the S of (7.7) for a nose-down glider."""
        return math.pi * self.diameter_m**2 / 4.0


# Virginia Tech Underwater Glider: 9 in hull, Table 7.2's 50 kg design basis, 5 L bladder
# trimmed neutral at 2.5 L (+-5 % lung), C_D = 0.1 as the worst case of Fig 7.8.
VTUG_HULL = Hull(dry_mass_kg=50.0, diameter_m=float(inch_to_m(9.0)), drag_coefficient=0.1)
VTUG_BLADDER = Bladder()


def lung_volume_m3(
    lung_fraction: ArrayLike, dry_mass_kg: ArrayLike, environment: Environment = FRESH_WATER
) -> np.ndarray | float:
    """Water volume displaced for a buoyant lung setting, V_eta = eta W / (rho g) (section 7.2)."""
    eta = finite_array("lung_fraction", lung_fraction)
    m = positive_array("dry_mass_kg", dry_mass_kg)
    return scalar_or_array(eta * m / environment.water_density_kg_m3)


def moles_per_cycle(
    volume_m3: ArrayLike,
    depth_m: ArrayLike,
    environment: Environment = FRESH_WATER,
    bladder: Bladder | None = None,
) -> np.ndarray | float:
    """Air to displace V at depth z, n_cycle = p V / (RT) with p = p_amb (7.1, 7.3).

    With a `bladder`, its elastic pressure is added (p = p_amb + p_blad(V), as in 7.5);
    without one the ideal estimate of section 7.2 is returned.
    """
    v = nonnegative_array("volume_m3", volume_m3)
    p = np.asarray(environment.ambient_pressure_pa(depth_m))
    if bladder is not None:
        p = p + np.asarray(bladder.elastic_pressure_pa(v))
    return scalar_or_array(p * v / (R_GAS_J_PER_MOL_K * environment.temperature_k))


def number_of_dives(
    tank: Tank,
    volume_m3: ArrayLike,
    depth_m: ArrayLike,
    environment: Environment = FRESH_WATER,
    *,
    usable_only: bool = False,
) -> np.ndarray | float:
    """Ideal number of dives N = n_tank / n_cycle for displacement V at depth z (7.1; Fig 7.3).

    `usable_only=True` subtracts the air left in the tank once its pressure has fallen to the
    ambient pressure at z (it can no longer inflate the bladder there). Raises
    `InvalidParameterError` naming `depth_m` if the full tank cannot inflate at that depth.
    """
    v = positive_array("volume_m3", volume_m3)
    z = nonnegative_array("depth_m", depth_m)
    z_max = tank.max_inflation_depth_m(environment)
    if np.any(z >= z_max):
        raise InvalidParameterError(
            "depth_m",
            float(np.max(z)),
            f"the tank ({tank.max_pressure_pa:.4g} Pa) cannot inflate below {z_max:.0f} m",
        )
    t = environment.temperature_k
    n_tank = float(tank.moles(t))
    n_cycle = np.asarray(moles_per_cycle(v, z, environment))
    if usable_only:
        n_residual = (
            np.asarray(environment.ambient_pressure_pa(z))
            * tank.internal_volume_m3
            / (R_GAS_J_PER_MOL_K * t)
        )
        return scalar_or_array((n_tank - n_residual) / n_cycle)
    return scalar_or_array(n_tank / n_cycle)


def net_weight_n(
    tank_air_mass_kg: ArrayLike,
    bladder_volume_m3: ArrayLike,
    *,
    trim_air_mass_kg: float,
    trim_bladder_volume_m3: float,
    environment: Environment = FRESH_WATER,
) -> np.ndarray | float:
    """Net weight B - W (N, + buoyant) as the tank empties, for a glider trimmed neutral (Fig 7.4).

    Neutral at (`trim_air_mass_kg`, `trim_bladder_volume_m3`); spending air lightens the
    glider by its weight and the bladder adds rho g (V - V_trim).
    """
    m = nonnegative_array("tank_air_mass_kg", tank_air_mass_kg)
    v = nonnegative_array("bladder_volume_m3", bladder_volume_m3)
    m0 = check_nonnegative("trim_air_mass_kg", trim_air_mass_kg)
    v0 = check_nonnegative("trim_bladder_volume_m3", trim_bladder_volume_m3)
    g = environment.gravity_m_s2
    return scalar_or_array(environment.specific_weight_n_m3 * (v - v0) + (m0 - m) * g)


def bladder_moles(
    bladder: Bladder,
    volume_m3: ArrayLike,
    depth_m: ArrayLike,
    environment: Environment = FRESH_WATER,
) -> np.ndarray | float:
    """Air n(z, V) that holds the bladder at volume V and depth z, from the equilibrium (7.5)."""
    return moles_per_cycle(bladder._volume(volume_m3), depth_m, environment, bladder)


def equilibrium_volume_m3(
    bladder: Bladder,
    moles: ArrayLike,
    depth_m: ArrayLike,
    environment: Environment = FRESH_WATER,
) -> np.ndarray | float:
    """Bladder volume holding `moles` of air at depth z: the root V of (7.5), saturated at V_max.

    The open-loop response of Fig 7.6. Solved by vectorised bisection on [0, V_max]
    (V (p_amb + p_blad(V)) increases with V, checked when the `Bladder` is built).
    """
    n = nonnegative_array("moles", moles)
    p_amb = np.asarray(environment.ambient_pressure_pa(depth_m))
    n, p_amb = np.broadcast_arrays(n, p_amb)
    target = n * R_GAS_J_PER_MOL_K * environment.temperature_k
    lo = np.zeros(n.shape)
    hi = np.full(n.shape, bladder.max_volume_m3)
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        f = mid * (p_amb + bladder._poly(mid / bladder.max_volume_m3)) - target
        lo = np.where(f < 0.0, mid, lo)
        hi = np.where(f < 0.0, hi, mid)
    return scalar_or_array(0.5 * (lo + hi))


def terminal_depth_rate_m_s(
    net_weight: ArrayLike,
    area_m2: float,
    drag_coefficient: float,
    environment: Environment = FRESH_WATER,
) -> np.ndarray | float:
    """Terminal depth rate zdot = -sign(W~) sqrt(2|W~| / (rho S C_D)) (7.7); z down, + descending.

    `net_weight` is B - W in N (positive = buoyant, so the glider rises and zdot < 0).
    """
    w = finite_array("net_weight", net_weight)
    s = check_positive("area_m2", area_m2)
    cd = check_positive("drag_coefficient", drag_coefficient)
    rho = environment.water_density_kg_m3
    return scalar_or_array(-np.sign(w) * np.sqrt(2.0 * np.abs(w) / (rho * s * cd)))


def air_exchange_rate_mol_s(
    volume_m3: ArrayLike, depth_rate_m_s: ArrayLike, environment: Environment = FRESH_WATER
) -> np.ndarray | float:
    """Air flow holding the bladder at V as depth changes, ndot = rho g V zdot / (RT) (7.6).

    Positive = inflate (descending, zdot > 0), negative = exhaust (ascending).
    """
    v = nonnegative_array("volume_m3", volume_m3)
    zdot = finite_array("depth_rate_m_s", depth_rate_m_s)
    rt = R_GAS_J_PER_MOL_K * environment.temperature_k
    return scalar_or_array(environment.specific_weight_n_m3 * v * zdot / rt)


def exchange_rate_sweep(
    bladder: Bladder,
    hull: Hull,
    environment: Environment = FRESH_WATER,
    *,
    drag_coefficient: float | None = None,
    num: int = 201,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Terminal depth rate and air exchange rate over bladder volumes 0..V_max (7.6, 7.7; Fig 7.7).

    Returns `(volume_m3, depth_rate_m_s, exchange_rate_mol_s)`, each of length `num`; the net
    weight at V is rho g (V - V_neutral). `drag_coefficient` overrides the hull's.
    """
    if int(num) < 2:
        raise InvalidParameterError("num", num, "must be >= 2")
    cd = hull.drag_coefficient if drag_coefficient is None else drag_coefficient
    v = np.linspace(0.0, bladder.max_volume_m3, int(num))
    w = bladder.net_weight_n(v, environment)
    zdot = np.asarray(terminal_depth_rate_m_s(w, hull.cross_section_m2, cd, environment))
    ndot = np.asarray(air_exchange_rate_mol_s(v, zdot, environment))
    return v, zdot, ndot
