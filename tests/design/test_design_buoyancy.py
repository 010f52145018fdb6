"""Hand checks for dives, net weight, bladder equilibrium and air exchange (7.1-7.7)."""

import numpy as np
import pytest

from glideplan.design import (
    FRESH_WATER,
    FX23DV,
    VTUG_BLADDER,
    VTUG_HULL,
    Bladder,
    Environment,
    Hull,
    air_exchange_rate_mol_s,
    bladder_moles,
    equilibrium_volume_m3,
    exchange_rate_sweep,
    lung_volume_m3,
    moles_per_cycle,
    net_weight_n,
    number_of_dives,
    terminal_depth_rate_m_s,
)
from glideplan.errors import InvalidParameterError
from glideplan.units import psi_to_pa

RT = 8.314 * 293.15  # 2437.25 J/mol


def test_lung_volume_5_percent_of_50_kg():
    # 0.05 * 50 kg * g / (1000 kg/m^3 * g) = 2.5e-3 m^3 = 2.5 L (Table 7.2)
    assert lung_volume_m3(0.05, 50.0) == pytest.approx(2.5e-3)


def test_moles_per_cycle_5_litres_100_m():
    # p = 1,082,325 Pa; n = 1,082,325 * 0.005 / 2437.25 = 5411.6 / 2437.25 = 2.2204 mol
    assert moles_per_cycle(5e-3, 100.0) == pytest.approx(2.2204, abs=1e-4)


def test_thirteen_dives_at_5_litres_100_m():
    # N = p_t V_t / (p_amb V) = 71,167.5 / 5,411.6 = 13.151 -> 13 full dives (dissertation: 13)
    n = number_of_dives(FX23DV, 5e-3, 100.0)
    assert n == pytest.approx(13.151, abs=2e-3)
    assert int(n) == 13


def test_dive_count_does_not_depend_on_temperature():
    # n_tank and n_cycle both scale as 1/T, so N = p_t V_t / (p_amb V) at any T
    cold = Environment(temperature_k=275.24)
    assert number_of_dives(FX23DV, 5e-3, 100.0, cold) == pytest.approx(
        number_of_dives(FX23DV, 5e-3, 100.0)
    )


def test_dive_counts_table_7_1_grid():
    # 3 L, 100 m: 71,167.5 / (1,082,325 * 0.003) = 21.918; 5 L, 50 m: 71,167.5 / (591,825 * 0.005)
    # = 24.050; 3 L, 50 m: 40.084 (Table 7.1 prints 21, 19 and 35; see REFERENCE_NOTES section 6)
    n = number_of_dives(FX23DV, [3e-3, 5e-3, 3e-3], [100.0, 50.0, 50.0])
    assert n == pytest.approx([21.918, 24.050, 40.084], abs=2e-3)


def test_usable_air_subtracts_residual_at_depth():
    # residual = 1,082,325 * 2.998833e-3 = 3245.7 J; (71,167.5 - 3245.7) / 5411.6 = 12.551
    assert number_of_dives(FX23DV, 5e-3, 100.0, usable_only=True) == pytest.approx(12.551, abs=2e-3)


def test_depth_the_tank_cannot_inflate_at():
    # fresh water: (23,731,755 - 101,325) / 9810 = 2408.8 m is the deepest possible inflation
    with pytest.raises(InvalidParameterError) as err:
        number_of_dives(FX23DV, 5e-3, 2500.0)
    assert err.value.name == "depth_m"
    assert "cannot inflate" in str(err.value)


def test_net_weight_as_tank_empties():
    # neutral at 0.9 kg of air and 2.5 L; empty tank, 5 L: 9810 * 0.0025 + 0.9 * 9.81 = 33.354 N
    w = net_weight_n(
        [0.9, 0.0], [2.5e-3, 5e-3], trim_air_mass_kg=0.9, trim_bladder_volume_m3=2.5e-3
    )
    assert w == pytest.approx([0.0, 33.354], abs=1e-3)


def test_default_elastic_curve_values():
    # p_blad(x) = (1.5 x - 2.5 x^2 + 1.5 x^3 + 0.5 x^4) psi: x = 1 -> 1 psi; x = 0.5 -> 0.34375 psi
    p = VTUG_BLADDER.elastic_pressure_pa([0.0, 2.5e-3, 5e-3])
    assert p == pytest.approx([0.0, psi_to_pa(0.34375), psi_to_pa(1.0)])


def test_bladder_moles_from_7_5():
    # n = (1,082,325 + 6894.76) * 0.005 / 2437.25 = 5446.10 / 2437.25 = 2.23453 mol
    assert bladder_moles(VTUG_BLADDER, 5e-3, 100.0) == pytest.approx(2.23453, abs=1e-4)


def test_equilibrium_volume_without_elasticity_is_boyle():
    # p_blad = 0: V = nRT / p_amb = 2437.249 / 1,082,325 = 2.25186e-3 m^3 for 1 mol at 100 m
    slack = Bladder(elastic_coefficients_pa=())
    assert equilibrium_volume_m3(slack, 1.0, 100.0) == pytest.approx(2.25186e-3, rel=1e-5)


