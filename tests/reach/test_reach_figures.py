"""The glide-reach map a pilot reads at a glance: elevation colour bar, km scale bar (checked
against the WGS84 geodesic), north and wind arrows, labels that do not collide (boxes measured
by the renderer), out-of-reach fields labelled with the height missing, missing terrain
marked. A small stand-in result is drawn (the figure reads only these attributes), so the
tests need no solve."""

import itertools
import math
from types import SimpleNamespace

import numpy as np
import pytest

from glideplan.reach import Landable
from glideplan.terrain import Terrain


def _result(lat0=46.0, fields=(), wind=(0.0, 0.0), n=121, span=0.6):
    """A stand-in ReachResult over a relief from 400 to 2600 m (a cone), start in the middle."""
    lat = lat0 + span * np.arange(n) / (n - 1)
    lon = 7.0 + span * np.arange(n) / (n - 1)
    r = np.hypot(*np.meshgrid((lat - lat.mean()) / span, (lon - lon.mean()) / span,
                              indexing="ij"))
    z = 400.0 + 2200.0 * np.clip(1.0 - 2 * r, 0.0, 1.0)
    terrain = Terrain(lat, lon, z.astype(np.float32))
    points = []
    for f in fields:
        lnd = Landable(f["name"], f["lat"], f["lon"], 400.0, 3)
        points.append(SimpleNamespace(
            landable=lnd, reachable=f.get("reachable", True), path=None,
            arrival_margin_m=f.get("margin"), short_by_m=f.get("short_by"),
            terrain_missing=f.get("missing", False)))
    glide = SimpleNamespace(wind=wind, polar=SimpleNamespace(name="test polar"), mc=0.0)
    return SimpleNamespace(terrain=terrain, footprint=[], start=(lat.mean(), lon.mean(), 2000.0),
                           points=tuple(points), glide=glide, safety_height=300.0,
                           message="stand-in")


def _plot(result, draw=False):
    from glideplan.reach.plot import plot_reach

    ax = plot_reach(result)
    fig = ax.get_figure()
    if draw:  # as saved (save_figure's tight_layout: unchanged, the layout is already tight)
        fig.tight_layout()
        fig.canvas.draw()
    return ax, fig


@pytest.fixture(autouse=True)
def _close():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


def test_elevation_colour_bar_spans_the_terrain_green_to_white():
    ax, fig = _plot(_result())
    bars = [a for a in fig.axes if a.get_ylabel().startswith("terrain elevation (m)")]
    assert len(bars) == 1
    assert bars[0].get_ylim() == pytest.approx((400.0, 2600.0), abs=1.0)
    assert "contours every 500 m" in bars[0].get_ylabel()  # 4 lines: 1000..2500
    from glideplan.reach.plot import hypsometric_cmap

    low, high = hypsometric_cmap()(0.0), hypsometric_cmap()(1.0)
    assert low[1] > low[0] and low[1] > low[2]  # green lowlands
    assert high[:3] == pytest.approx((1.0, 1.0, 1.0))  # white tops
    assert any(c.get_gid() is None for c in ax.collections)  # the contour lines are drawn


@pytest.mark.parametrize("lat0", [46.0, 69.0])
def test_scale_bar_length_is_the_geodesic_within_1_percent(lat0):
    """The bar's two ends (lon/lat) are as far apart on the WGS84 ellipsoid (pyproj.Geod, an
    independent geodesic) as its label says, within 1 %; it is a round length."""
    from pyproj import Geod

    ax, _ = _plot(_result(lat0=lat0))
    (bar,) = [ln for ln in ax.lines if ln.get_gid() == "scale_bar"]
    (label,) = [t for t in ax.texts if t.get_gid() == "scale_bar_label"]
    km = float(label.get_text().removesuffix(" km"))
    assert km in (1, 2, 5, 10, 20)
    (lo0, lo1), (la0, la1) = bar.get_xdata(), bar.get_ydata()
    assert la0 == la1
    _, _, dist = Geod(ellps="WGS84").inv(lo0, la0, lo1, la1)
    assert dist == pytest.approx(1000.0 * km, rel=0.01)
    assert next(t for t in ax.texts if t.get_gid() == "north_arrow").get_text() == "N"


