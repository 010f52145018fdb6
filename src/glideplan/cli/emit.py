"""`emit`: how every product command ends -- one output contract for the CLI.

    JSON on stdout (`Outcome.to_dict()`, success and failure alike) or the human summary;
    warnings on stderr, one line each ("glideplan: warning: ..."); the figure (`--plot`,
    `Outcome.plot()`) and the exports written; when not solved, one line on stderr
    ("glideplan: error: PRODUCT: STATUS: message"); then the exit code of the status
    (`Status.exit_code`: 0 solved, 1 any other outcome).

Bad input never reaches `emit`: it raises `InvalidParameterError` (exit 2, one line); an
internal error is exit 3 (one line, `--debug` for the traceback; `glideplan.cli.app.main`).
"""

from __future__ import annotations

import pathlib
import sys
from collections.abc import Callable, Mapping
from typing import Any, NoReturn

import typer

from glideplan.results import Outcome

__all__ = ["EXIT_CODES", "emit", "emit_files"]

#: The CLI's exit codes (documented once, README "Exit codes").
EXIT_CODES = {
    0: "solved (a path was found and verified)",
    1: "any other outcome: no_path, unreachable, not_verified, solver_failed, lost, "
       "infeasible, below_glide, failed -- the JSON's status and reason say which",
    2: "bad input (one line on stderr naming the option, its value and the rule)",
    3: "internal error (one line; --debug for the traceback)",
}

FileValue = pathlib.Path | str | list[str] | tuple[str, ...]


def emit(
    outcome: Outcome,
    *,
    json: bool,
    plot: pathlib.Path | None = None,
    exports: Mapping[str, FileValue] | None = None,
    summary: Callable[[Outcome], None] | None = None,
    plot_kw: Mapping[str, Any] | None = None,
    save_kw: Mapping[str, Any] | None = None,
    what: str = "",
) -> NoReturn:
    """Print `outcome` (JSON or `summary`), its warnings, write its figure and exports, and exit
    with its status's code (module docstring).

    exports: files already written for the outcome ({format: path(s)}): announced, and when
    given (even empty) listed as "files" in the JSON, with "plot" when drawn. plot_kw:
    keywords of `outcome.plot`; save_kw: of `plotting.save_figure`; what: the product's name
    in the failure line ("glideplan: error: WHAT: STATUS: message").
    """
    written: dict[str, Any] = {} if plot is None else {"plot": str(plot)}
    written.update({k: (str(v) if isinstance(v, pathlib.Path) else v)
                    for k, v in (exports or {}).items()})
    if plot is not None:
        _draw(outcome, plot, plot_kw or {}, save_kw or {})
    data = outcome.to_dict()
    if exports is not None:
        data["files"] = written
    if json:
        from glideplan.cli.common import print_json

        print_json(data)
    elif summary is not None:
        summary(outcome)
    else:
        typer.echo(f"{outcome.status.value}: {outcome.message}")
    emit_warnings(outcome.warnings)
    emit_files(written, json)
    if not outcome.ok:
        head = f"{what}: " if what else ""
        text = " ".join(outcome.message.split())
        print(f"glideplan: error: {head}{outcome.status.value}: {text}", file=sys.stderr)
    raise typer.Exit(outcome.status.exit_code)


def emit_warnings(warnings: tuple[str, ...] | list[str]) -> None:
    """One line on stderr per warning: `glideplan: warning: ...` (the one way)."""
    from glideplan.cli.common import print_warnings

    print_warnings(warnings)


def emit_files(files: Mapping[str, Any], json: bool) -> None:
    """`wrote PATH` for each file (`wrote FORMAT: PATH, PATH` for a format written as several
    files); on stderr with --json, else stdout."""
    from glideplan.cli.common import announce

    for fmt, path in files.items():
        if isinstance(path, str):
            announce(f"wrote {path}", json)
        else:
            announce(f"wrote {fmt}: {', '.join(str(p) for p in path)}", json)


def _draw(outcome: Outcome, plot: pathlib.Path, plot_kw: Mapping[str, Any],
          save_kw: Mapping[str, Any]) -> None:
    from glideplan.plotting import save_figure

    save_figure(outcome.plot(**plot_kw), str(plot), **save_kw)
