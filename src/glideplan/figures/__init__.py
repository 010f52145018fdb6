"""Dissertation figures and tables that `glideplan reproduce` regenerates.

One module per chapter (`ch2.py`, `ch3.py`, ...) registers its figures with `reproducible`;
`load_all()` imports every `ch*` module of this package.
"""

import importlib
import pkgutil

from glideplan.figures.registry import (
    Comparison,
    FigureReport,
    FigureSpec,
    figure_specs,
    get_figure,
    reproducible,
    run_figure,
)

__all__ = [
    "Comparison",
    "FigureReport",
    "FigureSpec",
    "figure_specs",
    "get_figure",
    "load_all",
    "reproducible",
    "run_figure",
]


def load_all() -> None:
    """Import every chapter module (ch*.py) so that its figures are registered."""
    for mod in pkgutil.iter_modules(__path__):
        if mod.name.startswith("ch"):
            importlib.import_module(f"{__name__}.{mod.name}")
