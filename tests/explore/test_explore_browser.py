"""`glideplan explore` in a real browser: Debian's Chromium driven by Playwright.

One server (in-process, threaded, on a free port of 127.0.0.1) and one browser serve every
test of the module. The reference for each displayed cost is `glideplan.plan()` called here
for the same inputs (built from the URL's values, independently of the page's own parsing);
the reference for an error message is the CLI's one-line message for the same bad value.
Screenshots of each planner family go to the test's temporary output directory.
"""

from __future__ import annotations

import csv
import io
import json
import math
import os
import pathlib
import socket
import time
from collections.abc import Callable, Iterator
from typing import Any
from urllib.parse import parse_qsl, urlparse

import pytest

CHROMIUM = "/usr/bin/chromium"
if not os.path.exists(CHROMIUM):
    pytest.skip(f"Chromium is not installed at {CHROMIUM}", allow_module_level=True)
playwright_api = pytest.importorskip("playwright.sync_api", reason="playwright is not installed")

from glideplan import (  # noqa: E402
    DubinsCar,
    DubinsCarInWind,
    LoadFactorGlider,
    Pose,
    VariableSpeedCar,
    plan,
)
from glideplan.units import wind_from_compass  # noqa: E402
from glideplan.vehicles import QuadraticPolarGlider  # noqa: E402

# JavaScript: the main figure's frame on the page and its data ranges.
FRAME_JS = """() => {
  const found = [];
  const walk = (v) => {
    if (v.frame && v.model.x_range && v.frame.bbox.width > 300) found.push(v);
    for (const c of (v.child_views || [])) walk(c);
  };
  for (const r of Bokeh.index.roots) walk(r);
  const v = found[0];
  const b = v.canvas_view.el.getBoundingClientRect();
  return {left: b.left + v.frame.bbox.left, top: b.top + v.frame.bbox.top,
          w: v.frame.bbox.width, h: v.frame.bbox.height,
          x0: v.model.x_range.start, x1: v.model.x_range.end,
          y0: v.model.y_range.start, y1: v.model.y_range.end,
          xlabel: v.model.below[0].axis_label, ylabel: v.model.left[0].axis_label,
          bottom: b.bottom};
}"""


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return int(s.getsockname()[1])


def _wait_listening(port: int, seconds: float = 20.0) -> None:
    """Until the server accepts connections on 127.0.0.1:port (or `seconds` pass)."""
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
            return
        except OSError:
            time.sleep(0.1)


@pytest.fixture(scope="module")
def server() -> Iterator[str]:
    from glideplan.explore.server import serve

    port = _free_port()
    srv = serve(port, "127.0.0.1", show=False, threaded=True)
    _wait_listening(port)
    yield f"http://127.0.0.1:{port}"
    srv.stop()


@pytest.fixture(scope="module")
def requests_seen() -> list[str]:
    return []


@pytest.fixture(scope="module")
def browser_context(requests_seen: list[str], open_context: Callable[..., Any]) -> Any:
    context = open_context(viewport={"width": 1500, "height": 1000}, accept_downloads=True)
    context.on("request", lambda r: requests_seen.append(r.url))
    return context


@pytest.fixture(scope="module")
def shots(tmp_path_factory: pytest.TempPathFactory) -> pathlib.Path:
    return tmp_path_factory.mktemp("explore_screenshots")


@pytest.fixture(scope="module")
def dubins_page(server: str, browser_context: Any) -> Iterator[Any]:
    """One Dubins page shared by the tests that drive it (cost, downloads, drag, bad value)."""
    page = _open(browser_context, f"{server}/?" + FAMILIES["dubins"])
    yield page
    page.close()


def _wait_result(page: Any, previous: str | None = None, timeout: float = 40.0) -> str:
    """The displayed cost once the page has finished planning (and differs from `previous`)."""
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        busy = page.locator(".gp-busy").count()
        cost = (
            page.locator(".gp-cost").first.inner_text() if page.locator(".gp-cost").count() else ""
        )
        if not busy and cost and cost != "n/a" and cost != previous:
            return str(cost)
        time.sleep(0.1)
    status = (
        page.locator(".gp-status").first.inner_text() if page.locator(".gp-status").count() else ""
    )
    raise AssertionError(f"no result within {timeout} s (cost {cost!r}, status {status!r})")


