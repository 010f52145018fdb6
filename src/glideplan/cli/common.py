"""Helpers shared by the command modules: pose parsing, solution output, figures."""

from __future__ import annotations

import contextlib
import math
import pathlib
import sys
from collections.abc import Callable, Iterator
from typing import Any, NoReturn, TypeVar

import typer

from glideplan.errors import InvalidParameterError
from glideplan.jsonio import json_default, to_json, write_json
from glideplan.pose import Pose
from glideplan.solution import Solution
from glideplan.validation import check_finite, check_physical

__all__ = [
    "FIGURE_SUFFIXES",
    "PoseValues",
    "announce",
    "check_figure_file",
    "check_input_file",
    "check_output_dir",
    "check_output_file",
    "check_writable",
    "emit_solution",
    "file_flag",
    "flag_names",
    "goal_option",
    "json_default",
    "json_flag",
    "parse_pose",
    "parse_start_goal",
    "phase_progress",
    "plot_option",
    "print_json",
    "print_warnings",
    "solving",
    "start_option",
    "time_limit_flag",
    "time_limit_option",
    "usage_error",
    "write_figure",
    "write_json",
]

T = TypeVar("T")

FIGURE_SUFFIXES = (".png", ".pdf", ".svg")

PoseValues = tuple[float, float, float]
"""A pose as typed on the command line: X Y HEADING_DEG."""


def goal_option(help: str) -> Any:
    """The required `--goal X Y HEADING_DEG` option, with the command's own help text."""
    return typer.Option("--goal", metavar="X Y HEADING_DEG", help=help, show_default=False)


def start_option(help: str) -> Any:
    """The `--start X Y HEADING_DEG` option (default shown), with the command's own help text."""
    return typer.Option("--start", metavar="X Y HEADING_DEG", help=help)


def json_flag(help: str = "Print one JSON object.") -> Any:
    """The `--json` flag: print one JSON object instead of a table."""
    return typer.Option("--json", help=help)


def plot_option(help: str) -> Any:
    """The `--plot FILE` option: the figure file a command draws."""
    return typer.Option("--plot", metavar="FILE", help=help)


def time_limit_flag() -> Any:
    """The `--time-limit SECONDS` option of the commands that can run a direct solver."""
    return typer.Option(
        "--time-limit",
        metavar="SECONDS",
        help="Stop the direct solver after SECONDS and report what it has (direct only).",
        show_default=False,
    )


@contextlib.contextmanager
def flag_names(**names: str) -> Iterator[None]:
    """Report a bad value under its command-line flag (`turn_radius` -> `--radius`).

    A name matches a key whole (`turn_radius`) or by its leading words (`goal x` -> `--goal x`,
    `from latitude` -> `--from latitude`; keys may hold spaces, the longest match wins).
    """
    try:
        yield
    except InvalidParameterError as exc:
        name = str(exc.name)
        if name in names:
            raise InvalidParameterError(names[name], exc.value, exc.rule) from None
        heads = [k for k in names if name.startswith(k + " ")]
        if heads:  # "goal x" -> "--goal x"
            head = max(heads, key=len)
            rest = name[len(head) + 1 :]
            raise InvalidParameterError(f"{names[head]} {rest}", exc.value, exc.rule) from None
        raise


