"""The CLI's fast start (issue 11): each invocation imports only the command module it needs.

`glideplan.cli._registry` reads which module defines which command from the decorators in the
source; `glideplan.cli._coerce` converts plain option values without Pydantic. The reference
for both is the slow path they replace: the full import of every command module, and Typer's
own (Pydantic) converter. The fast-path checks run in one child interpreter (this file run as a
script) because they re-import `glideplan.cli` from scratch for every command line.
"""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import os
import pathlib
import subprocess
import sys
from typing import Annotated, Any

import pytest
import typer

from glideplan.cli import _coerce
from glideplan.cli.app import app, command_index, load_commands

try:
    from typer._click import exceptions as click_exc
except ImportError:  # pragma: no cover - older Typer with external Click
    from click import exceptions as click_exc  # type: ignore[no-redef]


def _registered() -> dict[tuple[str, ...], str]:
    """Every command that the full import registers -> the module whose function it runs."""
    load_commands()
    found: dict[tuple[str, ...], str] = {}

    def name_of(info: Any) -> str:
        return str(info.name or typer.main.get_command_name(info.callback.__name__))

    for info in app.registered_commands:
        found[(name_of(info),)] = info.callback.__module__.rsplit(".", 1)[-1]
    for group in app.registered_groups:
        assert group.typer_instance is not None and group.name is not None
        for info in group.typer_instance.registered_commands:
            found[(group.name, name_of(info))] = info.callback.__module__.rsplit(".", 1)[-1]
    return found


def test_source_index_matches_the_registered_commands() -> None:
    """The index read from the source names every registered command and its module, no more.

    Reference: Typer's own registry after importing every command module (the slow path).
    A module whose decorators the scan cannot read would be imported on every invocation
    (correct but slow): none may be.
    """
    index = command_index()
    assert index.always == (), f"commands not readable from the source in {index.always}"
    assert dict(index.commands) == _registered()


# ---- fast path against full load, in a child interpreter ---------------------------------


def _fresh_cli() -> Any:
    """`glideplan.cli.app` imported anew: no command module registered yet."""
    for name in [m for m in sys.modules if m == "glideplan.cli" or m.startswith("glideplan.cli.")]:
        del sys.modules[name]
    return importlib.import_module("glideplan.cli.app")


def _run(module: Any, argv: list[str]) -> dict[str, Any]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = module.main(argv)
    return {"code": code, "out": out.getvalue(), "err": err.getvalue()}


def _loaded_commands(modules: tuple[str, ...]) -> list[str]:
    return sorted(m for m in modules if f"glideplan.cli.{m}" in sys.modules)


def _probe() -> dict[str, Any]:
    """Run in the child: fast-path and full-load results of the command lines to compare."""
    module = _fresh_cli()
    index = module.command_index()
    report: dict[str, Any] = {"modules": list(index.modules), "lines": {}}
    dubins = ["plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--json"]
    result = _run(module, dubins)
    result["loaded"] = _loaded_commands(index.modules)
    result["pydantic"] = "pydantic" in sys.modules
    report["dubins"] = result
    lines = [[*path, "--help"] for path in index.commands]
    lines += [[group] for group in sorted(index.groups)]
    lines += [[group, "--help"] for group in sorted(index.groups)]
    lines += [[], ["--help"], ["fly-me"], ["plan", "dubinz"], ["--debug", "plan", "dubins"]]
    for argv in lines:
        module = _fresh_cli()
        fast = _run(module, argv)
        fast["loaded"] = _loaded_commands(index.modules)
        report["lines"][" ".join(argv)] = {"fast": fast}
    module = _fresh_cli()
    module.load_commands()
    for argv in lines:
        report["lines"][" ".join(argv)]["full"] = _run(module, argv)
    return report


@pytest.fixture(scope="module")
def probe() -> dict[str, Any]:
    env = {**os.environ, "COLUMNS": "100", "MPLBACKEND": "Agg"}
    done = subprocess.run(
        [sys.executable, str(pathlib.Path(__file__).resolve())],
        capture_output=True,
        text=True,
        timeout=300,
        env=env,
        check=False,
    )
    assert done.returncode == 0, done.stderr
    return dict(json.loads(done.stdout))


def test_plan_dubins_loads_one_module_and_no_pydantic(probe: dict[str, Any]) -> None:
    """The issue's timed command imports only `plan_dubins` and never Pydantic, and works."""
    result = probe["dubins"]
    assert result["code"] == 0, result["err"]
    assert json.loads(result["out"])["status"] == "solved"
    assert result["loaded"] == ["plan_dubins"]
    assert result["pydantic"] is False