def _open(context: Any, url: str) -> Any:
    page = context.new_page()
    page.goto(url)
    page.wait_for_selector(".gp-cost", timeout=60_000)
    return page


def _query(page: Any) -> dict[str, str]:
    return dict(parse_qsl(urlparse(page.evaluate("() => location.href")).query))


def _pose(text: str) -> Pose:
    x, y, h = (float(v) for v in text.split(","))
    return Pose(x, y, math.radians(h))


def _floats(text: str) -> list[float]:
    return [float(v) for v in text.split(",")]


def _reference(q: dict[str, str]) -> float:
    """`plan()` for the inputs of a URL query, built here from the CLI-named values."""
    planner = q["planner"]
    goal = _pose(q["goal"])
    start = _pose(q.get("start", "0,0,0"))
    if planner == "dubins":
        v: Any = DubinsCar(float(q["speed"]), float(q["radius"]))
        return plan(start, goal, v, "length").cost
    if planner == "wind":
        w, d = _floats(q["wind"])
        v = DubinsCarInWind(float(q["speed"]), float(q["radius"]), wind_from_compass(w, d))
        return plan(start, goal, v).cost
    if planner == "time-optimal":
        v = VariableSpeedCar(float(q["v_min"]), float(q["v_max"]), float(q["u_max"]))
        return plan(start, goal, v, "time", "synthesis").cost
    if planner == "min-altitude":
        a, b, c = _floats(q["polar"])
        v = QuadraticPolarGlider(a, b, c, float(q["v_stall"]), float(q["v_max"]), float(q["u_max"]))
        return plan(start, goal, v, "altitude", "synthesis").cost
    if planner == "load-factor":
        v = LoadFactorGlider(
            float(q["l_over_d"]), float(q["v_min"]), float(q["v_max"]), float(q["n_max"])
        )
        return plan(start, goal, v, "altitude", "synthesis").cost  # --method synthesis
    raise AssertionError(planner)


FAMILIES = {
    "dubins": "planner=dubins&goal=4,3,90&radius=1",
    "wind": "planner=wind&goal=4,-2,135&speed=1&radius=1&wind=0.5,30",
    "time-optimal": "planner=time-optimal&goal=0.5,1.5,200&v_min=0.3&v_max=1&u_max=1",
    "min-altitude": "planner=min-altitude&goal=300,-250,180",
    "load-factor": "planner=load-factor&goal=3,2,60",
}


@pytest.mark.parametrize("family", list(FAMILIES))
def test_cost_matches_plan(
    family: str,
    server: str,
    browser_context: Any,
    dubins_page: Any,
    shots: pathlib.Path,
    run_cli: Any,
):
    """The page's `gp-cost` equals `plan()` for the inputs in its URL (1e-6 relative)."""
    shared = family == "dubins"
    page = dubins_page if shared else _open(browser_context, f"{server}/?{FAMILIES[family]}")
    try:
        cost = float(_wait_result(page))
        q = _query(page)
        assert q["planner"] == family
        ref = _reference(q)
        assert cost == pytest.approx(ref, rel=1e-6)
        assert page.locator(".gp-word").first.inner_text().strip()
        assert len(page.locator(".gp-cost").first.inner_text().replace(".", "").lstrip("0")) >= 7
        page.screenshot(path=str(shots / f"explore_{family}.png"), full_page=True)
        if family == "load-factor":  # the page says which method answered; the CLI agrees
            assert page.locator(".gp-method").first.inner_text().strip() == "synthesis"
            code, out, _ = run_cli("plan", "load-factor", "--method", "synthesis", "--goal",
                                   *q["goal"].split(","), "--json")
            assert code == 0 and cost == pytest.approx(json.loads(out)["cost"], rel=1e-9)
    finally:
        if not shared:
            page.close()


