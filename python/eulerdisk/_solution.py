"""What :meth:`eulerdisk.Model.solve` returns, shaped as SciPy's ``solve_ivp`` result.

``sol.t``, ``sol.y`` (states by times), ``sol.status``, ``sol.message``, ``sol.success``,
``sol.nfev``/``njev``/``nlu``, ``sol.t_events``/``sol.y_events`` and, with
``dense_output=True``, ``sol.sol(t)``; and by name, ``sol["x"]`` for a state or an output.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from ._native import DENSE_NODES

if TYPE_CHECKING:
    import pandas as pd

Array = npt.NDArray[np.float64]

#: SciPy's words for why a run ended, by ``status``.
MESSAGES = {
    0: "The solver successfully reached the end of the integration interval.",
    1: "A termination event occurred.",
}


@dataclass(frozen=True)
class Event:
    """One located event of :meth:`Model.solve`: its name, time, and every column there."""

    name: str
    t: float
    values: dict[str, float] = field(default_factory=dict)


class DenseOutput:
    """The integrator's own dense output over the run, as ``solve_ivp``'s ``sol``.

    Each accepted step's interpolant (a polynomial in ``t`` of degree at most 7: DOP853's is
    7, DOPRI5's 4, RODAS4's 3) is kept by the solver as its values at 8 Chebyshev-Lobatto
    nodes of the step, which determine it; calling this evaluates it by barycentric
    interpolation, the same polynomial to rounding. Times outside the run extrapolate the
    first or the last step, as SciPy does. At an event that resets the state, the step that
    ends there gives the value before the reset. A run backward in time has its steps in
    decreasing time; they are looked up the same way.
    """

    def __init__(self, spans: Array, values: Array) -> None:
        self._t0 = spans[:, 0]
        self._t1 = spans[:, 1]
        # -1 for a run backward in time: its steps' ends, negated, increase.
        self._sign = -1.0 if len(spans) and spans[-1, 1] < spans[0, 0] else 1.0
        self._values = values  # steps, nodes, states
        k = np.arange(DENSE_NODES)
        self._theta = (1.0 - np.cos(k * np.pi / (DENSE_NODES - 1))) / 2.0
        weights = (-1.0) ** k
        weights[[0, -1]] /= 2.0
        self._weights = weights

    @property
    def t_min(self) -> float:
        """The earliest time of the run (its start, or its end for a run backward)."""
        return float(min(self._t0[0], self._t1[-1]))

    @property
    def t_max(self) -> float:
        """The latest time of the run (its end, or its start for a run backward)."""
        return float(max(self._t0[0], self._t1[-1]))

    def __call__(self, t: float | npt.ArrayLike) -> Array:
        """The states at ``t``: shape ``(n_states,)`` for a number, ``(n_states, len(t))``
        for a sequence of times."""
        times = np.asarray(t, dtype=np.float64)
        flat = np.atleast_1d(times)
        ends, wanted = self._sign * self._t1, self._sign * flat
        step = np.clip(np.searchsorted(ends, wanted, side="left"), 0, len(self._t1) - 1)
        t0, t1 = self._t0[step], self._t1[step]
        nodes = t0[:, None] + (t1 - t0)[:, None] * self._theta[None, :]
        gap = flat[:, None] - nodes
        exact = gap == 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            terms = self._weights[None, :] / gap
        terms[exact] = 0.0
        hit = exact.any(axis=1)
        terms[hit] = exact[hit].astype(np.float64)
        values = self._values[step]  # queries, nodes, states
        with np.errstate(divide="ignore", invalid="ignore"):
            out = np.einsum("qk,qks->qs", terms, values) / terms.sum(axis=1)[:, None]
        # A run of no step (t_end = t0) keeps its start as one step of zero length: its
        # state, wherever asked.
        still = t0 == t1
        out[still] = values[still, 0]
        return out[0] if times.ndim == 0 else out.T


@dataclass(frozen=True)
class Solution:
    """What :meth:`Model.solve` gives, in the shape of SciPy's ``solve_ivp`` result.

    Attributes:
        t: the recorded times, shape ``(n_t,)``, in the run's order (decreasing for a run
            backward in time).
        y: the states at those times, shape ``(n_states, n_t)``, rows in ``states`` order.
        states: the states' names (the rows of ``y``).
        columns: the states, then the outputs (and a switched model's discrete values) at
            those times, by name; ``sol["x"]`` reads one. ``t``, ``y`` and the columns are
            views of one ``(columns, n_t)`` array (the solve's table, copied once, whole).
        events: the located events, in time order, each with every column there.
        t_events: per event, the times it was located at: for a smooth model one array per
            entry of ``events=`` in that order; for a switched model one per event of the
            file in the order they first fired (``event_names`` names them).
        y_events: per event, the states there, shape ``(len(t_events[i]), n_states)``.
        event_names: the event of each entry of ``t_events``.
        status: 0 the end time was reached, 1 a terminal event ended the run (a failed
            integration raises :class:`SolveError`, Ctrl-C ``KeyboardInterrupt``).
        message: SciPy's words for ``status``.
        success: True (a failure raises instead).
        stop: ``end_time``, or ``event NAME`` for a run a terminal event ended.
        nfev: right-hand-side evaluations; njev: Jacobian evaluations; nlu: LU
            decompositions (both zero for an explicit method).
        stats: all of the integrator's counters (``steps``, ``rejected``, ...).
        notes: remarks on the run (an accumulation of events, ...).
        sol: with ``dense_output=True``, the integrator's dense output (:class:`DenseOutput`),
            ``sol.sol(t)`` the states at ``t``; else None.
    """

    t: Array
    y: Array
    states: list[str]
    columns: dict[str, Array]
    events: list[Event]
    t_events: list[Array]
    y_events: list[Array]
    event_names: list[str]
    status: int
    stop: str
    stats: dict[str, int]
    notes: list[str]
    sol: DenseOutput | None = None

    @property
    def message(self) -> str:
        """Why the run ended, in SciPy's words."""
        return MESSAGES[self.status]

    @property
    def success(self) -> bool:
        """Whether the run reached its end or a terminal event (always, or it raised)."""
        return self.status >= 0

    @property
    def nfev(self) -> int:
        """The right-hand side's evaluations."""
        return self.stats["rhs_evals"]

    @property
    def njev(self) -> int:
        """The Jacobian's evaluations (an implicit method's)."""
        return self.stats["jacobian_evals"]

    @property
    def nlu(self) -> int:
        """The LU decompositions (an implicit method's)."""
        return self.stats["decompositions"]

    def __getitem__(self, name: str) -> Array:
        """A state's or output's values (``"t"``: the times)."""
        return self.t if name == "t" else self.columns[name]

    def to_pandas(self) -> pd.DataFrame:
        """``t``, the states and the outputs as a ``pandas.DataFrame``."""
        import pandas as pd

        return pd.DataFrame({"t": self.t, **self.columns})

    def __repr__(self) -> str:
        return (
            f"Solution({len(self.t)} times from {self.t[0] if len(self.t) else None} to "
            f"{self.t[-1] if len(self.t) else None}, {len(self.events)} events, "
            f"status={self.status}: {self.message!r})"
        )


def solution(raw: Mapping[str, Any], specs: Sequence[str], dense: bool) -> Solution:
    """The :class:`Solution` of a native solve's result; ``specs`` are the events asked for."""
    header: list[str] = raw["header"]
    n = int(raw["states"])
    # One (columns, rows) array, writable, from the native table without a copy: `t`, `y`
    # and every column are views of it.
    trajectory = np.frombuffer(raw["table"], dtype=np.float64).reshape(len(header), -1)
    columns = {name: trajectory[k] for k, name in enumerate(header) if k > 0}
    t = trajectory[0]
    states = header[1 : 1 + n]
    y = trajectory[1 : 1 + n]
    events = [
        Event(name=name, t=row[0], values=dict(zip(header, row, strict=True)))
        for name, _, row in raw["events"]
    ]
    if specs:
        names = [spec.split(":")[0] for spec in specs]
        rows: list[list[list[float]]] = [[] for _ in specs]
        for _, index, row in raw["events"]:
            if index is not None:
                rows[index].append(row)
    else:
        names = list(dict.fromkeys(name for name, _, _ in raw["events"]))
        rows = [[row for name, _, row in raw["events"] if name == wanted] for wanted in names]
    table = [np.array(r, dtype=np.float64).reshape(len(r), len(header)) for r in rows]
    stop: str = raw["stop"]
    sol = None
    if dense:
        spans = np.frombuffer(raw["dense_t"], dtype=np.float64).reshape(-1, 2)
        values = np.frombuffer(raw["dense_y"], dtype=np.float64).reshape(-1, DENSE_NODES, n)
        if len(spans) == 0 and len(t):
            # No step (t_end = t0): the start, as a step of zero length.
            spans = np.array([[t[0], t[0]]])
            values = np.broadcast_to(y[:, 0], (1, DENSE_NODES, n))
        sol = DenseOutput(spans, values)
    return Solution(
        t=t,
        y=y,
        states=states,
        columns=columns,
        events=events,
        t_events=[r[:, 0].copy() for r in table],
        y_events=[r[:, 1 : 1 + n].copy() for r in table],
        event_names=names,
        status=1 if stop.startswith("event") else 0,
        stop=stop,
        stats=dict(raw["stats"]),
        notes=list(raw["notes"]),
        sol=sol,
    )
