"""The explorer's maps carry the world on a fresh load, in Chromium driven by Playwright.

Checks (issue 27, "maps with the world"): the mission over Buzzards Bay loads with land
polygons and a coastline in its figure data (Natural Earth 1:10m, `explore.land`) and the
coast follows a pan beyond the region first sent; the reach page has its colour relief,
labelled contours, land outside the terrain tile, and its answer on the DEM's own 93 m grid
(`reach.native`, the SRTM3 tile's spacing at 46.5 N: 3 arc-seconds = 92.7 m north-south);
the mid-Atlantic route has a land layer that is empty (no coast within its box). Screenshots
go to the test's temporary directory. No page logs a script error.
"""

from __future__ import annotations

import os
import pathlib
import time
from collections.abc import Callable
from typing import Any

import pytest

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):
    pytest.skip(f"Chromium is not installed at {CHROMIUM}", allow_module_level=True)
playwright_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed")

pytestmark = pytest.mark.heavy  # make validate: each page computes its answer (seconds)

PAGES = {
    "mission": "planner=mission",
    "reach": "planner=reach&example=ridge&from=46.5,7.4,1800&wind=4,250&mc=0&safety=300",
    "route": "planner=route&example=double-gyre&from=30.2,-39.8&to=30.7,-38.3&speed=1"
    "&resolution=3000",
}
# Lengths of the named sources and renderers' data in the browser's document.
LAYERS_JS = """() => { const out = {};
  for (const d of Bokeh.documents) for (const m of d.all_models) {
    if (m.name === 'gp-land' && m.data) out.land = m.data.xs.length;
    if (m.name === 'gp-coast' && m.data) out.coast = m.data.x.filter(Number.isFinite).length;
    if (m.name === 'gp-coast' && m.data) out.coast_west = Math.min(
        ...m.data.x.filter(Number.isFinite), 1e9);
    if (m.name === 'gp-contours') out.contours = m.data.xs.length;
    if (m.name === 'gp-relief') out.relief = m.data_source.data.image.length; }
  return out; }"""
PAN_JS = """(dx) => { for (const d of Bokeh.documents) for (const m of d.all_models)
    if (m.x_range && m.renderers && m.renderers.some(r => r.name === 'gp-land')) {
      m.x_range.setv({start: m.x_range.start + dx, end: m.x_range.end + dx}); return true; }
  return false; }"""


@pytest.fixture(scope="module")
def context(open_context: Callable[..., Any]) -> Any:
    return open_context(viewport={"width": 1400, "height": 950})


def _load(context: Any, url: str, errors: list[str], timeout: float = 180.0) -> Any:
    """A fresh page at `url`, once its strip shows an answer (not busy)."""
    page = context.new_page()
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(url)
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if page.locator(".gp-status").count() and not page.locator(".gp-busy").count():
            if page.locator(".gp-status").first.inner_text().strip():
                page.wait_for_timeout(500)
                return page
        time.sleep(0.2)
    raise AssertionError(f"no answer within {timeout} s: {url}")


def test_mission_shows_the_buzzards_bay_coast_and_follows_a_pan(
    server: str, context: Any, tmp_path: pathlib.Path
):
    errors: list[str] = []
    page = _load(context, f"{server}/?{PAGES['mission']}", errors)
    layers = page.evaluate(LAYERS_JS)
    assert layers["land"] >= 2 and layers["coast"] > 30, layers  # mainland, islands
    page.screenshot(path=str(tmp_path / "mission.png"))
    assert page.evaluate(PAN_JS, -0.6)  # 0.6 deg west: past the region first sent
    deadline = time.monotonic() + 30
    while page.evaluate(LAYERS_JS)["coast_west"] > -71.3 and time.monotonic() < deadline:
        time.sleep(0.3)
    assert page.evaluate(LAYERS_JS)["coast_west"] <= -71.3  # Rhode Island's coast sent
    page.close()
    assert not errors


def test_reach_has_relief_contours_land_outside_and_the_dem_grid(
    server: str, context: Any, tmp_path: pathlib.Path
):
    errors: list[str] = []
    page = _load(context, f"{server}/?{PAGES['reach']}", errors)
    layers = page.evaluate(LAYERS_JS)
    assert layers["relief"] == 1 and layers["contours"] >= 4 and layers["land"] >= 1, layers
    assert page.locator(".gp-grid").first.inner_text().strip() == "93 m"
    page.screenshot(path=str(tmp_path / "reach.png"))
    page.close()
    assert not errors


def test_mid_atlantic_route_has_an_empty_land_layer(
    server: str, context: Any, tmp_path: pathlib.Path
):
    errors: list[str] = []
    page = _load(context, f"{server}/?{PAGES['route']}", errors)
    layers = page.evaluate(LAYERS_JS)
    assert layers["land"] == 0 and layers["coast"] == 0, layers
    page.screenshot(path=str(tmp_path / "route.png"))
    page.close()
    assert not errors
