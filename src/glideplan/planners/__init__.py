"""Planner modules; each registers itself with `glideplan.planning.register_planner`.

`load_all()` imports every module or subpackage here (importing `glideplan` calls it).
"""

import importlib
import pkgutil

__all__ = ["load_all"]


def load_all() -> None:
    """Import every planner module so that it registers its planners."""
    for mod in pkgutil.iter_modules(__path__):
        if not mod.name.startswith("_"):
            importlib.import_module(f"{__name__}.{mod.name}")
