"""The explorer's plots of the controls along the path: speed, turn rate (or bank) and load
factor against time, on one time axis, with axis ranges that hold still while they can."""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from bokeh.layouts import column
from bokeh.models import ColumnDataSource, Range1d
from bokeh.models.widgets import Div
from bokeh.plotting import figure

from glideplan.explore.solve import View

__all__ = ["ProfilePlots", "sticky_range"]

BLUE = "#1f5fa8"  # the answer's colour on every plot


def sticky_range(
    shown: tuple[Any, Any] | None, values: Any, zero: bool = False, fill: float = 0.0
) -> tuple[float, float]:
    """An axis range for `values`: `shown` while it holds them and they fill at least `fill`
    of it, else round bounds (steps of a fifth of a decade) around them and `shown` with 5 %
    room (`shown` None: around them alone); from 0 when `zero` (a time axis)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return (0.0, 1.0) if shown is None else (float(shown[0]), float(shown[1]))
    lo, hi = (0.0 if zero else float(v.min())), float(v.max())
    if shown is not None:
        s0, s1 = float(shown[0]), float(shown[1])
        if s0 <= lo and hi <= s1 and (hi - lo) >= fill * (s1 - s0):
            return s0, s1
        if (hi - lo) >= fill * (max(hi, s1) - min(lo, s0)):
            lo, hi = min(lo, s0), max(hi, s1)
    span = hi - lo if hi > lo else max(abs(hi), 1.0)
    pad = 0.05 * span
    step = 0.2 * 10.0 ** math.floor(math.log10(span + 2 * pad))
    start = 0.0 if zero else math.floor((lo - pad) / step) * step
    end = math.ceil((hi + pad) / step) * step
    return float(f"{start:.12g}"), float(f"{end:.12g}")


class ProfilePlots:
    """The profile plots and their sources (a part of `figures.PlanFigures`)."""

    def _add_profiles(self) -> None:
        """The controls along the path: speed, turn rate (or bank) and load factor against
        time, on one time axis."""
        self.prof_src = ColumnDataSource({"t": [], "speed": [], "second": []})
        # the load factor in a source of its own, written only while its plot is shown: a
        # hidden Bokeh plot repainted with its siblings' data measured a changed size on
        # every paint and re-laid out the whole page (one layout of 46 views per change)
        self.third_src = ColumnDataSource({"t": [], "third": []})
        # explicit ranges, set with the data and kept while they hold it (`sticky_range`):
        # auto-ranging moved the axes on every answer, and each move re-laid out and
        # repainted the three plots (2.7 paints and ~3 layouts of each per change)
        x_range = Range1d(start=0.0, end=1.0)
        self.speed_fig = self._profile_figure("speed", "speed (m/s)", BLUE, x_range)
        self.second_fig = self._profile_figure("second", "turn rate (deg/s)", "#8e44ad", x_range)
        self.third_fig = self._profile_figure(
            "third", "load factor n (g)", "#d35400", x_range, self.third_src
        )
        for f in (self.speed_fig, self.second_fig, self.third_fig):
            f.background_fill_color = "#fbfcfe"
            f.grid.grid_line_color = "#e3e9f0"
        self.profile_col = column(
            Div(text="<b>Controls along the path</b>", styles={"color": "#3b4a59"}),
            self.speed_fig,
            self.second_fig,
            self.third_fig,
            sizing_mode="stretch_width",
        )

    def _profile_figure(
        self, key: str, label: str, color: str, x_range: Any | None = None, source: Any = None
    ) -> Any:
        """A small plot of the profile column `key` of `source` (the profile's) against time
        (shared time axis)."""
        extra = {} if x_range is None else {"x_range": x_range}
        fig = figure(
            y_range=Range1d(start=0.0, end=1.0),
            min_border_left=56,  # tick labels of any width: the plot's frame does not move
            height=150,
            sizing_mode="stretch_width",
            min_width=200,
            **extra,
            x_axis_label="time (s)",
            y_axis_label=label,
            tools="save,reset",
            toolbar_location=None,
        )
        src = self.prof_src if source is None else source
        fig.line("t", key, source=src, line_color=color, line_width=2)
        return fig

    def show_profile(self, view: View) -> None:
        """Write the answer's profile into the plots (hidden without one) and fit the axes."""
        from glideplan.explore.figures import columns  # (figures imports this module)

        prof = view.profile
        if self.profile_col.visible != (prof is not None):
            self.profile_col.visible = prof is not None
        third = None if prof is None else prof.get("third")
        if prof is not None and third is not None:
            self.third_src.data = columns({"t": prof["t"], "third": third})
        elif len(self.third_src.data["t"]):
            self.third_src.data = {"t": [], "third": []}
        if prof is None:
            if len(self.prof_src.data["t"]):
                self.prof_src.data = {"t": [], "speed": [], "second": []}
            return
        self.prof_src.data = columns(
            {"t": prof["t"], "speed": prof["speed"], "second": prof["second"]}
        )
        # the axes grow to hold the answers of one vehicle (speeds, turn rates and load
        # factors stay within its limits) and start again for another; time from 0, shrunk
        # when a path fills less than a quarter of it
        key = (view.state.planner, tuple(sorted(view.state.values.items())))
        same = key == getattr(self, "_profile_key", None)
        self._profile_key = key
        ranges = [(self.speed_fig.x_range, prof["t"], True, 0.25)] + [
            (f.y_range, values, False, 0.0)
            for f, values in zip((self.speed_fig, self.second_fig, self.third_fig),
                                 (prof["speed"], prof["second"], third), strict=True)
            if values is not None
        ]
        for rng, values, zero, fill in ranges:
            shown = (rng.start, rng.end) if same else None
            lo, hi = sticky_range(shown, values, zero=zero, fill=fill)
            if (lo, hi) != (rng.start, rng.end):
                rng.update(start=lo, end=hi)
        if self.second_fig.yaxis[0].axis_label != view.profile_labels[1]:
            self.second_fig.yaxis.axis_label = view.profile_labels[1]
        if self.third_fig.visible != (third is not None):
            self.third_fig.visible = third is not None