def test_downloads_read_back(dubins_page: Any, run_cli: Any, tmp_path: pathlib.Path):
    """JSON as `plan --json` prints it, the CSV read by `csv`, the PNG read by Matplotlib."""
    page = dubins_page
    _wait_result(page)
    files = {}
    for label in ("JSON", "CSV", "PNG"):
        with page.expect_download(timeout=30_000) as info:
            page.get_by_role("button", name=label).click()
        target = tmp_path / info.value.suggested_filename
        info.value.save_as(target)
        files[label] = target
    data = json.loads(files["JSON"].read_text())
    code, out, _ = run_cli("plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--json")
    ref = json.loads(out)
    assert code == 0
    ignore = {"stats"}  # wall-clock times
    assert {k: v for k, v in data.items() if k not in ignore} == {
        k: v for k, v in ref.items() if k not in ignore
    }
    rows = list(csv.DictReader(io.StringIO(files["CSV"].read_text())))
    assert float(rows[-1]["x"]) == pytest.approx(4.0, abs=1e-9)
    assert float(rows[-1]["y"]) == pytest.approx(3.0, abs=1e-9)
    assert float(rows[-1]["cost"]) == pytest.approx(ref["cost"], rel=1e-9)
    from matplotlib.image import imread

    img = imread(files["PNG"])
    assert img.shape[0] > 300 and img.shape[1] > 300


def test_drag_goal_updates_cost_and_url(dubins_page: Any, shots: pathlib.Path):
    """Dragging the goal with the mouse moves it (URL) and re-plans (cost = plan() there)."""
    page = dubins_page
    before = _wait_result(page)
    assert _pose(_query(page)["goal"]) == _pose("4,3,90")
    f = page.evaluate(FRAME_JS)

    def screen(x: float, y: float) -> tuple[float, float]:
        sx = f["left"] + (x - f["x0"]) / (f["x1"] - f["x0"]) * f["w"]
        sy = f["top"] + (f["y1"] - y) / (f["y1"] - f["y0"]) * f["h"]
        return sx, sy

    sx, sy = screen(4.0, 3.0)
    tx, ty = screen(1.5, -2.0)
    page.mouse.move(sx, sy)
    page.mouse.down()
    for k in range(1, 9):
        page.mouse.move(sx + (tx - sx) * k / 8, sy + (ty - sy) * k / 8)
    # the page re-plans while the point is still held (live), then commits it on the drop;
    # the live answers follow the pointer, so the last one (stable) is for where it is held
    live = _wait_result(page, previous=before, timeout=20.0)
    for _ in range(50):
        time.sleep(0.2)
        now = _wait_result(page, timeout=20.0)
        if now == live:
            break
        live = now
    page.mouse.up()
    after = float(_wait_result(page, previous=before))
    assert float(live) == pytest.approx(after, rel=1e-3)
    q = _query(page)
    goal = _pose(q["goal"])
    assert goal.x == pytest.approx(1.5, abs=0.1) and goal.y == pytest.approx(-2.0, abs=0.1)
    assert math.degrees(goal.heading) == pytest.approx(90.0)  # a drag keeps the heading
    assert after == pytest.approx(_reference(q), rel=1e-6)
    assert after != pytest.approx(float(before), rel=1e-3)
    page.screenshot(path=str(shots / "explore_dubins_dragged.png"), full_page=True)


def test_bad_value_shows_cli_message(dubins_page: Any, server: str, browser_context: Any,
                                     cli_error: Any):
    """A radius typed outside its physical range (PHYSICAL_RANGES["turn_radius"]: (0,
    100 km]) never reaches the state: the spinner keeps its last value and shows it again
    when left. A link with a bad radius shows the CLI's one-line message for it in
    `gp-error`, and no result."""
    page = dubins_page
    _enter(page, "radius", "1")
    _wait_result(page)
    box = page.locator(".gp-input-radius input")
    for typed in ("-1", "200000"):
        box.fill(typed)
        box.press("Enter")
        box.press("Tab")
        page.wait_for_timeout(500)
        assert _query(page)["radius"] == "1" and box.input_value() == "1"
    bad = _open(browser_context, f"{server}/?planner=dubins&goal=4,3,90&radius=-1")
    try:
        bad.wait_for_selector(".gp-error", timeout=20_000)
        shown = bad.locator(".gp-error").first.inner_text().strip()
        line = cli_error("plan", "dubins", "--goal", "4", "3", "90", "--radius", "-1")
        assert line == f"glideplan: error: {shown}"
        assert bad.locator(".gp-cost").first.inner_text() == "n/a"
        assert _query(bad)["radius"] == "-1"
    finally:
        bad.close()


