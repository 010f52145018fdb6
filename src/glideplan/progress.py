"""The one progress bar: Rich on stderr, for the batch runner, the study runner, the mission
phases, the router's front and the glide-reach search alike.

`start_progress_bar` draws it; `DelayedBar` starts it only once the work has run `delay`
seconds (a short run prints nothing) and only when enabled, and stops it on `close()`.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

__all__ = ["DelayedBar", "start_progress_bar"]


def start_progress_bar(
    description: str, total: float, *, with_rate: bool = False, info: bool = False,
    count: bool = True, transient: bool = False, remaining: str = "",
) -> tuple[Any, Any]:
    """Start a Rich progress bar on stderr with one task; return (progress, task id).

    Columns: description, bar, done/total (unless `count` is false), elapsed time, remaining
    time. With `with_rate` the bar also shows the percentage and a `rate` text field (set it
    with `progress.update(task, rate=...)`), and labels the remaining time "ETA"; with `info`
    a free text field `info` follows the bar; `remaining` labels the remaining time (e.g.
    "left"); `transient` removes the bar when it stops.
    """
    from rich.console import Console
    from rich.progress import (
        BarColumn,
        MofNCompleteColumn,
        Progress,
        TaskProgressColumn,
        TextColumn,
        TimeElapsedColumn,
        TimeRemainingColumn,
    )

    columns: list[Any] = [TextColumn("{task.description}"), BarColumn()]
    fields: dict[str, Any] = {}
    if info:
        columns.append(TextColumn("{task.fields[info]}"))
        fields["info"] = ""
    if count:
        columns.append(MofNCompleteColumn())
    if with_rate:
        columns += [TaskProgressColumn(), TextColumn("{task.fields[rate]}")]
        fields["rate"] = ""
    columns.append(TimeElapsedColumn())
    label = "ETA" if with_rate and not remaining else remaining
    if label:
        columns.append(TextColumn(label))
    columns.append(TimeRemainingColumn())
    bar = Progress(*columns, console=Console(stderr=True), transient=transient)
    bar.start()
    return bar, bar.add_task(description, total=total, **fields)


class DelayedBar:
    """`start_progress_bar(description, total, **style)` once `enabled` work has run more
    than `delay` seconds and is not finished yet; `update` moves it (Rich's `update`
    keywords: completed, total, advance, fields), `close` stops it."""

    def __init__(self, description: str, total: float, *, enabled: bool = True,
                 delay: float = 0.0, clock: Callable[[], float] = time.perf_counter,
                 **style: Any) -> None:
        self.description, self.total = description, total
        self.enabled, self.delay, self.clock = enabled, delay, clock
        self.style = style
        self.started = clock()
        self.bar: Any = None
        self.task: Any = None

    def update(self, **kwargs: Any) -> None:
        """Rich's `progress.update(task, **kwargs)`, the bar started when it is due."""
        if not self.enabled:
            return
        if self.bar is None:
            done = kwargs.get("completed")
            if self.clock() - self.started <= self.delay or (
                    done is not None and done >= kwargs.get("total", self.total)):
                return
            self.bar, self.task = start_progress_bar(
                self.description, kwargs.get("total", self.total), **self.style)
        self.bar.update(self.task, **kwargs)

    def close(self, **final: Any) -> None:
        """Stop the bar (after a last `update(**final)` when given)."""
        if self.bar is not None:
            if final:
                self.bar.update(self.task, **final)
            self.bar.stop()
            self.bar = None
