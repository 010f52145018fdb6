"""Shared test configuration and fixtures.

Strict numerics, a non-interactive Matplotlib backend, and helpers that run the real CLI
entry point (`glideplan.cli.app.main`) and check its one-line errors.
"""

import collections
import os
import time

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


# GLIDEPLAN_CPU_DURATIONS=1 pytest ... -p no:xdist: per-test CPU seconds of this process
# (setup + call + teardown), summed per directory, at the end of the run. On a machine
# shared with other jobs the wall-clock `--durations` inflate; CPU time much less. Work done
# in subprocesses or worker processes (examples, the batch runner) is not counted.
_CPU_SECONDS: dict[str, float] = {}


if os.environ.get("GLIDEPLAN_CPU_DURATIONS"):

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(item, nextitem):
        t0 = time.process_time()
        yield
        _CPU_SECONDS[item.nodeid] = time.process_time() - t0

    def pytest_terminal_summary(terminalreporter):
        by_dir: collections.Counter[str] = collections.Counter()
        for nodeid, sec in _CPU_SECONDS.items():
            parts = nodeid.split("::")[0].split("/")
            by_dir["/".join(parts[:2]) if len(parts) > 2 else parts[0]] += sec
        write = terminalreporter.write_line
        write(f"CPU seconds in this process: {sum(by_dir.values()):.1f}")
        for name, sec in by_dir.most_common():
            write(f"  {sec:7.2f}  {name}")
        write("slowest tests (CPU seconds):")
        for nodeid, sec in sorted(_CPU_SECONDS.items(), key=lambda kv: -kv[1])[:25]:
            write(f"  {sec:7.2f}  {nodeid}")
