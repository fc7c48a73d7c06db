"""`eulerdisk.sweep`: the command line's sweep table, DataFrame-ready, resumable."""

import concurrent.futures
import multiprocessing
import time

import numpy as np
import pytest
from support import seconds_to_interrupt

import eulerdisk

SWEEP = {
    "name": "two-frictions",
    "scene": "tangent-toy",
    "keep": "none",
    "keys": ["transitions", "theta_period_first_s"],
    "set": {"run.t_end": 0.5},
    "axis": [{"key": "friction.mu_d", "values": [0.1, 0.15]}],
}


def test_a_sweep_gives_one_row_per_point_matching_single_runs(tmp_path):
    done = eulerdisk.sweep(SWEEP, jobs=2, out=tmp_path, progress=False)
    table = done.table
    assert done.points == 2 and done.ran == 2 and done.failed == 0 and done.skipped == 0
    assert table.rows == 2
    assert list(table["friction.mu_d"]) == [0.1, 0.15]
    assert list(table["status"]) == ["completed", "completed"]
    for mu_d, transitions in zip(table["friction.mu_d"], table["transitions"], strict=True):
        alone = eulerdisk.run(
            "tangent-toy", t_end=0.5, set={"friction.mu_d": float(mu_d)}, progress=False
        )
        assert transitions == alone.summary["transitions"]
    frame = done.to_pandas()
    assert {"run", "friction.mu_d", "transitions", "cpu_s"} <= set(frame.columns)
    assert (tmp_path / "sweep.csv").is_file()


def test_a_sweep_into_the_same_folder_resumes(tmp_path):
    eulerdisk.sweep(SWEEP, out=tmp_path, progress=False)
    again = eulerdisk.sweep(SWEEP, out=tmp_path, progress=False)
    assert again.ran == 0 and again.skipped == 2
    assert again.table.rows == 2


def test_a_sweep_without_a_folder_leaves_none():
    done = eulerdisk.sweep(SWEEP, progress=False, set={"run.t_end": 0.2})
    assert done.out is None
    assert np.all(done.table["transitions"] >= 0)


def test_sweep_errors_are_the_command_lines():
    with pytest.raises(eulerdisk.SweepError, match="no-such-sweep"):
        eulerdisk.sweep("no-such-sweep", progress=False)
    bad = {**SWEEP, "axis": [{"key": "friction.nothing", "values": [1.0]}]}
    with pytest.raises(eulerdisk.SweepError, match=r"friction\.nothing"):
        eulerdisk.sweep(bad, progress=False)
    with pytest.raises(eulerdisk.SweepError, match="jobs"):
        eulerdisk.sweep(SWEEP, jobs=0)


def test_a_sweep_on_an_executor_gives_the_same_table_and_resumes(tmp_path, capsys):
    local = eulerdisk.sweep(SWEEP, out=tmp_path / "local", progress=False)
    spawn = multiprocessing.get_context("spawn")
    executors = [
        lambda: concurrent.futures.ThreadPoolExecutor(2),
        lambda: concurrent.futures.ProcessPoolExecutor(2, mp_context=spawn),
    ]
    for k, make in enumerate(executors):
        out = tmp_path / f"executor-{k}"
        with make() as pool:
            done = eulerdisk.sweep(SWEEP, out=out, executor=pool, shards=2, progress=True)
            again = eulerdisk.sweep(SWEEP, out=out, executor=pool, shards=2, progress=False)
        # What a notebook shows: a line as each shard is done.
        said = capsys.readouterr().err
        assert "shard 1/2 done: 1 ran, 0 skipped, 0 failed" in said, said
        assert "shard 2/2 done" in said and "(2 of 2 shards)" in said, said
        assert done.points == 2 and done.ran == 2 and done.failed == 0
        assert sorted((out).glob("shard-*")) == [out / "shard-0-of-2", out / "shard-1-of-2"]
        for column in ["friction.mu_d", "transitions", "theta_period_first_s"]:
            assert list(done.table[column]) == list(local.table[column])
        assert again.ran == 0 and again.skipped == 2 and again.table.rows == 2


def test_a_sweep_on_a_dask_cluster(tmp_path):
    distributed = pytest.importorskip("distributed")
    with (
        distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True) as cluster,
        distributed.Client(cluster) as client,
    ):
        done = eulerdisk.sweep(SWEEP, out=tmp_path, executor=client.get_executor(), shards=2)
    assert done.ran == 2 and list(done.table["status"]) == ["completed", "completed"]


def test_ctrl_c_stops_a_sweep_on_a_thread_pool_within_a_second(tmp_path):
    # The shards run on the pool's threads, which signals do not reach: Ctrl-C in the waiting
    # thread stops them through the sweep's token, so the pool is free at once.
    long = {**SWEEP, "set": {"run.t_end": 100.0}}
    with concurrent.futures.ThreadPoolExecutor(2) as pool:
        sweep = lambda: eulerdisk.sweep(long, out=tmp_path, executor=pool, shards=2)  # noqa: E731
        assert seconds_to_interrupt(sweep) < 1.0
        stopping = time.monotonic()
    assert time.monotonic() - stopping < 1.0
