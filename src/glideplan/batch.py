"""One small runner for every batch job: a local process pool, Dask distributed, or in-process.

`run_batch(fn, items)` maps a picklable function over items and returns the results in item
order. By default it uses a local `concurrent.futures.ProcessPoolExecutor` (one worker per
core; `processes=1` runs in this process without a pool); with `scheduler="tcp://host:8786"`
it submits to a Dask distributed cluster. A Rich progress bar appears on stderr once the job
has run for more than a second. An exception raised for an item propagates unchanged, with a
note and a `batch_index` attribute naming the item.

`chunk_slices` / `map_chunks` hand vectorised kernels arrays of items instead of single items.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Sequence
from typing import Any, TypeVar

import numpy as np

from glideplan.errors import InvalidParameterError
from glideplan.progress import DelayedBar

__all__ = ["chunk_slices", "default_processes", "map_chunks", "run_batch"]

T = TypeVar("T")
R = TypeVar("R")

_PROGRESS_DELAY_S = 1.0
_POLL_S = 0.2


def default_processes() -> int:
    """Cores available to this process (at least 1)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not on Linux
        return max(1, os.cpu_count() or 1)


class _Progress(DelayedBar):
    """The batch's bar (`glideplan.progress.DelayedBar`): it appears after a second."""

    def __init__(self, total: int, enabled: bool, description: str) -> None:
        super().__init__(description or "batch", total, enabled=enabled and total > 0,
                         delay=_PROGRESS_DELAY_S)
        self.done = 0

    def update(self, done: int) -> None:  # type: ignore[override]
        self.done = done
        super().update(completed=done)

    def close(self) -> None:  # type: ignore[override]
        super().close(completed=self.done)


def _tag(exc: BaseException, index: int) -> BaseException:
    """Name the failing item on the exception (a note, and `batch_index`)."""
    try:
        exc.batch_index = index  # type: ignore[attr-defined]
    except AttributeError:  # pragma: no cover - exceptions with __slots__
        pass
    exc.add_note(f"raised by batch item {index}")
    return exc


def _run_local(fn: Callable[[T], R], items: list[T], bar: _Progress) -> list[R]:
    out: list[R] = []
    for i, item in enumerate(items):
        try:
            out.append(fn(item))
        except Exception as exc:
            raise _tag(exc, i) from None
        bar.update(i + 1)
    return out


def _run_pool(fn: Callable[[T], R], items: list[T], processes: int, bar: _Progress) -> list[R]:
    import concurrent.futures as cf  # imported where used (start-up time)

    results: list[Any] = [None] * len(items)
    with cf.ProcessPoolExecutor(max_workers=processes) as pool:
        index = {pool.submit(fn, item): i for i, item in enumerate(items)}
        pending = set(index)
        try:
            while pending:
                done, pending = cf.wait(pending, timeout=_POLL_S, return_when=cf.FIRST_COMPLETED)
                for fut in done:
                    exc = fut.exception()
                    if exc is not None:
                        raise _tag(exc, index[fut]) from None
                    results[index[fut]] = fut.result()
                bar.update(len(items) - len(pending))
        except BaseException:
            pool.shutdown(wait=True, cancel_futures=True)
            raise
    return results


def _run_dask(fn: Callable[[T], R], items: list[T], scheduler: Any, bar: _Progress) -> list[R]:
    try:
        from distributed import Client, as_completed
    except ImportError:  # pragma: no cover - dask is an optional extra
        raise InvalidParameterError(
            "scheduler", scheduler, "needs dask[distributed] (pip install glideplan[dask])"
        ) from None
    own = not isinstance(scheduler, Client)
    try:
        client = Client(scheduler, timeout=10) if own else scheduler
    except (OSError, ValueError, TypeError) as exc:
        raise InvalidParameterError(
            "scheduler", scheduler, f"cannot connect to the Dask scheduler ({exc})"
        ) from None
    try:
        futures = client.map(fn, items, pure=False)
        index = {f.key: i for i, f in enumerate(futures)}
        results: list[Any] = [None] * len(items)
        done = 0
        for fut in as_completed(futures):
            i = index[fut.key]
            if fut.status == "error":
                err = fut.exception()
                client.cancel(futures)
                raise _tag(err, i) from None
            results[i] = fut.result()
            done += 1
            bar.update(done)
        return results
    finally:
        if own:
            client.close()


