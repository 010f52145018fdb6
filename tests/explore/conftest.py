"""Fixtures shared by the explorer's browser tests: one explorer server and one Chromium per
test module (`server`, `open_context`)."""

from __future__ import annotations

import socket
import time
from collections.abc import Callable, Iterator
from typing import Any

import pytest


@pytest.fixture(scope="module")
def server() -> Iterator[str]:
    """`glideplan explore` served on a free local port (threaded), its URL once it listens."""
    from glideplan.explore.server import serve

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        port = int(s.getsockname()[1])
    srv = serve(port, "127.0.0.1", show=False, threaded=True)
    deadline = time.monotonic() + 20
    while time.monotonic() < deadline:
        try:
            socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
            break
        except OSError:
            time.sleep(0.1)
    yield f"http://127.0.0.1:{port}"
    srv.stop()


CHROMIUM = "/usr/bin/chromium"
# No background traffic of Chromium's own: the tests count every request the pages make.
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run",
                 "--disable-quic"]


@pytest.fixture(scope="module")
def open_context() -> Iterator[Callable[..., Any]]:
    """A function giving a new Chromium context (`Browser.new_context` keywords) of one
    browser per module; every context and the browser are closed at the module's end."""
    from playwright.sync_api import sync_playwright

    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        contexts: list[Any] = []

        def make(**kw: Any) -> Any:
            contexts.append(browser.new_context(**kw))
            return contexts[-1]

        yield make
        for ctx in contexts:
            ctx.close()
        browser.close()