def test_wind_arrow_points_downwind():
    """Wind FROM 240 deg blows towards 60 deg: the arrow (tail -> tip, display space) points
    60 deg east of north, i.e. 30 deg above the +x axis on the equal-metre map."""
    from glideplan.units import wind_from_compass

    ax, _ = _plot(_result(wind=wind_from_compass(8.0, 240.0)))
    (arrow,) = [t for t in ax.texts if t.get_gid() == "wind_arrow"]
    dx, dy = -np.asarray(arrow.xyann, dtype=float)  # tail at xytext (offset points), tip at xy
    assert math.degrees(math.atan2(dy, dx)) == pytest.approx(30.0, abs=0.5)


def _crowd():
    """Five fields on a gently rising line 4.6 km apart (closer than a label is long), a pair
    1 km apart, one far off and one on missing terrain, on a 46 km wide map."""
    fields = [{"name": f"Field {k}", "lat": 46.2 + 0.004 * k, "margin": 50.0 * k,
               "lon": 7.1 + 0.06 * k} for k in range(5)]
    pair = [{"name": f"Pair {k}", "lat": 46.45, "lon": 7.15 + 0.012 * k, "margin": 300.0}
            for k in range(2)]
    return [*fields, *pair,
            {"name": "Far", "lat": 46.5, "lon": 7.5, "reachable": False, "short_by": 240.4},
            {"name": "Hole", "lat": 46.1, "lon": 7.45, "reachable": False, "missing": True}]


def _boxes(ax, fig, gid):
    r = fig.canvas.get_renderer()
    return [t.get_window_extent(r) for t in ax.texts if t.get_gid() == gid]


def _overlap(a, b):
    return min(a.x1, b.x1) > max(a.x0, b.x0) and min(a.y1, b.y1) > max(a.y0, b.y0)


def test_labels_do_not_collide():
    """Every label's box (from the renderer) meets no other label and no field marker and
    lies inside the map; the same labels all put north-east (the naive placement) would
    collide, so the check can fail."""
    from glideplan.plotting import marker_boxes

    result = _result(fields=_crowd())
    ax, fig = _plot(result, draw=True)
    boxes = _boxes(ax, fig, "landable_label")
    assert len(boxes) == len(result.points)
    for a, b in itertools.combinations(boxes, 2):
        assert not _overlap(a, b), (a, b)
    markers = marker_boxes(ax, [(p.landable.lon, p.landable.lat) for p in result.points], 4.0)
    frame = ax.get_window_extent(fig.canvas.get_renderer())
    for b in boxes:
        assert not any(_overlap(b, m) for m in markers)
        assert frame.x0 <= b.x0 and b.x1 <= frame.x1 and frame.y0 <= b.y0 and b.y1 <= frame.y1
    naive = [ax.annotate(t.get_text(), t.xy, xytext=(6, 6), textcoords="offset points",
                         fontsize=7, gid="naive") for t in ax.texts
             if t.get_gid() == "landable_label"]
    nb = _boxes(ax, fig, "naive")
    assert len(naive) == len(nb)
    assert any(_overlap(a, b) for a, b in itertools.combinations(nb, 2))


def test_out_of_reach_and_missing_terrain_are_labelled_apart():
    """Out of reach: a red cross labelled with the height missing; on missing terrain: a
    hollow grey circle labelled "no terrain" (not "out of reach")."""
    ax, _ = _plot(_result(fields=_crowd()))
    texts = {t.get_text() for t in ax.texts if t.get_gid() == "landable_label"}
    assert "Far -240 m" in texts and "Hole: no terrain" in texts
    assert "Field 3 +150 m" in texts
    (hollow,) = [c for c in ax.collections if c.get_gid() == "landable_no_terrain"]
    assert hollow.get_facecolor().size == 0 or hollow.get_facecolor()[0][3] == 0.0
    assert [ln for ln in ax.lines if ln.get_gid() == "landable_out_of_reach"]
