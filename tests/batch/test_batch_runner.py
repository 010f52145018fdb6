"""The batch runner: in-process, local process pool, Dask distributed; order, errors, chunks."""

import time

import numpy as np
import pytest

from glideplan.batch import chunk_slices, map_chunks, run_batch
from glideplan.errors import InvalidParameterError


def _square(x):
    return x * x


def _fail_on_three(x):
    if x == 3:
        raise KeyError(f"item {x}")
    return x


def _slow_square(x):
    time.sleep(0.15)
    return x * x


def _norms(a, b):
    return np.hypot(a, b), a + b


@pytest.mark.parametrize("processes", [1, 2])
def test_results_in_item_order(processes):
    assert run_batch(_square, range(23), processes=processes, progress=False) == [
        i * i for i in range(23)
    ]


def test_in_process_accepts_closures_and_empty_input():
    offset = 5
    assert run_batch(lambda x: x + offset, [1, 2], processes=1) == [6, 7]
    assert run_batch(_square, [], processes=2) == []


@pytest.mark.parametrize("processes", [1, 2])
def test_exception_propagates_with_item_index(processes):
    with pytest.raises(KeyError, match="item 3") as info:
        run_batch(_fail_on_three, range(8), processes=processes, progress=False)
    assert info.value.batch_index == 3
    assert any("batch item 3" in n for n in info.value.__notes__)


def test_progress_bar_on_stderr_for_jobs_over_a_second(capsys):
    out = run_batch(_slow_square, range(10), processes=1, progress=True, description="squares")
    assert out == [i * i for i in range(10)]
    err = capsys.readouterr().err
    assert "squares" in err and "10/10" in err


def test_no_progress_bar_for_quick_jobs(capsys):
    run_batch(_square, range(10), processes=1, progress=True, description="quick")
    assert "quick" not in capsys.readouterr().err


def test_dask_distributed_cluster():
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(
        n_workers=1, processes=False, threads_per_worker=2, dashboard_address=None
    ) as cluster:
        address = cluster.scheduler_address
        assert run_batch(_square, range(12), scheduler=address, progress=False) == [
            i * i for i in range(12)
        ]
        with pytest.raises(KeyError) as info:
            run_batch(_fail_on_three, range(6), scheduler=address, progress=False)
        assert info.value.batch_index == 3
        with distributed.Client(address) as client:
            assert run_batch(_square, [4], scheduler=client) == [16]


@pytest.mark.parametrize("processes", [0, -1, 1.5, True, "2"])
def test_bad_processes(processes):
    with pytest.raises(InvalidParameterError, match="processes"):
        run_batch(_square, [1], processes=processes)


def test_bad_scheduler_address():
    with pytest.raises(InvalidParameterError, match="scheduler"):
        run_batch(_square, [1], scheduler="  ")


def test_chunk_slices_cover_the_range():
    s = chunk_slices(10, 4)
    assert [(a.start, a.stop) for a in s] == [(0, 4), (4, 8), (8, 10)]
    assert chunk_slices(0, 3) == []
    for bad in (0, -2, 2.0):
        with pytest.raises(InvalidParameterError, match="chunk_size"):
            chunk_slices(5, bad)
    with pytest.raises(InvalidParameterError, match="n"):
        chunk_slices(-1, 2)


@pytest.mark.parametrize("processes", [1, 2])
def test_map_chunks_equals_one_call(processes):
    rng = np.random.default_rng(0)
    a, b = rng.normal(size=1001), rng.normal(size=1001)
    h, s = map_chunks(_norms, [a, b], chunk_size=100, processes=processes, progress=False)
    np.testing.assert_array_equal(h, np.hypot(a, b))
    np.testing.assert_array_equal(s, a + b)
    single = map_chunks(np.negative, [a], chunk_size=64, processes=1)
    np.testing.assert_array_equal(single, -a)


def test_map_chunks_rejects_mismatched_arrays():
    with pytest.raises(InvalidParameterError, match="arrays"):
        map_chunks(_norms, [np.zeros(3), np.zeros(4)])
    with pytest.raises(InvalidParameterError, match="arrays"):
        map_chunks(_norms, [])
