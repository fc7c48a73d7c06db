"""Many solves of one model at once, for :meth:`eulerdisk.Model.solve_many`.

A parameter array or a batch of initial states makes one solve per row; the solves run on
the local cores (a thread each, at most ``workers`` at a time: every solve releases the
GIL), and their results are stacked into arrays whose first axis is the row.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

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


def solve_many(
    solve: Callable[..., Solution],
    pairs: list[tuple[dict[str, Any] | None, Array | None]],
    workers: int | None,
) -> Batch:
    """Runs ``solve(params=, y0=)`` for every pair on ``workers`` threads and stacks them."""
    workers = workers or os.cpu_count() or 1
    if workers < 1:
        raise ModelInputError(f"workers = {workers}: at least 1")
    with ThreadPoolExecutor(min(workers, len(pairs))) as pool:
        solutions = list(pool.map(lambda pair: solve(params=pair[0], y0=pair[1]), pairs))
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
