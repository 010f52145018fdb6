"""The curated public namespace: what `import glideplan` offers, and what it does not import.

The products above `plan()` are importable from `glideplan` but loaded on first use, so the
CLI starts fast: a fresh interpreter that imports `glideplan` must not have loaded any of the
heavy libraries (checked in a subprocess, where nothing else has imported them yet).
"""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import glideplan
from glideplan.results import Outcome
from glideplan.solution import Status

HEAVY = ("scipy.integrate", "matplotlib", "xarray", "pyproj", "casadi", "numba", "dask")

PUBLIC = ("plan", "route", "plan_mission", "final_glide", "glide_reach", "turnback",
          "Sailplane", "SailplanePolar", "FlowField", "open_field", "Status", "Track", "Outcome",
          "DubinsCar", "DubinsCarInWind", "VariableSpeedCar", "QuadraticPolarGlider",
          "LoadFactorGlider")


def test_import_glideplan_loads_no_heavy_library():
    code = (
        "import json, sys, glideplan\n"
        f"print(json.dumps([m for m in {HEAVY!r} if m in sys.modules]))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert json.loads(out.stdout) == []


def test_public_names_are_listed():
    assert set(PUBLIC) <= set(glideplan.__all__)
    assert set(PUBLIC) <= set(dir(glideplan))


LAZY = {"route": "glideplan.routing", "plan_mission": "glideplan.missions",
        "final_glide": "glideplan.sailplane.request", "glide_reach": "glideplan.reach",
        "turnback": "glideplan.reach", "FlowField": "glideplan.fields",
        "open_field": "glideplan.fields", "Sailplane": "glideplan.vehicles.sailplane",
        "SailplanePolar": "glideplan.vehicles.sailplane_polar", "Track": "glideplan.track",
        "Outcome": "glideplan.results"}


@pytest.mark.parametrize("name", sorted(LAZY))
def test_lazy_products_resolve_to_their_modules(name):
    import importlib

    module = LAZY[name]
    assert getattr(glideplan, name) is getattr(importlib.import_module(module), name)


def test_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        _ = glideplan.nonsense  # type: ignore[attr-defined]


def test_status_carries_every_product_word():
    """One vocabulary: the words routes, following, missions and glides answer with."""
    for word in ("solved", "unreachable", "not_verified", "lost", "infeasible", "failed",
                 "below_glide", "no_path"):
        assert Status(word).value == word


def test_solution_is_an_outcome():
    sol = glideplan.plan(glideplan.Pose(0.0, 0.0, 0.0), glideplan.Pose(4.0, 3.0, 1.0),
                         glideplan.DubinsCar(speed=1.0, turn_radius=1.0), "length")
    assert isinstance(sol, Outcome)
    d = sol.to_dict()
    assert d["status"] == sol.status.value == "solved" and "message" in d