def test_every_command_help_is_the_same_through_the_fast_path(probe: dict[str, Any]) -> None:
    """`--help` of every command, group, the root, and usage errors: fast path == full load.

    Reference: the same command line after importing every command module. A command's own
    help imports fewer modules than there are (only its own, plus any it imports).
    """
    n_modules = len(probe["modules"])
    assert len(probe["lines"]) >= 24 + 3
    for line, got in probe["lines"].items():
        fast, full = got["fast"], got["full"]
        assert (fast["code"], fast["out"], fast["err"]) == (
            full["code"],
            full["out"],
            full["err"],
        ), line
        assert fast["out"] or fast["err"], line
        words = line.split()
        if len(words) == 3 and words[0] in ("plan", "design", "glide", "map"):
            assert len(fast["loaded"]) < n_modules, line
    assert probe["lines"]["--help"]["fast"]["loaded"] == sorted(probe["modules"])
    assert "No such command" in probe["lines"]["fly-me"]["fast"]["err"]


# ---- plain option values without Pydantic -------------------------------------------------

_probe_app = typer.Typer(add_completion=False)


@_probe_app.command()
def _values(
    f: Annotated[float, typer.Option("--f")] = 0.0,
    i: Annotated[int, typer.Option("--i")] = 0,
    s: Annotated[str, typer.Option("--s")] = "",
    p: Annotated[pathlib.Path, typer.Option("--p")] = pathlib.Path("out"),
    t: Annotated[tuple[float, float, float], typer.Option("--t")] = (0.0, 0.0, 0.0),
    v: Annotated[list[float] | None, typer.Option("--v")] = None,
    b: Annotated[bool, typer.Option("--b")] = False,
) -> dict[str, Any]:
    return {"f": f, "i": i, "s": s, "p": p, "t": t, "v": v, "b": b}


PLAIN = [
    ["--f", "1"], ["--f", "-3.5e2"], ["--f", ".5"], ["--f", "5."], ["--f", "1e400"],
    ["--i", "3"], ["--i", "-0"], ["--i", "007"], ["--s", "word"], ["--s", ""],
    ["--p", "a.txt"], ["--p", ""], ["--p", "-"], ["--t", "1", "-2", "3.5"],
    ["--v", "1", "--v", "2"], ["--b"], [],
]  # fmt: skip
OTHER = [
    ["--f", "nan"], ["--f", "inf"], ["--f", "1_0"], ["--f", "wide"], ["--f", ""],
    ["--f", "\u0661"], ["--f", " 2"], ["--f", "0x10"], ["--i", "3.0"], ["--i", "3.5"],
    ["--i", "1_000"], ["--i", "x"], ["--i", "1e3"], ["--i", "\u0663"], ["--t", "1", "x", "3"],
    ["--v", "a"],
]  # fmt: skip


def _invoke(argv: list[str], fast: bool) -> tuple[str, Any]:
    command = typer.main.get_command(_probe_app)
    if fast:
        _coerce.fast_coercion(command)
    try:
        result = command.main(args=argv, prog_name="probe", standalone_mode=False)
    except click_exc.BadParameter as exc:
        return "error", exc.format_message()
    return "value", repr(result)


@pytest.mark.parametrize("argv", PLAIN + OTHER, ids=" ".join)
def test_fast_conversion_gives_typers_values_and_messages(argv: list[str]) -> None:
    """Values and error messages equal Typer's own (Pydantic) converter's, for plain values
    (converted without Pydantic) and for the others (handed to Typer's converter)."""
    assert _invoke(argv, fast=True) == _invoke(argv, fast=False)


def test_plain_values_do_not_reach_typers_converter() -> None:
    """Plain values are converted by the fast converter itself, the others by Typer's."""
    for argv, plain in [(a, True) for a in PLAIN] + [(a, False) for a in OTHER]:
        command = typer.main.get_command(_probe_app)
        assert _coerce.fast_coercion(command) == 7
        with contextlib.suppress(click_exc.BadParameter):
            command.main(args=argv, prog_name="probe", standalone_mode=False)
        used_typer = any(p._runtime_param._typer for p in command.params)  # type: ignore[attr-defined]
        assert used_typer is not plain, argv


if __name__ == "__main__":
    print(json.dumps(_probe()))
