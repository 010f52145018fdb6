"""The Typer application: command groups, one-line errors and exit codes.

Exit codes: 0 success; 1 planning failure (no verified path: `PlanningError`); 2 bad input
(`InvalidParameterError`, `ResultsFileError`, a usage error, a missing or unreadable file);
3 internal error (any other exception is a bug: one line, and `glideplan --debug ...` prints
the traceback); 130 interrupted. Command modules in this package register on the sub-apps;
`load_commands()` imports them all, `load_commands(argv)` only those that the command line
needs (`glideplan plan dubins ...` imports `plan_dubins` alone; help, no command or an unknown
one import all): start-up time is part of the interface.
"""

from __future__ import annotations

import importlib
import os
import pathlib
import sys
import traceback
from typing import Any

import typer

try:  # Typer >= 0.20 vendors Click as typer._click
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older Typer with external Click
    from click import exceptions as click_exc  # type: ignore[no-redef]

from glideplan.cli import _coerce, _registry
from glideplan.errors import InvalidParameterError, PlanningError, ResultsFileError

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
    help="Sailplane polars, final glide (MacCready, wind, arrival heading), glide reach over "
         "terrain and the turn-back point.",
    no_args_is_help=True,
)


@app.callback()
def _global_options(
    debug: bool = typer.Option(
        False,
        "--debug",
        help="On an internal error print the full traceback (also GLIDEPLAN_DEBUG=1).",
    ),
) -> None:
    """Optimal paths for gliding vehicles (Wolek 2015): plan, map, study, design, reproduce."""


app.add_typer(plan_app, name="plan")
app.add_typer(mission_app, name="mission")
app.add_typer(glide_app, name="glide")
app.add_typer(map_app, name="map")
app.add_typer(study_app, name="study")
app.add_typer(design_app, name="design")

_SKIP = frozenset({"app", "common", "emit"})
_GLOBAL_FLAGS = frozenset({"--debug"})


def command_index() -> _registry.CommandIndex:
    """Which module defines which command, read from the command modules' source."""
    group_of: dict[str, str | None] = {"app": None}
    names = {id(v): k for k, v in globals().items() if isinstance(v, typer.Typer)}
    for info in app.registered_groups:  # the groups defined here (plan_app -> "plan")
        if id(info.typer_instance) in names and info.name:
            group_of[names[id(info.typer_instance)]] = info.name
    return _registry.build_index(pathlib.Path(__file__).parent, _SKIP, group_of)


def load_commands(argv: list[str] | None = None) -> None:
    """Import the command modules of `glideplan.cli` so that they register their commands.

    Without `argv`, every module; with it, only those that the invocation needs (see
    `glideplan.cli._registry`): help, no command or an unknown one still load every module.
    """
    index = command_index()
    modules = None if argv is None else _registry.modules_for(argv, index, _GLOBAL_FLAGS)
    for name in index.modules if modules is None else modules:
        importlib.import_module(f"glideplan.cli.{name}")


def _error(message: str, code: int) -> int:
    first = " ".join(str(message).split())
    print(f"glideplan: error: {first}", file=sys.stderr)
    return code


def _debug_requested(argv: list[str]) -> bool:
    """`--debug` given before the command name (a global option), or GLIDEPLAN_DEBUG=1."""
    if os.environ.get("GLIDEPLAN_DEBUG", "") not in ("", "0"):
        return True
    for arg in argv:
        if arg == "--debug":
            return True
        if not arg.startswith("-"):
            return False
    return False