def test_equilibrium_volume_inverts_bladder_moles_and_saturates():
    v = np.linspace(0.2e-3, 4.8e-3, 7)
    z = np.linspace(0.0, 100.0, 7)
    n = bladder_moles(VTUG_BLADDER, v, z)
    assert equilibrium_volume_m3(VTUG_BLADDER, n, z) == pytest.approx(v, rel=1e-9)
    # 1 mol at the surface would need 2437.25 / (101,325 + p_blad) > 5 L -> saturates at 5 L
    assert equilibrium_volume_m3(VTUG_BLADDER, 1.0, 0.0) == pytest.approx(5e-3)


def test_open_loop_bladder_expands_on_ascent():
    # fixed air: shallower -> lower p_amb -> larger volume (Fig 7.6 contours lean to larger V)
    v = equilibrium_volume_m3(VTUG_BLADDER, 1.0, [100.0, 60.0, 30.0])
    assert np.all(np.diff(v) > 0)


def test_terminal_depth_rate_7_7():
    # S = pi 0.2286^2 / 4 = 0.0410433 m^2; 2 * 24.525 / (1000 * 0.0410433 * 0.1) = 11.9508
    # -> 3.4570 m/s, rising (negative) because the net weight is buoyant
    s = VTUG_HULL.cross_section_m2
    assert s == pytest.approx(0.0410433, rel=1e-5)
    zdot = terminal_depth_rate_m_s([24.525, -24.525, 0.0], s, 0.1)
    assert zdot == pytest.approx([-3.4570, 3.4570, 0.0], abs=1e-4)


def test_air_exchange_rate_7_6():
    # 9810 * 0.005 * (-3.4570) / 2437.25 = -0.069572 mol/s (exhaust while rising)
    assert air_exchange_rate_mol_s(5e-3, -3.4570) == pytest.approx(-0.069572, abs=1e-6)
    # REFERENCE_NOTES check: 5 L at 1 m/s -> 9810 * 0.005 / 2437.25 = 0.020125 mol/s
    assert air_exchange_rate_mol_s(5e-3, 1.0) == pytest.approx(0.020125, abs=1e-6)


def test_fig_7_7_maximum_inflation_rate():
    # descent: V = 2.5 L (1 - s), ndot ~ (1 - s) sqrt(s), maximal at s = 1/3 -> V = 1.6667 L;
    # W~ = 9810 * 0.8333e-3 = 8.175 N, zdot = sqrt(2 * 8.175 / 4.10433) = 1.99590 m/s,
    # ndot = 9810 * 1.6667e-3 * 1.99590 / 2437.25 = 0.013390 mol/s
    v, zdot, ndot = exchange_rate_sweep(VTUG_BLADDER, VTUG_HULL, num=3001)
    assert np.all(zdot[v < 2.5e-3] > 0)  # heavy -> descending
    k = int(np.argmax(ndot))
    assert v[k] == pytest.approx(1.6667e-3, abs=5e-6)
    assert ndot[k] == pytest.approx(0.013390, abs=2e-6)
    # at neutral (2.5 L) and empty (0 L) no exchange is needed
    assert ndot[0] == 0.0
    assert ndot[np.argmin(abs(v - 2.5e-3))] == pytest.approx(0.0, abs=1e-12)
    # lower drag -> faster -> more air to exchange
    _, _, slow = exchange_rate_sweep(VTUG_BLADDER, VTUG_HULL, drag_coefficient=1.0, num=3001)
    assert np.min(ndot) < np.min(slow)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: moles_per_cycle(-1e-3, 10.0), "volume_m3"),
        (lambda: number_of_dives(FX23DV, -5e-3, 100.0), "volume_m3"),
        (lambda: number_of_dives(FX23DV, 5e-3, -1.0), "depth_m"),
        (lambda: Bladder(max_volume_m3=-5e-3), "max_volume_m3"),
        (lambda: Bladder(neutral_volume_m3=6e-3), "neutral_volume_m3"),
        (lambda: Bladder(elastic_coefficients_pa=(-1e4,)), "elastic_coefficients_pa"),
        (lambda: VTUG_BLADDER.elastic_pressure_pa(6e-3), "volume_m3"),
        (lambda: Hull(diameter_m=0.0), "diameter_m"),
        (lambda: terminal_depth_rate_m_s(10.0, 0.04, -0.1), "drag_coefficient"),
        (lambda: lung_volume_m3(0.05, -50.0), "dry_mass_kg"),
        (lambda: equilibrium_volume_m3(VTUG_BLADDER, -1.0, 10.0), "moles"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(InvalidParameterError) as err:
        call()
    assert err.value.name == name


def test_fresh_water_is_default():
    assert FRESH_WATER.water_density_kg_m3 == 1000.0
