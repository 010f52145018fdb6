"""Rich progress bars on stderr, shared by the batch runner and the study runner."""

from __future__ import annotations

from typing import Any

__all__ = ["start_progress_bar"]


def start_progress_bar(
    description: str, total: float, *, with_rate: bool = False
) -> tuple[Any, Any]:
    """Start a Rich progress bar on stderr with one task; return (progress, task id).

    Columns: description, bar, done/total, elapsed time, remaining time. With `with_rate` the bar
    also shows the percentage and a `rate` text field (set it with
    `progress.update(task, rate=...)`), and labels the remaining time "ETA".
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

    columns: list[Any] = [
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        TimeRemainingColumn(),
    ]
    fields: dict[str, Any] = {}
    if with_rate:
        columns[3:3] = [TaskProgressColumn(), TextColumn("{task.fields[rate]}")]
        columns.insert(-1, TextColumn("ETA"))
        fields["rate"] = ""
    bar = Progress(*columns, console=Console(stderr=True))
    bar.start()
    return bar, bar.add_task(description, total=total, **fields)
