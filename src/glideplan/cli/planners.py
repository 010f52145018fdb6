"""`glideplan planners`: list the registered planners (vehicle model, objective, method)."""

from __future__ import annotations

from glideplan.cli.app import app


@app.command("planners")
def list_planners() -> None:
    """List every registered planner with its vehicle model, objective, method and options."""
    from rich.console import Console
    from rich.table import Table

    from glideplan.planning import registered_planners

    table = Table(title="glideplan planners", show_lines=True)
    table.add_column("planner", no_wrap=True)
    table.add_column("vehicle / objective / method", no_wrap=True)
    table.add_column("description and options", ratio=1)
    for s in sorted(registered_planners(), key=lambda s: (s.vehicle.__name__, s.method)):
        method = s.method + (" (default)" if s.default else "")
        opts = ", ".join(s.options) or "none"
        table.add_row(
            s.name,
            f"{s.vehicle.__name__}\n{s.objective}\n{method}",
            f"{s.description}\n[dim]options: {opts}[/dim]",
        )
    Console().print(table)
