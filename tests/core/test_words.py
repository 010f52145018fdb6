"""The one turn-word labeller (`glideplan.words`) and the constants of `glideplan.units`."""

import numpy as np
import pytest
import scipy.constants as sc

from glideplan import units
from glideplan.words import run_word, turn_letters


def test_run_word_merges_runs_and_drops_light_ones():
    """Hand-worked: L(2) S(0) L(1) R(0.5), min 1: S and R dropped, the two L runs merge: 'L'."""
    assert run_word("LSLR", [2.0, 0.0, 1.0, 0.5], min_weight=1.0) == "L"
    assert run_word("LSLR", [2.0, 0.0, 1.0, 0.5], min_weight=0.0, strict=True) == "LR"
    assert run_word("LLSSRR") == "LSR"
    assert run_word("LR", [0.1, 0.1], min_weight=1.0) == ""
    assert run_word("LR", [0.1, 0.1], min_weight=1.0, keep_all_if_empty=True) == "LR"
    with pytest.raises(ValueError, match="weights"):
        run_word("LR", [1.0])


def test_turn_letters_follow_the_sign_convention():
    """L = counter-clockwise = turn rate > 0 (docs/ARCHITECTURE.md)."""
    assert "".join(turn_letters([0.5, 1e-4, -0.5, 0.0], tol=1e-3)) == "LSRS"


def test_unit_factors_are_the_scipy_constants():
    """The exact definitions written in units.py equal scipy.constants (NIST values)."""
    assert units.G0 == sc.g
    assert units.LB_KG == pytest.approx(sc.pound, rel=1e-15)
    assert units.LBF_N == pytest.approx(sc.lbf, rel=1e-15)
    assert units.INCH_M == sc.inch and units.FT_M == pytest.approx(sc.foot, rel=1e-15)
    assert units.PSI_PA == pytest.approx(sc.psi, rel=1e-15)
    assert units.celsius_to_kelvin(0.0) == sc.zero_Celsius
    assert units.kmh_to_ms(36.0) == pytest.approx(10.0, rel=1e-15)
    np.testing.assert_allclose(units.feet_to_m(np.array([1.0, 2.0])), [sc.foot, 2 * sc.foot])
