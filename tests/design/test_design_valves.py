"""Hand checks for the valve flow formula (7.8) and the deflator/inflator sizing (Fig 7.8)."""

import numpy as np
import pytest

from glideplan.design import (
    VTUG_BLADDER,
    VTUG_HULL,
    deflator_cv,
    flow_coefficient,
    gas_flow_scfm,
    inflator_cv,
    molar_flow_to_scfm,
    required_cv,
    scfm_to_molar_flow,
)
from glideplan.errors import InvalidParameterError
from glideplan.units import psi_to_pa


def test_one_mol_per_second_is_50_scfm():
    # 8.314 * 288.706 K / 101,325 Pa = 0.0236893 m^3/mol = 0.836578 ft^3/mol; * 60 = 50.195 scfm
    assert molar_flow_to_scfm(1.0) == pytest.approx(50.195, abs=1e-3)
    assert scfm_to_molar_flow(50.195) == pytest.approx(1.0, abs=1e-4)


def test_subsonic_flow_7_8():
    # Cv = 1, p1 = 100 psia, p2 = 90 psia, T = 520 R:
    # 22.67 * 100 * (1 - 20/300) * sqrt(10 / (100 * 520)) = 2115.87 * 0.0138675 = 29.342 scfm
    assert gas_flow_scfm(1.0, 100.0, 90.0, 520.0) == pytest.approx(29.342, abs=2e-3)


def test_choked_flow():
    # p2 = 20 < p1/2: q = (2/3) sqrt(1/2) * 22.67 * 100 / sqrt(520) = 1068.67 * 0.0438529 = 46.864
    assert gas_flow_scfm(1.0, 100.0, 20.0, 520.0) == pytest.approx(46.864, abs=2e-3)
    # (7.8) as printed past choking: 2267 * (1 - 160/300) * sqrt(80/52000) = 41.496 (smaller)
    assert gas_flow_scfm(1.0, 100.0, 20.0, 520.0, choked="never") == pytest.approx(41.496, abs=2e-3)


def test_choked_branch_is_continuous():
    q_sub = gas_flow_scfm(1.0, 100.0, 50.0 + 1e-9, 520.0)
    q_ch = gas_flow_scfm(1.0, 100.0, 50.0 - 1e-9, 520.0)
    assert q_sub == pytest.approx(q_ch, rel=1e-6)


def test_flow_coefficient_inverts_flow():
    p2 = np.array([95.0, 60.0, 10.0])
    q = gas_flow_scfm(0.37, 100.0, p2, 530.0)
    assert flow_coefficient(q, 100.0, p2, 530.0) == pytest.approx(0.37)


def test_deflator_cv_hand_check():
    # V = 5 L, 100 m: dp = p_blad = 1 psi; p2 = 1,082,325 Pa = 156.977 psia, p1 = 157.977 psia
    # ndot = 0.069572 mol/s -> q = 3.49217 scfm; T1 = 293.15 * 1.8 = 527.67 R
    # 157.977 * (1 - 2/(3 * 157.977)) * sqrt(1 / (157.977 * 527.67)) = 0.544846
    # Cv = 3.49217 / (22.67 * 0.544846) = 0.28273
    assert deflator_cv(VTUG_BLADDER, VTUG_HULL, 5e-3, 100.0) == pytest.approx(0.28273, abs=2e-4)


def test_deflator_cv_falls_with_depth():
    # ndot (7.6) does not depend on depth, and q ~ Cv sqrt(p1 dp) for dp << p1, so the needed
    # Cv falls as 1/sqrt(p1): the opposite of the trend the dissertation states for Fig 7.8a.
    cv = deflator_cv(VTUG_BLADDER, VTUG_HULL, 4e-3, [0.0, 50.0, 100.0])
    assert np.all(np.diff(cv) < 0)


def test_inflator_choked_vs_printed_formula():
    # tank 500 psia vs a bladder near 15 psia: choked; (7.8) as printed overstates Cv
    v = np.linspace(0.0, 2.4e-3, 25)
    ch = inflator_cv(VTUG_BLADDER, VTUG_HULL, v, psi_to_pa(500.0))
    pr = inflator_cv(VTUG_BLADDER, VTUG_HULL, v, psi_to_pa(500.0), choked="never")
    ratio = pr[1:] / ch[1:]
    assert np.all(ratio > 1.2)
    # at very high pressure ratio: (2/3 sqrt(1/2)) / (1/3) = 1.414 is the printed/choked limit
    assert np.all(ratio < 1.42)


def test_required_cv_si_matches_imperial():
    # 0.02 mol/s = 1.00390 scfm; 200 kPa -> 29.0075 psia, 150 kPa -> 21.7557 psia; 300 K = 540 R
    si = required_cv(0.02, 200e3, 150e3, 300.0)
    imp = flow_coefficient(1.00390, 29.0075, 21.7557, 540.0)
    assert si == pytest.approx(imp, rel=1e-4)


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: gas_flow_scfm(1.0, 50.0, 60.0, 520.0), "inlet_pressure_psia"),
        (lambda: gas_flow_scfm(-1.0, 100.0, 60.0, 520.0), "cv"),
        (lambda: gas_flow_scfm(1.0, -100.0, 60.0, 520.0), "inlet_pressure_psia"),
        (lambda: gas_flow_scfm(1.0, 100.0, 60.0, 520.0, choked="sometimes"), "choked"),
        (lambda: flow_coefficient(-1.0, 100.0, 60.0, 520.0), "q_scfm"),
        (
            lambda: inflator_cv(VTUG_BLADDER, VTUG_HULL, 1e-3, 1e5, depth_m=100.0),
            "tank_pressure_pa",
        ),
        (lambda: inflator_cv(VTUG_BLADDER, VTUG_HULL, 3e-3, 1e7), "volume_m3"),
        (lambda: deflator_cv(VTUG_BLADDER, VTUG_HULL, 1e-3, 10.0), "volume_m3"),
        (lambda: deflator_cv(VTUG_BLADDER, VTUG_HULL, 4e-3, -10.0), "depth_m"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(InvalidParameterError) as err:
        call()
    assert err.value.name == name
