"""Option values converted without Pydantic for the plain cases (start-up time).

Typer 0.29 converts every option value through a Pydantic `TypeAdapter`, and importing Pydantic
costs about as much as importing NumPy. Most values on a glideplan command line are plain
numbers, words, flags and file names: `fast_coercion(command)` gives each parameter of
`command` whose type is `bool`, `float`, `int`, `str` or `pathlib.Path` (or a tuple or list of
them) and whose settings are plain (no range, choices, parser, `exists=True`...) a converter
that handles a plain value itself (`12`, `-3.5e2`, a flag, a file name, with Typer's own path
checks) and hands anything else (`nan`, `1_000`, `wide`, ...) to Typer's own converter, built
only then, so results and error messages are Typer's (checked in tests/cli/test_fast_start.py).
"""

from __future__ import annotations

import functools
import pathlib
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, get_args, get_origin

_PLAIN_FLOAT = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?", re.ASCII)
_PLAIN_INT = re.compile(r"[+-]?\d+", re.ASCII)


PathCheck = Callable[[pathlib.Path], Any]


class _NotPlain(Exception):
    """The value needs Typer's own converter."""


def _to_float(value: Any, check_path: PathCheck) -> float:
    if isinstance(value, str) and _PLAIN_FLOAT.fullmatch(value):
        return float(value)
    if type(value) in (int, float):
        return float(value)
    raise _NotPlain


def _to_int(value: Any, check_path: PathCheck) -> int:
    if isinstance(value, str) and _PLAIN_INT.fullmatch(value):
        return int(value)
    if type(value) is int:
        return int(value)
    raise _NotPlain


def _to_bool(value: Any, check_path: PathCheck) -> bool:
    if type(value) is bool:  # a flag; words such as "yes" go to Typer
        return value
    raise _NotPlain


def _to_str(value: Any, check_path: PathCheck) -> str:
    if isinstance(value, str):
        return value
    raise _NotPlain


def _to_path(value: Any, check_path: PathCheck) -> Any:
    if isinstance(value, (str, pathlib.Path)):
        return check_path(pathlib.Path(value))  # Typer's checks (readable, file or folder)
    raise _NotPlain


Convert = Callable[[Any, PathCheck], Any]
_LEAF: dict[Any, Convert] = {
    bool: _to_bool,
    float: _to_float,
    int: _to_int,
    str: _to_str,
    pathlib.Path: _to_path,
}


def _converter(annotation: Any) -> Convert | None:
    """A converter of plain values of `annotation`, or None where Typer's is always used."""
    if annotation in _LEAF:
        return _LEAF[annotation]
    args = get_args(annotation)
    if get_origin(annotation) is tuple and args and Ellipsis not in args:
        leaves = [_LEAF.get(a) for a in args]
        if any(leaf is None for leaf in leaves):
            return None
        arity = len(args)

        def to_tuple(value: Any, check_path: PathCheck) -> tuple[Any, ...]:
            if not isinstance(value, (list, tuple)) or len(value) != arity:
                raise _NotPlain
            pairs = zip(leaves, value, strict=True)
            return tuple(leaf(item, check_path) for leaf, item in pairs)  # type: ignore[misc]

        return to_tuple
    if get_origin(annotation) is list and len(args) == 1 and args[0] in _LEAF:
        leaf = _LEAF[args[0]]

        def to_list(value: Any, check_path: PathCheck) -> list[Any]:
            if not isinstance(value, (list, tuple)):
                raise _NotPlain
            return [leaf(item, check_path) for item in value]

        return to_list
    return None


def _plain_parameter_info(info: Any) -> bool:
    """No option setting that changes the conversion (parser, range, path checks...)."""
    if getattr(info, "parser", None) is not None or getattr(info, "click_type", None) is not None:
        return False
    if getattr(info, "min", None) is not None or getattr(info, "max", None) is not None:
        return False
    if getattr(info, "path_type", None) is not None:
        return False
    path_checks = ("exists", "writable", "resolve_path", "allow_dash")
    return not any(getattr(info, name, False) for name in path_checks)


@functools.cache
def _runtime_param_class() -> type | None:
    """Typer's `RuntimeParam` base class, or None if this Typer has none (no fast path)."""
    try:
        from typer._coercion import RuntimeParam, build_runtime_param
        from typer._param_types import coerce_cli_path
    except ImportError:  # pragma: no cover - another Typer version: Typer converts everything
        return None

    @dataclass(frozen=True)
    class FastRuntimeParam(RuntimeParam):
        """Plain values converted here, any other value by Typer's converter (built once)."""

        convert: Convert = field(default=lambda value, check_path: value)
        descriptor: Any = None
        _typer: list[Any] = field(default_factory=list)

        def _coerce_value(self, value: Any, param: Any, ctx: Any) -> Any:
            def check_path(path: pathlib.Path) -> Any:
                info = self.parameter_info
                return coerce_cli_path(path, info, path_type=pathlib.Path, param=param, ctx=ctx)

            try:
                return self.convert(value, check_path)
            except _NotPlain:
                pass
            if not self._typer:
                self._typer.append(build_runtime_param(self.descriptor))
            return self._typer[0]._coerce_value(value, param=param, ctx=ctx)

    return FastRuntimeParam


def fast_param(param: Any) -> bool:
    """Give `param` the fast converter if its type and settings are plain; say if it got it.

    A parameter that already has a converter, or whose type or settings are not plain
    (choices, ranges, `exists=True`, ...), keeps Typer's.
    """
    descriptor = getattr(param, "type_descriptor", None)
    if descriptor is None or getattr(param, "_runtime_param", "absent") is not None:
        return False
    if descriptor.file_annotation is not None:
        return False
    convert = _converter(descriptor.annotation)
    if convert is None or not _plain_parameter_info(descriptor.parameter_info):
        return False
    cls = _runtime_param_class()
    if cls is None:
        return False
    param._runtime_param = cls(
        parameter_info=descriptor.parameter_info,
        annotation=descriptor.annotation,
        convert=convert,
        descriptor=descriptor,
    )
    return True


def fast_coercion(command: Any) -> int:
    """Give the plain parameters of `command` and its subcommands the fast converter.

    Returns how many parameters got it (see `fast_param`).
    """
    count = 0
    stack = [command]
    while stack:
        cmd = stack.pop()
        stack.extend(getattr(cmd, "commands", {}).values())
        count += sum(fast_param(param) for param in cmd.params)
    return count
