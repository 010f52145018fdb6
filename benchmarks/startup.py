"""CLI start-up time: `glideplan plan dubins ... --json` against `python -c "import numpy"`.

Issue 11's target: the command runs within 2.5x of importing NumPy, measured in the same run.
The two commands alternate (`--runs` times each, after one warm-up of each) so that the load of
the machine affects both alike; the medians of the wall time and of the CPU time (user + system
of the child, from `resource.getrusage(RUSAGE_CHILDREN)`) are compared.

Python's bytecode cache matters here: with `PYTHONDONTWRITEBYTECODE=1` (set in some
development shells) every glideplan module is compiled from source on every run, while NumPy's
cache sits in site-packages. By default the runs use a bytecode cache in a temporary
`PYTHONPYCACHEPREFIX` (what an installed user has; the warm-up fills it, the source tree gets
no `__pycache__`); `--no-bytecode-cache` measures the environment as it is.

Peer figures: `python -c "import numpy"` is measured in this run (same interpreter, same
machine, interleaved). Nothing is quoted.
"""

from __future__ import annotations

import argparse
import os
import pathlib
import resource
import statistics
import subprocess
import sys
import tempfile
import time

TARGET_RATIO = 2.5
VENV_BIN = pathlib.Path(sys.executable).parent
GLIDEPLAN = [str(VENV_BIN / "glideplan")]
COMMAND = ["plan", "dubins", "--goal", "4", "3", "90", "--radius", "1", "--json"]
BASELINE = [sys.executable, "-c", "import numpy"]


def _time_once(argv: list[str], env: dict[str, str]) -> tuple[float, float]:
    """Wall time and CPU time (user + system, s) of one run of `argv`; raises if it fails."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(argv, check=True, stdout=subprocess.DEVNULL, env=env)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return wall, cpu


def measure(runs: int, command: list[str], env: dict[str, str]) -> dict[str, dict[str, float]]:
    """Medians (s) of wall and CPU time of the CLI command and of the NumPy import, interleaved."""
    cli = GLIDEPLAN + command
    _time_once(cli, env)
    _time_once(BASELINE, env)
    samples: dict[str, list[tuple[float, float]]] = {"glideplan": [], "numpy": []}
    for _ in range(runs):
        samples["glideplan"].append(_time_once(cli, env))
        samples["numpy"].append(_time_once(BASELINE, env))
    return {
        name: {
            "wall": statistics.median(w for w, _ in rows),
            "cpu": statistics.median(c for _, c in rows),
        }
        for name, rows in samples.items()
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=15, help="runs of each command (default 15)")
    parser.add_argument(
        "--no-bytecode-cache",
        action="store_true",
        help="keep the environment's PYTHONDONTWRITEBYTECODE (compile glideplan every run)",
    )
    args = parser.parse_args()
    env = os.environ.copy()
    with tempfile.TemporaryDirectory(prefix="glideplan-pyc-") as cache:
        if not args.no_bytecode_cache:
            env.pop("PYTHONDONTWRITEBYTECODE", None)
            env["PYTHONPYCACHEPREFIX"] = cache
        medians = measure(args.runs, COMMAND, env)
    cli, ref = medians["glideplan"], medians["numpy"]
    mode = "no bytecode cache" if args.no_bytecode_cache else "bytecode cache in a temporary prefix"
    print(f"command: glideplan {' '.join(COMMAND)}; {args.runs} interleaved runs each; {mode}")
    print(f"{'':28s}{'wall median (s)':>17s}{'CPU median (s)':>16s}")
    label = 'python -c "import numpy"'
    print(f"{label:28s}{ref['wall']:17.3f}{ref['cpu']:16.3f}")
    print(f"{'glideplan plan dubins':28s}{cli['wall']:17.3f}{cli['cpu']:16.3f}")
    ratio_wall, ratio_cpu = cli["wall"] / ref["wall"], cli["cpu"] / ref["cpu"]
    print(f"{'ratio':28s}{ratio_wall:17.2f}{ratio_cpu:16.2f}")
    ok = ratio_wall <= TARGET_RATIO
    print(f"target: wall ratio <= {TARGET_RATIO}: {'PASS' if ok else 'FAIL'}")
    print('peer figures: `python -c "import numpy"` measured in this run (interleaved)')
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
