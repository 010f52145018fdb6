"""Dissertation figures and tables that `glideplan reproduce` regenerates.

One module per chapter (`ch2.py`, `ch3.py`, ...) registers its figures with `reproducible`;
`load_all()` imports every `ch*` module of this package. A figure computes with library code,
keeps the dissertation's printed values as `Printed` data and compares with `compare()`:
one `Comparison` row type whose verdict `verdict()` computes. Output files are named
`<id with _ for .>[_what].<ext>` (fig7_17.png, fig4_7_candidates.png).
"""

import importlib
import pkgutil

from glideplan.figures.registry import (
    Comparison,
    FigureReport,
    FigureSpec,
    Printed,
    compare,
    figure_specs,
    get_figure,
    reproducible,
    run_figure,
    verdict,
)

__all__ = [
    "Comparison",
    "FigureReport",
    "FigureSpec",
    "Printed",
    "compare",
    "figure_specs",
    "get_figure",
    "load_all",
    "reproducible",
    "run_figure",
    "verdict",
]


def load_all() -> None:
    """Import every chapter module (ch*.py) so that its figures are registered."""
    for mod in pkgutil.iter_modules(__path__):
        if mod.name.startswith("ch"):
            importlib.import_module(f"{__name__}.{mod.name}")
