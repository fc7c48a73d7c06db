"""A sweep run by a :class:`concurrent.futures.Executor`: one shard of its points per task.

What the command line does on a cluster (``eulerdisk sweep --shard i/n`` in each job, then
``eulerdisk sweep merge``), from Python: each task runs shard ``i`` of ``n`` into
``out/shard-i-of-n`` (resuming what that folder holds), and the shards are merged into
``out``'s table once every task is done. The executor may be the standard library's (threads
or processes) or any other that takes picklable calls, such as Dask's
(``distributed.Client(...).get_executor()``); its workers must see ``out`` at the same path
(one machine, or a shared file system).
"""

from __future__ import annotations

import sys
from collections.abc import Iterator
from concurrent.futures import FIRST_COMPLETED, Executor, Future, wait
from pathlib import Path
from typing import Any

from . import _native
from ._batch import WAIT_SLICE_S


def run_shard(
    source: tuple[str, str | None, str | None],
    sets: list[str],
    out: str,
    jobs: int,
    shard: tuple[int, int],
    cancel: _native.Cancel | None = None,
) -> dict[str, Any]:
    """One task: shard ``(index, count)`` of the sweep ``source`` (name, TOML text, folder)
    into ``out``, its runs ``jobs`` at a time; the counts of its runs. ``cancel`` set (by the
    caller, for a task on one of its threads) stops it as Ctrl-C does."""
    name, toml, folder = source
    return _native.sweep(name, toml, folder, sets, out, jobs, False, shard, cancel)


def _completed(futures: list[Future[Any]]) -> Iterator[Future[Any]]:
    """The futures as they are done, waiting in slices so that Python handles signals
    between them (see :data:`eulerdisk._batch.WAIT_SLICE_S`)."""
    pending = set(futures)
    while pending:
        done, pending = wait(pending, timeout=WAIT_SLICE_S, return_when=FIRST_COMPLETED)
        yield from done


def on_executor(
    executor: Executor,
    source: tuple[str, str | None, str | None],
    sets: list[str],
    out: Path,
    shards: int,
    jobs: int,
    progress: bool = False,
) -> tuple[dict[str, Any], dict[str, int]]:
    """Runs the sweep's ``shards`` shards as tasks of ``executor`` and merges them into
    ``out``; the merge's report and the runs' counts summed over the shards. With
    ``progress``, a line on standard error as each shard is done.

    Ctrl-C while it waits (or a shard that fails) cancels the shards not started, stops the
    ones running on this process's threads at their next step (their complete runs kept), and
    raises; shards running in other processes (a process pool, a Dask cluster) finish their
    runs into ``out``, where the same call again finds them and resumes.
    """
    cancel = _native.Cancel()
    futures = {
        executor.submit(run_shard, source, sets, str(out), jobs, (index, shards), cancel): index
        for index in range(shards)
    }
    counts = {"ran": 0, "skipped": 0, "failed": 0}
    folders: dict[int, str] = {}
    try:
        for future in _completed(list(futures)):
            done = future.result()
            index = futures[future]
            for key in counts:
                counts[key] += int(done[key])
            # The shard's folder: its table's (named by the library).
            folders[index] = str(Path(done["table"]).parent)
            if progress:
                print(
                    f"shard {index + 1}/{shards} done: {done['ran']} ran, {done['skipped']} "
                    f"skipped, {done['failed']} failed ({len(folders)} of {shards} shards)",
                    file=sys.stderr,
                    flush=True,
                )
    except BaseException:
        cancel.set()
        for future in futures:
            future.cancel()
        raise
    merged = _native.merge_sweep([folders[i] for i in range(shards)], str(out))
    return merged, counts