@contextlib.contextmanager
def file_flag(flag: str, path: pathlib.Path | str, *aliases: str) -> Iterator[None]:
    """Report a bad file under the flag or argument that named it (`--polar`, `ROUTE`).

    Library readers name the file itself (`one.csv`, `one.csv line 3 latitude`) or an alias
    (`polar file one.plr`); a message about the whole file becomes `FLAG='one.csv': RULE`
    (the reader's value, when it adds something, joins the rule: `(got 1 waypoint(s))`); one
    about a place in it keeps the place: `FLAG one.csv line 3 latitude=95.0: ...`. An
    `OSError` on the file (cannot be read or written) becomes `FLAG='FILE': <reason>`.
    """
    text = str(path)
    keys = sorted({text, *aliases}, key=len, reverse=True)
    try:
        yield
    except InvalidParameterError as exc:
        name = str(exc.name)
        if name in keys:
            value = "" if exc.value is None else str(exc.value)
            quiet = value in ("", text) or value.lower() in str(exc.rule).lower()
            rule = exc.rule if quiet else f"{exc.rule} (got {value})"
            raise InvalidParameterError(flag, text, rule) from None
        head = next((k for k in keys if name.startswith((k + " ", k + ","))), None)
        if head is not None:  # "one.csv line 3" -> "FLAG one.csv line 3"
            place = text + name[len(head) :]
            raise InvalidParameterError(f"{flag} {place}", exc.value, exc.rule) from None
        raise
    except OSError as exc:
        reason = exc.strerror.lower() if exc.strerror else str(exc)
        raise InvalidParameterError(flag, text, reason) from None


def check_input_file(path: pathlib.Path, flag: str) -> pathlib.Path:
    """A file to read: it exists and is not a directory (else an error naming `flag`)."""
    if path.is_dir():
        raise InvalidParameterError(flag, str(path), "is a directory, not a file")
    if not path.is_file():
        raise InvalidParameterError(flag, str(path), "no such file")
    return path


def check_output_file(path: pathlib.Path | None, flag: str) -> pathlib.Path | None:
    """A file to write (None passes): not a directory, in a directory that exists."""
    if path is None:
        return None
    if path.is_dir():
        raise InvalidParameterError(flag, str(path), "is a directory; give a file name")
    parent = path.parent if str(path.parent) else pathlib.Path(".")
    if not parent.is_dir():
        raise InvalidParameterError(flag, str(path), f"directory {str(parent)!r} does not exist")
    return path


def check_output_dir(path: pathlib.Path, flag: str) -> pathlib.Path:
    """A directory to write into (made if missing): not an existing file."""
    if path.exists() and not path.is_dir():
        raise InvalidParameterError(flag, str(path), "is a file, not a directory")
    if not str(path).strip():
        raise InvalidParameterError(flag, str(path), "must name a directory")
    return path


def check_writable(path: pathlib.Path, flag: str) -> pathlib.Path:
    """A file or directory glideplan will create or write: its nearest existing directory
    (the path itself when it is one) must be writable, else an error naming `flag`."""
    import os

    here = path if path.is_dir() else path.parent
    while not here.exists() and here != here.parent:
        here = here.parent
    if here.exists() and not here.is_dir():
        raise InvalidParameterError(flag, str(path), f"{str(here)!r} is a file, not a directory")
    if here.exists() and not os.access(here, os.W_OK | os.X_OK):
        raise InvalidParameterError(flag, str(path), f"directory {str(here)!r} is not writable")
    return path


class _PhaseProgress:
    """A `progress(phase, done, total)` callback: a Rich bar on stderr for each phase that
    runs longer than `delay` seconds (terminals), or one note line on stderr (pipes, logs)."""

    def __init__(self, labels: dict[str, str], delay: float) -> None:
        import time

        self.labels = labels
        self.delay = delay
        self.clock = time.perf_counter
        self.last = self.clock()
        self.phase: str | None = None
        self.start = self.last
        self.bar: Any = None
        self.task: Any = None
        self.terminal = sys.stderr.isatty()

    def __call__(self, phase: str, done: int, total: int) -> None:
        now = self.clock()
        if phase != self.phase:
            self.close()
            self.phase, self.start = phase, self.last
        self.last = now
        if now - self.start < self.delay or (done >= total and self.bar is None):
            return
        label = self.labels.get(phase, phase)
        if not self.terminal:
            if self.bar is None:
                self.bar = "noted"
                print(f"glideplan: note: {label}: {done}/{total} after {now - self.start:.0f} s",
                      file=sys.stderr)
            return
        if self.bar is None:
            from glideplan.progress import start_progress_bar

            self.bar, self.task = start_progress_bar(label, total)
        self.bar.update(self.task, completed=done)

    def close(self) -> None:
        if self.bar is not None and self.bar != "noted":
            self.bar.stop()
        self.bar = None


