"""Chapter 6 analysis: extremal locus, stall-boundary arcs, best turns, classification."""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan import LoadFactorGlider
from glideplan.analysis import load_factor as lf
from glideplan.errors import InvalidParameterError

G = LoadFactorGlider()


def test_locus_meets_stall_boundary():
    v, n = lf.locus_stall_intersection(G)
    assert v**4 + n**2 == pytest.approx(2.0)
    assert n == pytest.approx(G.p2 * v**2)


@pytest.mark.parametrize("p3", [1.02, 1.1, 1.5, 3.0])
def test_locus_speed_closed_form_matches_integration(p3):
    s, v, s1 = lf.locus_speed_history(G, p3)
    assert v[0] == pytest.approx(lf.locus_stall_intersection(G)[0])
    assert v[-1] == pytest.approx(1.0, abs=1e-9)
    assert np.all(np.diff(v) > 0)
    assert np.max(np.abs(v - lf.locus_speed_history_numeric(G, p3, s))) < 1e-7
    assert s1 == pytest.approx(s[-1])


def test_locus_arc_length_grows_as_p3_tends_to_one():
    lengths = [lf.locus_speed_history(G, p3)[2] for p3 in (3.0, 1.5, 1.1, 1.01, 1.001)]
    assert np.all(np.diff(lengths) > 0) and lengths[-1] > 3.0
    with pytest.raises(InvalidParameterError):
        lf.locus_speed_history(G, 1.0)


def test_only_large_p3_reaches_the_corner():
    # Fig 6.10: only p3 = 10 reaches the corner; small p3 returns to n_lim
    reached = {p3: lf.stall_load_factor_history(G, p3)["corner"] for p3 in (1.0, 2.0, 4.0, 10.0)}
    assert reached == {1.0: False, 2.0: False, 4.0: False, 10.0: True}
    r = lf.stall_load_factor_history(G, 1.0, s_max=10.0)
    _, n_lim = lf.locus_stall_intersection(G)
    assert r["n"][-1] == pytest.approx(n_lim, abs=1e-6)
    # (6.49) holds along the arc
    lhs = 2 * G.p2 * 1.0 * np.cos(r["psi"] - r["theta"])
    assert np.allclose(lhs, (1 + G.p2**2) * r["n"] * (r["n"] ** 2 - 2), atol=1e-8)


@pytest.mark.parametrize("radius", [0.65, 0.7, 0.9, 1.0, 1.5, 3.0, 10.0])
def test_best_turn_is_the_minimum_sink_per_length_for_the_radius(radius):
    v, n = lf.best_turn(G, radius)
    assert math.sqrt(n * n - 1) / v**2 == pytest.approx(1 / radius, rel=1e-9)
    assert G.admissible(v, n)
    # brute force over the admissible speeds for this curvature
    vv = np.linspace(G.v_min, G.v_max, 200001)
    nn = np.sqrt(1 + (vv**2 / radius) ** 2)
    ok = G.admissible(vv, nn)
    best = np.min(G.sink_per_length(vv[ok], nn[ok]))
    ours = float(G.sink_per_length(v, n))
    assert best * (1 - 1e-5) <= ours <= best * (1 + 1e-12)  # the grid misses the stall edge


def test_best_turn_rejects_radii_below_the_corner():
    with pytest.raises(InvalidParameterError):
        lf.best_turn(G, 0.6)


def test_hodograph_southern_boundary_is_the_locus():
    hod = lf.hodograph(G, 300)
    pts = hod["points"]
    loc = hod["curves"]["extremal_locus"]
    kx, f0 = loc.x[::-1], loc.y[::-1]  # increasing turn rate
    inside = (pts[:, 0] >= kx[0]) & (pts[:, 0] <= kx[-1])
    assert np.all(pts[inside, 1] >= np.interp(pts[inside, 0], kx, f0) - 1e-6)
    # and the locus image is attained: some sampled points lie close to it
    gap = pts[inside, 1] - np.interp(pts[inside, 0], kx, f0)
    assert np.min(gap) < 1e-4


def test_control_set_curves():
    cs = lf.control_set(G)
    assert np.allclose(cs["stall"].y, G.p2 * cs["stall"].x ** 2)
    assert np.allclose(cs["extremal_locus"].x ** 4 + cs["extremal_locus"].y ** 2, 2.0)
    assert cs["stall"].x[-1] == pytest.approx(G.corner_speed)
    polar = lf.turn_polar(G)
    c = polar["n=1.5"]
    assert c.x[np.argmin(c.y)] == pytest.approx(math.sqrt(1.5), abs=0.01)
    dog = lf.doghouse(G)
    assert dog["stall"].y[-1] == pytest.approx(1 / G.corner_radius)


def test_classification_of_synthetic_history():
    v_lim, _ = lf.locus_stall_intersection(G)
    s = np.linspace(0.0, 4.0, 401)
    v = np.empty_like(s)
    n = np.empty_like(s)
    a, b, c = s < 1, (s >= 1) & (s < 2), (s >= 2) & (s < 3)
    v[a], n[a] = G.corner_speed, 2.0  # corner
    vs = np.linspace(G.corner_speed, v_lim, b.sum())
    v[b], n[b] = vs, G.p2 * vs**2  # stall boundary
    vl = np.linspace(v_lim, 1.0, c.sum())
    v[c], n[c] = vl, np.sqrt(2 - vl**4)  # locus
    d = ~(a | b | c)
    v[d], n[d] = 1.0, 1.0  # wings level
    out = lf.classify_controls(G, s, v, n, np.where(s < 3.5, 1.0, -1.0))
    assert out.fractions["corner"] == pytest.approx(0.25, abs=0.01)
    assert out.fractions["stall"] == pytest.approx(0.25, abs=0.01)
    assert out.fractions["locus"] == pytest.approx(0.25, abs=0.02)
    assert out.fractions["wings_level"] == pytest.approx(0.25, abs=0.02)
    assert out.reaches_corner
    assert [a["kind"] for a in out.arcs][:3] == ["corner", "stall", "locus"]
    assert out.to_dict()["turn_word"] == "L"
