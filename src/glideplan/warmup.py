"""Compile every numba kernel once, so that the first real call does not wait for it.

glideplan's compiled kernels (Dubins lengths and the mission DP, the chapter 4-6 syntheses,
the routing front and its Zermelo shooting, glide reach at the DEM's resolution) are compiled
on first use and cached on disk (`cache=True`, next to their modules). A fresh install pays
~35-50 s of compilation spread over its first calls; `glideplan warm-up` pays it once, up
front, by running one small case of each product through the CLI. `make test` runs it beside
`mypy` (one core each) so the test workers load the kernels from the cache.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from importlib import resources

__all__ = ["WARM_UP_CASES", "WarmUpCase", "warm_up"]


@dataclass(frozen=True)
class WarmUpCase:
    """One small CLI run that compiles the kernels named in `kernels`."""

    kernels: str
    args: tuple[str, ...]


def _mission_file() -> str:
    return str(resources.files("glideplan.missions") / "data" / "buzzards_bay.gpx")


WARM_UP_CASES: tuple[WarmUpCase, ...] = (  # the longest compilations first
    WarmUpCase("chapter 6 synthesis", ("plan", "load-factor", "--goal", "1.1", "2", "0",
                                       "--method", "synthesis", "--json")),
    WarmUpCase("mission heading DP", ("mission", "plan", "@mission", "--speed", "0.3",
                                      "--radius", "150")),
    WarmUpCase("routing front", ("route", "--example", "double-gyre", "--from", "30.45",
                                 "-39.8", "--to", "30.45", "-38.2", "--speed", "0.5", "--json")),
    WarmUpCase("glide reach (native grid)", ("glide", "reach", "--example", "ridge", "--json")),
    WarmUpCase("chapter 5 synthesis", ("plan", "min-altitude", "--vehicle", "dg1001m", "--goal",
                                       "0", "1", "120", "--normalized", "--json")),
    WarmUpCase("turn-back search", ("glide", "turnback", "--example", "ridge")),
    WarmUpCase("chapter 4 synthesis", ("plan", "time-optimal", "--goal", "0", "2", "120",
                                       "--v-min", "0.3", "--v-max", "1", "--u-max", "1")),
)  # `plan wind` and `plan dubins` compile nothing (NumPy paths: cold CPU = warm CPU)


# The CLI with numba loaded first: planners that keep a one-off call on NumPy (the chapter 4
# synthesis, for a fast `glideplan plan` start) take their compiled path when numba is loaded.
_LAUNCH = "import sys, numba; from glideplan.cli.app import main; sys.exit(main(sys.argv[1:]))"


def _run(case: WarmUpCase) -> tuple[str, float, int]:
    args = [_mission_file() if a == "@mission" else a for a in case.args]
    env = dict(os.environ, MPLBACKEND="Agg", NUMBA_NUM_THREADS="1")
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", _LAUNCH, *args], env=env,
                          stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=False)
    return case.kernels, time.perf_counter() - t0, proc.returncode


def warm_up(cases: Sequence[WarmUpCase] = WARM_UP_CASES, jobs: int = 1
            ) -> list[tuple[str, float, int]]:
    """Run each case in a fresh `glideplan` process (numba loaded first), `jobs` at a time
    (the longest compilations first, in the order of `cases`); (kernels, seconds, exit code).

    A case that fails (exit code != 0) costs only its own compilation: it is reported, never
    raised, since the kernels it did reach are cached all the same.
    """
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        return list(pool.map(_run, cases))