@contextlib.contextmanager
def phase_progress(
    labels: dict[str, str], delay: float = 2.0
) -> Iterator[Callable[[str, int, int], None]]:
    """A `progress(phase, done, total)` callback for the long phases of a library call.

    A phase that has run `delay` seconds shows a Rich progress bar on stderr (`labels` names
    the phases for the reader); off a terminal it writes one note line instead, so a long run
    is never silent and a short one prints nothing.
    """
    progress = _PhaseProgress(labels, delay)
    try:
        yield progress
    finally:
        progress.close()


def usage_error(message: str) -> NoReturn:
    """Stop with a usage error (exit 2, one line: `glideplan: error: MESSAGE`)."""
    from glideplan.cli.app import click_exc

    raise click_exc.UsageError(message)


def check_figure_file(path: pathlib.Path | None, flag: str = "--plot") -> pathlib.Path | None:
    """A figure file to write: not a directory, in an existing directory, a known format."""
    if path is None:
        return None
    if path.is_dir():
        raise InvalidParameterError(flag, str(path), "is a directory; give a file such as path.png")
    if path.suffix.lower() not in FIGURE_SUFFIXES:
        raise InvalidParameterError(
            flag, str(path), f"must end in {', '.join(FIGURE_SUFFIXES)} (the figure format)"
        )
    parent = path.parent if str(path.parent) else pathlib.Path(".")
    if not parent.is_dir():
        raise InvalidParameterError(flag, str(path), f"directory {str(parent)!r} does not exist")
    return path


def solving(description: str, function: Callable[[], T]) -> T:
    """Run `function()` with a spinner and the elapsed seconds on stderr (terminals only).

    Nothing is drawn when stderr is not a terminal, so piped output and `--json` stay clean.
    """
    if not sys.stderr.isatty():  # decided before importing Rich (start-up time)
        return function()
    from rich.console import Console

    console = Console(stderr=True)
    if not console.is_terminal:
        return function()
    from rich.progress import Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        TimeElapsedColumn(),
        console=console,
        transient=True,
    ) as progress:
        hint = " (Ctrl-C stops; --time-limit SECONDS bounds it)" if "direct" in description else ""
        progress.add_task(description + hint, total=None)
        return function()


def time_limit_option(
    vehicle: Any, objective: str, method: str | None, time_limit: float | None
) -> dict[str, Any]:
    """`{"time_limit": seconds}` for the planner that will run, or {} when not given.

    Refused (naming `--time-limit`) when the value is not positive or the planner cannot
    honour it (the synthesis methods finish in milliseconds and take no limit).
    """
    if time_limit is None:
        return {}
    from glideplan.planning import find_planner
    from glideplan.validation import check_positive

    seconds = check_positive("--time-limit", time_limit)
    spec = find_planner(vehicle, objective, method)
    if "time_limit" not in spec.options:
        hint = "; use --method direct" if spec.method != "direct" else ""
        raise InvalidParameterError(
            "--time-limit",
            time_limit,
            f"planner {spec.name!r} ({spec.method}) takes no time limit{hint}",
        )
    return {"time_limit": seconds}


def print_warnings(warnings: tuple[str, ...] | list[str]) -> None:
    """One line on stderr per warning: `glideplan: warning: ...`."""
    for w in warnings:
        print(f"glideplan: warning: {' '.join(str(w).split())}", file=sys.stderr)


def announce(message: str, json_out: bool) -> None:
    """A note such as `wrote FILE`: stdout, or stderr when stdout carries JSON."""
    if json_out:
        print(message, file=sys.stderr)
    else:
        typer.echo(message)


