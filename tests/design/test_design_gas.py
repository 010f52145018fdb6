"""Hand checks for the ideal-gas tank model (7.1) and water pressure (7.3)."""

import math

import pytest

from glideplan.design import (
    FRESH_WATER,
    FX23DV,
    SEA_WATER,
    Environment,
    Tank,
    ideal_gas_moles,
    ideal_gas_volume_m3,
)
from glideplan.errors import InvalidParameterError


def test_fx23dv_moles_at_room_temperature():
    # p = 3442 psi * 6894.757 = 23,731,755 Pa; V = 183 in^3 * 1.6387064e-5 = 2.998833e-3 m^3
    # pV = 71,167.5 J; RT = 8.314 * 293.15 = 2437.25 J/mol -> n = 29.200 mol
    assert FX23DV.moles(293.15) == pytest.approx(29.200, abs=2e-3)


def test_dissertation_31_1_mol_needs_275_k():
    # 31.1 mol: T = pV / (n R) = 71,167.5 / (31.1 * 8.314) = 275.24 K (about 2 degC, not room temp)
    assert FX23DV.moles(275.24) == pytest.approx(31.10, abs=5e-3)


def test_air_mass_about_two_pounds():
    # 31.1 mol * 28.97 g/mol = 0.9010 kg = 1.986 lb ("about 2 lbs")
    assert FX23DV.air_mass_kg(275.24) / 0.45359237 == pytest.approx(1.986, abs=2e-3)


def test_ambient_pressure_and_inverse():
    # 101,325 + 1000 * 9.81 * 100 = 1,082,325 Pa
    assert FRESH_WATER.ambient_pressure_pa(100.0) == pytest.approx(1_082_325.0)
    assert FRESH_WATER.depth_at_pressure_m(1_082_325.0) == pytest.approx(100.0)


def test_tank_inflation_depth_about_2_km():
    # (23,731,755 - 101,325) / (1025 * 9.81) = 23,630,430 / 10,055.25 = 2350.1 m ("up to 2 km")
    assert FX23DV.max_inflation_depth_m(SEA_WATER) == pytest.approx(2350.1, abs=0.2)


def test_ideal_gas_inverse_and_vectorised():
    # 1 mol at 293.15 K and 101,325 Pa: V = 2437.25 / 101,325 = 0.0240538 m^3
    v = ideal_gas_volume_m3([1.0, 2.0], 101_325.0, 293.15)
    assert v[0] == pytest.approx(0.0240538, rel=1e-5)
    assert v[1] == pytest.approx(2 * v[0])
    assert ideal_gas_moles(101_325.0, v[0], 293.15) == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: ideal_gas_moles(-1.0, 1e-3, 293.0), "pressure_pa"),
        (lambda: ideal_gas_moles(1e5, -1e-3, 293.0), "volume_m3"),
        (lambda: ideal_gas_moles(1e5, 1e-3, 0.0), "temperature_k"),
        (lambda: Environment(water_density_kg_m3=-1000.0), "water_density_kg_m3"),
        (lambda: Tank(internal_volume_m3=-3e-3), "internal_volume_m3"),
        (lambda: Tank(max_pressure_pa=float("nan")), "max_pressure_pa"),
        (lambda: FRESH_WATER.ambient_pressure_pa(-5.0), "depth_m"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(InvalidParameterError) as err:
        call()
    assert err.value.name == name
    assert name in str(err.value)


def test_frozen():
    with pytest.raises(AttributeError):
        FX23DV.max_pressure_pa = 1.0  # type: ignore[misc]
    assert math.isclose(SEA_WATER.specific_weight_n_m3, 1025 * 9.81)
