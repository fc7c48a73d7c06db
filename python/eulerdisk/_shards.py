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

from concurrent.futures import Executor
from pathlib import Path
from typing import Any

from . import _native


def run_shard(
    source: tuple[str, str | None, str | None],
    sets: list[str],
    out: str,
    jobs: int,
    shard: tuple[int, int],
) -> dict[str, Any]:
    """One task: shard ``(index, count)`` of the sweep ``source`` (name, TOML text, folder)
    into ``out``, its runs ``jobs`` at a time; the counts of its runs."""
    name, toml, folder = source
    return _native.sweep(name, toml, folder, sets, out, jobs, False, shard)


def on_executor(
    executor: Executor,
    source: tuple[str, str | None, str | None],
    sets: list[str],
    out: Path,
    shards: int,
    jobs: int,
) -> tuple[dict[str, Any], dict[str, int]]:
    """Runs the sweep's ``shards`` shards as tasks of ``executor`` and merges them into
    ``out``; the merge's report and the runs' counts summed over the shards."""
    futures = [
        executor.submit(run_shard, source, sets, str(out), jobs, (index, shards))
        for index in range(shards)
    ]
    counts = {"ran": 0, "skipped": 0, "failed": 0}
    folders = []
    for future in futures:
        done = future.result()
        for key in counts:
            counts[key] += int(done[key])
        # The shard's folder: its table's (named by the library).
        folders.append(str(Path(done["table"]).parent))
    return _native.merge_sweep(folders, str(out)), counts
