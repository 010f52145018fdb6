"""The main job: plan the dissertation's example paths with every planner the package has.

One module per chapter in this package (`ch2.py`, `ch4.py`, ...) adds its examples with
`register_demo_case`; `load_all()` imports them; the CLI plans each, writes JSON and figures
and prints the summary table.
"""

from __future__ import annotations

import importlib
import pkgutil
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.vehicles.base import Vehicle

__all__ = [
    "DemoCase",
    "DemoResult",
    "demo_cases",
    "load_all",
    "register_demo_case",
    "run_demo_case",
]


@dataclass(frozen=True)
class DemoCase:
    """One example: where it comes from and the value the dissertation reports (if any)."""

    name: str
    source: str
    start: Pose
    goal: Pose
    vehicle: Vehicle
    objective: str | None = None
    method: str | None = None
    options: dict[str, Any] = field(default_factory=dict)
    reference_cost: float | None = None
    reference_word: str = ""
    postprocess: Callable[[Solution], dict[str, Any]] | None = None


@dataclass(frozen=True)
class DemoResult:
    case: DemoCase
    solution: Solution
    seconds: float
    extra: dict[str, Any]


_CASES: list[DemoCase] = []


def register_demo_case(case: DemoCase) -> DemoCase:
    """Add an example to the demo (replaces one of the same name)."""
    _CASES[:] = [c for c in _CASES if c.name != case.name]
    _CASES.append(case)
    return case


def load_all() -> None:
    """Import every chapter module of this package so that its examples are registered."""
    for mod in pkgutil.iter_modules(__path__):
        if not mod.name.startswith("_"):
            importlib.import_module(f"{__name__}.{mod.name}")


def demo_cases() -> list[DemoCase]:
    """All registered examples, after loading every chapter module."""
    load_all()
    return list(_CASES)


def run_demo_case(case: DemoCase) -> DemoResult:
    """Plan one example and time it."""
    from glideplan.planning import plan

    t0 = time.perf_counter()
    sol = plan(case.start, case.goal, case.vehicle, case.objective, case.method, **case.options)
    seconds = time.perf_counter() - t0
    extra = case.postprocess(sol) if case.postprocess and sol.ok else {}
    return DemoResult(case, sol, seconds, extra)