def test_slow_planner_shows_busy(server: str, browser_context: Any):
    """A direct method shows `gp-busy` while it works; the page still answers meanwhile."""
    page = _open(
        browser_context,
        f"{server}/?planner=time-optimal-direct&goal=2,1.5,90&synthesis_starts=1",
    )
    try:
        first = _wait_result(page)
        box = page.locator(".gp-input-goal input")
        box.fill("2.5,1.5,90")
        box.press("Enter")
        page.wait_for_selector(".gp-busy", timeout=20_000)
        assert page.evaluate("() => 1 + 1") == 2  # the page's thread is free
        cost = float(_wait_result(page, previous=first))
        q = _query(page)
        v = VariableSpeedCar(float(q["v_min"]), float(q["v_max"]), float(q["u_max"]))
        opts: dict[str, Any] = {"synthesis_starts": int(q["synthesis_starts"])}
        ref = plan(Pose(), _pose(q["goal"]), v, "time", "direct", **opts).cost
        assert cost == pytest.approx(ref, rel=1e-6)
    finally:
        page.close()


def _frame(page: Any) -> dict[str, Any]:
    """The main figure's frame once the browser has laid it out (its size settles)."""
    last: dict[str, Any] = {}
    for _ in range(50):
        f = page.evaluate(FRAME_JS)
        if f == last:
            return f
        last = f
        time.sleep(0.1)
    return last


SCREENS = ((1280, 720), (1366, 768), (1440, 900), (1920, 1080))


def _enter(page: Any, name: str, text: str) -> None:
    """Type `text` into the input `name` and press Enter (unless it already holds it)."""
    box = page.locator(f".gp-input-{name} input")
    if box.input_value() != text:
        box.fill(text)
        box.press("Enter")


def test_equal_scales_and_fold_on_every_screen(dubins_page: Any, shots: pathlib.Path):
    """At each screen size the x and y scales (px per m, measured on Bokeh's frame) agree to
    one pixel over the frame, and the result strip and the whole plot with its x axis lie
    above the fold (reference: the window's size)."""
    page = dubins_page
    _enter(page, "radius", "1")  # the shared page may hold an earlier test's bad value
    _wait_result(page)
    try:
        for w, h in SCREENS:
            page.set_viewport_size({"width": w, "height": h})
            f = _frame(page)
            sx = f["w"] / (f["x1"] - f["x0"])
            sy = f["h"] / (f["y1"] - f["y0"])
            assert sx == pytest.approx(sy, rel=1.0 / min(f["w"], f["h"])), (w, h, f)
            assert f["w"] >= 300 and f["h"] >= 300, (w, h, f)
            assert f["bottom"] <= h, (w, h, f)  # the figure, x axis included
            strip = page.locator(".gp-strip").first.bounding_box()
            assert strip is not None and strip["y"] + strip["height"] <= f["top"], (w, h)
            assert page.evaluate("() => document.scrollingElement.scrollWidth") <= w
            page.screenshot(path=str(shots / f"explore_{w}x{h}.png"))
    finally:
        page.set_viewport_size({"width": 1500, "height": 1000})


