"""Issue 26, one place each: the Earth's radius, great-circle (and rhumb-line) destination,
the wind conversions, the wind arrow and the progress bar are each defined once; the explorer
uses the library, never `glideplan.cli`; `explore.map_page` does not import `explore.app`.

Checked on the source (AST), with closed forms for the two destinations.
"""

from __future__ import annotations

import ast
import functools
import math
import pathlib
import re

import numpy as np
import pytest

SRC = pathlib.Path(__file__).parents[2] / "src" / "glideplan"
FILES = sorted(p for p in SRC.rglob("*.py"))


@functools.cache
def _texts() -> tuple[tuple[str, str], ...]:
    return tuple((p.relative_to(SRC).as_posix(), p.read_text(encoding="utf-8")) for p in FILES)


def _where(pattern: str) -> list[str]:
    """The modules with a line matching `pattern` (regex, multi-line)."""
    rx = re.compile(pattern, re.MULTILINE)
    return [rel for rel, text in _texts() if rx.search(text)]


def _imports(tree):
    """Every module an import statement of `tree` names (module level or inside functions)."""
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module:
            yield node.module
        elif isinstance(node, ast.Import):
            yield from (a.name for a in node.names)


def test_each_definition_lives_in_one_module():
    assert _where(r"^\s*EARTH_RADIUS_M\s*[:=]") == ["geodesy.py"]
    assert _where(r"^\s*R_EARTH\s*[:=]") == []
    for name, home in (("destination", "geodesy.py"), ("rhumb_destination", "geodesy.py"),
                       ("wind_from_compass", "units.py"), ("wind_to_compass", "units.py"),
                       ("wind_arrow", "plotting.py"), ("start_progress_bar", "progress.py")):
        assert _where(rf"^\s*def {name}\(") == [home], name
    for old in ("wind_from_to_vector", "wind_compass", "_wind_from_deg"):
        assert _where(rf"^\s*def {old}\(") == [], old  # the former converters are gone


def test_no_other_earth_radius_literal():
    for rel, text in _texts():
        if rel != "geodesy.py":
            for literal in ("6371008", "6_371_008", "6371000", "6_371_000"):
                assert literal not in text, (rel, literal)


def test_rich_progress_is_built_in_one_place():
    """Rich bars (`BarColumn`) are built by `glideplan.progress` only (the CLI's spinner
    `solving` has no bar)."""
    assert _where(r"\bBarColumn\b") == ["progress.py"]


def test_explorer_uses_the_library_not_the_cli_and_map_page_not_app():
    for rel, text in _texts():
        if rel.startswith("explore/"):
            mods = set(_imports(ast.parse(text)))
            assert not any(m == "glideplan.cli" or m.startswith("glideplan.cli.")
                           for m in mods), rel
            if rel == "explore/map_page.py":
                assert "glideplan.explore.app" not in mods


def test_great_circle_and_rhumb_destination_closed_forms():
    """Great circle from (60 N, 0) due east (bearing 90 deg) for d: sin(phi2) = sin(60)
    cos(d / R) (it leaves the parallel towards the equator); the rhumb line due east stays on
    the parallel with lon = d / (R cos 60). Both due north: lat = d / R."""
    from glideplan.geodesy import EARTH_RADIUS_M as R
    from glideplan.geodesy import destination, rhumb_destination

    d = np.array([1e4, 5e5, 2e6])
    la, _ = destination(60.0, 0.0, math.pi / 2, d)
    np.testing.assert_allclose(np.sin(np.radians(la)), math.sin(math.radians(60.0))
                               * np.cos(d / R), rtol=1e-12)
    la_r, lo_r = rhumb_destination(60.0, 0.0, 0.0, d)  # chi = 0: east
    np.testing.assert_allclose(la_r, 60.0, atol=1e-12)
    np.testing.assert_allclose(np.radians(lo_r), d / (R * 0.5), rtol=1e-12)
    np.testing.assert_allclose(destination(0.0, 10.0, 0.0, d)[0], np.degrees(d / R),
                               rtol=1e-12)
    np.testing.assert_allclose(rhumb_destination(0.0, 10.0, math.pi / 2, d)[0],
                               np.degrees(d / R), rtol=1e-12)


def test_delayed_bar_waits_and_never_starts_a_finished_job(monkeypatch):
    import glideplan.progress as progress

    started = []

    class _Bar:
        def update(self, task, **kw):
            started.append(kw)

        def stop(self):
            started.append("stop")

    monkeypatch.setattr(progress, "start_progress_bar", lambda *a, **k: (_Bar(), 0))
    now = [0.0]
    bar = progress.DelayedBar("x", 10, delay=1.0, clock=lambda: now[0])
    bar.update(completed=3)
    assert started == []  # within the delay: nothing
    now[0] = 2.0
    bar.update(completed=10)
    assert started == []  # finished before it was due: nothing
    bar.update(completed=5)
    bar.close(completed=6)
    assert started == [{"completed": 5}, {"completed": 6}, "stop"]
    off = progress.DelayedBar("y", 10, enabled=False, delay=-1.0)
    off.update(completed=1)
    off.close()
    assert started[-1] == "stop" and len(started) == 3


@pytest.mark.parametrize("name", ["vehicles/dubins_car_in_wind.py", "vehicles/sailplane.py"])
def test_vehicles_hold_one_wind_field(name):
    """The vehicles' wind is the one (east, north) field `wind`, not a speed and direction."""
    tree = ast.parse((SRC / name).read_text(encoding="utf-8"))
    fields = {t.target.id for t in ast.walk(tree)
              if isinstance(t, ast.AnnAssign) and isinstance(t.target, ast.Name)}
    assert "wind" in fields and not {"wind_speed", "wind_direction"} & fields
