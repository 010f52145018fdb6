"""Concurrency of the compiled kernels: the threading layer, a lock where it is needed, cancelling.

The front's kernels (`glideplan.fronts.kernel`) run in parallel over the band's nodes (numba
`prange`). Which library runs those threads -- numba's "threading layer" -- decides whether two
Python threads may launch parallel kernels at once (two browser tabs of `glideplan explore`, a
Dask worker with several threads, a user calling `route()` from a thread pool):

- `tbb` (Intel oneTBB, the `tbb` wheel on PyPI) is both thread-safe and fork-safe: chosen
  whenever its library can be loaded. The wheel puts `libtbb.so.12` in `<prefix>/lib`, where
  numba's `tbbpool` extension does not look (no rpath), so it is loaded here first by its path.
- `workqueue` (numba's own, always present) is fork-safe but aborts the whole process
  (SIGABRT, "Concurrent access has been detected") when two threads launch kernels at once.
  Without TBB every parallel launch is therefore serialised by one process-wide lock
  (`kernel_section`): the answers are the same, the threads take turns step by step.
- GNU OpenMP (`omp`) is thread-safe but aborts a process that forks after using it (`run_batch`
  forks workers), so it is never chosen here; a user's `NUMBA_THREADING_LAYER` still wins, and
  any layer but `tbb`/`omp` gets the lock.

Cancelling: a computation started inside `cancel_scope(is_cancelled)` stops at the next
`checkpoint()` (the front calls it once per time step) by raising `ComputationCancelled` -- a
`BaseException`, like `KeyboardInterrupt`, so no `except Exception` on the way turns it into an
answer. The scope is per thread (a context variable), so other threads are untouched.
"""

from __future__ import annotations

import contextlib
import contextvars
import ctypes
import os
import sys
import threading
from collections.abc import Callable, Iterator
from pathlib import Path

__all__ = [
    "ComputationCancelled",
    "cancel_scope",
    "checkpoint",
    "configure_threading",
    "kernel_section",
    "threading_layer",
]

_THREAD_SAFE = ("tbb", "omp", "threadsafe", "safe")
_KERNEL_LOCK = threading.Lock()
_configured: str | None = None
_CANCEL: contextvars.ContextVar[Callable[[], bool] | None] = contextvars.ContextVar(
    "glideplan_cancel", default=None)


class ComputationCancelled(BaseException):  # a signal, like KeyboardInterrupt
    """Raised by `checkpoint()` when the current thread's `cancel_scope` says so."""


def _load_tbb() -> bool:
    """Load `libtbb.so.12` from the interpreter's prefix (pip's `tbb` wheel) so numba finds it."""
    if not sys.platform.startswith("linux"):
        return False
    names = ("libtbb.so.12",)
    for base in {sys.prefix, sys.base_prefix, os.environ.get("CONDA_PREFIX", "")}:
        for name in names:
            p = Path(base) / "lib" / name
            if base and p.is_file():
                try:
                    ctypes.CDLL(str(p), mode=ctypes.RTLD_GLOBAL)
                except OSError:
                    continue
                return True
    try:  # on the loader's own path already (system TBB, conda, LD_LIBRARY_PATH)
        ctypes.CDLL("libtbb.so.12", mode=ctypes.RTLD_GLOBAL)
    except OSError:
        return False
    return True


def configure_threading() -> str:
    """Choose numba's threading layer once per process (before any parallel kernel runs):
    the user's NUMBA_THREADING_LAYER, else `tbb` if it loads, else `workqueue` (+ the lock)."""
    global _configured
    if _configured is not None:
        return _configured
    import numba

    user = os.environ.get("NUMBA_THREADING_LAYER")
    if user:
        _configured = user.lower()
    else:
        _configured = "tbb" if _load_tbb() else "workqueue"
        numba.config.THREADING_LAYER = _configured  # type: ignore[attr-defined]
    return _configured


def threading_layer() -> str:
    """The layer chosen by `configure_threading` (configuring it if not done yet)."""
    return configure_threading()


def kernel_section() -> contextlib.AbstractContextManager[object]:
    """Context for one launch of parallel compiled kernels: nothing where the threading layer
    is thread-safe, else the process-wide lock (numba's workqueue aborts on concurrent use)."""
    if configure_threading() in _THREAD_SAFE:
        return contextlib.nullcontext()
    return _KERNEL_LOCK


@contextlib.contextmanager
def cancel_scope(is_cancelled: Callable[[], bool]) -> Iterator[None]:
    """Run the body so that `checkpoint()` in this thread raises once `is_cancelled()` is true."""
    token = _CANCEL.set(is_cancelled)
    try:
        yield
    finally:
        _CANCEL.reset(token)


def checkpoint() -> None:
    """Raise `ComputationCancelled` if this thread's computation was cancelled (cheap: one
    context-variable read when no scope is set)."""
    check = _CANCEL.get()
    if check is not None and check():
        raise ComputationCancelled("computation cancelled")
