"""`glideplan explore`: serve the interactive explorer page on this machine."""

from __future__ import annotations

import pathlib
from typing import Annotated

import typer

from glideplan.cli.app import app


@app.command("explore")
def explore_command(
    port: Annotated[int, typer.Option("--port", help="TCP port of the page.")] = 5006,
    host: Annotated[
        str, typer.Option("--host", help="Address to bind (this machine only by default).")
    ] = "127.0.0.1",
    no_show: Annotated[
        bool, typer.Option("--no-show", help="Do not open a browser; just serve.")
    ] = False,
    field: Annotated[
        pathlib.Path | None,
        typer.Option(
            "--field",
            metavar="FILE",
            help="Current/wind file (NetCDF or GRIB) for the route map (?planner=route); "
            "without it the map shows the built-in double gyre.",
            show_default=False,
        ),
    ] = None,
    route: Annotated[
        pathlib.Path | None,
        typer.Option(
            "--route",
            metavar="FILE",
            help="Route file (GPX, KML, GeoJSON, CSV) for the mission map (?planner=mission); "
            "without it the map shows a bundled example route.",
            show_default=False,
        ),
    ] = None,
) -> None:
    """Serve a web page at http://HOST:PORT/ to drag the start and goal and watch the plan.

    Every registered planner with its vehicle's parameters (named like `plan` options),
    every candidate and its cost, the endpoint error and the planner time; the state lives
    in the URL (e.g. /?planner=dubins&goal=4,3,90&radius=1). The route map (/?planner=route)
    drags a route through the --field file's currents (or the double gyre, needing no file);
    the mission map (/?planner=mission) drags the waypoints of the --route file.
    Works offline. Ctrl-C stops.
    """
    from glideplan.explore.server import check_address, serve

    if field is not None:
        from glideplan.cli.common import check_input_file, flag_names
        from glideplan.fields import open_field

        check_input_file(field, "--field")
        with flag_names(field="--field"):
            open_field(field)  # a foreign or broken file: one line now, not on the page
    if route is not None:
        from glideplan.cli.common import check_input_file, file_flag
        from glideplan.formats.readers import read_route

        check_input_file(route, "--route")
        with file_flag("--route", route):  # named as the option, as `mission plan`'s ROUTE
            read_route(route)  # a foreign or broken file: one line now, not on the page
    check_address(host, port)  # a busy port or a foreign host: one line, before announcing
    typer.echo(f"glideplan explore: serving http://{host}:{port}/ (Ctrl-C to stop)", err=True)
    serve(
        port,
        host,
        show=not no_show,
        field=None if field is None else str(field),
        route=None if route is None else str(route),
    )
