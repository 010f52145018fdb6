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


def _fly_linear_controls(path):
    """The end pose (x, y, heading) of `path` flown exactly along its controls, for segments
    whose controls are linear between their breakpoints (direct-method `Sampled` paths).

    Between two breakpoints u is linear, so the heading is an exact quadratic in t, and the
    position increments integral(v cos psi), integral(v sin psi) are taken by 16-point
    Gauss-Legendre quadrature on each interval (a smooth integrand over an interval where
    psi changes by ~0.01 rad: error ~1e-15 relative). The linearity is asserted at the
    quadrature points. Independent of `glideplan.verify`, whose single DOP853 pass over
    hundreds of control kinks is ~1e-6 m off on a 2 km path."""
    from glideplan.pose import Pose

    nodes, weights = np.polynomial.legendre.leggauss(16)
    tau = 0.5 * (nodes + 1.0)
    x, y, psi = path.start.x, path.start.y, path.start.heading
    for seg in path.segments:
        t = np.asarray(seg.breakpoints(), dtype=float)
        v, u = seg.controls(t)
        h = np.diff(t)
        a, v0, v1, u0, u1 = t[:-1], v[:-1], v[1:], u[:-1], u[1:]
        tq = a[:, None] + h[:, None] * tau
        vq, uq = seg.controls(tq.ravel())
        vl = v0[:, None] + (v1 - v0)[:, None] * tau
        ul = u0[:, None] + (u1 - u0)[:, None] * tau
        scale = 1e-12 * max(1.0, float(np.max(np.abs(v))), float(np.max(np.abs(u))))
        assert np.allclose(vq.reshape(tq.shape), vl, rtol=0, atol=scale)
        assert np.allclose(uq.reshape(tq.shape), ul, rtol=0, atol=scale)
        dpsi = 0.5 * h * (u0 + u1)
        psi_a = psi + np.concatenate([[0.0], np.cumsum(dpsi)[:-1]])
        du = (u1 - u0)[:, None]
        psi_q = psi_a[:, None] + h[:, None] * (u0[:, None] * tau + 0.5 * du * tau**2)
        x += float(np.sum(0.5 * h * ((vl * np.cos(psi_q)) @ weights)))
        y += float(np.sum(0.5 * h * ((vl * np.sin(psi_q)) @ weights)))
        psi += float(np.sum(dpsi))
    return Pose(x, y, psi)


@pytest.fixture
def fly_linear_controls():
    """`fly_linear_controls(path) -> Pose`: the end of a direct-method path flown exactly
    along its piecewise-linear controls (see `_fly_linear_controls`)."""
    return _fly_linear_controls


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
        by_dir: dict[str, float] = collections.defaultdict(float)
        for nodeid, sec in _CPU_SECONDS.items():
            parts = nodeid.split("::")[0].split("/")
            by_dir["/".join(parts[:2]) if len(parts) > 2 else parts[0]] += sec
        write = terminalreporter.write_line
        write(f"CPU seconds in this process: {sum(by_dir.values()):.1f}")
        for name, sec in sorted(by_dir.items(), key=lambda kv: -kv[1]):
            write(f"  {sec:7.2f}  {name}")
        write("slowest tests (CPU seconds):")
        for nodeid, sec in sorted(_CPU_SECONDS.items(), key=lambda kv: -kv[1])[:25]:
            write(f"  {sec:7.2f}  {nodeid}")
