"""Planner modules; each registers itself with `glideplan.planning.register_planner`.

Planners are imported when first needed, not by `import glideplan`: `plan()` imports the
modules listed for the request's vehicle model in `PLANNER_MODULES` (so that a Dubins plan
does not import the direct methods and CasADi), and falls back to `load_all()` — every
module or subpackage here — when those register no planner for the request, or when the
vehicle model is not listed. `registered_planners()` always loads them all. A new planner
for a listed vehicle model adds its module to that model's entry.
"""

import importlib
import pkgutil

__all__ = ["PLANNER_MODULES", "load_all", "load_for"]

# vehicle model class name -> planner modules (relative to this package) serving it
PLANNER_MODULES: dict[str, tuple[str, ...]] = {
    "DubinsCar": ("dubins",),
    "DubinsCarInWind": ("wind",),
    "VariableSpeedCar": ("min_time",),
    "QuadraticPolarGlider": ("min_altitude",),
    "LoadFactorGlider": ("load_factor", "load_factor_synthesis"),
    "Sailplane": ("final_glide",),
}

_loaded_all = False


def load_all() -> None:
    """Import every planner module so that it registers its planners."""
    global _loaded_all
    if _loaded_all:
        return
    for mod in pkgutil.iter_modules(__path__):
        if not mod.name.startswith("_"):
            importlib.import_module(f"{__name__}.{mod.name}")
    _loaded_all = True


def load_for(vehicle_type: type) -> bool:
    """Import the planner modules listed for exactly `vehicle_type`; False if it is not listed.

    A subclass of a listed model is not listed (its own planners may live elsewhere): the
    caller then loads every module.
    """
    names = PLANNER_MODULES.get(vehicle_type.__name__, ())
    for name in names:
        importlib.import_module(f"{__name__}.{name}")
    return bool(names)
