"""Shared test configuration and fixtures.

Strict numerics, a non-interactive Matplotlib backend, and helpers that run the real CLI
entry point (`glideplan.cli.app.main`) and check its one-line errors.
"""

import os

import numpy as np
import pytest
from hypothesis import settings

os.environ.setdefault("MPLBACKEND", "Agg")

# CI is reproducible (the same examples every run); local runs keep exploring new ones.
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

ERROR_PREFIX = "glideplan: error:"


@pytest.fixture(autouse=True)
def _strict_numpy():
    """Floating-point warnings (overflow, invalid, divide) are errors in every test."""
    with np.errstate(all="raise", under="ignore"):
        yield


@pytest.fixture
def run_cli(capsys):
    """Run `glideplan ARGS...` in-process; `run_cli(*args)` returns (exit code, stdout, stderr)."""
    from glideplan.cli.app import main

    def run(*args: str) -> tuple[int, str, str]:
        code = main(list(args))
        out, err = capsys.readouterr()
        return code, out, err

    return run


def _error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(ERROR_PREFIX), err
    assert "Traceback" not in err
    return lines[0]


@pytest.fixture
def error_line():
    """`error_line(stderr)`: assert one `glideplan: error:` line and no traceback; return it."""
    return _error_line


@pytest.fixture
def cli_error(run_cli):
    """`cli_error(*args, code=2)`: run the CLI, expect exit `code` and one error line; return it."""

    def run(*args: str, code: int = 2) -> str:
        got, _, err = run_cli(*args)
        assert got == code, err
        return _error_line(err)

    return run