def parse_pose(values: list[float] | tuple[float, ...] | None, name: str) -> Pose:
    """X Y HEADING_DEG from the command line to a `Pose` (heading in radians)."""
    if values is None:
        return Pose(0.0, 0.0, 0.0)
    if len(values) != 3:
        raise InvalidParameterError(name, values, "needs 3 values (x y heading_deg)")
    x, y, h = (check_finite(f"{name} {c}", v) for c, v in zip("xyh", values, strict=True))
    check_physical(f"{name} h", h, "heading")  # 1e300 deg is a typo, not a planning failure
    return Pose(x, y, math.radians(h))


def parse_start_goal(start: PoseValues, goal: PoseValues) -> tuple[Pose, Pose]:
    """`--start` and `--goal` from the command line to `Pose`s (start checked first)."""
    return parse_pose(start, "--start"), parse_pose(goal, "--goal")


def write_figure(
    plot_file: pathlib.Path | None, json_out: bool, draw: Callable[[], None] | None
) -> None:
    """Call `draw()` and say `wrote FILE`, or warn when there is no path to draw (`draw=None`)."""
    if plot_file is None:
        return
    if draw is None:
        print_warnings([f"no path to draw: {plot_file} not written"])
        return
    draw()
    announce(f"wrote {plot_file}", json_out)


def print_json(data: Any) -> None:
    typer.echo(to_json(data))


def _solution_table(solution: Solution, data: dict[str, Any]) -> Any:
    """The Rich table of a solution: quantity, value and unit of each row.

    Units follow the vehicle model (`glideplan.plotting.cost_unit` / `length_unit`): m and s,
    or `l_ref` = V_ref^2 / g and `t_ref` = V_ref / g for the nondimensional load-factor
    glider (chapter 6). The cost's unit depends on the objective (length, altitude: a
    length; time: a time). The endpoint error is the integrated end's distance to the goal
    (a length) and its heading difference (degrees).
    """
    from rich.table import Table

    from glideplan.plotting import cost_unit, length_unit

    length = length_unit(solution.vehicle)
    duration = cost_unit("time", solution.vehicle)
    table = Table(title=f"{solution.planner} ({solution.objective})")
    table.add_column("quantity")
    table.add_column("value", justify="right")
    table.add_column("unit")
    table.add_row("status", solution.status.value, "")
    if solution.ok:
        err = solution.endpoint_error
        table.add_row(
            "cost", f"{solution.cost:.6g}", cost_unit(solution.objective, solution.vehicle)
        )
        table.add_row("word", solution.word, "")
        table.add_row("family", solution.family, "")
        table.add_row("length", f"{data['length']:.6g}", length)
        table.add_row("duration", f"{data['duration']:.6g}", duration)
        if err is None:
            table.add_row("endpoint error", "n/a", "")
        else:
            table.add_row("endpoint error (position)", f"{err.position:.2e}", length)
            table.add_row("endpoint error (heading)", f"{math.degrees(err.heading):.2e}", "deg")
        table.add_row("candidates", str(len(solution.candidates)), "")
    return table


def emit_solution(
    solution: Solution,
    json_out: bool,
    plot_file: pathlib.Path | None,
    *,
    extra: dict[str, Any] | None = None,
    plot_candidates: bool = False,
) -> NoReturn:
    """`cli.emit.emit` of a `plan` command's solution (`extra` joins its JSON as extras; a
    table for people; a failed plan has no path to draw: said in a warning)."""
    from dataclasses import replace

    from glideplan.cli.emit import emit

    if extra:
        solution = replace(solution, extras={**solution.extras, **extra})
    if plot_file is not None and solution.path is None:
        print_warnings([f"no path to draw: {plot_file} not written"])
        plot_file = None

    def table(outcome: Any) -> None:
        from rich.console import Console

        Console().print(_solution_table(outcome, outcome.to_dict()))

    emit(solution, json=json_out, plot=plot_file, summary=table,
         plot_kw={"candidates": plot_candidates}, what=solution.planner)
