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


def test_hidden_load_factor_plot_is_sent_no_data():
    """Minimum time has no load factor: its plot is hidden and its source stays empty (a
    hidden Bokeh plot fed its siblings' data re-laid out the whole page on every change);
    the load-factor page fills it with the vehicle's n(V, u) along the answer's path."""
    e = Explorer(build_catalog(), {"planner": "time-optimal", "goal": "2,1,90"}, sync=True)
    assert not e.figs.third_fig.visible and len(e.figs.third_src.data["t"]) == 0
    assert len(e.figs.prof_src.data["t"]) > 2 and "third" not in e.figs.prof_src.data
    lf = Explorer(build_catalog(), {"planner": "load-factor", "goal": "3,2,60"}, sync=True)
    data = lf.figs.third_src.data
    assert lf.figs.third_fig.visible and len(data["t"]) == len(lf.figs.prof_src.data["t"]) > 2
    assert np.nanmin(np.asarray(data["third"], dtype=float)) >= 1.0 - 1e-12  # n >= 1 in a turn


def test_candidates_wait_until_no_newer_answer_came():
    """A candidates timer set for an answer that a newer one replaced does nothing; the
    newest answer's own timer adds its candidates (lines and table)."""
    e = Explorer(build_catalog(), {"planner": "time-optimal", "goal": "2,1,90"}, sync=True)
    shown = replace(e.view, candidates=None, candidates_pending=True)
    older = replace(shown)
    e.view, e._candidates_for = shown, shown
    e._add_candidates(older)
    assert e.view is shown and e.view.candidates_pending
    e._add_candidates(shown)
    assert not e.view.candidates_pending
    assert len(e.figs.cand_src.data["word"]) == len(e.view.solution.candidates) > 8