def _usage_message(exc: click_exc.ClickException, root: Any, argv: list[str]) -> str:
    """Click's message, reworded for options taking several values (`--goal X Y HEADING_DEG`)."""
    param = getattr(exc, "param", None)
    if param is None and isinstance(exc, click_exc.BadOptionUsage):
        param = _find_option(root, argv, exc.option_name)
    if isinstance(exc, click_exc.NoSuchOption):  # `--from 30.45,-39.8 --to 30.45 -38.2`:
        swallowed = _swallowed(root, argv)  # --from took `--to`, then `-38.2` looked an option
        if swallowed is not None:
            return swallowed
    nargs = getattr(param, "nargs", 1)
    if param is None or not isinstance(nargs, int) or nargs <= 1:
        return exc.format_message()
    flag = max(getattr(param, "opts", None) or [param.name or "value"], key=len)
    metavar = getattr(param, "metavar", None) or " ".join(["VALUE"] * nargs)
    head = f"{flag} needs {nargs} values ({metavar.lower()})"
    detail = exc.format_message()
    if isinstance(exc, click_exc.BadOptionUsage):
        return head
    taken = _words_after(argv, list(getattr(param, "opts", None) or []), nargs)
    cut = next((i for i, word in enumerate(taken) if _is_option_name(word)), None)
    if cut is not None:  # `--goal 4 3 --radius 1`: the option took the next option's name
        return _got_before(head, taken, cut)
    return f"{head}: {detail.split(': ', 1)[-1]}"


def _got_before(head: str, taken: list[str], cut: int) -> str:
    """"--goal needs 3 values (...), got 2 (4 3) before --radius" (and the hint for commas)."""
    got = f"{head}, got {cut} ({' '.join(taken[:cut]) or 'none'}) before {taken[cut]}"
    if any("," in word for word in taken[:cut]):
        got += "; separate the values by spaces, not commas"
    return got


def _swallowed(root: Any, argv: list[str]) -> str | None:
    """The message for the first multi-value option of the command that took an option's
    name as one of its values, or None."""
    command = root
    for arg in argv:
        command = getattr(command, "commands", {}).get(arg, command)
    for i, arg in enumerate(argv):
        param = next((p for p in command.params if arg in getattr(p, "opts", ())), None)
        nargs = getattr(param, "nargs", 1)
        if param is None or not isinstance(nargs, int) or nargs <= 1:
            continue
        taken = argv[i + 1 : i + 1 + nargs]
        cut = next((k for k, word in enumerate(taken) if _is_option_name(word)), None)
        if cut is not None:
            metavar = getattr(param, "metavar", None) or " ".join(["VALUE"] * nargs)
            head = f"{max(param.opts, key=len)} needs {nargs} values ({metavar.lower()})"
            return _got_before(head, taken, cut)
    return None


def _words_after(argv: list[str], opts: list[str], nargs: int) -> list[str]:
    """The `nargs` words after the last occurrence of one of `opts` in `argv`."""
    where = [i for i, arg in enumerate(argv) if arg in opts]
    return argv[where[-1] + 1 : where[-1] + 1 + nargs] if where else []


def _is_option_name(word: str) -> bool:
    """`--radius` or `-h`, not a negative number such as `-3` or `-1e-3`."""
    if not word.startswith("-"):
        return False
    try:
        float(word)
    except ValueError:
        return True
    return False


def _reflow(text: str | None) -> str | None:
    """Join the lines of each help paragraph (Rich would keep docstring line breaks)."""
    if not text:
        return text

    def keep(p: str) -> bool:  # \b paragraphs (Click's "no rewrap") and lists stay as written
        lines = [line.strip() for line in p.strip().splitlines()]
        return p.lstrip().startswith("\b") or any(
            line[:2] in ("- ", "* ") or line.split(".")[0].isdigit() for line in lines
        )

    return "\n\n".join(p if keep(p) else " ".join(p.split()) for p in text.split("\n\n"))


def _polish(command: Any) -> Any:
    """Help as users read it: whole paragraphs, flags without a `<bool>` value placeholder."""
    command.help = _reflow(command.help)
    for param in command.params:
        if getattr(param, "is_flag", False) and param.metavar is None:
            param.metavar = ""  # a flag takes no value: show none
    make_help = command.get_help_option

    def get_help_option(ctx: Any) -> Any:
        option = make_help(ctx)
        if option is not None:
            if option.metavar is None:
                option.metavar = ""
            _coerce.fast_param(option)
        return option

    command.get_help_option = get_help_option
    for sub in getattr(command, "commands", {}).values():
        _polish(sub)
    return command


