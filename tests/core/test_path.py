"""Path: continuity, words, costs, sampling, transforms."""

import math
from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest

from glideplan import Arc, HeadingSpeedArc, InvalidParameterError, Path, Pose, Straight
from glideplan.vehicles.base import Vehicle
from glideplan.verify import integrate_path


@dataclass(frozen=True)
class ToyGlider(Vehicle):
    """Sink rate w = 0.01 v^2 + 0.1 |u| (made up, for cost integration)."""

    model: ClassVar[str] = "toy_glider"

    def sink_rate(self, speed, turn_rate):
        return 0.01 * np.asarray(speed) ** 2 + 0.1 * np.abs(turn_rate)


def lsr(start=Pose(0, 0, 0)):
    a = Arc(start, math.pi / 2, 1.0, 1, speed=2.0, label="C")
    s = Straight(a.end, 3.0, speed=2.0)
    b = Arc(s.end, 1.0, 2.0, -1, speed=2.0)
    return Path((a, s, b))


def test_length_duration_word_family():
    p = lsr()
    assert p.length == pytest.approx(math.pi / 2 + 3.0 + 2.0)
    assert p.duration == pytest.approx(p.length / 2.0)
    assert p.word == "LSR"
    assert p.family == "CSB"


def test_word_merges_same_direction_turns_and_drops_empty_segments():
    a = Arc(Pose(0, 0, 0), 1.0, 1.0, 1, label="B")
    c = Arc(a.end, 0.5, 0.3, 1, speed=0.3, label="C")
    z = Straight(c.end, 0.0)
    b = Arc(z.end, 1.0, 1.0, 1, label="B")
    p = Path((a, c, z, b))
    assert p.word == "L"
    assert p.family == "BCSB"


def test_discontinuous_segments_are_rejected():
    a = Arc(Pose(0, 0, 0), 1.0, 1.0, 1)
    with pytest.raises(InvalidParameterError, match="does not start"):
        Path((a, Straight(Pose(5, 5, 0), 1.0)))
    with pytest.raises(InvalidParameterError):
        Path(())


def test_costs_time_length_altitude():
    p = lsr().with_vehicle(ToyGlider())
    # altitude: every segment at v = 2: 0.04 per second, plus 0.1 |u| per second on arcs
    # = 0.04 * T + 0.1 * (total heading change) = 0.04 T + 0.1 (pi/2 + 1)
    expect = 0.04 * p.duration + 0.1 * (math.pi / 2 + 1.0)
    assert p.cost("altitude") == pytest.approx(expect, rel=1e-12)
    assert integrate_path(p, "altitude").cost == pytest.approx(expect, rel=1e-9)
    assert p.cost("time") == p.duration
    with pytest.raises(InvalidParameterError, match="objective"):
        p.cost("fuel")
    with pytest.raises(InvalidParameterError, match="sink"):
        lsr().cost("altitude")


def test_sampling_by_time_and_length_agree():
    p = lsr()
    smp = p.sample(n=50)
    assert smp.t[0] == 0 and smp.t[-1] == pytest.approx(p.duration)
    assert smp.s[-1] == pytest.approx(p.length)
    by_len = p.sample(lengths=smp.s)
    np.testing.assert_allclose(by_len.t, smp.t, atol=1e-9)
    np.testing.assert_allclose(by_len.x, smp.x, atol=1e-9)
    assert np.all(np.diff(smp.s) > 0)
    assert (smp.x[-1], smp.y[-1]) == pytest.approx((p.end.x, p.end.y))


def test_cumulative_cost_samples():
    p = lsr().with_vehicle(ToyGlider())
    smp = p.sample(n=30, objective="altitude")
    assert smp.cost[0] == pytest.approx(0.0)
    assert smp.cost[-1] == pytest.approx(p.cost("altitude"))
    assert np.all(np.diff(smp.cost) >= 0)


def test_transforms_and_concatenation():
    p = lsr()
    r = p.reflected()
    assert r.word == "RSL"
    assert (r.end.x, r.end.y, r.end.heading) == pytest.approx((p.end.x, -p.end.y, -p.end.heading))
    t = p.translated(1.0, -2.0)
    assert t.end.x == pytest.approx(p.end.x + 1.0)
    q = p.rotated(math.pi)
    assert q.end.x == pytest.approx(-p.end.x)
    second = lsr(p.end)
    both = p + second
    assert both.length == pytest.approx(2 * p.length)
    assert both.word == "LSRLSR"
    with pytest.raises(InvalidParameterError):
        p + p  # does not start where p ends


def test_heading_speed_arc_in_a_path_verifies():
    h = HeadingSpeedArc(Pose(0, 0, 0), 2.0, -1, 0.2, 30.0, 2.0, 1.0)
    s = Straight(h.end, 100.0, speed=29.0)
    p = Path((h, s))
    end = integrate_path(p).end
    assert end.distance_to(p.end) < 1e-7


def test_verification_does_not_trust_a_false_constant_controls_claim():
    class Liar(HeadingSpeedArc):
        constant_controls = True  # wrong: the speed varies with heading

    seg = Liar(Pose(0, 0, 0), 3.0, 1, 0.2, 30.0, 5.0, 0.3)
    end = integrate_path(Path((seg,))).end
    assert end.distance_to(seg.end) < 1e-7  # integrated with the real, varying speed


def test_sample_refuses_more_points_than_its_stated_limit():
    """n = 1e10 would need ~800 GB: a clear error naming n and the limit, not a MemoryError."""
    from glideplan.path import MAX_SAMPLES

    p = Path((Straight(Pose(), 3.0), Arc(Pose(3.0, 0.0, 0.0), 1.0, 2.0, 1)))
    with pytest.raises(InvalidParameterError, match=rf"n=.*{MAX_SAMPLES}"):
        p.sample(n=10**10)
    with pytest.raises(InvalidParameterError, match="integer"):
        p.sample(n=2.5)
    assert p.sample(n=MAX_SAMPLES // 1000).x.size == MAX_SAMPLES // 1000


def test_word_drops_zero_length_segments():
    """A straight flown as an LSL type with empty arcs is the word "S" (issue 11)."""
    p = Path(
        (
            Arc(Pose(), 0.0, 1.0, 1),
            Straight(Pose(), 5.0),
            Arc(Pose(5.0, 0.0, 0.0), 0.0, 1.0, 1),
        )
    )
    assert p.word == "S" and p.family == "BSB"


def test_path_arrays_round_trip_keeps_the_geometry():
    """Path -> PathArrays (simulation) -> Path: same word, length and end pose; the reference
    is the original path's closed-form end."""
    from glideplan import dubins_path
    from glideplan.simulation import PathArrays

    paths = [
        dubins_path(Pose(), Pose(4.0, 3.0, 1.0), 1.0),
        dubins_path(Pose(1.0, 2.0, 0.5), Pose(-4.0, 3.0, 2.0), 2.0),
        Path((Straight(Pose(), 2.0),)),
    ]
    arrays = PathArrays.from_paths(paths)
    for i, p in enumerate(paths):
        q = arrays.path(i)
        assert q.word == p.word
        assert q.length == pytest.approx(p.length, abs=1e-12)
        assert q.end.distance_to(p.end) < 1e-12
        np.testing.assert_allclose(arrays.end[i], p.end.as_array(), atol=1e-12)
    with pytest.raises(InvalidParameterError, match="constant curvature"):
        PathArrays.from_paths([Path((HeadingSpeedArc(Pose(), 1.0, 1, 0.2, 30.0, 2.0, 1.0),))])