def test_phone_layout(server: str, browser_context: Any, shots: pathlib.Path):
    """At 390 x 844: a viewport meta tag, no sideways scrolling, the plot first (within the
    first screen, above the controls), inside the screen with equal scales."""
    page = browser_context.new_page()
    page.set_viewport_size({"width": 390, "height": 844})
    try:
        page.goto(f"{server}/?" + FAMILIES["dubins"])
        page.wait_for_selector(".gp-cost", timeout=60_000)
        _wait_result(page)
        assert page.evaluate(
            "() => document.querySelector('meta[name=viewport]').content"
        ).startswith("width=device-width")
        assert page.evaluate("() => document.scrollingElement.scrollWidth <= innerWidth")
        f = _frame(page)
        goal_box = page.locator(".gp-input-goal").first.bounding_box()
        assert goal_box is not None and f["top"] + f["h"] <= goal_box["y"]
        assert f["top"] + f["h"] <= 844  # the whole plot on the first screen
        assert f["left"] >= 0 and f["left"] + f["w"] <= 390
        sx, sy = f["w"] / (f["x1"] - f["x0"]), f["h"] / (f["y1"] - f["y0"])
        assert sx == pytest.approx(sy, rel=1.0 / min(f["w"], f["h"]))
        page.screenshot(path=str(shots / "explore_phone.png"), full_page=True)
    finally:
        page.close()


def test_units_in_labels_and_header(dubins_page: Any):
    """Axes and inputs carry units; the cost header keeps its unit after a bad value."""
    page = dubins_page
    _enter(page, "radius", "1")
    _wait_result(page)
    f = _frame(page)
    assert (f["xlabel"], f["ylabel"]) == ("x (m)", "y (m)")
    for label in ("speed (m/s)", "radius (m)", "heading (deg"):
        assert page.get_by_text(label).count() >= 1, label
    helps = page.locator(".gp-help").all_inner_texts()
    assert helps and not any("`" in t for t in helps)  # no raw code quotes
    header = page.locator(".gp-k").first.inner_text().lower()
    assert header == "cost (length, m)"
    box = page.locator(".gp-input-speed input")
    box.fill("0")  # inside PHYSICAL_RANGES["speed"]'s closed end, refused by the vehicle
    box.press("Enter")
    page.wait_for_selector(".gp-error", timeout=20_000)
    assert page.locator(".gp-k").first.inner_text().lower() == header
    box.fill("1")
    box.press("Enter")
    _wait_result(page)


def test_wind_in_knots_and_wheel_zoom_in_the_link(server: str, browser_context: Any):
    """The wind's speed shown in kt while the link keeps m/s: 3 m/s shows 5.83 kt; typing
    10 kt puts 10 * 1852 / 3600 = 5.144444444 m/s in the link, and the cost is plan()'s for
    it. The mouse wheel zooms without picking a tool, and the zoom goes into the link."""
    page = _open(browser_context, f"{server}/?planner=wind&goal=4,3,90&speed=10&radius=1"
                 "&wind=3,40&wind_unit=kt")
    try:
        _wait_result(page)
        box = page.locator(".gp-input-wind-speed input")
        assert box.input_value() == "5.83"  # 3 m/s = 5.8315 kt, 4 digits
        before = page.locator(".gp-cost").first.inner_text()
        box.fill("10")
        box.press("Enter")
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and _query(page).get("wind") != "5.144444444,40":
            time.sleep(0.1)
        q = _query(page)
        assert q["wind"] == "5.144444444,40" and q["wind_unit"] == "kt"
        cost = float(_wait_result(page, previous=before))
        assert cost == pytest.approx(_reference(q), rel=1e-9)
        f = _frame(page)
        page.mouse.move(f["left"] + f["w"] / 2, f["top"] + f["h"] / 2)
        page.mouse.wheel(0, -400)  # zoom in
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and _floats(_query(page)["view"]) == _floats(q["view"]):
            time.sleep(0.1)
        x0, y0, x1, y1 = _floats(_query(page)["view"])
        ox0, oy0, ox1, oy1 = _floats(q["view"])
        assert x1 - x0 < 0.95 * (ox1 - ox0) and y1 - y0 < 0.95 * (oy1 - oy0)
    finally:
        page.close()


