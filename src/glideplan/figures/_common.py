"""What the chapter figure modules share: pyplot and saving a PNG (`plotting.save_figure`).

The backend is not chosen here: `glideplan reproduce` (`figures.registry.run_figure`) selects
Agg where it makes files; a notebook keeps its own backend.
"""

from __future__ import annotations

import pathlib
from typing import Any


def pyplot() -> Any:
    """`matplotlib.pyplot` (Matplotlib imported on use)."""
    import matplotlib.pyplot as plt

    return plt


def save_png(fig: Any, path: pathlib.Path | str, *, crop: bool = False) -> pathlib.Path:
    """Write `fig` to `path` with the one saver (`plotting.save_figure`), close it, return
    `path`; the subplots are spaced by `tight_layout`, or with `crop` the image is instead
    cropped to what is drawn (`bbox_inches="tight"`)."""
    from glideplan.plotting import save_figure

    save_figure(fig, path, crop=crop, tight=not crop)
    return pathlib.Path(path)
