"""The base drawing of an `Outcome` (`glideplan.results`): its status and message as text."""

from __future__ import annotations

import textwrap
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from glideplan.results import Outcome

__all__ = ["plot_outcome_text"]


def plot_outcome_text(outcome: Outcome, ax: Any = None, **kwargs: Any) -> Figure:
    """A figure with the outcome's status, message and warnings (results with no drawing)."""
    import matplotlib.pyplot as plt

    from glideplan.results import as_figure

    if ax is None:
        _, ax = plt.subplots(figsize=kwargs.pop("figsize", (6.0, 2.5)))
    lines = [f"status: {outcome.status.value}", *textwrap.wrap(outcome.message, 70)]
    lines += [f"warning: {w}" for w in outcome.warnings]
    ax.text(0.02, 0.95, "\n".join(lines), va="top", ha="left", transform=ax.transAxes)
    ax.set_axis_off()
    return as_figure(ax)
