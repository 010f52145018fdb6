"""The explorer without a browser: its planner catalogue, URL state, messages and figure data.

References: the planner registry and the Typer commands of `glideplan plan` (the names the
page must use), `plan()` for costs, the CLI's one-line messages, and the partition map
of `glideplan.studies.maps` against the optimal word of `plan()`.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from glideplan import DubinsCar, Pose, plan, registered_planners
from glideplan.explore.catalog import build_catalog, planner_key
from glideplan.explore.solve import partition_image, solve_view
from glideplan.explore.state import initial_state, state_from_query, state_to_query

# registry key -> `glideplan plan` command of the built-in planners
CLI_COMMANDS = {
    "dubins": "dubins",
    "wind": "wind",
    "time-optimal": "time-optimal",
    "time-optimal-direct": "time-optimal",
    "min-altitude": "min-altitude",
    "min-altitude-direct": "min-altitude",
    "load-factor": "load-factor",
    "load-factor-direct": "load-factor",
}


@pytest.fixture(scope="module")
def catalog():
    return build_catalog()


def test_every_registered_planner_is_offered(catalog):
    """One entry per registered (planner, objective, method), with a readable label."""
    specs = {(planner_key(s.name), s.objective, s.method) for s in registered_planners()}
    offered = {(planner_key(e.spec.name), e.objective, e.method) for e in catalog.entries}
    assert offered == specs
    assert len(set(catalog.keys)) == len(catalog.entries)
    assert all(e.label and e.label != e.key for e in catalog.entries)


def _cli_options(command: str) -> set[str]:
    import typer

    from glideplan.cli.app import app, load_commands, plan_app

    load_commands()
    group = typer.main.get_command(app).commands["plan"]  # type: ignore[attr-defined]
    assert plan_app is not None
    return {o for p in group.commands[command].params for o in p.opts}


@pytest.mark.parametrize("key", sorted(CLI_COMMANDS))
def test_vehicle_inputs_are_named_like_cli_options(key, catalog):
    """Each vehicle input of a built-in planner is an option of its `glideplan plan` command."""
    entry = catalog.get(key)
    options = _cli_options(CLI_COMMANDS[key])
    names = {p.flag for p in entry.parameters if p.target == "vehicle"}
    assert names <= options, names - options


def test_url_round_trip_and_defaults(catalog):
    """A state survives its URL; the issue's example URL sets the goal and the radius."""
    st = state_from_query(catalog, "planner=dubins&goal=4,3,90&radius=2&eps=0.1&partition=1")
    assert (st.planner, st.goal, st.values["radius"], st.values["eps"]) == (
        "dubins",
        "4,3,90",
        "2",
        "0.1",
    )
    assert st.partition and st.candidates
    again = state_from_query(catalog, state_to_query(catalog, st))
    assert again == st
    wind = state_from_query(catalog, "planner=wind&objective=time&wind=0.5,30")
    assert wind.planner == "wind" and wind.values["wind"] == "0.5,30"
    assert state_from_query(catalog, "planner=dubins&objective=time").planner == "dubins/time"
    for entry in catalog.entries:
        assert state_from_query(catalog, state_to_query(catalog, initial_state(entry))).planner == (
            entry.key
        )


def test_cost_and_word_match_plan(catalog):
    """`solve_view` shows plan()'s cost with 10 significant digits and its word."""
    view = solve_view(catalog, state_from_query(catalog, "planner=dubins&goal=4,3,90&radius=1"))
    ref = plan(Pose(0, 0, 0), Pose(4, 3, math.pi / 2), DubinsCar(1.0, 1.0))
    assert float(view.cost_text) == pytest.approx(ref.cost, rel=1e-9)
    assert view.word == ref.word
    feasible = [c for c in ref.candidates if c.feasible]
    assert len([x for x in view.candidates["xs"] if len(x)]) == len(feasible)
    assert view.path["x"][-1] == pytest.approx(4.0, abs=1e-9)


@pytest.mark.parametrize(
    ("query", "name", "cli_args"),
    [
        (
            "planner=dubins&radius=-1",
            "radius",
            ("dubins", "--goal", "4", "3", "90", "--radius", "-1"),
        ),
        (
            "planner=dubins&radius=1&eps=2",
            "eps",
            ("dubins", "--goal", "4", "3", "90", "--radius", "1", "--eps", "2"),
        ),
        (
            "planner=time-optimal&v_min=2&v_max=1&u_max=1",
            "v_min",
            (
                "time-optimal",
                "--goal",
                "4",
                "3",
                "90",
                "--v-min",
                "2",
                "--v-max",
                "1",
                "--u-max",
                "1",
            ),
        ),
    ],
)
def test_bad_input_gives_the_cli_line(catalog, cli_error, query, name, cli_args):
    """The message under an input is the CLI's one-line message for the same value."""
    view = solve_view(catalog, state_from_query(catalog, query + "&goal=4,3,90"))
    assert not view.ok
    assert cli_error("plan", *cli_args) == f"glideplan: error: {view.errors[name]}"


