"""Registry of reproducible dissertation figures and tables for `glideplan reproduce`.

A figure function computes (library code), takes the dissertation's printed values from data
(`Printed`, with their source) and compares: each comparison is a `Comparison` row whose
verdict is computed by `verdict()` from the numbers and the tolerance, never written.
"""

from __future__ import annotations

import functools
import math
import pathlib
import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from decimal import Decimal, InvalidOperation
from typing import Any

from glideplan.errors import InvalidParameterError

__all__ = [
    "AGREES",
    "DIFFERS",
    "NOT_PRINTED",
    "Comparison",
    "FigureReport",
    "FigureSpec",
    "Printed",
    "Value",
    "compare",
    "figure_specs",
    "get_figure",
    "half_unit",
    "reproducible",
    "reproducible_each",
    "run_figure",
    "verdict",
    "yes_no",
]

AGREES = "agrees"
DIFFERS = "differs"
NOT_PRINTED = "not printed"

Value = float | str | None


def half_unit(text: str) -> float:
    """Half a unit of the last printed digit of a number as printed: "31.1" -> 0.05,
    "13" -> 0.5, "2.875" -> 0.0005, "8,000" -> 0.5."""
    try:
        exponent = Decimal(text.replace(",", "").strip()).as_tuple().exponent
    except InvalidOperation:
        raise InvalidParameterError("text", text, "must be a printed number") from None
    assert isinstance(exponent, int)
    return 0.5 * 10.0**exponent


@dataclass(frozen=True)
class Printed:
    """A value printed in the dissertation, where it is printed, and the tolerance it allows.

    value: a number (as printed, e.g. "31.1") or a word/list; source: section, table or
    figure; tolerance: absolute, by default half a unit of the last printed digit (None for
    words); unit: the unit the value is printed in.
    """

    text: str
    source: str
    unit: str = ""
    tolerance: float | None = None
    word: bool = False

    def __post_init__(self) -> None:
        if not self.source:
            raise InvalidParameterError("source", self.source, "a printed value needs a source")
        if not self.word and self.tolerance is None:
            object.__setattr__(self, "tolerance", half_unit(self.text))

    @property
    def value(self) -> float | str:
        """The number (float) or, for a word, the text."""
        return self.text if self.word else float(self.text.replace(",", ""))


def verdict(ours: Value, dissertation: Value, tolerance: float | None) -> str:
    """The one rule for every row.

    "not printed" when the dissertation gives no value; with strings "agrees" iff equal;
    with numbers "agrees" iff |ours - dissertation| <= tolerance (absolute); otherwise (or
    when ours could not be computed) "differs".
    """
    if dissertation is None:
        return NOT_PRINTED
    if isinstance(dissertation, str) or isinstance(ours, str):
        return AGREES if ours == dissertation else DIFFERS
    if ours is None or not math.isfinite(ours):
        return DIFFERS
    if tolerance is None:
        raise InvalidParameterError("tolerance", tolerance, "a numeric comparison needs one")
    return AGREES if abs(ours - dissertation) <= tolerance else DIFFERS


def _value(name: str, value: Any) -> Value:
    """A row cell: float for numbers (NumPy scalars and ints included), str, or None."""
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, bool):
        raise InvalidParameterError(name, value, "booleans are written as words (yes/no)")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InvalidParameterError(name, value, "must be a number, a string or None") from None


