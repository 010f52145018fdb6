"""VariableSpeedCar validation and the candidate table (4.26) as data."""

import math
from collections import Counter

import pytest

from glideplan import InvalidParameterError, VariableSpeedCar
from glideplan.planners.min_time import CANDIDATE_TYPES, alpha_subopt
from glideplan.planners.min_time.table import (
    SUPPLEMENTARY_TYPES,
    conditions,
    long_form,
    rigid_types,
)


def test_vehicle_radii_and_defaults():
    car = VariableSpeedCar(v_min=0.6, v_max=2.0, u_max=0.5)
    assert car.bang_radius == pytest.approx(4.0)
    assert car.corner_radius == pytest.approx(1.2)
    assert car.speed_ratio == pytest.approx(0.3)
    assert car.length_scale == pytest.approx(4.0)
    assert car.default_objective == "time"
    assert car.to_dict() == {
        "model": "variable_speed_car",
        "v_min": 0.6,
        "v_max": 2.0,
        "u_max": 0.5,
    }
    VariableSpeedCar(1.0, 1.0, 1.0)  # equal speeds: a Dubins car


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"v_min": 0.0}, "v_min"),
        ({"v_min": -0.1}, "v_min"),
        ({"v_min": 1.5, "v_max": 1.0}, "v_min"),
        ({"v_min": math.nan}, "v_min"),
        ({"v_max": math.inf}, "v_max"),
        ({"u_max": 0.0}, "u_max"),
        ({"u_max": math.nan}, "u_max"),
        ({"v_min": "fast"}, "v_min"),
    ],
)
def test_vehicle_rejects_bad_input(kwargs, name):
    with pytest.raises(InvalidParameterError) as err:
        VariableSpeedCar(**kwargs)
    assert err.value.name == name
    assert name in str(err.value)


def test_seventy_two_candidate_types():
    assert len(CANDIDATE_TYPES) == 72
    groups = Counter(t.group for t in CANDIDATE_TYPES)
    assert groups == {"TTTT": 24, "TST": 32, "umax": 8, "Dubins": 8}
    names = [t.name for t in CANDIDATE_TYPES]
    assert len(set(names)) == 72
    tst = {t.orientation for t in CANDIDATE_TYPES if t.group == "TST"}
    assert tst == {"LSL", "LSR", "RSL", "RSR"}
    assert {t.word for t in CANDIDATE_TYPES if t.group == "TTTT"} == {
        "BTTB", "BTBCB", "BTBC", "BTB", "BBCB", "BCBTB",
        "BCBBCB", "BCBBC", "BCBB", "CBTB", "CBBCB", "CBBC",
    }  # fmt: skip
    for t in CANDIDATE_TYPES:
        if t.group == "TTTT":  # consecutive turns alternate (rigid reversals)
            assert len(t.orientation) == t.interior + 2
            assert all(a != b for a, b in zip(t.orientation, t.orientation[1:], strict=False))
            assert t.word.replace("T", "BCB") == t.first + "BCB" * t.interior + t.last
        if t.group == "TST":
            assert t.word == t.first + "S" + t.last
    assert "BTB RLR" in names and "CBSB LSR" in names and "CBBCB LL" in names


def test_alpha_subopt_b12():
    rho = 0.3
    k = (1 - rho) / (1 + rho)
    for beta in (0.1, 1.0, math.pi / 2, math.pi, 5.0):
        a = alpha_subopt(beta, rho)
        assert a == pytest.approx(math.pi - beta / 2 - math.asin(math.sin(beta / 2) * k))
        # (B.13): the sub-optimal symmetric turn subtends less than 2 pi
        assert 2 * a + beta < 2 * math.pi
        # (B.11) with the angle sum of triangle EHG: sin(delta/2)/sin(beta/2) = (R-r)/(R+r)
        delta = 2 * (math.pi - a - beta / 2)
        assert math.sin(delta / 2) / math.sin(beta / 2) == pytest.approx(k)
    assert alpha_subopt(0.0, rho) == pytest.approx(math.pi)


def test_conditions_are_checked_on_the_long_form():
    btb = next(t for t in CANDIDATE_TYPES if t.name == "BTB RLR")
    a = 0.8
    turns = long_form(btb, "B", "B", 0.3, 0.5, a)
    assert turns == ((0.0, 0.0, 0.3), (a, math.pi, a), (0.5, 0.0, 0.0))
    ok = conditions(btb, turns, 0.3)
    assert ok == {"4.20": True, "4.23": True, "4.22": True, "4.24": True}
    # both boundary arcs as long as the interior ones: the sub-optimal B T_RS B of B.4
    bad = conditions(btb, long_form(btb, "B", "B", a, a, a), 0.3)
    assert bad["4.24"] is False
    # an interior B arc beyond alpha_subopt(pi) breaks (4.22)
    big = alpha_subopt(math.pi, 0.3) + 0.1
    assert conditions(btb, long_form(btb, "B", "B", 0.1, 0.1, big), 0.3)["4.22"] is False


def test_supplementary_rigid_types():
    assert len(SUPPLEMENTARY_TYPES) == 42
    assert all(not t.in_dissertation and t.group == "TTTT" for t in SUPPLEMENTARY_TYPES)
    assert all(t.in_dissertation for t in CANDIDATE_TYPES)
    words = {t.word for t in SUPPLEMENTARY_TYPES}
    assert {"CBTBC", "CBTBCB", "BCBTBC", "BCBTBCB"} <= words  # B.4's excluded B T_RS B
    table = {(t.first, t.interior, t.last) for t in CANDIDATE_TYPES if t.group == "TTTT"}
    assert not table & {(t.first, t.interior, t.last) for t in SUPPLEMENTARY_TYPES}
    assert len(rigid_types(5)) == 18  # every (first, last) pair, two orientations
