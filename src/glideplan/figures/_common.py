"""What the chapter figure modules share: pyplot on the Agg backend and saving a PNG."""

from __future__ import annotations

import pathlib
from typing import Any


def pyplot() -> Any:
    """`matplotlib.pyplot` on the non-interactive Agg backend (Matplotlib imported on use)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def save_png(
    fig: Any, path: pathlib.Path | str, *, dpi: int = 120, crop: bool = False
) -> pathlib.Path:
    """Write `fig` to `path`, close it and return `path`.

    The subplots are first spaced with `fig.tight_layout()`; with `crop` the saved image is
    instead cropped to what is drawn (`bbox_inches="tight"`).
    """
    if crop:
        fig.savefig(path, dpi=dpi, bbox_inches="tight")
    else:
        fig.tight_layout()
        fig.savefig(path, dpi=dpi)
    pyplot().close(fig)
    return pathlib.Path(path)
