"""The Typer application: command groups, one-line errors and exit codes.

Exit codes: 0 success, 1 planning failure (no verified path), 2 bad input, 130 interrupted.
Command modules in this package register on the sub-apps; `load_commands()` imports them.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys

import typer

try:  # Typer >= 0.20 vendors Click as typer._click
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older Typer with external Click
    from click import exceptions as click_exc  # type: ignore[no-redef]

from glideplan.errors import PlanningError, ResultsFileError

app = typer.Typer(
    name="glideplan",
    help="Optimal paths for gliding vehicles (Wolek 2015): plan, map, study, design, reproduce.",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)
plan_app = typer.Typer(help="Plan an optimal path with one planner.", no_args_is_help=True)
map_app = typer.Typer(
    help="Maps over grids of goals (partition, tradespace).", no_args_is_help=True
)
study_app = typer.Typer(help="Monte Carlo and batch studies (resumable).", no_args_is_help=True)
design_app = typer.Typer(
    help="Underwater glider design analysis (chapter 7).", no_args_is_help=True
)
mission_app = typer.Typer(
    help="Multi-leg missions on the Earth: plan waypoint routes, export vehicle files.",
    no_args_is_help=True,
)
glide_app = typer.Typer(
    help="Sailplane polars and final glide (MacCready, wind, arrival heading).",
    no_args_is_help=True,
)
app.add_typer(plan_app, name="plan")
app.add_typer(mission_app, name="mission")
app.add_typer(glide_app, name="glide")
app.add_typer(map_app, name="map")
app.add_typer(study_app, name="study")
app.add_typer(design_app, name="design")

_SKIP = {"app", "common"}


def load_commands() -> None:
    """Import every command module of `glideplan.cli` so that it registers its commands."""
    package = importlib.import_module("glideplan.cli")
    for mod in pkgutil.iter_modules(package.__path__):
        if mod.name not in _SKIP and not mod.name.startswith("_"):
            importlib.import_module(f"glideplan.cli.{mod.name}")


def _error(message: str, code: int) -> int:
    first = " ".join(str(message).split())
    print(f"glideplan: error: {first}", file=sys.stderr)
    return code


def main(argv: list[str] | None = None) -> int:
    """Run the CLI with `argv` (default: sys.argv[1:]) and return the exit code."""
    load_commands()
    command = typer.main.get_command(app)
    try:
        result = command.main(args=argv, prog_name="glideplan", standalone_mode=False)
    except typer.Exit as exc:
        return int(exc.exit_code)
    except typer.Abort:
        return _error("interrupted", 130)
    except click_exc.NoArgsIsHelpError as exc:
        typer.echo(exc.ctx.get_help() if exc.ctx else "")
        return 0
    except click_exc.ClickException as exc:
        return _error(exc.format_message(), 2)
    except KeyboardInterrupt:
        return _error("interrupted", 130)
    except PlanningError as exc:
        return _error(str(exc), 1)
    except (ValueError, ResultsFileError, FileNotFoundError, IsADirectoryError) as exc:
        return _error(str(exc), 2)
    except OSError as exc:
        return _error(f"{exc.strerror or exc}: {exc.filename or ''}", 2)
    return int(result) if isinstance(result, int) else 0


def run() -> None:
    """Console-script entry point."""
    sys.exit(main())
