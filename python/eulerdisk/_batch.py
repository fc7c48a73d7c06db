"""Many solves of one model at once, for :meth:`eulerdisk.Model.solve_many`.

A parameter array or a batch of initial states makes one solve per row; the solves run on
the local cores (a thread each, at most ``workers`` at a time: every solve releases the
GIL), and their results are stacked into arrays whose first axis is the row.
"""

from __future__ import annotations

import os
import threading
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import FIRST_EXCEPTION, Future, wait
from contextvars import ContextVar
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _native
from ._native import ModelInputError
from ._solution import Solution

Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class Batch:
    """What :meth:`Model.solve_many` gives: every solve's result, stacked.

    Attributes:
        t: the recorded times, shared by every solve, shape ``(n_t,)``.
        y: the states, shape ``(n_runs, n_states, n_t)``.
        states: the states' names (the second axis of ``y``).
        solutions: each solve's :class:`Solution` (its events, counters, ...), in row order.
    """

    t: Array
    y: Array
    states: list[str]
    solutions: list[Solution]

    def __getitem__(self, name: str) -> Array:
        """A state or an output of every solve, shape ``(n_runs, n_t)``."""
        return np.stack([s[name] for s in self.solutions])

    def __len__(self) -> int:
        return len(self.solutions)


def rows(
    params: Mapping[str, Any] | Sequence[Mapping[str, Any]] | None,
    y0: npt.ArrayLike | None,
    n_states: int,
) -> list[tuple[dict[str, Any] | None, Array | None]]:
    """The solves' ``params`` and ``y0``, one pair per row: ``params`` as a mapping of name
    to a 1-d array (a number applies to every row) or as a sequence of mappings, ``y0`` as an
    ``(n_runs, n_states)`` array."""
    by_row: list[dict[str, Any]] | None = None
    if isinstance(params, Mapping):
        columns = {k: np.asarray(v) for k, v in params.items()}
        sizes = {len(v) for v in columns.values() if v.ndim == 1}
        if len(sizes) > 1 or any(v.ndim > 1 for v in columns.values()):
            raise ModelInputError(
                "params: give each parameter a number or a 1-d array, all "
                f"of one length (got lengths {sorted(sizes)})"
            )
        states = None if y0 is None else np.asarray(y0, dtype=np.float64)
        # Numbers alone apply to every row of y0.
        n = sizes.pop() if sizes else (len(states) if states is not None and states.ndim else 0)
        by_row = [{k: v[i] if v.ndim else v for k, v in columns.items()} for i in range(n)]
    elif params is not None:
        by_row = [dict(p) for p in params]
    states = None if y0 is None else np.asarray(y0, dtype=np.float64)
    if states is not None and (states.ndim != 2 or states.shape[1] != n_states):
        raise ModelInputError(
            f"y0 has shape {states.shape}: solve_many takes one row of {n_states} states per solve"
        )
    if by_row is not None and states is not None and len(by_row) != len(states):
        raise ModelInputError(
            f"params give {len(by_row)} solves and y0 {len(states)}: give as many of each"
        )
    if not by_row and states is None:
        raise ModelInputError("solve_many needs params with arrays or y0 with rows")
    n = len(by_row) if by_row is not None else len(states)  # type: ignore[arg-type]
    return [
        (by_row[i] if by_row is not None else None, states[i] if states is not None else None)
        for i in range(n)
    ]


#: How long a wait for a batch's (or a sweep's shards') results lasts before it looks at
#: Python's signals again: a signal taken by another thread (or on a platform whose waits
#: signals do not interrupt) is then handled within this.
WAIT_SLICE_S = 0.1

#: The token that stops the solves of one :func:`solve_many` call, set in the threads that
#: run them (:meth:`Model.solve` passes it to the native solve). Signals reach the main
#: thread only: Ctrl-C there sets the token, and the solves on the pool's threads stop.
_CANCEL: ContextVar[_native.Cancel | None] = ContextVar("eulerdisk_cancel", default=None)


def cancel_token() -> _native.Cancel | None:
    """The token of the :func:`solve_many` call this thread solves for, if any."""
    return _CANCEL.get()


def solve_many(
    solve: Callable[..., Solution],
    pairs: list[tuple[dict[str, Any] | None, Array | None]],
    workers: int | None,
) -> Batch:
    """Runs ``solve(params=, y0=)`` for every pair on ``workers`` threads and stacks them.

    Ctrl-C (in the main thread, waiting) or the first failed solve sets the batch's token: the
    running solves stop at their next step, those not started are dropped, and the exception
    is raised once the threads are done, within a second.
    """
    workers = workers or os.cpu_count() or 1
    if workers < 1:
        raise ModelInputError(f"workers = {workers}: at least 1")
    cancel = _native.Cancel()
    futures: list[Future[Solution]] = [Future() for _ in pairs]
    todo = iter(range(len(pairs)))
    taking = threading.Lock()

    def worker() -> None:
        token = _CANCEL.set(cancel)
        try:
            while not cancel.is_set():
                with taking:
                    k = next(todo, None)
                if k is None:
                    return
                if not futures[k].set_running_or_notify_cancel():
                    continue
                try:
                    futures[k].set_result(solve(params=pairs[k][0], y0=pairs[k][1]))
                except BaseException as error:
                    futures[k].set_exception(error)
        finally:
            _CANCEL.reset(token)

    # Daemon threads, not a ThreadPoolExecutor's: an interpreter that exits while a batch
    # runs (in a daemon thread of the caller's) does not wait for its solves, which stop
    # where they wait, as a lone solve's thread does.
    threads = [
        threading.Thread(target=worker, name=f"eulerdisk-solve-{k}", daemon=True)
        for k in range(min(workers, len(pairs)))
    ]
    for thread in threads:
        thread.start()
    try:
        pending = set(futures)
        while pending:
            # In slices: a signal handled by another thread wakes no one waiting here.
            done, pending = wait(pending, timeout=WAIT_SLICE_S, return_when=FIRST_EXCEPTION)
            for future in done:
                if future.exception() is not None:
                    raise future.exception()  # type: ignore[misc]
        solutions = [future.result() for future in futures]
    except BaseException:
        # The running solves stop at their next step; the others do not start.
        cancel.set()
        for future in futures:
            future.cancel()
        raise
    finally:
        for thread in threads:
            thread.join()
    t = solutions[0].t
    for k, s in enumerate(solutions):
        if not np.array_equal(s.t, t):
            raise ModelInputError(
                f"solve {k} recorded other times than solve 0 ({len(s.t)} against {len(t)}: "
                "a terminal event ends a solve early); solve_many stacks solves that share "
                "their times, so leave out `:stop` or solve one by one"
            )
    y = np.stack([s.y for s in solutions])
    return Batch(t=t, y=y, states=solutions[0].states, solutions=solutions)
