"""The :class:`Model` class: a model file of the DSL, compiled, evaluated and solved."""

from __future__ import annotations

import json
import os
from collections.abc import Mapping, Sequence
from concurrent.futures import CancelledError
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from . import _batch, _native, _values
from ._batch import Batch
from ._solution import Solution, solution

PathLike = str | os.PathLike[str]
#: A real number: Python's, or a NumPy scalar or 0-d array of any float or integer type.
Real = float | np.floating[Any] | np.integer[Any] | npt.NDArray[Any]


class Model:
    """A model file of the DSL, compiled by the equation compiler and run by its interpreter.

    The same as ``eulerdisk model show|eval|solve FILE``: make one with :meth:`from_file` or
    :meth:`from_str`. In Jupyter it displays its solved equations. A model pickles as its
    text (and compiles again where it is unpickled), so it goes to a process pool.
    """

    def __init__(self, native: _native.NativeModel, source: tuple[str, str]) -> None:
        """Wraps a compiled model and its ``(text, name)``; use :meth:`from_file` or
        :meth:`from_str`."""
        self._native = native
        self._source = source

    def __reduce__(self) -> tuple[Any, tuple[str, str]]:
        return Model.from_str, self._source

    @classmethod
    def from_file(cls, path: PathLike, cache: bool = True) -> Model:
        """Compiles the model file at ``path``.

        Args:
            path: the model file.
            cache: take the compiled models from the cache of compiled models, and keep them
                there, as ``eulerdisk model`` does (``$XDG_CACHE_HOME/eulerdisk/models``, else
                ``~/.cache/eulerdisk/models``; an entry is data checked against the text, never
                code); False compiles the file, as ``--no-cache``. :attr:`cache_hit` says
                whether the cache held it.

        Raises:
            DslError: the file has errors; the message gives each as ``file:line:col``, with
                the line and a caret under the offending token.
        """
        native = _native.NativeModel.from_file(os.fspath(path), cache)
        return cls(native, (Path(path).read_text(encoding="utf-8"), os.fspath(path)))

    @classmethod
    def from_str(cls, text: str, name: str = "<string>", cache: bool = True) -> Model:
        """Compiles a model given as text; ``name`` stands for the file in error messages.

        Args:
            text: the model.
            name: the file it stands for, in messages.
            cache: as :meth:`from_file` (the entry is keyed by the text, whatever its name:
                a model unpickled in a worker process finds the entry its parent wrote).

        Raises:
            DslError: as :meth:`from_file`.
        """
        return cls(_native.NativeModel.from_text(name, text, cache), (text, name))

    @property
    def cache_hit(self) -> bool:
        """Whether the compiled models came from the cache of compiled models (nothing was
        compiled)."""
        return self._native.cache_hit

    @property
    def name(self) -> str:
        """The model's name (``mod NAME { .. }``)."""
        return self._native.name

    @property
    def states(self) -> list[str]:
        """The states, in order."""
        return self._native.states

    @property
    def params(self) -> dict[str, float | None]:
        """The parameters and their defaults (None: the parameter must be given)."""
        return dict(self._native.params)

    @property
    def outputs(self) -> list[str]:
        """The outputs, in order."""
        return self._native.outputs

    @property
    def charts(self) -> list[str]:
        """The names of the model's other charts."""
        return self._native.charts

    @property
    def modes(self) -> list[str]:
        """The modes of a switched model (empty for a smooth one)."""
        return self._native.modes

    def markdown(self) -> str:
        """The solved equations in Markdown (``eulerdisk model show``)."""
        return self._native.show(False)

    def latex(self) -> str:
        """The solved equations as LaTeX (``eulerdisk model show --format latex``)."""
        return self._native.show(True)

    def _repr_markdown_(self) -> str:
        return self.markdown()

    def _repr_latex_(self) -> str:
        return self.latex()

    def __repr__(self) -> str:
        kind = f"modes {self.modes}" if self.modes else f"states {self.states}"
        return f"Model({self.name!r}, {kind})"

    def eval(
        self,
        state: Mapping[str, Real] | None = None,
        params: Mapping[str, Real] | None = None,
        *,
        t: Real = 0.0,
        chart: str | None = None,
    ) -> dict[str, dict[str, float]]:
        """The derivatives and outputs at one point (``eulerdisk model eval``).

        States not given start at the file's initial values (``states { x = 2 }``), or zero;
        parameters not given take the file's defaults.

        Returns:
            ``{"derivatives": {"der(x)": ...}, "outputs": {...}}``.

        Raises:
            ModelInputError: an unknown name, a parameter without default not given.
            SolveError: the model cannot be evaluated there (a singular pivot, a non-finite
                value), said in the model's terms.
        """
        raw = json.loads(
            self._native.eval(
                chart, float(t), _values.assignments(state), _values.assignments(params)
            )
        )
        return {"derivatives": raw["derivatives"], "outputs": raw["outputs"]}

    def solve(
        self,
        t_end: Real,
        *,
        state: Mapping[str, Real] | None = None,
        params: Mapping[str, Real] | None = None,
        y0: npt.ArrayLike | None = None,
        t0: Real = 0.0,
        t_eval: Real | npt.ArrayLike | None = None,
        events: Sequence[str] = (),
        method: str = "dop853",
        rtol: Real = 1e-8,
        atol: Real = 1e-10,
        dense_output: bool = False,
        max_step: Real | None = None,
        first_step: Real | None = None,
        chart: str | None = None,
    ) -> Solution:
        """Integrates the model from ``t0`` to ``t_end`` (``eulerdisk model solve``).

        Numbers may be Python's or NumPy's (scalars or 0-d arrays of any float or integer
        type); the result has the shape of SciPy's ``solve_ivp`` result (:class:`Solution`).

        A ``t_end`` before ``t0`` integrates backward in time, as ``solve_ivp`` does with
        ``t_span=(t0, t1)``, ``t1 < t0``: ``sol.t`` decreases, ``t_eval`` times must
        decrease, ``max_step`` and ``first_step`` are lengths, and an event's ``up``/``down``
        is the crossing as the run proceeds (SciPy's ``direction``), here as ``t`` decreases.
        The runtime integrates the model in ``-t`` (exactly the steps a method would take
        with negative step sizes). A switched model runs forward only (its resets have no
        inverse in the file): a ``t_end`` before ``t0`` is refused.

        Args:
            t_end: the end time (before ``t0``: backward in time).
            state: initial states by name, overriding the file's initial values
                (``states { x = 2 }``); a state given neither here nor there starts at zero.
            params: parameters by name (others: the file's defaults).
            y0: instead of ``state``, every initial state, in :attr:`states` order.
            t0: the start time.
            t_eval: a number: record every ``t_eval`` from ``t0`` towards ``t_end`` (and at
                ``t_end``); a sequence (or NumPy array) of times inside the span, in the run's
                order (increasing, or decreasing backward): record at exactly those (a smooth
                model only), as ``solve_ivp``'s ``t_eval``; by default every accepted step.
            events: zero crossings to locate, a list of ``NAME[:up|:down][:stop]`` of a state
                or an output (a switched model declares its own in the file).
            method: ``dop853`` (default, SciPy's ``DOP853``), ``dopri5`` (``RK45``) or
                ``rodas4`` (stiff models, where SciPy would use ``Radau`` or ``BDF``); any case.
            rtol: relative tolerance (positive).
            atol: absolute tolerance (positive).
            dense_output: keep every step's interpolant: ``sol.sol(t)`` then gives the states
                at any ``t`` (:class:`DenseOutput`).
            max_step: the largest step size (default: unbounded).
            first_step: the first step size, and that after each event (default: chosen by
                the integrator).
            chart: solve the model in this chart of the file.

        Raises:
            ModelInputError: an unknown name or method, a bad event, an unusable setting,
                ``t_eval`` times out of the run's order, a switched model asked to run back.
            SolveError: the integration failed; the message says where and why.
            KeyboardInterrupt: Ctrl-C; the integration stops at its next step.
        """
        start, end = float(t0), float(t_end)
        specs = _values.event_specs(events)
        initial = _values.initial_states(self.states, state, y0)
        cancel = _batch.cancel_token()
        raw = self._native.solve(
            chart,
            _values.assignments(initial),
            _values.assignments(params),
            specs,
            start,
            end,
            *_values.sampling(t_eval),
            _values.method(method),
            _values.tolerance("rtol", rtol),
            _values.tolerance("atol", atol),
            _values.step("first_step", first_step),
            _values.step("max_step", max_step),
            dense_output,
            cancel,
        )
        if cancel is not None and cancel.is_set():
            raise CancelledError("the solve was cancelled: another solve of its batch ended it")
        return solution(raw, specs, dense_output)

    def solve_many(
        self,
        t_end: Real,
        *,
        params: Mapping[str, Any] | Sequence[Mapping[str, Any]] | None = None,
        y0: npt.ArrayLike | None = None,
        t_eval: Real | npt.ArrayLike,
        workers: int | None = None,
        **options: object,
    ) -> Batch:
        """Solves the model once per row of ``params`` or ``y0``, on the local cores.

        The solves run on ``workers`` threads (default: one per core); each releases the GIL,
        so they run in parallel. Their results share ``t_eval``'s times and are stacked.

        Args:
            t_end: the end time of every solve.
            params: parameters by name, each a number or a 1-d array (one value per solve),
                or a sequence of mappings (one per solve).
            y0: the initial states, one row of :attr:`states` per solve (``(n, n_states)``).
            t_eval: the times every solve records at: a step, or times in the run's order.
            workers: solves at once (default: the number of cores).
            options: any other keyword of :meth:`solve` (``method``, ``rtol``, ``events``...).

        Returns:
            A :class:`Batch`: ``t`` ``(n_t,)``, ``y`` ``(n, n_states, n_t)``, each
            :class:`Solution` in ``solutions``, and ``batch["name"]`` ``(n, n_t)``.

        Raises:
            ModelInputError: rows of different lengths, solves that recorded different times
                (a terminal event), or what :meth:`solve` raises.
            KeyboardInterrupt: Ctrl-C; every running solve stops at its next step, the
                others do not start, within a second.

        The first solve that fails stops the others the same way, and its error is raised.
        """
        pairs = _batch.rows(params, y0, len(self.states))

        def one(params: dict[str, Any] | None, y0: npt.ArrayLike | None) -> Solution:
            return self.solve(t_end, params=params, y0=y0, t_eval=t_eval, **options)

        return _batch.solve_many(one, pairs, workers)
