"""Serve the explorer page locally with Panel (Bokeh server): every script and style sheet
comes from this server (Panel and Bokeh's bundled resources), nothing from a CDN."""

from __future__ import annotations

import errno
import socket
import threading
from typing import Any

from glideplan.errors import InvalidParameterError

__all__ = ["check_address", "serve", "warm_up"]


def check_address(host: str, port: int) -> None:
    """Refuse, naming `--host` or `--port`, an address the server could not listen on.

    The host must resolve to an address of this machine and the port be free: a socket is
    bound (with SO_REUSEADDR, as the server's own) and closed again, before anything is
    announced. The port must lie in 1..65535.
    """
    if not 0 < port < 65536:
        raise InvalidParameterError("--port", port, "must be in 1..65535")
    try:
        infos = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
    except (socket.gaierror, UnicodeError) as exc:
        reason = getattr(exc, "strerror", None) or str(exc)
        raise InvalidParameterError("--host", host, f"is not a known address ({reason})") from None
    family, kind, proto, _, address = infos[0]
    with socket.socket(family, kind, proto) as sock:
        sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            sock.bind(address)
        except OSError as exc:
            if exc.errno == errno.EADDRINUSE:
                raise InvalidParameterError(
                    "--port", port, f"is in use on {host} (another server?): choose another"
                ) from None
            if exc.errno == errno.EACCES:
                raise InvalidParameterError(
                    "--port", port, "needs privileges (ports below 1024): choose one above"
                ) from None
            if exc.errno == errno.EADDRNOTAVAIL:
                raise InvalidParameterError(
                    "--host", host, "is not an address of this machine"
                ) from None
            reason = exc.strerror or str(exc)
            raise InvalidParameterError(
                "--host", host, f"cannot listen on port {port}: {reason}"
            ) from None


def warm_up() -> None:
    """Plan each fast planner once so that the first page does not pay the imports
    (SciPy's integrators for the verification, the planners' tables)."""
    from glideplan.explore.catalog import build_catalog
    from glideplan.explore.land import land_shapes
    from glideplan.explore.solve import solve_view
    from glideplan.explore.state import initial_state

    land_shapes(-71.0, 41.4, -70.7, 41.6)  # the bundled land's one-off load (0.5 s)
    catalog = build_catalog()
    for entry in catalog.entries:
        if not entry.slow:
            solve_view(catalog, initial_state(entry))


def serve(
    port: int = 5006,
    host: str = "127.0.0.1",
    *,
    show: bool = True,
    threaded: bool = False,
    field: str | None = None,
    route: str | None = None,
) -> Any:
    """Serve the page at http://HOST:PORT/ (blocks unless `threaded`; then returns the server).

    Connections are accepted from `host` only (127.0.0.1 unless told otherwise). `field`: a
    current/wind file (server-side path) for the route map (`?planner=route`); without it
    the route map shows the built-in double gyre. `route`: a route file (server-side path)
    for the mission map (`?planner=mission`); without it, the bundled example route.
    """
    import panel as pn

    from glideplan.explore.catalog import build_catalog
    from glideplan.explore.page import create_page

    catalog = build_catalog()
    threading.Thread(target=warm_up, daemon=True, name="glideplan-warm-up").start()
    # The page's websocket is accepted from the page's own origin only; a user who binds
    # another address (e.g. 0.0.0.0 to share on a network) is reached by names we cannot know.
    loopback = host in ("127.0.0.1", "localhost", "::1")
    origin: list[str] | str = [f"127.0.0.1:{port}", f"localhost:{port}"] if loopback else "*"
    return pn.serve(
        {"/": lambda: create_page(catalog, field_path=field, route_path=route)},
        port=port,
        address=host,
        show=show,
        threaded=threaded,
        start=True,
        title="glideplan explore",
        websocket_origin=origin,
        # a closed tab's session (and its running work, cancelled) is freed within ~5 s
        check_unused_sessions_milliseconds=2000,
        unused_session_lifetime_milliseconds=3000,
        verbose=False,
    )
