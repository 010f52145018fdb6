"""Run a study's work units through `glideplan.batch.run_batch`, storing each as it finishes.

Units go to the batch runner in waves of a few per worker (local processes by default, a Dask
cluster with a scheduler address); each wave's results are committed to the `ResultsStore`
before the next wave starts, so an interruption loses at most the wave in flight and a
restart runs only the units the store does not hold. A unit's outcome must depend only on
its own description (derive its random numbers from the study seed and the unit index), so
the order and grouping of execution never change the results.
"""

from __future__ import annotations

import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from typing import Any

from glideplan.batch import default_processes, run_batch
from glideplan.progress import DelayedBar
from glideplan.studies.store import ResultsStore

__all__ = ["RunReport", "run_units"]


@dataclass(frozen=True)
class RunReport:
    """What one call ran: units run now, units found done, wall time (s)."""

    ran: int
    skipped: int
    seconds: float


class _Bar(DelayedBar):
    """The study's bar (`glideplan.progress.DelayedBar`, rate and ETA) over the work the study
    still has to do."""

    def __init__(self, enabled: bool, total: float, label: str, unit: str) -> None:
        super().__init__(label, total, enabled=enabled and total > 0, delay=-1.0,
                         with_rate=True)
        self.unit = unit

    def advance(self, amount: float, done: float) -> None:
        rate = done / max(1e-9, time.perf_counter() - self.started)
        self.update(advance=amount, rate=f"{rate:,.0f} {self.unit}/s")


def run_units(
    fn: Callable[[Any], Any],
    units: Sequence[Any],
    store: ResultsStore,
    rows_of: Callable[[int, Any], Iterable[Sequence[Any]]],
    *,
    weight: Callable[[Any], float] = lambda unit: 1.0,
    scheduler: str | None = None,
    processes: int | None = None,
    wave: int | None = None,
    progress: bool = True,
    label: str = "study",
    unit_name: str = "runs",
) -> RunReport:
    """Run every unit the store lacks: `fn(units[i])` in a worker, then
    `store.add_unit(i, rows_of(i, result), seconds)` in this process.

    `weight(unit)` is the unit's share of the progress bar (e.g. its number of runs); `wave`
    the units per call of `run_batch` (default: twice the local workers, 16 on Dask).
    """
    t0 = time.perf_counter()
    done = store.done_units()
    todo = [i for i in range(len(units)) if i not in done]
    if wave is None:
        wave = 16 if scheduler else 2 * int(processes or default_processes())
    wave = max(1, int(wave))
    total = sum(weight(units[i]) for i in todo)
    bar = _Bar(progress, total, label, unit_name)
    finished = 0.0
    try:
        for start in range(0, len(todo), wave):
            batch = todo[start : start + wave]
            results = run_batch(
                _Timed(fn),
                [units[i] for i in batch],
                scheduler=scheduler,
                processes=processes,
                progress=False,
            )
            for i, (seconds, result) in zip(batch, results, strict=True):
                store.add_unit(i, rows_of(i, result), seconds)
                finished += weight(units[i])
                bar.advance(weight(units[i]), finished)
    finally:
        bar.close()
    return RunReport(ran=len(todo), skipped=len(done), seconds=time.perf_counter() - t0)


class _Timed:
    """Picklable wrapper returning (seconds, fn(unit))."""

    def __init__(self, fn: Callable[[Any], Any]) -> None:
        self.fn = fn

    def __call__(self, unit: Any) -> tuple[float, Any]:
        t = time.perf_counter()
        out = self.fn(unit)
        return time.perf_counter() - t, out
