"""The glide model: ground glide ratio per bearing against brute force over the polar."""

import math

import numpy as np
import pytest

from glideplan.errors import InvalidParameterError
from glideplan.reach import Glide
from glideplan.sailplane import speed_to_fly


def brute(polar, wind, chi, mc=0.0, ratio_cap=None, n=400001):
    """Reference: every airspeed of the polar on a fine grid; crab to hold the track."""
    v = np.linspace(polar.v_min, polar.v_max, n)
    w = polar.sink(v)
    if ratio_cap is not None:
        w = np.maximum(w, v / ratio_cap)
    u = np.array([math.cos(chi), math.sin(chi)])
    wt = wind[0] * u[0] + wind[1] * u[1]
    wc = -wind[0] * u[1] + wind[1] * u[0]
    ok = v > abs(wc)
    g = np.where(ok, np.sqrt(np.where(ok, v * v - wc * wc, 0.0)) + wt, -1.0)
    good = g > 0
    if mc == 0:
        return float(np.max(np.where(good, g / w, -np.inf)))
    cost = np.where(good, (w + mc) / np.where(good, g, 1.0), np.inf)
    k = int(np.argmin(cost))
    return float(g[k] / w[k])


BEARINGS = np.radians(np.arange(0, 360, 30))


def test_still_air_is_best_glide_one_disk(polar):
    g = Glide(polar)
    a, b = g.front_terms()
    assert a.shape == (1,)
    assert a[0] == pytest.approx(polar.best_glide_ratio, rel=1e-9)
    assert not np.any(b)


@pytest.mark.parametrize("wind", [(0.0, -8.0), (5.0, 3.0)])
@pytest.mark.parametrize("mc", [0.0, 1.5])
def test_ratio_per_bearing_matches_brute_force(polar, wind, mc):
    g = Glide(polar, mc=mc, wind=wind)
    got = g.ratio(BEARINGS)
    ref = [brute(polar, wind, c, mc) for c in BEARINGS]
    # the brute-force grid's speed step 2e-4 m/s bounds its own error far below 1e-6
    np.testing.assert_allclose(got, ref, rtol=1e-6)


def test_mc_in_still_air_is_the_speed_to_fly(polar):
    """Reference: MacCready's closed form (`sailplane.speed_to_fly`). The cost is flat at its
    optimum, so a search finds the speed to ~sqrt(machine epsilon): ratio to 1e-7."""
    v = float(speed_to_fly(polar, 2.0))
    assert Glide(polar, mc=2.0).still_air_ratio == pytest.approx(v / float(polar.sink(v)),
                                                                 rel=1e-7)


def test_mc_never_reaches_farther_than_best_glide(polar):
    """The MC > 0 set is inside the MC 0 set: support and ratio smaller in every direction."""
    wind = (4.0, -6.0)
    th = np.linspace(0, 2 * np.pi, 360, endpoint=False)
    n = np.stack([np.cos(th), np.sin(th)], axis=-1)
    assert np.all(Glide(polar, mc=2.0, wind=wind).support(n)
                  <= Glide(polar, wind=wind).support(n) + 1e-9)
    assert np.all(Glide(polar, mc=2.0, wind=wind).ratio(th)
                  <= Glide(polar, wind=wind).ratio(th) + 1e-9)


def test_front_terms_support_is_the_hull_of_the_ratios(polar):
    """The gauge of the front's velocity set (sup_n u.n / F(n)) gives back r(chi): the
    front's terms and the flown ratio describe one glide (to the stated sampling error)."""
    for mc in (0.0, 2.0):
        g = Glide(polar, mc=mc, wind=(3.0, -7.0))
        th = np.linspace(0, 2 * np.pi, 2880, endpoint=False)
        n = np.stack([np.cos(th), np.sin(th)], axis=-1)
        F = g.support(n)
        for chi in BEARINGS:
            u = np.array([math.cos(chi), math.sin(chi)])
            gauge = np.max((n @ u) / F)  # altitude per metre along u
            assert 1.0 / gauge == pytest.approx(float(g.ratio(chi)[0]), rel=2e-3)


def test_safety_glide_ratio_caps_the_polar(polar):
    R = 25.0
    g = Glide(polar, safety_glide_ratio=R)
    assert g.still_air_ratio == pytest.approx(R, rel=1e-9)
    gw = Glide(polar, wind=(0.0, -8.0), safety_glide_ratio=R)
    ref = [brute(polar, (0.0, -8.0), c, ratio_cap=R) for c in BEARINGS]
    np.testing.assert_allclose(gw.ratio(BEARINGS), ref, rtol=1e-6)
    # above the polar's best glide the cap does nothing
    big = Glide(polar, safety_glide_ratio=1000.0)
    assert big.still_air_ratio == pytest.approx(polar.best_glide_ratio, rel=1e-9)


@pytest.mark.parametrize("kw,name", [({"mc": -1.0}, "mc"), ({"wind": (float("nan"), 0.0)},
                                      "wind east"), ({"safety_glide_ratio": 0.0},
                                                     "safety_glide_ratio"),
                                     ({"wind": (100.0, 0.0)}, "wind")])
def test_bad_glide_parameters(polar, kw, name):
    with pytest.raises(InvalidParameterError) as e:
        Glide(polar, **kw)
    assert e.value.name == name