def test_bad_text_is_named(catalog):
    view = solve_view(catalog, state_from_query(catalog, "planner=dubins&goal=4,x,90&radius=abc"))
    assert set(view.errors) == {"goal", "radius"}
    assert view.errors["radius"].startswith("--radius='abc'")


def test_partition_background_agrees_with_plan(catalog):
    """The partition map's word at a goal is plan()'s optimal word there (away from borders)."""
    view = solve_view(catalog, state_from_query(catalog, "planner=dubins&goal=4,3,90&radius=1"))
    assert view.request is not None
    img = partition_image(view.request, (-6.0, 6.0, -6.0, 6.0), n=121)
    assert img is not None and img["image"].shape == (121, 121)
    from glideplan.explore.solve import _WORD_COLOURS

    # the pixel at the goal (4, 3): column (4 + 6) / 12 * 120, row (3 + 6) / 12 * 120
    pixel = img["image"][90, 100]
    colour = np.array([*_WORD_COLOURS[view.word], 70], dtype=np.uint8).view(np.uint32)[0]
    assert view.word == "LSL" and pixel == colour
    assert "LSL" in img["labels"]["text"]


def test_cli_serves_the_page_locally(tmp_path):
    """`glideplan explore --port P --no-show` serves `/` on 127.0.0.1 with local resources only."""
    import re
    import socket
    import subprocess
    import sys
    import time
    import urllib.request

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    code = "from glideplan.cli.app import main; raise SystemExit(main())"
    args = [sys.executable, "-c", code, "explore", "--port", str(port), "--no-show"]
    proc = subprocess.Popen(args, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    try:
        html = ""
        deadline = time.monotonic() + 60.0
        while time.monotonic() < deadline and not html:
            try:
                with urllib.request.urlopen(
                    f"http://127.0.0.1:{port}/?planner=wind", timeout=5
                ) as r:
                    assert r.status == 200
                    html = r.read().decode()
            except OSError:
                if proc.poll() is not None:
                    raise AssertionError(proc.communicate()[1].decode()) from None
                time.sleep(0.3)
        assert "glideplan explore" in html
        urls = re.findall(r'(?:src|href)="([^"]+)"', html)
        assert urls
        assert all(u.startswith(("/", "static/", "./")) or "127.0.0.1" in u for u in urls), urls
    finally:
        proc.terminate()
        proc.communicate(timeout=20)


def test_cli_refuses_a_bad_port(cli_error):
    assert cli_error("explore", "--port", "0") == "glideplan: error: --port=0: must be in 1..65535"


def test_labels_carry_units_and_angles_are_degrees(catalog):
    """Every input's label names its unit (m/s, m, rad/s, deg, kg, ...) or is a pure number;
    bank max is entered in degrees (the Sailplane default, 45 deg = pi/4 rad inside)."""
    units = ("(m/s)", "(m)", "(rad/s)", "(deg", "(kg)", "(nondim.)", "(g)", "(ratio", "(L)",
             "(%)", "(m²)", "(relative)", "(true/false)", "(s/m)")
    counts = ("n intervals", "max starts", "max refinements", "max iterations", "scheme",
              "formulation", "seeds", "synthesis starts", "polar name")
    for entry in catalog.entries:
        if not entry.spec.function.__module__.startswith("glideplan."):
            continue  # a planner some test registered (tests/core/test_planning.py)
        for p in entry.parameters:
            label = p.caption(entry.nondimensional)
            assert "_" not in label and "((" not in label, label
            assert any(u in label for u in units) or label in counts, (entry.key, label)
    glide = catalog.get("final-glide")
    bank = glide.parameter("bank_max")
    assert bank is not None and bank.caption() == "bank max (deg)" and bank.default == "45"
    assert bank.parse("30") == {"bank_max": pytest.approx(math.pi / 6, rel=1e-15)}
    dubins = catalog.get("dubins")
    assert [p.caption() for p in dubins.parameters][:2] == ["speed (m/s)", "radius (m)"]
    assert "`" not in dubins.help


def test_cost_header_keeps_its_unit_after_an_error(catalog):
    """The strip's cost header comes from the planner: 'cost (length, m)' with or without an
    answer, 'cost (altitude, nondim.)' for the nondimensional glider; never doubled '(('."""
    from glideplan.explore.texts import strip_html

    good = solve_view(catalog, state_from_query(catalog, "planner=dubins&goal=4,3,90"))
    bad = solve_view(catalog, state_from_query(catalog, "planner=dubins&radius=-1"))
    for view in (good, bad):
        html = strip_html(view)
        assert "cost (length, m)" in html and "((" not in html and "nondim" not in html
    lf = state_from_query(catalog, "planner=load-factor&v_min=-1")
    assert "cost (altitude, nondim.)" in strip_html(solve_view(catalog, lf))
    assert "gp-stale" in strip_html(good, stale=True)


def test_downloads_after_an_error_carry_the_message(catalog, cli_error):
    """JSON and CSV written for a bad input hold the CLI's one-line message (read back by
    `json` and `csv`); the PNG is a readable image."""
    import csv
    import io
    import json

    from glideplan.explore.downloads import path_csv, solution_json, solution_png

    view = solve_view(catalog, state_from_query(catalog, "planner=dubins&radius=-1&goal=4,3,90"))
    line = cli_error("plan", "dubins", "--goal", "4", "3", "90", "--radius", "-1")
    message = line.removeprefix("glideplan: error: ")
    data = json.loads(solution_json(None, view.errors))
    assert data["status"] is None and data["ok"] is False and data["message"] == message
    assert data["errors"] == {"radius": message}
    rows = list(csv.DictReader(io.StringIO(path_csv(None, view.errors))))
    assert rows == [{"error": message}]
    from matplotlib.image import imread

    assert imread(io.BytesIO(solution_png(None, view.errors))).shape[0] > 100


def test_link_view_is_parsed():
    from glideplan.explore.app import _parse_view

    assert _parse_view("-1,-2,6,5") == (-1.0, -2.0, 6.0, 5.0)
    for bad in ("", "1,2,3", "1,2,0,5", "a,b,c,d", "0,0,nan,1", "0,0,1,inf"):
        assert _parse_view(bad) is None, bad


def test_isochrones_of_still_water_are_circles():
    """In still water the arrival time is T = d / V (d great-circle-free local distance), so
    the isochrone of level L is the circle of radius V L about the start (closed form); its
    points lie within one grid spacing of it."""
    from types import SimpleNamespace

    from glideplan.explore.route_page import isochrones

    lat0, lon0, speed = 30.0, -40.0, 1.0
    lat = np.linspace(29.5, 30.5, 121)
    lon = np.linspace(-40.6, -39.4, 141)
    r_earth = 6_371_000.0
    y = np.radians(lat - lat0)[:, None] * r_earth
    x = np.radians(lon - lon0)[None, :] * r_earth * math.cos(math.radians(lat0))
    arrival = np.hypot(x, y) / speed
    arrival[:5, :5] = np.inf  # never reached: no contour drawn along that edge
    lines, step = isochrones(SimpleNamespace(lat=lat, lon=lon, arrival=arrival), 12 * 3600.0)
    assert step in (1.0, 2.0) and lines["xs"]
    spacing = np.radians(lat[1] - lat[0]) * r_earth
    for xs, ys, label in zip(lines["xs"], lines["ys"], lines["label"], strict=True):
        level_h = float(label.removesuffix(" h"))
        px = np.radians(np.asarray(xs) - lon0) * r_earth * math.cos(math.radians(lat0))
        py = np.radians(np.asarray(ys) - lat0) * r_earth
        assert np.abs(np.hypot(px, py) - speed * level_h * 3600.0).max() < spacing


def test_cli_refuses_missing_field_and_route_files(cli_error, tmp_path):
    """`explore --field` / `--route` with a missing file: one line naming the flag, exit 2,
    before anything is served."""
    missing = tmp_path / "nope.nc"
    assert "--field" in cli_error("explore", "--no-show", "--field", str(missing))
    assert "--route" in cli_error("explore", "--no-show", "--route", str(tmp_path / "r.gpx"))


def test_load_factor_page_is_the_synthesis(catalog):
    """`planner=load-factor` is `plan load-factor --method synthesis` (the same cost as
    plan() with method "synthesis", exactly: the same call), says which method answered,
    and the direct method is `load-factor-direct`; the registered name still opens it."""
    from dataclasses import replace
    from types import SimpleNamespace

    from glideplan.explore.texts import strip_html
    from glideplan.vehicles.load_factor_glider import LoadFactorGlider

    assert catalog.get("load-factor").method == "synthesis"
    assert catalog.get("load-factor-direct").method == "direct"
    assert catalog.get("load-factor-synthesis").key == "load-factor"
    assert catalog.get("load-factor").background and not catalog.get("load-factor").slow
    view = solve_view(catalog, state_from_query(catalog, "planner=load-factor&goal=3,2,60"))
    ref = plan(Pose(0, 0, 0), Pose(3, 2, math.radians(60)), LoadFactorGlider(), "altitude",
               "synthesis")
    assert view.ok and view.solution.cost == ref.cost
    assert view.method_text == "synthesis"
    assert 'gp-method">synthesis<' in strip_html(view)
    # where the synthesis found no candidate its answer says the direct method answered
    fallback = replace(view, solution=SimpleNamespace(extras={"answered_by": "direct"}))
    assert fallback.method_text == "direct (synthesis: no candidate)"
