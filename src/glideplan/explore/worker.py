"""A browser session's document lock and worker thread, shared by the explorer's pages.

Bokeh models may change only under their document's lock; slow answers are computed on one
worker thread per page, which always takes the latest state (older ones are dropped) and
sends its answer back under the lock, unless the tab was closed meanwhile.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from panel.io.document import hold
from panel.io.state import set_curdoc

__all__ = ["SessionWorker"]


class SessionWorker:
    """A page's document (`_doc`, None outside a server) and worker; the page defines
    `_compute(state)` (run on the worker), `_failed(state, message)` (the answer of an
    internal error) and `_deliver(answer)` (show it; called under the lock)."""

    _doc: Any
    _closed: bool
    _lock: threading.Lock
    _pending: Any
    _running: bool
    state: Any

    def _locked(self, fn: Callable[[], None]) -> None:
        """Run `fn` holding the document's lock (Panel's widget callbacks do not hold it,
        and Bokeh models may only change under it), its model changes sent as one message."""
        if self._doc is None:
            fn()
        else:
            self._doc.add_next_tick_callback(lambda: self._held(fn))

    def _held(self, fn: Callable[[], None]) -> None:
        """`fn` with the document's events held and sent together (one patch, one render)."""
        if self._closed or self._doc is None:
            return
        with set_curdoc(self._doc), hold(self._doc):
            fn()

    def _compute(self, state: Any) -> Any:
        raise NotImplementedError

    def _failed(self, state: Any, message: str) -> Any:
        raise NotImplementedError

    def _deliver(self, answer: Any) -> None:
        raise NotImplementedError

    def _submit(self, name: str) -> None:
        """Compute the current state on the worker thread `name` (started if idle)."""
        with self._lock:
            self._pending = self.state
            start = not self._running
            self._running = True
        if start:
            threading.Thread(target=self._work, daemon=True, name=name).start()

    def _work(self) -> None:
        while True:
            with self._lock:
                state, self._pending = self._pending, None
                if state is None:
                    self._running = False
                    return
            try:
                answer = self._compute(state)
            except Exception as exc:  # a bug: show it on the page rather than lose the thread
                answer = self._failed(state, f"internal error: {exc!r}")
            with self._lock:
                latest = self._pending is None
            if latest:
                self._schedule(lambda a=answer: self._deliver(a))  # type: ignore[misc]

    def _schedule(self, fn: Callable[[], None]) -> None:
        if self._doc is None:
            fn()
            return
        if self._closed:
            return  # the tab was closed while planning: nobody to show it to
        try:
            self._doc.add_next_tick_callback(lambda: self._held(fn))
        except Exception:  # the session went away between the check and the call
            self._closed = True
