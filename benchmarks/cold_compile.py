"""Cold numba compilation per warm-up case: what a fresh clone pays before its first answers.

Each case of `glideplan warm-up` (glideplan/warmup.py) runs in a fresh process twice: first with
an empty NUMBA_CACHE_DIR (cold: every kernel it reaches is compiled), then again on the cache it
just wrote (warm: the kernels are loaded). The difference in process CPU time is that case's
compilation. With `--kernels`, numba's compile events name the kernels that took longest (the
exclusive time of each dispatcher: its own compilation, without the kernels it compiled inside).

    python benchmarks/cold_compile.py [--only WORD] [--kernels N]

Measures CPU time (user + sys of the child), so another process on the machine changes it
little; the wall time is printed beside it.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

# A child process: the warm-up's launcher (numba loaded first, then the CLI) with a recorder of
# numba's compile events, written as JSON to the path in argv[1].
_CHILD = r"""
import json, sys, time
import numba
from numba.core import event
records = []
class L(event.Listener):
    def on_start(self, ev):
        records.append((time.perf_counter(), 1, ev.data.get("dispatcher")))
    def on_end(self, ev):
        records.append((time.perf_counter(), -1, ev.data.get("dispatcher")))
event.register("numba:compile", L())
out = sys.argv[1]
from glideplan.cli.app import main
try:
    code = main(sys.argv[2:])
except SystemExit as e:
    code = e.code
stack, excl = [], {}
for t, kind, disp in records:
    name = getattr(getattr(disp, "py_func", None), "__qualname__", str(disp))
    mod = getattr(getattr(disp, "py_func", None), "__module__", "")
    key = f"{mod}.{name}"
    if kind == 1:
        stack.append([key, t, 0.0])
    else:
        k, t0, child = stack.pop()
        excl[k] = excl.get(k, 0.0) + (t - t0) - child
        if stack:
            stack[-1][2] += t - t0
json.dump({"code": code, "kernels": excl}, open(out, "w"))
"""


def _run(args: list[str], cache: str) -> tuple[float, float, dict]:
    """(CPU s, wall s, {code, kernels}) of one CLI run in a fresh process on `cache`."""
    env = dict(os.environ, MPLBACKEND="Agg", NUMBA_NUM_THREADS="1", NUMBA_CACHE_DIR=cache)
    with tempfile.NamedTemporaryFile(suffix=".json") as out:
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-c", _CHILD, out.name, *args], env=env,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
        wall = time.perf_counter() - t0
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
        try:
            data = json.load(open(out.name))
        except ValueError:
            data = {"code": "?", "kernels": {}}
    return cpu, wall, data


def main() -> None:
    """Print cold and warm CPU per warm-up case, and the slowest kernels with `--kernels`."""
    from glideplan.warmup import WARM_UP_CASES, _mission_file

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="", help="only the cases whose name contains this")
    parser.add_argument("--kernels", type=int, default=0, help="list the N slowest kernels")
    opts = parser.parse_args()
    print(f"load {os.getloadavg()[0]:.1f}")
    print(f"{'case':28s} {'cold CPU':>9s} {'warm CPU':>9s} {'compile':>8s} {'cold wall':>9s}")
    total = 0.0
    for case in WARM_UP_CASES:
        if opts.only not in case.kernels:
            continue
        args = [_mission_file() if a == "@mission" else a for a in case.args]
        with tempfile.TemporaryDirectory() as cache:
            cold, wall, data = _run(args, cache)
            warm, _, _ = _run(args, cache)
        total += cold - warm
        print(f"{case.kernels:28s} {cold:8.1f}s {warm:8.1f}s {cold - warm:7.1f}s {wall:8.1f}s"
              f"  exit {data['code']}", flush=True)
        for name, sec in sorted(data["kernels"].items(), key=lambda kv: -kv[1])[:opts.kernels]:
            print(f"    {sec:6.2f}s  {name}")
    print(f"{'total compile':28s} {'':9s} {'':9s} {total:7.1f}s")


if __name__ == "__main__":
    main()
