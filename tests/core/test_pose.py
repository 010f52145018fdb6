"""Poses, angle wrapping and frame changes."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from glideplan import InvalidParameterError, Pose, mod_2pi, wrap_to_pi
from glideplan.pose import to_local, to_world

coord = st.floats(-100, 100, allow_nan=False)
angle = st.floats(-20, 20, allow_nan=False)


def test_wrap_to_pi_and_mod_2pi_hand_values():
    # 3pi/2 is -pi/2 modulo 2pi; -pi/2 is 3pi/2 in [0, 2pi)
    assert wrap_to_pi(1.5 * math.pi) == pytest.approx(-0.5 * math.pi)
    assert mod_2pi(-0.5 * math.pi) == pytest.approx(1.5 * math.pi)
    assert mod_2pi(2 * math.pi) == 0.0
    assert wrap_to_pi(math.pi) == pytest.approx(-math.pi)
    np.testing.assert_allclose(wrap_to_pi(np.array([0.0, 7.0])), [0.0, 7.0 - 2 * math.pi])


def test_relative_to_hand_value():
    # frame at (1, 1) facing +y: the world point (1, 3) is 2 ahead, 0 to the side
    frame = Pose(1.0, 1.0, math.pi / 2)
    local = Pose(1.0, 3.0, math.pi).relative_to(frame)
    assert (local.x, local.y, local.heading) == pytest.approx((2.0, 0.0, math.pi / 2))


@settings(max_examples=60, deadline=None)
@given(coord, coord, angle, coord, coord, angle, st.booleans())
def test_local_world_round_trip(x, y, h, fx, fy, fh, reflect):
    frame = np.array([fx, fy, fh])
    p = np.array([x, y, h])
    back = to_world(to_local(p, frame, reflect=reflect), frame, reflect=reflect)
    np.testing.assert_allclose(back, p, atol=1e-9)


def test_frame_change_preserves_distance():
    rng = np.random.default_rng(1)
    p, q, f = rng.normal(size=(3, 50, 3)) * 5
    dl = np.hypot(*(to_local(p, f)[:, :2] - to_local(q, f)[:, :2]).T)
    dw = np.hypot(*(p[:, :2] - q[:, :2]).T)
    np.testing.assert_allclose(dl, dw, rtol=1e-12)


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf, "a"])
def test_pose_rejects_non_finite(bad):
    with pytest.raises(InvalidParameterError, match="x"):
        Pose(bad, 0.0, 0.0)


def test_from_array_needs_three_values():
    with pytest.raises(InvalidParameterError, match="three"):
        Pose.from_array([1.0, 2.0])