def run_batch(
    fn: Callable[[T], R],
    items: Iterable[T],
    *,
    scheduler: Any = None,
    processes: int | None = None,
    progress: bool = True,
    description: str = "",
) -> list[R]:
    """Apply `fn` to every item and return the results in item order.

    `fn` must be picklable (a module-level function) unless `processes=1`. `scheduler` is a
    Dask distributed scheduler address (or a `distributed.Client`); without it a local process
    pool of `processes` workers runs the items (default: one per available core; `1` runs them
    in this process). A progress bar labelled `description` appears on stderr when `progress`
    is true and the job takes over a second. The first exception raised by an item propagates
    with `batch_index` set to that item's position.
    """
    items = list(items)
    if processes is not None:
        if isinstance(processes, bool) or not isinstance(processes, (int, np.integer)):
            raise InvalidParameterError("processes", processes, "must be a positive integer")
        if processes < 1:
            raise InvalidParameterError("processes", processes, "must be >= 1")
    bar = _Progress(len(items), progress, description)
    try:
        if scheduler is not None:
            if isinstance(scheduler, str) and not scheduler.strip():
                raise InvalidParameterError("scheduler", scheduler, "must be a scheduler address")
            return _run_dask(fn, items, scheduler, bar)
        workers = min(int(processes or default_processes()), len(items))
        if workers <= 1:
            return _run_local(fn, items, bar)
        return _run_pool(fn, items, workers, bar)
    finally:
        bar.close()


def chunk_slices(n: int, chunk_size: int) -> list[slice]:
    """Slices that cover range(n) in consecutive chunks of at most `chunk_size` items."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 0:
        raise InvalidParameterError("n", n, "must be an integer >= 0")
    if isinstance(chunk_size, bool) or not isinstance(chunk_size, (int, np.integer)):
        raise InvalidParameterError("chunk_size", chunk_size, "must be a positive integer")
    if chunk_size < 1:
        raise InvalidParameterError("chunk_size", chunk_size, "must be >= 1")
    return [slice(i, min(n, i + chunk_size)) for i in range(0, n, chunk_size)]


class _ChunkCall:
    """Picklable adapter: call a kernel on one tuple of array chunks."""

    def __init__(self, kernel: Callable[..., Any]) -> None:
        self.kernel = kernel

    def __call__(self, arrays: Sequence[np.ndarray]) -> Any:
        return self.kernel(*arrays)


def map_chunks(
    kernel: Callable[..., Any],
    arrays: Sequence[np.ndarray],
    *,
    chunk_size: int = 65536,
    **batch_options: Any,
) -> Any:
    """Run a vectorised `kernel(*arrays)` over chunks of the leading axis with `run_batch`.

    All `arrays` must share the length of their leading axis. The kernel returns an array (or a
    tuple of arrays) whose leading axis matches its input chunk; the chunk results are
    concatenated back in order. `batch_options` go to `run_batch` (scheduler, processes, ...).
    """
    arrays = [np.asarray(a) for a in arrays]
    if not arrays:
        raise InvalidParameterError("arrays", arrays, "needs at least one array")
    n = arrays[0].shape[0] if arrays[0].ndim else 0
    if any(a.ndim == 0 or a.shape[0] != n for a in arrays):
        raise InvalidParameterError(
            "arrays", [a.shape for a in arrays], "must share the length of their leading axis"
        )
    slices = chunk_slices(n, chunk_size)
    if not slices:
        return kernel(*arrays)
    parts = run_batch(
        _ChunkCall(kernel), [tuple(a[s] for a in arrays) for s in slices], **batch_options
    )
    if isinstance(parts[0], tuple):
        return tuple(np.concatenate(p, axis=0) for p in zip(*parts, strict=True))
    return np.concatenate(parts, axis=0)
