"""The explorer's world: bundled land/coast (Natural Earth 1:10m) and the reach page's relief.

References: lighthouse and cape positions from nautical light lists and charts (degrees to
4 decimals, ~10 m); the tolerance for a coast point is 2 km: 0.2 mm at the data's scale of
1:10,000,000 (its generalisation) plus half the file's grid step (<= 0.2 km) -- measured
distances are 0.04-1.0 km. Clipping is checked against boxes whose answer is known exactly
(all land: the box itself; open ocean: nothing). Contour levels are checked by hand
(range 500-3000 m, at most 8 round intervals: 500 m); contour lines of a cone against its
closed form.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

from glideplan.explore import land as L
from glideplan.explore.relief import contour_levels, contour_lines, relief_rgba

ROOT = Path(__file__).parents[2]

# (lat, lon) of points on the shore: lights standing at the water's edge and cape tips
COAST_POINTS = {
    "Race Point Light, Cape Cod": (42.0623, -70.2433),
    "Gay Head Light, Martha's Vineyard (Buzzards Bay's mouth)": (41.3484, -70.8348),
    "Montauk Point Light": (41.0709, -71.8570),
    "Cap Gris-Nez": (50.8703, 1.5839),
    "Europa Point, Gibraltar": (36.1094, -5.3456),
    "Land's End": (50.0664, -5.7147),
    "Cape Agulhas Light": (-34.8289, 20.0092),
}


@pytest.mark.parametrize("name", list(COAST_POINTS))
def test_known_coast_points_lie_on_the_drawn_coast(name: str):
    lat, lon = COAST_POINTS[name]
    assert L.distance_to_coast_m(lat, lon) <= 2000.0, name


def test_land_and_sea_far_from_the_coast():
    # > 5 km from any shore: city centres inland, open water of Buzzards Bay and the ocean
    assert L.on_land(41.64, -70.98)  # Dartmouth, MA (inland of New Bedford)
    assert L.on_land(39.0, -100.0)  # Kansas
    assert L.on_land(46.5, 7.4)  # the reach example's tile (Bernese Alps)
    assert not L.on_land(41.55, -70.80)  # Buzzards Bay
    assert not L.on_land(30.4, -39.0)  # the double gyre's mid-Atlantic box
    for lat, lon in zip([41.4950, 41.5000, 41.5140], [-70.9050, -70.9000, -70.8650], strict=True):
        assert not L.on_land(lat, lon)  # the Buzzards Bay mission's waypoints are at sea
    assert L.distance_to_coast_m(30.4, -39.0) == math.inf  # no coast within 0.5 deg


def _area(x: np.ndarray, y: np.ndarray) -> float:
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def test_clipping_to_the_box_is_exact_in_known_boxes():
    polys, coast = L.land_shapes(-100.5, 38.5, -99.5, 39.5)  # all land
    assert coast["x"].size == 0
    outer = [np.asarray(p[0][0]) for p in polys["xs"]]
    assert len(outer) == 1
    x, y = np.asarray(polys["xs"][0][0][0]), np.asarray(polys["ys"][0][0][0])
    assert _area(x, y) == pytest.approx(1.0, rel=1e-9)
    assert x.min() == pytest.approx(-100.5) and y.max() == pytest.approx(39.5)
    polys, coast = L.land_shapes(-40.0, 30.0, -38.0, 31.0)  # open ocean
    assert polys["xs"] == [] and coast["x"].size == 0


def test_buzzards_bay_box_has_land_inside_the_box_and_a_coast():
    box = (-71.0, 41.40, -70.75, 41.60)
    polys, coast = L.land_shapes(*box)
    assert len(polys["xs"]) >= 3  # the mainland and the Elizabeth Islands
    for xs, ys in zip(polys["xs"], polys["ys"], strict=True):
        for rx, ry in zip(xs[0], ys[0], strict=True):
            assert np.all((np.asarray(rx) >= box[0] - 1e-12) & (np.asarray(rx) <= box[2] + 1e-12))
            assert np.all((np.asarray(ry) >= box[1] - 1e-12) & (np.asarray(ry) <= box[3] + 1e-12))
    assert np.isfinite(coast["x"]).sum() > 30  # 1:10m: ~1 vertex per km of coast


def test_mission_view_grows_to_the_nearest_coast():
    w, s, e, n = -70.91, 41.49, -70.86, 41.52  # the mission's own box: no coast in it
    assert L.land_shapes(w, s, e, n)[1]["x"].size == 0
    gw, gs, ge, gn = L.view_with_coast(w, s, e, n)
    assert L.land_shapes(gw, gs, ge, gn)[1]["x"].size > 0
    assert (gn - gs) * 111.32 < 40.0  # at most 40 km across


def test_license_note_and_data_are_package_data():
    data = Path(L.__file__).with_name("data")
    text = (data / "LICENSE-naturalearth.txt").read_text()
    assert "public domain" in text and "Natural Earth" in text
    assert L.LAND_FILE.stat().st_size < 1_000_000
    conf = tomllib.loads((ROOT / "pyproject.toml").read_text())
    shipped = conf["tool"]["setuptools"]["package-data"]["glideplan"]
    assert "explore/data/*.npz" in shipped and "explore/data/*.txt" in shipped


def test_contour_levels_round_and_inside_the_range():
    assert list(contour_levels(500.0, 3000.0)) == [1000.0, 1500.0, 2000.0, 2500.0]
    assert list(contour_levels(412.0, 655.0)) == [450.0, 500.0, 550.0, 600.0, 650.0]


class _Cone:
    """A cone z = 2000 - r / 10 (r in m from (46.5 N, 7.5 E)) on a 201 x 201 grid."""

    def __init__(self) -> None:
        self.lat = np.linspace(46.4, 46.6, 201)
        self.lon = np.linspace(7.35, 7.65, 201)
        lo, la = np.meshgrid(self.lon, self.lat)
        r = 6_371_000.0 * np.hypot(np.radians(la - 46.5),
                                   np.radians(lo - 7.5) * math.cos(math.radians(46.5)))
        self.z = 2000.0 - r / 10.0
        self.shape = self.z.shape
        self.extent = (46.4, 46.6, 7.35, 7.65)
        self.spacing_m = (111_195.0 * 0.0015 * math.cos(math.radians(46.5)), 111_195.0 * 0.001)


def test_contours_of_a_cone_are_its_circles():
    cone = _Cone()
    lines, labels = contour_lines(cone, np.array([1000.0, 1500.0]))
    for xs, ys in zip(lines["xs"], lines["ys"], strict=True):
        r = 6_371_000.0 * np.hypot(np.radians(ys - 46.5),
                                   np.radians(xs - 7.5) * math.cos(math.radians(46.5)))
        z = 2000.0 - r / 10.0  # each point's height on the cone
        level = round(float(np.median(z)) / 500.0) * 500.0
        assert np.max(np.abs(z - level)) < 5.0  # linear interpolation across ~100 m cells
    assert len(lines["xs"]) == 2 and sorted(labels["text"]) == ["1000", "1500"]  # r 10, 5 km


def test_relief_image_rows_go_north_and_colours_follow_height():
    cone = _Cone()
    image, step = relief_rgba(cone)
    assert step == 1 and image.shape == cone.shape
    rgba = image.view(np.uint8).reshape(*image.shape, 4)
    top, low = rgba[100, 100, :3].astype(int), rgba[0, 0, :3].astype(int)
    assert top.sum() > 600  # the summit nearly white
    assert low[1] > low[0] and low[1] > low[2]  # the lowest corner green
    tilted = _Cone()
    tilted.z = np.where(tilted.lat[:, None] > 46.55, np.nan, tilted.z)  # no data in the north
    image, _ = relief_rgba(tilted)
    grey = image.view(np.uint8).reshape(*image.shape, 4)
    assert tuple(grey[-1, 0]) == (209, 209, 209, 255)  # last row = north = no data
    assert tuple(grey[0, 0]) != (209, 209, 209, 255)