def test_planner_switch_keeps_poses(server: str, browser_context: Any):
    """Switching the planner keeps the entered start and goal (inputs and link)."""
    page = _open(browser_context, f"{server}/?planner=dubins&goal=2,5,45&start=1,-1,30")
    try:
        _wait_result(page)
        from glideplan.explore.catalog import LABELS

        page.locator("select").first.select_option(label=LABELS["wind"])
        deadline = time.monotonic() + 20
        while time.monotonic() < deadline and _query(page).get("planner") != "wind":
            time.sleep(0.1)
        _wait_result(page)
        q = _query(page)
        assert q["planner"] == "wind"
        assert (_pose(q["goal"]), _pose(q["start"])) == (_pose("2,5,45"), _pose("1,-1,30"))
        assert page.locator(".gp-input-goal input").input_value() == "2,5,45"
        assert float(page.locator(".gp-cost").first.inner_text()) == pytest.approx(
            _reference(q), rel=1e-6
        )
    finally:
        page.close()


def test_zoom_restored_from_link(server: str, browser_context: Any):
    """A link's `view=x0,y0,x1,y1` is shown (grown on one side to equal scales), and a zoom
    goes into the address."""
    page = _open(browser_context, f"{server}/?planner=dubins&goal=4,3,90&view=-1,-2,6,5")
    try:
        _wait_result(page)
        f = _frame(page)
        assert f["x0"] <= -1 + 1e-9 and f["x1"] >= 6 - 1e-9
        assert f["y0"] <= -2 + 1e-9 and f["y1"] >= 5 - 1e-9
        # one side is the link's exactly, the other grew about the same centre
        assert min(abs(f["x1"] - f["x0"] - 7), abs(f["y1"] - f["y0"] - 7)) < 1e-6
        assert 0.5 * (f["x0"] + f["x1"]) == pytest.approx(2.5)
        assert 0.5 * (f["y0"] + f["y1"]) == pytest.approx(1.5)
        vx0, vy0, vx1, vy1 = _floats(_query(page)["view"])
        assert (vx1 - vx0, vy1 - vy0) == pytest.approx(
            (f["x1"] - f["x0"], f["y1"] - f["y0"]), rel=1e-3
        )
    finally:
        page.close()


