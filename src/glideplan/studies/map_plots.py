"""Drawing of the partition and tradespace maps (Figs 3.1, 3.2); Matplotlib imported inside."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from glideplan.studies.maps import PartitionMap, TradespaceMap, partition_regions

__all__ = ["plot_partition", "plot_tradespace"]


_COLOURS = {
    "LSL": "#a6cee3",
    "RSR": "#fdbf6f",
    "LSR": "#b2df8a",
    "RSL": "#fb9a99",
    "RLR": "#cab2d6",
    "LRL": "#ffff99",
    "LSL/RSR": "#8dd3c7",
    "RLR/LRL": "#bebada",
}


def _axes(ax: Any) -> Any:
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    _, ax = plt.subplots(figsize=(6, 5.6))
    return ax


def _heading_text(psi1: float) -> str:
    for num, den in ((0, 1), (1, 3), (1, 2), (2, 3), (3, 4), (1, 1), (4, 3), (3, 2), (7, 4)):
        for sign in (1, -1):
            if math.isclose(psi1, sign * num * math.pi / den, abs_tol=1e-12):
                if num == 0:
                    return "0"
                s = "-" if sign < 0 else ""
                top = "π" if num == 1 else f"{num}π"
                return s + (top if den == 1 else f"{top}/{den}")
    return f"{math.degrees(psi1):.1f}°"


def plot_partition(pmap: PartitionMap, ax: Any = None, *, min_region: int = 12) -> Any:
    """Draw the partition by optimal word, each connected region labelled at its centre."""
    from matplotlib.colors import ListedColormap

    ax = _axes(ax)
    n_labels = len(pmap.labels)
    colours = [_COLOURS.get(label, "#d9d9d9") for label in pmap.labels]
    ax.pcolormesh(
        pmap.x,
        pmap.y,
        pmap.label_index,
        cmap=ListedColormap(colours),
        vmin=-0.5,
        vmax=n_labels - 0.5,
        shading="nearest",
    )
    # Region boundaries: where the label changes.
    ax.contour(
        pmap.x,
        pmap.y,
        pmap.label_index,
        levels=np.arange(n_labels) + 0.5,
        colors="k",
        linewidths=0.4,
    )
    for region in partition_regions(pmap, min_region):
        ax.text(
            region.x, region.y, region.label, ha="center", va="center", fontsize=8, weight="bold"
        )
    ax.plot(0, 0, "ko", ms=3)
    ax.set_aspect("equal")
    ax.set_xlabel("x / R0")
    ax.set_ylabel("y / R0")
    eps = f", ε = {pmap.eps:g}" if pmap.eps else ""
    ax.set_title(f"Dubins partition, ψ1 = {_heading_text(pmap.heading)}{eps}")
    return ax


def plot_tradespace(
    tmap: TradespaceMap, ax: Any = None, *, vmax: float = 5.0, step: float = 0.2
) -> Any:
    """Colour map of T truncated at `vmax` with contour lines every `step` (Fig 3.2)."""
    ax = _axes(ax)
    ratio = np.where(np.isnan(tmap.ratio), 1.0, np.minimum(tmap.ratio, vmax))
    mesh = ax.pcolormesh(
        tmap.x, tmap.y, ratio, cmap="hot_r", vmin=1.0, vmax=vmax, shading="nearest"
    )
    ax.contour(
        tmap.x,
        tmap.y,
        ratio,
        levels=np.arange(1.0 + step, vmax, step),
        colors="k",
        linewidths=0.3,
    )
    ax.figure.colorbar(mesh, ax=ax, label="T = d_feasible / d_optimal")
    ax.set_aspect("equal")
    ax.set_xlabel("x / R0")
    ax.set_ylabel("y / R0")
    ax.set_title(f"T(x1, y1, {_heading_text(tmap.heading)}, {tmap.eps:g})")
    return ax
