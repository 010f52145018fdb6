"""Ideal gas, water properties and compressed-air tanks for the buoyancy engine (7.1, 7.3)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from glideplan.errors import InvalidParameterError
from glideplan.units import inch3_to_m3, lb_to_kg, psi_to_pa
from glideplan.validation import check_fields, check_positive, scalar_or_array
from glideplan.validation import check_nonnegative_array as nonnegative_array
from glideplan.validation import check_positive_array as positive_array

__all__ = [
    "FRESH_WATER",
    "FX23DV",
    "M_AIR_KG_PER_MOL",
    "R_GAS_J_PER_MOL_K",
    "SEA_WATER",
    "Environment",
    "Tank",
    "ideal_gas_moles",
    "ideal_gas_pressure_pa",
    "ideal_gas_volume_m3",
]

R_GAS_J_PER_MOL_K = 8.314  # universal gas constant as printed under (7.1)
M_AIR_KG_PER_MOL = 0.02897  # molar mass of dry air


@dataclass(frozen=True)
class Environment:
    """Water and air conditions: density, gravity, surface pressure and gas temperature (SI)."""

    water_density_kg_m3: float = 1000.0
    gravity_m_s2: float = 9.81
    atmospheric_pressure_pa: float = 101_325.0
    temperature_k: float = 293.15

    def __post_init__(self) -> None:
        names = ("water_density_kg_m3", "gravity_m_s2", "atmospheric_pressure_pa", "temperature_k")
        check_fields(self, check_positive, names)

    @property
    def specific_weight_n_m3(self) -> float:
        """rho g of the water (N/m^3)."""
        return self.water_density_kg_m3 * self.gravity_m_s2

    def ambient_pressure_pa(self, depth_m: ArrayLike) -> np.ndarray | float:
        """Absolute water pressure at depth z >= 0: p_atm + rho g z (7.3)."""
        z = nonnegative_array("depth_m", depth_m)
        return scalar_or_array(self.atmospheric_pressure_pa + self.specific_weight_n_m3 * z)

    def depth_at_pressure_m(self, pressure_pa: ArrayLike) -> np.ndarray | float:
        """Depth where the absolute water pressure equals `pressure_pa` (inverse of 7.3)."""
        p = positive_array("pressure_pa", pressure_pa)
        return scalar_or_array((p - self.atmospheric_pressure_pa) / self.specific_weight_n_m3)


FRESH_WATER = Environment()
SEA_WATER = Environment(water_density_kg_m3=1025.0)


def ideal_gas_moles(pressure_pa: ArrayLike, volume_m3: ArrayLike, temperature_k: ArrayLike):
    """Amount of gas n = pV/(RT) in mol (7.1)."""
    p = nonnegative_array("pressure_pa", pressure_pa)
    v = nonnegative_array("volume_m3", volume_m3)
    t = positive_array("temperature_k", temperature_k)
    return scalar_or_array(p * v / (R_GAS_J_PER_MOL_K * t))


def ideal_gas_pressure_pa(moles: ArrayLike, volume_m3: ArrayLike, temperature_k: ArrayLike):
    """Pressure p = nRT/V in Pa (7.1, 7.4)."""
    n = nonnegative_array("moles", moles)
    v = positive_array("volume_m3", volume_m3)
    t = positive_array("temperature_k", temperature_k)
    return scalar_or_array(n * R_GAS_J_PER_MOL_K * t / v)


def ideal_gas_volume_m3(moles: ArrayLike, pressure_pa: ArrayLike, temperature_k: ArrayLike):
    """Volume V = nRT/p in m^3 (7.1)."""
    n = nonnegative_array("moles", moles)
    p = positive_array("pressure_pa", pressure_pa)
    t = positive_array("temperature_k", temperature_k)
    return scalar_or_array(n * R_GAS_J_PER_MOL_K * t / p)


@dataclass(frozen=True)
class Tank:
    """A compressed-air cylinder: rated pressure, internal volume and empty mass (Table 7.3)."""

    name: str = "custom"
    max_pressure_pa: float = 23.73e6
    internal_volume_m3: float = 3.0e-3
    empty_mass_kg: float = 3.9

    def __post_init__(self) -> None:
        if not isinstance(self.name, str):
            raise InvalidParameterError("name", self.name, "must be a string")
        check_fields(
            self, check_positive, ("max_pressure_pa", "internal_volume_m3", "empty_mass_kg")
        )

    def moles(self, temperature_k: ArrayLike, pressure_pa: ArrayLike | None = None):
        """Air in the tank n_tank = pV/(RT) (7.1); full tank unless `pressure_pa` is given."""
        p = self.max_pressure_pa if pressure_pa is None else pressure_pa
        return ideal_gas_moles(p, self.internal_volume_m3, temperature_k)

    def air_mass_kg(self, temperature_k: ArrayLike, pressure_pa: ArrayLike | None = None):
        """Mass of the air in the tank m = n M_air (kg)."""
        n = np.asarray(self.moles(temperature_k, pressure_pa))
        return scalar_or_array(n * M_AIR_KG_PER_MOL)

    def pressure_pa(self, moles: ArrayLike, temperature_k: ArrayLike):
        """Tank pressure holding `moles` of air at `temperature_k` (7.1)."""
        return ideal_gas_pressure_pa(moles, self.internal_volume_m3, temperature_k)

    def max_inflation_depth_m(self, environment: Environment) -> float:
        """Deepest point where a full tank can still push air out: p_tank = p_amb (7.3)."""
        return float(environment.depth_at_pressure_m(self.max_pressure_pa))


# Faber FX23DV steel pony tank, Table 7.3: 3,442 psi, 183 in^3, 8.6 lb empty.
FX23DV = Tank(
    name="Faber FX23DV",
    max_pressure_pa=psi_to_pa(3442.0),
    internal_volume_m3=inch3_to_m3(183.0),
    empty_mass_kg=lb_to_kg(8.6),
)
