"""One figure home: one saver at one resolution, and no backend switching in library figures.

References: a PNG saved without cropping is figsize x dpi pixels (Matplotlib's definition of
dpi); `matplotlib.use` appears in the library only where `glideplan reproduce` makes files
(`figures.registry.run_figure`), read from the source text.
"""

from __future__ import annotations

import pathlib
import re

import numpy as np
import pytest

import glideplan
from glideplan.plotting import FIGURE_DPI, plot_track, save_figure
from glideplan.track import Track

SRC = pathlib.Path(glideplan.__file__).parent


def test_save_figure_writes_at_the_one_resolution(tmp_path):
    import matplotlib.image
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(4.0, 3.0))
    t = np.linspace(0.0, 10.0, 5)
    plot_track(Track(t, t, 0.5 * t, np.full(5, 0.46)), ax)
    out = save_figure(fig, tmp_path / "t.png", crop=False)
    h, w = matplotlib.image.imread(out).shape[:2]
    assert (w, h) == (round(4.0 * FIGURE_DPI), round(3.0 * FIGURE_DPI))
    assert not plt.get_fignums()  # closed


def test_matplotlib_use_only_where_reproduce_makes_files():
    calls = sorted(
        str(p.relative_to(SRC)) for p in SRC.rglob("*.py")
        if re.search(r"matplotlib\.use\(", p.read_text(encoding="utf-8"))
    )
    assert calls == ["figures/registry.py"]


def test_library_figures_keep_the_users_backend():
    """A notebook's backend survives drawing a glide figure (the svg backend as a marker)."""
    import matplotlib

    from glideplan.sailplane.plot import final_glide_figure
    from glideplan.sailplane.request import FinalGlideDrawing

    before = matplotlib.get_backend()
    matplotlib.use("svg")
    try:
        x = np.linspace(0.0, 8000.0, 5)
        fig = final_glide_figure(FinalGlideDrawing(
            x=x, y=0.5 * x, distance=np.hypot(x, 0.5 * x), altitude=np.linspace(1500, 900, 5),
            goal_elevation=450.0, safety_height=300.0, title="t"))
        assert matplotlib.get_backend() == "svg"
        import matplotlib.pyplot as plt

        plt.close(fig)
    finally:
        matplotlib.use(before)


@pytest.mark.parametrize("module", ["figures.ch5", "figures.ch6"])
def test_solution_figures_live_beside_the_path_plotting(module):
    """The chapter modules reuse `glideplan.solution_figures` (the CLI's --plot draws it)."""
    import importlib

    from glideplan import solution_figures

    mod = importlib.import_module(f"glideplan.{module}")
    assert "solution_figures" in (SRC / (module.replace(".", "/") + ".py")).read_text()
    assert callable(mod.solution_figure) and callable(solution_figures.min_altitude_figure)
