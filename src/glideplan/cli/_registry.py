"""Which command module defines which command, read from the modules' source without importing.

The CLI starts faster when an invocation imports only the module that defines its command
(`glideplan plan dubins ...` needs `plan_dubins.py`, not the study or mission modules and their
libraries). The index is derived from the decorators themselves, `@<typer>.command("name")` or
`@<typer>.command()` above `def name(...)`, so it cannot drift from the code: a module whose
commands the scan cannot read (another decorator form, a sub-app of its own) is imported on
every invocation, which is slower but still correct. A test checks that the scan finds every
command that the full import registers, in the module that registers it.
"""

from __future__ import annotations

import pathlib
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

# `@obj.command(` then optionally a quoted name as first argument (possibly on the next line).
_DECORATOR = re.compile(
    r"^@(?P<obj>\w+)\.command\(\s*(?:(?P<q>[\"'])(?P<name>[^\"']+)(?P=q))?", re.M
)
_DEF_AFTER = re.compile(r"\)\s*\n(?:@.*\n)*def (?P<func>\w+)\(")
_SUBAPP = ("add_typer(", "Typer(")  # a module with a sub-app of its own: imported every time

ALL = None  # `modules_for` result meaning "import every command module"


@dataclass(frozen=True)
class CommandIndex:
    """Command paths (`("plan", "dubins")`, `("route",)`) -> defining module, from the source.

    `groups` are the sub-app names (`plan`, `mission`, ...); `always` the modules whose
    commands could not be read (imported on every invocation); `modules` every command module.
    """

    commands: Mapping[tuple[str, ...], str]
    groups: frozenset[str]
    always: tuple[str, ...]
    modules: tuple[str, ...]


def command_modules(package_dir: pathlib.Path, skip: frozenset[str]) -> list[str]:
    """Names of the command modules in `package_dir` (not private, not in `skip`), sorted."""
    return sorted(
        p.stem
        for p in package_dir.glob("*.py")
        if not p.stem.startswith("_") and p.stem not in skip
    )


def _scan_source(source: str, group_of: Mapping[str, str | None]) -> list[tuple[str, ...]] | None:
    """Command paths that `source` registers, or None when some registration cannot be read."""
    if any(marker in source for marker in _SUBAPP):
        return None
    found: list[tuple[str, ...]] = []
    for match in _DECORATOR.finditer(source):
        obj = match.group("obj")
        if obj not in group_of:
            return None
        name = match.group("name")
        if name is None:  # `@app.command()` or keyword arguments only: name from the function
            rest = source[match.end() :]
            if not rest.lstrip().startswith(")"):
                return None
            func = _DEF_AFTER.match(rest.lstrip())
            if func is None:
                return None
            name = func.group("func").replace("_", "-")
        group = group_of[obj]
        found.append((name,) if group is None else (group, name))
    return found


def build_index(
    package_dir: pathlib.Path, skip: frozenset[str], group_of: Mapping[str, str | None]
) -> CommandIndex:
    """Scan the command modules of `package_dir`.

    `group_of` maps the name of each Typer object defined in `app.py` to its group name
    (`"plan_app" -> "plan"`), and the root application to None (`"app" -> None`).
    """
    modules = command_modules(package_dir, skip)
    commands: dict[tuple[str, ...], str] = {}
    always: list[str] = []
    for module in modules:
        source = (package_dir / f"{module}.py").read_text(encoding="utf-8")
        paths = _scan_source(source, group_of)
        if paths is None:
            always.append(module)
            continue
        for path in paths:
            commands[path] = module
    groups = frozenset(g for g in group_of.values() if g is not None)
    return CommandIndex(commands, groups, tuple(always), tuple(modules))


def modules_for(
    argv: Sequence[str], index: CommandIndex, global_flags: frozenset[str]
) -> list[str] | None:
    """The modules that `argv` needs, or `ALL` (None) for help, no command or an unknown one.

    The first word that is not a global flag names a top-level command or a group; after a
    group, the next word names its command. `glideplan plan --help` loads the whole group so
    that its help lists every command.
    """
    words = [a for a in argv if a not in global_flags]
    if not words or words[0].startswith("-"):
        return ALL
    first = words[0]
    if first in index.groups:
        if len(words) < 2 or words[1].startswith("-"):
            group = sorted({m for path, m in index.commands.items() if path[0] == first})
            return [*group, *index.always]
        module = index.commands.get((first, words[1]))
    else:
        module = index.commands.get((first,))
    if module is None:
        return ALL
    return [module, *index.always]
