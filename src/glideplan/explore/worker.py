"""A browser session's document lock and worker thread, shared by the explorer's pages.

Bokeh models may change only under their document's lock; slow answers are computed on one
worker thread per page, which always takes the latest state (older ones are dropped) and
sends its answer back under the lock, unless the tab was closed meanwhile. A computation that
a newer state supersedes, or whose tab closes, is cancelled at its front's next time step
(`glideplan.compute.cancel_scope`): its thread moves on at once instead of finishing it.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from panel.io.document import hold
from panel.io.state import set_curdoc

from glideplan.compute import ComputationCancelled, cancel_scope

__all__ = ["SessionWorker", "local_dist", "local_styles", "resend_data"]


class SessionWorker:
    """A page's document (`_doc`, None outside a server) and worker; the page defines
    `_compute(state)` (run on the worker), `_failed(state, message)` (the answer of an
    internal error) and `_deliver(answer)` (show it; called under the lock)."""

    _doc: Any
    _closed: bool
    _lock: threading.Lock
    _pending: Any
    _running: bool
    _loop: Any = None  # the server's tornado IOLoop, taken on its thread by `_submit`
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
            fn()  # new models link local style sheets (`local_dist`): no walk over them here

    def _compute(self, state: Any) -> Any:
        raise NotImplementedError

    def _failed(self, state: Any, message: str) -> Any:
        raise NotImplementedError

    def _deliver(self, answer: Any) -> None:
        raise NotImplementedError

    def _submit(self, name: str) -> None:
        """Compute the current state on the worker thread `name` (started if idle)."""
        if self._doc is not None and getattr(self, "_loop", None) is None:
            from tornado.ioloop import IOLoop

            self._loop = IOLoop.current()  # called on the server's thread: its loop
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
                # a newer state, or the tab closed, stops the front at its next step
                with cancel_scope(self._superseded):
                    answer = self._compute(state)
            except ComputationCancelled:
                continue  # its answer would be dropped: take the newer state (or stop)
            except Exception as exc:  # a bug: show it on the page rather than lose the thread
                answer = self._failed(state, f"internal error: {exc!r}")
            with self._lock:
                latest = self._pending is None
            if latest:
                self._undelivered = answer
                self._schedule(lambda a=answer: self._deliver_once(a))  # type: ignore[misc]

    def _deliver_once(self, answer: Any) -> None:
        """Show `answer` unless it was shown already or a newer one is on its way."""
        if getattr(self, "_undelivered", None) is answer:
            self._undelivered = None
            self._deliver(answer)

    def deliver_pending(self) -> None:
        """Show the last answer if its scheduled delivery has not run (call on page load, via
        `_held`: one patch, local style sheets): a next-tick callback added from the worker
        while the server builds the session can be lost (the strip said "computing" forever
        in 2 of 4 fresh mission loads on a loaded machine)."""
        answer = getattr(self, "_undelivered", None)
        if answer is not None:
            self._deliver_once(answer)

    def _superseded(self) -> bool:
        """The computation running is no longer wanted: a newer state waits, or the tab
        closed (then the waiting state is dropped too)."""
        if self._closed:
            with self._lock:
                self._pending = None
            return True
        return self._pending is not None

    def _schedule(self, fn: Callable[[], None]) -> None:
        if self._doc is None:
            fn()
            return
        if self._closed:
            return  # the tab was closed while planning: nobody to show it to
        loop = getattr(self, "_loop", None)
        if loop is not None:
            # hop to the server's thread first (tornado's add_callback is the one thread-safe
            # call): a document callback added from this thread was sometimes never run (an
            # answer computed, never shown: 1 of ~80 load-factor changes, and fresh loads)
            loop.add_callback(lambda: self._add_on_server(fn))
            return
        self._add_on_server(fn)

    def _add_on_server(self, fn: Callable[[], None]) -> None:
        if self._closed or self._doc is None:
            return
        try:
            self._doc.add_next_tick_callback(lambda: self._held(fn))
        except Exception:  # the session went away between the check and the call
            self._closed = True


def resend_data(doc: Any) -> None:
    """Send every data source of `doc` to the browser again, as one message.

    An answer that arrives while the browser is still building the page (between the
    server's copy of the document and the browser's first render) can be lost: the strip
    said `solved` over an empty figure in 1-8 of 8 fresh loads. Called once the page has
    loaded (`pn.state.onload`), this makes the figure show what the text says. The events are
    sent as they are, without setting the data, so no Python `on_change` callback runs.
    """
    from bokeh.document.events import ColumnDataChangedEvent
    from bokeh.models import ColumnDataSource

    if doc is None:
        return
    with set_curdoc(doc), hold(doc):
        for src in doc.select({"type": ColumnDataSource}):
            cols = list(src.data)
            if cols:
                doc.callbacks.trigger_on_change(ColumnDataChangedEvent(doc, src, "data",
                                                                       cols=cols))


def local_dist(doc: Any) -> None:
    """Make every Panel style sheet of `doc` point at this server from the start.

    Panel writes `dist_url` (where its CSS lives) into a session's document only when it
    serves the page's HTML, and patches the CDN links of the models present then. A session
    can also be built without that step: when a tab's websocket connects after the session
    was dropped as unused (3 s, `server.serve`; several tabs loading at once on a busy
    machine take longer), Bokeh builds a new session for its id without serving HTML, and
    every model of that page linked loading.css, default.css, listpanel.css, ... from
    cdn.holoviz.org (reproduced: 23-35 of 77 requests with 6 tabs opened at once). Set
    here before the page is built, `dist_url` makes Panel patch each style sheet as its
    model is made (`Reactive._get_properties`).
    """
    from panel.io.resources import LOCAL_DIST
    from panel.io.state import state

    if doc is None:
        return
    variables = doc._template_variables
    if "dist_url" not in variables:
        rel = state.rel_path
        variables["dist_url"] = f"{rel}/{LOCAL_DIST}" if rel else LOCAL_DIST


def local_styles(doc: Any) -> None:
    """Point the style sheets of models made after the page was served at this server.

    Panel rewrites its components' CDN style sheet links (cdn.holoviz.org) to the server's
    own copies only for the models present when the page is first served; a model made later
    (a loading spinner, a column) kept its CDN link: a failed request offline, a request to a
    third party online. Costs one walk over the document's style sheets (~0.1 ms).
    """
    from bokeh.models import ImportedStyleSheet
    from panel.io.resources import CDN_DIST, patch_stylesheet

    dist = getattr(doc, "_template_variables", {}).get("dist_url")
    if not dist or dist == CDN_DIST:
        return
    for model in list(doc.models):
        if isinstance(model, ImportedStyleSheet) and model.url.startswith(CDN_DIST):
            patch_stylesheet(model, dist)
