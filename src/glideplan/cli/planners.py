"""`glideplan planners`: list the registered planners (vehicle model, objective, method)."""

from __future__ import annotations

from glideplan.cli.app import app


@app.command("planners")
def list_planners() -> None:
    """List every registered planner with its vehicle model, objective, method and options."""
    from rich.console import Console
    from rich.table import Table

    from glideplan.planning import registered_planners

    table = Table(title="glideplan planners")
    for col in ("planner", "vehicle", "objective", "method", "options", "description"):
        table.add_column(col)
    for s in sorted(registered_planners(), key=lambda s: (s.vehicle.__name__, s.method)):
        method = s.method + (" (default)" if s.default else "")
        table.add_row(
            s.name, s.vehicle.__name__, s.objective, method, ", ".join(s.options), s.description
        )
    Console().print(table)
