"""Registry of reproducible dissertation figures and tables for `glideplan reproduce`."""

from __future__ import annotations

import pathlib
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

from glideplan.errors import InvalidParameterError

__all__ = [
    "Comparison",
    "FigureReport",
    "FigureSpec",
    "figure_specs",
    "get_figure",
    "reproducible",
]


@dataclass(frozen=True)
class Comparison:
    """One number we computed next to the dissertation's (as text: values, units, notes)."""

    quantity: str
    ours: str
    dissertation: str
    note: str = ""


@dataclass(frozen=True)
class FigureReport:
    """Files written for one figure/table, the comparisons and free-text notes."""

    files: tuple[str, ...] = ()
    rows: tuple[Comparison, ...] = ()
    notes: str = ""
    data: dict[str, Any] = field(default_factory=dict)


FigureFunction = Callable[..., FigureReport]


@dataclass(frozen=True)
class FigureSpec:
    """A registered figure: id (e.g. 'fig3.1'), title, what the dissertation shows, function."""

    id: str
    title: str
    dissertation: str
    function: FigureFunction


_FIGURES: dict[str, FigureSpec] = {}
_ID = re.compile(r"^(fig|table)\d+\.\d+[a-z]?$")


def reproducible(
    figure_id: str, *, title: str, dissertation: str
) -> Callable[[FigureFunction], FigureFunction]:
    """Decorator: register `function(out_dir: pathlib.Path, *, full: bool) -> FigureReport`."""
    if not _ID.match(figure_id):
        raise InvalidParameterError("figure_id", figure_id, "must look like fig3.1 or table4.3")

    def deco(function: FigureFunction) -> FigureFunction:
        _FIGURES[figure_id] = FigureSpec(figure_id, title, dissertation, function)
        return function

    return deco


def _sort_key(fid: str) -> tuple[int, int, str]:
    m = re.match(r"^(fig|table)(\d+)\.(\d+)([a-z]?)$", fid)
    assert m
    return int(m.group(2)), int(m.group(3)), m.group(1) + m.group(4)


def figure_specs() -> list[FigureSpec]:
    """All registered figures, ordered by chapter and number."""
    return [_FIGURES[k] for k in sorted(_FIGURES, key=_sort_key)]


def get_figure(figure_id: str) -> FigureSpec:
    """The figure registered as `figure_id`."""
    try:
        return _FIGURES[figure_id.strip().lower()]
    except KeyError:
        known = ", ".join(s.id for s in figure_specs())
        raise InvalidParameterError(
            "only", figure_id, f"unknown figure id (known: {known})"
        ) from None


def run_figure(spec: FigureSpec, out_dir: pathlib.Path, *, full: bool = False) -> FigureReport:
    """Run one figure function into `out_dir`."""
    out_dir.mkdir(parents=True, exist_ok=True)
    return spec.function(out_dir, full=full)
