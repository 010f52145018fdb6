"""What the explorer draws for what was computed: unverified answers marked, safe columns."""

from __future__ import annotations

import types
from dataclasses import replace

import numpy as np

from glideplan.explore.app import Explorer
from glideplan.explore.catalog import build_catalog
from glideplan.explore.figures import columns
from glideplan.explore.map_page import warnings_item


def test_unverified_path_is_dashed_muted_and_labelled():
    e = Explorer(build_catalog(), {"planner": "dubins", "goal": "4,3,90"}, sync=True)
    glyph = e.figs.path_renderer.glyph
    assert e.view.ok and list(glyph.line_dash) == []
    labels = lambda: [i.label.value for i in e.figs._legend_items]  # noqa: E731
    assert "optimal path" in labels()
    bad = replace(e.view, solution=types.SimpleNamespace(ok=False))
    e.figs.show(bad, None, False)
    assert list(glyph.line_dash) != [] and glyph.line_alpha < 1.0
    assert "path (not verified)" in labels() and "optimal path" not in labels()
    e.figs.show(e.view, None, False)
    assert list(glyph.line_dash) == [] and "optimal path" in labels()


def test_columns_are_sent_with_equal_lengths_and_no_empty_arrays():
    assert columns({"x": np.zeros(0), "y": np.zeros(0)}) == {"x": [], "y": []}
    assert columns({"x": [1.0, 2.0], "y": [1.0]}) == {"x": [], "y": []}
    good = columns({"x": np.arange(3.0), "y": np.arange(3.0)})
    assert np.array_equal(good["x"], [0.0, 1.0, 2.0])


def test_warnings_are_listed_in_the_strip():
    r = types.SimpleNamespace(warnings=("footprint clipped", "refinement <not> used"))
    text = warnings_item(r)
    assert "gp-warn" in text and "footprint clipped" in text and "&lt;not&gt;" in text
    assert warnings_item(types.SimpleNamespace(warnings=())) == ""
