"""Hand checks for CG, CB and equilibrium pitch (7.9-7.14)."""

import math

import numpy as np
import pytest

from glideplan.design import (
    VTUG_TRIM,
    TrimLayout,
    centre_of_buoyancy_m,
    centre_of_gravity_m,
    equilibrium_pitch_rad,
    net_vertical_force_n,
    pitch_range_rad,
)
from glideplan.errors import InvalidParameterError

# 10 kg moving mass 0.05 m below the centreline, 5 kg tank and 35 kg body at 1.0 m from the tail,
# 0.05 m^3 hull (50 kg of fresh water) centred at 1.0 m, bladder at 1.6 m.
SIMPLE = TrimLayout(
    moving_mass_kg=10.0,
    moving_mass_offset_m=0.05,
    moving_mass_min_station_m=0.9,
    moving_mass_max_station_m=1.1,
    tank_mass_kg=5.0,
    tank_station_m=1.0,
    body_mass_kg=35.0,
    body_station_m=1.0,
    body_volume_m3=0.05,
    body_buoyancy_station_m=1.0,
    bladder_station_m=1.6,
)


def test_centre_of_gravity_7_11_7_12():
    # l_MM = 1.1: CGx = (10 * 1.1 + 5 * 1.0 + 35 * 1.0) / 50 = 1.02; CGz = 0.05 * 10 / 50 = 0.01
    cgx, cgz = centre_of_gravity_m(SIMPLE, 1.1)
    assert cgx == pytest.approx(1.02)
    assert cgz == pytest.approx(0.01)


def test_centre_of_buoyancy_7_13():
    # (1.0 * 0.05 + 1.6 * 0.0025) / 0.0525 = 0.054 / 0.0525 = 1.028571
    assert centre_of_buoyancy_m(SIMPLE, 2.5e-3) == pytest.approx(1.028571, abs=1e-6)


def test_pitch_nose_down_when_mass_moves_forward():
    # tan theta = (CBx - CGx) / CGz = (1.0 - 1.02) / 0.01 = -2 -> theta = -63.435 deg
    theta = equilibrium_pitch_rad(SIMPLE, [1.0, 1.1, 0.9], 0.0)
    assert np.degrees(theta) == pytest.approx([0.0, -63.435, 63.435], abs=1e-3)


def test_tail_moments_agree_when_neutrally_buoyant():
    # (7.9) holds at bladder 0 (50 kg of buoyancy, 50 kg of mass): both references agree
    assert net_vertical_force_n(SIMPLE, 0.0) == pytest.approx(0.0, abs=1e-9)
    lmm = np.linspace(0.9, 1.1, 9)
    a = equilibrium_pitch_rad(SIMPLE, lmm, 0.0)
    b = equilibrium_pitch_rad(SIMPLE, lmm, 0.0, reference="tail")
    assert a == pytest.approx(b, abs=1e-12)


def test_net_vertical_force_7_9():
    # bladder 2.5 L: 9810 * 0.0525 - 50 * 9.81 = 515.025 - 490.5 = 24.525 N up
    assert net_vertical_force_n(SIMPLE, 2.5e-3) == pytest.approx(24.525)


def test_pitch_range_brackets_zero_for_example_layout():
    aft, fwd = pitch_range_rad(VTUG_TRIM, 2.5e-3)
    assert aft > 0.0 > fwd
    assert -math.pi / 2 < fwd and aft < math.pi / 2


@pytest.mark.parametrize(
    ("call", "name"),
    [
        (lambda: TrimLayout(moving_mass_kg=-1.0), "moving_mass_kg"),
        (
            lambda: TrimLayout(moving_mass_min_station_m=1.2, moving_mass_max_station_m=1.0),
            "moving_mass_min_station_m",
        ),
        (lambda: equilibrium_pitch_rad(SIMPLE, 1.0, -1e-3), "bladder_volume_m3"),
        (lambda: equilibrium_pitch_rad(SIMPLE, 1.0, 0.0, reference="nose"), "reference"),
    ],
)
def test_bad_input_names_the_parameter(call, name):
    with pytest.raises(InvalidParameterError) as err:
        call()
    assert err.value.name == name
