"""Compiled kernels shared by threads (`glideplan.compute`): same answers, no abort, cancelling.

Reference for every duration: the same `route()` call made alone, one at a time, in the same
process (the kernels are deterministic node by node, so the answers must agree to the last bit).
"""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import threading
from importlib import metadata

import pytest

from glideplan.compute import ComputationCancelled, cancel_scope, checkpoint, threading_layer
from glideplan.fields import double_gyre
from glideplan.routing import route

PAIRS = [((30.1, -39.9), (30.5, -39.2)), ((30.5, -39.9), (30.1, -39.2)),
         ((30.2, -39.8), (30.4, -39.1)), ((30.3, -39.95), (30.3, -39.1))]
CELLS = 40


def _durations_in_threads(pairs):
    field = double_gyre()
    out: list[float | None] = [None] * len(pairs)
    errors: list[BaseException] = []
    start = threading.Barrier(len(pairs))

    def work(i):
        try:
            start.wait()
            out[i] = route(field, *pairs[i], 0.3, cells=CELLS).duration_s
        except BaseException as exc:  # reported below, not lost in the thread
            errors.append(exc)

    threads = [threading.Thread(target=work, args=(i,)) for i in range(len(pairs))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors
    return out


def test_route_from_four_threads_equals_one_at_a_time():
    field = double_gyre()
    alone = [route(field, a, b, 0.3, cells=CELLS).duration_s for a, b in PAIRS]
    assert _durations_in_threads(PAIRS) == alone


@pytest.mark.heavy  # make validate: a subprocess compiling the kernels cold
def test_workqueue_layer_is_serialised_not_aborted():
    """Without TBB numba's work queue aborts the process on concurrent launches (SIGABRT,
    "Concurrent access has been detected"); `kernel_section` must serialise them."""
    code = textwrap.dedent(f"""
        import threading
        from glideplan.compute import threading_layer
        from glideplan.fields import double_gyre
        from glideplan.routing import route
        pairs = {PAIRS!r}
        f = double_gyre()
        out = [None] * 4
        def w(i):
            out[i] = route(f, *pairs[i], 0.3, cells={CELLS}).duration_s
        ts = [threading.Thread(target=w, args=(i,)) for i in range(4)]
        [t.start() for t in ts]
        [t.join() for t in ts]
        alone = [route(f, a, b, 0.3, cells={CELLS}).duration_s for a, b in pairs]
        assert threading_layer() == "workqueue"
        print(out == alone)
    """)
    env = dict(os.environ, NUMBA_THREADING_LAYER="workqueue", NUMBA_NUM_THREADS="2")
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         timeout=300)
    assert res.returncode == 0, res.stderr[-2000:]
    assert res.stdout.strip() == "True"


def test_tbb_is_chosen_when_installed():
    try:
        metadata.version("tbb")
    except metadata.PackageNotFoundError:
        pytest.skip("the tbb wheel is not installed")
    if os.environ.get("NUMBA_THREADING_LAYER"):
        pytest.skip("the user's NUMBA_THREADING_LAYER wins")
    assert threading_layer() == "tbb"


def test_cancel_scope_stops_the_front_and_only_in_its_thread():
    field = double_gyre()
    steps = {"n": 0}

    def cancelled():
        steps["n"] += 1
        return steps["n"] > 5

    with cancel_scope(cancelled), pytest.raises(ComputationCancelled):
        route(field, *PAIRS[0], 0.3, cells=CELLS)
    assert steps["n"] == 6  # stopped at the first check that said so
    checkpoint()  # outside the scope: nothing to cancel
    # another thread's scope does not reach this one
    other = threading.Thread(target=lambda: None)
    with cancel_scope(lambda: True):
        other.start()
        other.join()
    assert route(field, *PAIRS[0], 0.3, cells=CELLS).ok
