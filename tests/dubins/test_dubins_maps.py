"""Partition (Fig 3.1) and tradespace (Fig 3.2) maps over grids of goals."""

import math

import numpy as np
import pytest

from glideplan import InvalidParameterError
from glideplan.planners.dubins import dubins_distance
from glideplan.studies.maps import (
    partition_map,
    partition_regions,
    tradespace_map,
    tradespace_ratio,
)

PI = math.pi


@pytest.mark.parametrize(
    ("x", "y", "psi1", "expected"),
    [
        # REFERENCE_NOTES 4.4, eps = 0.25 (k = 1.5625): T = k L1(x/k, y/k) / L1(x, y).
        (3.0, 3.0, 2 * PI / 3, 1.07),
        (0.5, 0.5, PI, 1.62),
        (-2.0, 0.0, PI, 1.71),
        (6.0, 0.0, 0.0, 1.00),
        # The notes print 1.42 here; L1 = 8.51925 and 1.5625 L1(0.64, 1.28) = 12.05355 give
        # 1.41486 (OMPL agrees to 1e-15), so we test 1.415.
        (1.0, 2.0, 0.0, 1.415),
    ],
)
def test_tradespace_spot_values(x, y, psi1, expected):
    assert float(tradespace_ratio(x, y, psi1, 0.25)) == pytest.approx(expected, abs=0.005)


def test_tradespace_ratio_by_scaling_identity():
    # d_feasible(x, y) = k d_optimal(x / k, y / k) with k = (1 + eps)^2.
    rng = np.random.default_rng(2)
    g = np.c_[rng.uniform(-6, 6, (200, 2)), rng.uniform(-PI, PI, 200)]
    k = 1.5**2
    num = k * dubins_distance(np.zeros(3), g * [1 / k, 1 / k, 1])
    den = dubins_distance(np.zeros(3), g)
    np.testing.assert_allclose(tradespace_ratio(g[:, 0], g[:, 1], g[:, 2], 0.5), num / den)


def test_tradespace_map_properties():
    tmap = tradespace_map(2 * PI / 3, 0.25, extent=6.0, n=61)
    assert tmap.ratio.shape == (61, 61)
    finite = np.isfinite(tmap.ratio)
    assert finite.all()  # the origin with heading 2pi/3 is not the start pose
    assert tmap.ratio.min() >= 1.0 - 1e-12  # a larger radius never helps
    assert tmap.ratio_at(6, -6) < 1.2  # far from the origin the ratio tends to 1
    assert tmap.ratio.max() > 4.0  # near the start it approaches the figure's colour cap, 5
    cols = tmap.columns()
    assert cols["x"].shape == (61 * 61,) and set(cols) >= {"ratio", "word_optimal"}


def test_tradespace_undefined_at_the_start():
    tmap = tradespace_map(0.0, 0.25, extent=1.0, n=3)
    assert np.isnan(tmap.ratio[1, 1])  # goal = start: 0 / 0
    assert np.isfinite(tmap.ratio[0, 0])


@pytest.mark.parametrize(
    ("psi1", "points"),
    [
        # Fig 3.1(a), psi1 = 0: LSR above, RSL below, RSR/LSL behind, RLR/LRL lenses.
        (0.0, {(3, 4): "LSR", (3, -4): "RSL", (-4, 0): "LSL/RSR", (0, 3.5): "RLR/LRL"}),
        # Fig 3.1(b), psi1 = 2pi/3.
        (
            2 * PI / 3,
            {(3, 4): "LSL", (-4, 4): "LSR", (-3, -3): "RSR", (4, -2): "RSL", (0, 0): "LRL"},
        ),
        # Fig 3.1(c), psi1 = pi: LSL above y = 2, RSR below y = -2, RLR / LRL in the disc.
        (
            PI,
            {(0, 4): "LSL", (0, -4): "RSR", (0, 1): "RLR", (0, -1): "LRL", (4, 1): "RSL"},
        ),
    ],
)
def test_partition_labels_match_fig_3_1(psi1, points):
    pmap = partition_map(psi1, extent=6.0, n=121)
    for (x, y), label in points.items():
        assert pmap.label_at(x, y) == label, (x, y)
    fr = pmap.fractions()
    assert sum(fr.values()) == pytest.approx(1.0)


@pytest.mark.parametrize(
    ("psi1", "labels"),
    [
        # The region labels printed in Fig 3.1 (a), (b), (c), one per connected region.
        (0.0, ["LSR", "RLR/LRL", "RLR/LRL", "RSR/LSL", "RSL"]),
        (2 * PI / 3, ["LRL", "RLR", "RSL", "LSR", "RSL", "LSL", "RSR", "LSR"]),
        (PI, ["LSL", "RLR", "LRL", "RSR", "LSR", "RSL", "LSR", "RSL"]),
    ],
)
def test_partition_regions_are_those_of_fig_3_1(psi1, labels):
    def canon(ls):
        return sorted("/".join(sorted(s.split("/"))) for s in ls)

    regions = partition_regions(partition_map(psi1, extent=6.0, n=161))
    assert canon([r.label for r in regions]) == canon(labels)


def test_partition_mirror_symmetry():
    # P(-psi) is the mirror of P(psi) about the x axis with L and R swapped.
    swap = str.maketrans("LR", "RL")
    a = partition_map(2 * PI / 3, extent=5.0, n=51)
    b = partition_map(-2 * PI / 3, extent=5.0, n=51)
    la, lb = a.label_grid, b.label_grid[::-1]

    def canon(label):
        return "/".join(sorted(label.translate(swap).split("/")))

    flipped = np.vectorize(canon)(la)
    assert np.mean(flipped == np.vectorize(lambda s: "/".join(sorted(s.split("/"))))(lb)) > 0.999


def test_partition_with_eps_is_the_scaled_partition():
    # Planning with R0' maps goal (x, y) to (x, y) / k in the unit partition.
    k = 1.25**2
    a = partition_map(PI, extent=6.0, n=61, eps=0.25)
    b = partition_map(PI, extent=6.0 / k, n=61)
    assert np.array_equal(a.label_grid, b.label_grid)


def test_chunked_batch_equals_direct():
    direct = partition_map(PI / 3, extent=4.0, n=41)
    pooled = partition_map(PI / 3, extent=4.0, n=41, processes=2, progress=False)
    assert np.array_equal(direct.label_grid, pooled.label_grid)
    np.testing.assert_array_equal(direct.lengths, pooled.lengths)


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"psi1": math.nan}, "heading"),
        ({"psi1": 0.0, "eps": 1.0}, "eps"),
        ({"psi1": 0.0, "n": 1}, "n"),
        ({"psi1": 0.0, "n": 2.5}, "n"),
        ({"psi1": 0.0, "extent": 0.0}, "extent"),
    ],
)
def test_bad_map_arguments(kwargs, name):
    with pytest.raises(InvalidParameterError, match=name):
        partition_map(**kwargs)
    with pytest.raises(InvalidParameterError, match=name):
        tradespace_map(**kwargs)