def test_route_link_duration_equals_cli(server: str, browser_context: Any, shots: pathlib.Path):
    """The route link's `gp-cost` is `glideplan route --json`'s duration_s (10 significant
    digits, as printed) for the same example, points, speed and grid spacing (a coarse 3 km
    grid keeps the test short; the CLI runs meanwhile)."""
    import subprocess
    import sys

    args = [
        "--example",
        "double-gyre",
        "--from",
        "30.2",
        "-39.8",
        "--to",
        "30.7",
        "-38.3",
        "--speed",
        "1",
        "--resolution",
        "3000",
        "--json",
    ]
    code = "from glideplan.cli.app import main; raise SystemExit(main())"
    proc = subprocess.Popen(
        [sys.executable, "-c", code, "route", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    page = _open(
        browser_context,
        f"{server}/?planner=route&example=double-gyre&from=30.2,-39.8&to=30.7,-38.3&speed=1"
        "&resolution=3000",
    )
    try:
        shown = _wait_result(page, timeout=120.0)
        out, err = proc.communicate(timeout=120)
        assert proc.returncode == 0, err
        ref = json.loads(out)["duration_s"]
        assert shown == f"{ref:.10g}"
        assert page.locator(".gp-status").first.inner_text().strip() == "solved"
        q = _query(page)
        assert (q["planner"], q["from"], q["to"], q["speed"]) == (
            "route",
            "30.2,-39.8",
            "30.7,-38.3",
            "1",
        )
        f = _frame(page)
        assert (f["xlabel"], f["ylabel"]) == ("longitude (deg E)", "latitude (deg N)")
        # equal metres per pixel at the field's middle latitude (30.45 deg)
        k = math.cos(math.radians(30.4497))
        sx, sy = f["w"] / ((f["x1"] - f["x0"]) * k), f["h"] / (f["y1"] - f["y0"])
        assert sx == pytest.approx(sy, rel=1.0 / min(f["w"], f["h"]))
        page.screenshot(path=str(shots / "explore_route.png"))
    finally:
        if proc.poll() is None:
            proc.kill()
        proc.communicate()
        page.close()


def test_mission_map_total_and_exports(server: str, browser_context: Any, tmp_path: pathlib.Path):
    """The mission map of the bundled route: `gp-cost` is `plan_mission`'s total length
    (the call of `glideplan mission plan`) for the URL's speed and radius; its JSON download
    is that plan's `to_dict()` (read by `json`), its GPX is read by the XML parser."""
    import xml.etree.ElementTree as ET

    from glideplan.explore.mission_page import EXAMPLE_ROUTE
    from glideplan.formats.readers import read_route
    from glideplan.missions import plan_mission

    page = _open(browser_context, f"{server}/?planner=mission&speed=1.5&radius=150")
    try:
        shown = float(_wait_result(page, timeout=60.0))
        ref = plan_mission(read_route(EXAMPLE_ROUTE), speed=1.5, radius=150.0)
        assert shown == pytest.approx(ref.total_length_m, rel=1e-9)
        files = {}
        for label in ("JSON", "GPX"):
            with page.expect_download(timeout=30_000) as info:
                page.get_by_role("button", name=label).click()
            files[label] = tmp_path / info.value.suggested_filename
            info.value.save_as(files[label])
        data = json.loads(files["JSON"].read_text())
        assert data["total_length_m"] == pytest.approx(ref.total_length_m, rel=1e-12)
        assert [leg["word"] for leg in data["legs"]] == [leg.word for leg in ref.legs]
        root = ET.parse(files["GPX"]).getroot()
        assert root.tag.endswith("gpx") and len(list(root.iter())) > 10
    finally:
        page.close()


def test_reach_map_counts_reachable_landables(server: str, browser_context: Any):
    """The reach map of the `ridge` example: `gp-cost` counts the landables that
    `glide_reach` (the call of `glide reach --example ridge`) finds reachable for the URL's
    start, wind, MC and safety height."""
    from glideplan.cli.glide import _polar
    from glideplan.reach import glide_reach
    from glideplan.reach.examples import example
    from glideplan.units import wind_from_compass

    page = _open(
        browser_context,
        f"{server}/?planner=reach&example=ridge&from=46.5,7.4,1800&wind=4,250&mc=0&safety=300",
    )
    ex = example("ridge")
    polar = _polar(ex.polar_file, None, 0.0, 0.0, "--polar")
    # the reference while the page computes the same on the server's worker thread
    ref = glide_reach(
        ex.terrain,
        (46.5, 7.4, 1800.0),
        polar,
        landables=ex.landables,
        mc=0.0,
        wind=wind_from_compass(4.0, 250.0),
        safety_height=300.0,
        resolution_m=None,  # the CLI's: the terrain's own grid
    )
    try:
        shown = _wait_result(page, timeout=60.0)
        n = sum(1 for p in ref.points if p.reachable)
        assert shown.strip() == f"{n} of {len(ref.points)}"
        f = _frame(page)
        assert (f["xlabel"], f["ylabel"]) == ("longitude (deg E)", "latitude (deg N)")
    finally:
        page.close()


@pytest.mark.heavy  # 6 s: make validate
def test_closing_a_tab_mid_update_logs_nothing(
    server: str, browser_context: Any, caplog: pytest.LogCaptureFixture
):
    """A tab closed while a slow planner works: the server logs no error and no thread dies
    with a traceback (the worker's answer is dropped)."""
    import logging
    import threading

    died: list[str] = []
    hook = threading.excepthook
    threading.excepthook = lambda args: died.append(repr(args.exc_value))

    page = _open(
        browser_context, f"{server}/?planner=time-optimal-direct&goal=2,1.5,90&synthesis_starts=1"
    )
    with caplog.at_level(logging.WARNING):
        box = page.locator(".gp-input-goal input")
        box.fill("2.5,1,90")
        box.press("Enter")
        page.wait_for_selector(".gp-stale", timeout=20_000)
        page.close()
        time.sleep(2.5)  # the worker finishes its plan for nobody
    threading.excepthook = hook
    bad = [r for r in caplog.records if r.levelno >= logging.ERROR or r.exc_info]
    assert not bad, [r.getMessage() for r in bad]
    assert not died


def test_latency_benchmark_runs(dubins_page: Any):
    """The browser latency benchmark's measurement (benchmarks/explore_browser.py) works on
    the page: each goal change shows a new cost (no timing is asserted here)."""
    import importlib.util

    _enter(dubins_page, "radius", "1")
    path = pathlib.Path(__file__).parents[2] / "benchmarks" / "explore_browser.py"
    spec = importlib.util.spec_from_file_location("explore_browser", path)
    assert spec is not None and spec.loader is not None
    bench = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(bench)
    _wait_result(dubins_page)
    goals = bench.goal_texts(4.0, 3.0, 90.0, 1.0, 4)
    ms, cost = bench.measure(dubins_page, goals, warm=1)
    assert len(ms) == 3 and all(0 < m < 10_000 for m in ms)
    # per-change costs read: CPU of this process's threads (here the server is another
    # process), Chromium's own counters
    assert cost["server_cpu_ms"] >= 0 and cost["TaskDuration"] > 0 and cost["LayoutCount"] >= 0
    _wait_result(dubins_page)
    deadline = time.monotonic() + 10.0  # the address follows the answer (with its candidates)
    while _query(dubins_page)["goal"] != goals[-1] and time.monotonic() < deadline:
        time.sleep(0.05)
    q = _query(dubins_page)
    assert q["goal"] == goals[-1]
    assert float(dubins_page.locator(".gp-cost").first.inner_text()) == pytest.approx(
        _reference(q), rel=1e-6
    )


def test_every_request_stays_local(server: str, browser_context: Any, requests_seen: list[str]):
    """No request leaves 127.0.0.1: scripts and style sheets are served by the app itself.

    The test loads two pages of its own (pytest-xdist may give it a worker on which no other
    test of this module ran), then checks every request the context has seen so far."""
    for family in ("dubins", "load-factor"):
        page = _open(browser_context, f"{server}/?{FAMILIES[family]}")
        _wait_result(page)
        page.close()
    assert any(urlparse(u).path.endswith(".js") for u in requests_seen), requests_seen[:5]
    for url in requests_seen:
        parsed = urlparse(url[len("blob:") :] if url.startswith("blob:") else url)
        if parsed.scheme == "data":
            continue
        assert parsed.hostname == "127.0.0.1", url


def test_route_map_of_a_field_file(browser_context: Any, tmp_path: pathlib.Path, run_cli: Any):
    """`explore --field FILE`: a Copernicus-like file with a rectangular headland (land from
    its NaN mask), served from its server-side path; the route page's `gp-cost` equals
    `glideplan route --field FILE --json`'s duration_s for the same points, speed and grid."""
    from glideplan.explore.server import serve
    from glideplan.fields.synthetic import copernicus_headland_dataset

    path = tmp_path / "headland.nc"
    copernicus_headland_dataset().to_netcdf(path)
    frm, to = ("30.3", "-40.5"), ("30.3", "-40.0")
    code, out, err = run_cli("route", "--field", str(path), "--from", *frm, "--to", *to,
                             "--speed", "0.5", "--resolution", "1000", "--json")
    assert code == 0, err
    ref = json.loads(out)["duration_s"]
    port = _free_port()
    srv = serve(port, "127.0.0.1", show=False, threaded=True, field=str(path))
    try:
        _wait_listening(port)
        page = _open(browser_context, f"http://127.0.0.1:{port}/?planner=route"
                     f"&from={frm[0]},{frm[1]}&to={to[0]},{to[1]}&speed=0.5&resolution=1000")
        try:
            shown = _wait_result(page, timeout=120.0)
            assert shown == f"{ref:.10g}"
        finally:
            page.close()
    finally:
        srv.stop()