def _find_option(root: Any, argv: list[str], flag: str) -> Any:
    """The option `flag` of the (sub)command that `argv` names, or None."""
    command = root
    for arg in argv:
        sub = getattr(command, "commands", {}).get(arg)
        if sub is not None:
            command = sub
    return next((p for p in command.params if flag in getattr(p, "opts", ())), None)


_BUILT: dict[tuple[int, ...], Any] = {}


def _click_command() -> Any:
    """The Click command of the commands registered so far, built once per set of commands.

    Command modules only add commands, so the numbers registered on the root and on each
    group identify the set; the tests run `main` many times in one process.
    """
    groups = [group.typer_instance for group in app.registered_groups]
    key = (
        len(app.registered_commands),
        *(len(group.registered_commands) for group in groups if group is not None),
    )
    if key not in _BUILT:
        command = _polish(typer.main.get_command(app))
        _coerce.fast_coercion(command)
        _alias_names(command)
        _BUILT[key] = command
    return _BUILT[key]


#: `glideplan route replay ...` runs the hidden command `route-replay` (`route` itself stays
#: one command with options, so `glideplan route --field ...` is unchanged).
_SUBCOMMANDS = {("route", "replay"): "route-replay"}


def _subcommand(args: list[str]) -> list[str]:
    """`route replay ...` -> `route-replay ...` (global flags before the command kept)."""
    words = [i for i, a in enumerate(args) if a not in _GLOBAL_FLAGS]
    if len(words) >= 2 and words[1] == words[0] + 1:
        name = _SUBCOMMANDS.get((args[words[0]], args[words[1]]))
        if name is not None:
            return [*args[: words[0]], name, *args[words[1] + 1 :]]
    return args


def _alias_names(root: Any) -> None:
    """Usage and errors of a hidden `route-replay` read `glideplan route replay` (the name the
    user typed): its context is named with the two words."""
    for words, name in _SUBCOMMANDS.items():
        sub = getattr(root, "commands", {}).get(name)
        if sub is None:
            continue
        make = sub.make_context

        def make_context(info_name: str | None, args: list[str], parent: Any = None,
                         _make: Any = make, _name: str = name, _words: str = " ".join(words),
                         **extra: Any) -> Any:
            return _make(_words if info_name == _name else info_name, args, parent=parent,
                         **extra)

        sub.make_context = make_context


def main(argv: list[str] | None = None) -> int:
    """Run the CLI with `argv` (default: sys.argv[1:]) and return the exit code."""
    args = _subcommand(list(sys.argv[1:] if argv is None else argv))
    debug = _debug_requested(args)
    load_commands(args)
    command = _click_command()
    try:
        result = command.main(args=args, prog_name="glideplan", standalone_mode=False)
    except typer.Exit as exc:
        return int(exc.exit_code)
    except typer.Abort:
        return _error("interrupted", 130)
    except click_exc.NoArgsIsHelpError as exc:
        # With Rich, building the error already printed the help and left the message empty
        if exc.format_message():
            typer.echo(exc.format_message())
        return 0
    except click_exc.ClickException as exc:
        return _error(_usage_message(exc, command, args), 2)
    except KeyboardInterrupt:
        return _error("interrupted", 130)
    except PlanningError as exc:
        return _error(str(exc), 1)
    except (InvalidParameterError, ResultsFileError) as exc:
        if debug:
            traceback.print_exc(file=sys.stderr)
        return _error(str(exc), 2)
    except OSError as exc:  # a file or address the user gave cannot be used
        if debug:
            traceback.print_exc(file=sys.stderr)
        where = f": {exc.filename}" if exc.filename else ""
        return _error(f"{exc.strerror or exc}{where}", 2)
    except Exception as exc:  # a bug, not bad input
        if debug:
            traceback.print_exc(file=sys.stderr)
        detail = " ".join(str(exc).split()) or "(no message)"
        return _error(
            f"internal error: {type(exc).__name__}: {detail}; rerun with --debug for the traceback",
            3,
        )
    return int(result) if isinstance(result, int) else 0


def run() -> None:
    """Console-script entry point."""
    sys.exit(main())
