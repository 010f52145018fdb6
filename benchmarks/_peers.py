"""What each benchmark says about its peer figures: measured in this run, or quoted.

A peer figure (another library's speed, a published timing) is either measured in the same
process and run as glideplan's (`measured`), or quoted from a source we did not run here
(`Quoted`: the figure, its source and the date of the quote). Every benchmark ends with
`report_peers(...)`, so a reader never mistakes a quoted number for a measurement.
Also `count(minimum)`, an argparse type for integer options with a lower bound.
"""

from __future__ import annotations

import argparse
from collections.abc import Callable, Sequence
from dataclasses import dataclass


@dataclass(frozen=True)
class Quoted:
    """A peer figure quoted, not measured here: what, the value, where from, and when."""

    what: str
    value: str
    source: str
    date: str


def report_peers(measured: Sequence[str], quoted: Sequence[Quoted]) -> None:
    """Print the benchmark's peer figures, each labelled measured (this run) or quoted."""
    print("\npeer figures:")
    if not measured:
        print("  measured in this run: none (no peer code runs in this benchmark)")
    for line in measured:
        print(f"  measured in this run: {line}")
    if not quoted:
        print("  quoted: none")
    for q in quoted:
        print(f"  quoted, NOT run here: {q.what}: {q.value} (source: {q.source}; {q.date})")


def count(minimum: int) -> Callable[[str], int]:
    """argparse type: an integer >= minimum (a clear usage error otherwise)."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if value < minimum:
            raise argparse.ArgumentTypeError(f"{value} must be >= {minimum}")
        return value

    return parse