@dataclass(frozen=True)
class Comparison:
    """One row of a reproduction report: a quantity we computed beside the dissertation's
    printed value (if any) and an independent reference (if any).

    `verdict` is a property computed by `verdict()`; a row that differs must say why.
    """

    quantity: str
    ours: Value
    unit: str = ""
    dissertation: Value = None
    dissertation_source: str | None = None
    reference: Value = None
    reference_source: str | None = None
    tolerance: float | None = None
    note: str = ""

    def __post_init__(self) -> None:
        for name in ("ours", "dissertation", "reference"):
            object.__setattr__(self, name, _value(name, getattr(self, name)))
        if self.tolerance is not None:
            object.__setattr__(self, "tolerance", float(self.tolerance))
        if self.dissertation is not None and not self.dissertation_source:
            raise InvalidParameterError(
                "dissertation_source", self.dissertation_source, "a printed value needs a source"
            )
        if self.reference is not None and not self.reference_source:
            raise InvalidParameterError(
                "reference_source", self.reference_source, "a reference needs a source"
            )
        if self.verdict == DIFFERS and not self.note.strip():
            raise InvalidParameterError("note", self.quantity, "a row that differs must say why")

    @property
    def verdict(self) -> str:
        """Computed from ours, dissertation and tolerance (see `verdict()`)."""
        return verdict(self.ours, self.dissertation, self.tolerance)

    def to_dict(self) -> dict[str, Any]:
        """The row of `index.json`."""
        return {
            "quantity": self.quantity,
            "unit": self.unit,
            "ours": self.ours,
            "dissertation": self.dissertation,
            "dissertation_source": self.dissertation_source,
            "reference": self.reference,
            "reference_source": self.reference_source,
            "tolerance": self.tolerance,
            "verdict": self.verdict,
            "note": self.note,
        }


def compare(
    quantity: str,
    ours: Any,
    printed: Printed | None = None,
    *,
    unit: str | None = None,
    reference: Any = None,
    reference_source: str | None = None,
    note: str = "",
) -> Comparison:
    """A row comparing `ours` with a printed value (its unit, source and tolerance)."""
    return Comparison(
        quantity=quantity,
        ours=ours,
        unit=(printed.unit if printed is not None else "") if unit is None else unit,
        dissertation=None if printed is None else printed.value,
        dissertation_source=None if printed is None else printed.source,
        reference=reference,
        reference_source=reference_source,
        tolerance=None if printed is None else printed.tolerance,
        note=note,
    )


def yes_no(flag: bool, yes: str = "yes", no: str = "no") -> str:
    """A computed truth value as the word a row compares."""
    return yes if flag else no


@dataclass(frozen=True)
class FigureReport:
    """Files written for one figure/table, the comparison rows, notes, and data for tests."""

    files: tuple[str, ...] = ()
    rows: tuple[Comparison, ...] = ()
    notes: str = ""
    data: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for row in self.rows:
            if not isinstance(row, Comparison):
                raise InvalidParameterError("rows", row, "must be Comparison rows")


FigureFunction = Callable[..., FigureReport]


@dataclass(frozen=True)
class FigureSpec:
    """A registered figure: id (e.g. 'fig3.1'), title, what the dissertation shows, function."""

    id: str
    title: str
    dissertation: str
    function: FigureFunction

    @property
    def stem(self) -> str:
        """The file-name stem of this figure's outputs: 'fig7.17' -> 'fig7_17'."""
        return self.id.replace(".", "_")


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


def reproducible_each(
    figures: Mapping[str, tuple[str, str]],
    draw: Callable[[str, pathlib.Path, bool], FigureReport],
) -> None:
    """Register one figure per id (title, dissertation text), drawn by `draw(id, out, full)`."""
    for figure_id, (title, dissertation) in figures.items():
        reproducible(figure_id, title=title, dissertation=dissertation)(
            functools.partial(_draw_one, draw, figure_id)
        )


def _draw_one(
    draw: Callable[[str, pathlib.Path, bool], FigureReport],
    figure_id: str,
    out_dir: pathlib.Path,
    *,
    full: bool = False,
) -> FigureReport:
    return draw(figure_id, out_dir, full)


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
    """Run one figure function into `out_dir` (on Matplotlib's file backend, Agg: the one
    place the library chooses a backend, since `reproduce` only makes files)."""
    import matplotlib

    matplotlib.use("Agg")
    out_dir.mkdir(parents=True, exist_ok=True)
    report = spec.function(out_dir, full=full)
    if not isinstance(report, FigureReport):
        raise TypeError(f"{spec.id} returned {type(report).__name__}, not a FigureReport")
    return report
