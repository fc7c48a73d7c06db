"""Euler's disk, and equations of motion of your own, from Python.

The simulator and the model language of the ``eulerdisk`` command line, called in process:

* :func:`run` simulates a scene (``eulerdisk run``) and returns its trajectory as NumPy arrays,
  its transitions, its located extrema, its summary and its provenance.
* :class:`Model` compiles a model file of the DSL (``eulerdisk model ...``), evaluates it at a
  point and integrates it, events included; switched models (modes and events) too.
* :func:`sweep` runs a sweep (``eulerdisk sweep``) and returns its table.

Every argument is checked, and every error worded, exactly as by the command line: the package
passes ``set={"run.t_end": 2}`` on as ``--set run.t_end=2``.

Long calls release the GIL, so Python threads run simulations in parallel, and Ctrl-C raises
:class:`KeyboardInterrupt` within a second (a run or a sweep stops at its next step).
"""

from __future__ import annotations

import csv
import json
import math
import os
import re
import sys
import tempfile
from collections.abc import Iterable, Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _native
from ._native import (
    DslError,
    ModelInputError,
    RunError,
    SceneError,
    SolveError,
    SweepError,
)

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "DslError",
    "Event",
    "Model",
    "ModelInputError",
    "RunError",
    "RunResult",
    "SceneError",
    "Solution",
    "SolveError",
    "SweepError",
    "SweepResult",
    "Table",
    "run",
    "sweep",
]

Array = npt.NDArray[np.float64]
PathLike = str | os.PathLike[str]


def _setting(value: object) -> str:
    """One value as the command line's ``--set`` writes it (TOML's spelling)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    return str(value)


def _assignments(values: Mapping[str, object] | None) -> list[str]:
    """``{"a.b": 1}`` as ``["a.b=1"]``: the command line's ``NAME=VALUE`` arguments."""
    return [f"{key}={_setting(value)}" for key, value in (values or {}).items()]


def _key(name: str) -> str:
    """A TOML key: bare (dotted keys nest, as in a file: ``run.t_end``), else quoted."""
    return name if re.fullmatch(r"[A-Za-z0-9_.-]+", name) else json.dumps(name)


def _toml(table: Mapping[str, Any]) -> str:
    """A scene or sweep given as nested dicts, written as the TOML file it stands for."""
    lines: list[str] = []

    def value(v: object) -> str:
        if isinstance(v, bool):
            return "true" if v else "false"
        if isinstance(v, int | float):
            return _setting(v)
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, Sequence):
            return "[" + ", ".join(value(x) for x in v) + "]"
        if isinstance(v, Mapping):
            return "{" + ", ".join(f"{_key(k)} = {value(x)}" for k, x in v.items()) + "}"
        raise TypeError(f"a scene or sweep value must be TOML-like, not {type(v).__name__}")

    def emit(prefix: str, t: Mapping[str, Any]) -> None:
        plain = {k: v for k, v in t.items() if not isinstance(v, Mapping)}
        nested = {k: v for k, v in t.items() if isinstance(v, Mapping)}
        if prefix and (plain or not nested):
            lines.append(f"[{prefix}]")
        lines.extend(f"{_key(k)} = {value(v)}" for k, v in plain.items())
        for k, v in nested.items():
            emit(f"{prefix}.{_key(k)}" if prefix else _key(k), v)

    emit("", table)
    return "\n".join(lines) + "\n"


def _progress(progress: bool | None) -> bool:
    """Whether to show progress: as asked, or by default on a terminal or in a notebook."""
    if progress is not None:
        return progress
    return sys.stderr.isatty() or _in_notebook()


def _in_notebook() -> bool:
    """Whether this runs in a Jupyter kernel (whose cells show what goes to standard error)."""
    ipython = sys.modules.get("IPython")
    shell = ipython.get_ipython() if ipython is not None else None
    return shell is not None and hasattr(shell, "kernel")


def _columns(raw: Mapping[str, bytes]) -> dict[str, Array]:
    """Columns of native ``f64`` bytes as read-only NumPy arrays viewing those bytes."""
    return {name: np.frombuffer(data, dtype=np.float64) for name, data in raw.items()}


def _read_csv(path: Path) -> list[dict[str, str]]:
    if not path.is_file():
        return []
    with path.open(newline="") as f:
        return list(csv.DictReader(f))


def _number(text: str) -> float | str | None:
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


class Table(Mapping[str, "npt.NDArray[Any]"]):
    """Named columns of equal length, ready for ``pandas.DataFrame``.

    A mapping from column name to NumPy array; numeric columns are ``float64``, text columns
    ``object`` arrays (empty cells are NaN or None).
    """

    def __init__(self, columns: Mapping[str, npt.NDArray[Any]]) -> None:
        self._columns = dict(columns)

    @classmethod
    def from_rows(cls, rows: Sequence[Mapping[str, str]], names: Sequence[str]) -> Table:
        """A table of CSV rows (as :class:`csv.DictReader` reads them), numbers as floats."""
        out: dict[str, npt.NDArray[Any]] = {}
        for name in names:
            cells = [_number(r.get(name, "") or "") for r in rows]
            if all(c is None or isinstance(c, float) for c in cells):
                out[name] = np.array([math.nan if c is None else c for c in cells], dtype=float)
            else:
                out[name] = np.array(cells, dtype=object)
        return cls(out)

    @classmethod
    def read_csv(cls, path: Path) -> Table:
        """The table of a CSV file written by the command line."""
        with path.open(newline="") as f:
            reader = csv.DictReader(f)
            rows = list(reader)
            names = list(reader.fieldnames or [])
        return cls.from_rows(rows, names)

    def __getitem__(self, name: str) -> npt.NDArray[Any]:
        return self._columns[name]

    def __iter__(self) -> Iterator[str]:
        return iter(self._columns)

    def __len__(self) -> int:
        return len(self._columns)

    @property
    def rows(self) -> int:
        """The number of rows."""
        return len(next(iter(self._columns.values()))) if self._columns else 0

    def to_pandas(self) -> pd.DataFrame:
        """The table as a ``pandas.DataFrame`` (needs pandas)."""
        import pandas as pd

        return pd.DataFrame(self._columns)

    def __repr__(self) -> str:
        return f"Table({self.rows} rows: {', '.join(self._columns)})"


@dataclass(frozen=True)
class RunResult:
    """What :func:`run` gives: ``eulerdisk run``'s outputs, in memory.

    Attributes:
        trajectory: the samples at the scene's rate, by column: ``t`` (s), ``mode``
            (``rolling``/``sliding``...), and the scene's quantities under their names
            (``theta``, ``N_over_mg``, ...: ``trajectory.csv``'s columns without the units).
        transitions: the mode decisions (``events.csv`` without its final stop row); a start
            that slides opens with an ``initial_friction`` row, which ``summary["transitions"]``
            does not count.
        extrema: the located extrema of θ, N/mg and the slip speed (``extrema.csv``).
        stop_reason: why the run ended (``end_time``, ``contact_lost``, ``interrupted``, ...).
        stop: the stop row: ``t_s``, ``mode``, ``reason``, ``detail``.
        summary: ``summary.json`` without its provenance.
        provenance: how the run was produced (program, revision, scene, overrides, settings).
        ending: ``completed``, ``interrupted`` or ``failed`` (the exit status's meaning).
        out: the folder holding the files written, or None when none was asked for.
    """

    trajectory: Table
    transitions: Table
    extrema: Table
    stop_reason: str
    stop: dict[str, Any]
    summary: dict[str, Any]
    provenance: dict[str, Any]
    ending: str
    out: Path | None = None

    def __getitem__(self, column: str) -> npt.NDArray[Any]:
        """One column of the trajectory."""
        return self.trajectory[column]

    def to_pandas(self) -> pd.DataFrame:
        """The trajectory as a ``pandas.DataFrame``."""
        return self.trajectory.to_pandas()

    def __repr__(self) -> str:
        return (
            f"RunResult(scene={self.summary.get('scene')!r}, {self.trajectory.rows} samples, "
            f"{len(self.transitions['t_s']) if 't_s' in self.transitions else 0} transitions, "
            f"stop={self.stop_reason!r})"
        )


def _scene_source(scene: str | PathLike | Mapping[str, Any] | None) -> tuple[str, str | None]:
    if scene is None:
        return _native.default_scene(), None
    if isinstance(scene, Mapping):
        name = str(scene.get("name", "python-scene"))
        body = {k: v for k, v in scene.items() if k != "name"}
        return name, _toml(body)
    return os.fspath(scene), None


def run(
    scene: str | PathLike | Mapping[str, Any] | None = None,
    *,
    t_end: float | None = None,
    set: Mapping[str, object] | None = None,
    progress: bool | None = None,
    out: PathLike | None = None,
    figures: bool = False,
) -> RunResult:
    """Simulates a scene, as ``eulerdisk run`` does, and returns its results in memory.

    Args:
        scene: a built-in scene's name (``"tangent-toy"``, the paper's, by default), a scene
            file's path, or the scene as nested dicts (the TOML file's tables; an optional
            top-level ``"name"``).
        t_end: the end time (s); the same as ``set={"run.t_end": t_end}``.
        set: scene overrides by ``"table.key"``, as ``--set table.key=value``.
        progress: a progress bar on a terminal, lines on standard error in a notebook;
            ``False`` shows nothing. By default shown on a terminal or in a notebook.
        out: a folder to write the command line's files into too (``trajectory.csv``,
            ``events.csv``, ``extrema.csv``, ``summary.json``); none by default.
        figures: with ``out``, draw the paper's figures there as well.

    Raises:
        SceneError: the scene cannot be run (unknown name, bad key or value); ``.key`` says
            which key (``table.key``), the message is the command line's.
        KeyboardInterrupt: Ctrl-C; the run stops at its next step, and files written to
            ``out`` are complete (each is written under a temporary name and then renamed).
    """
    name, toml = _scene_source(scene)
    sets = _assignments(set)
    if t_end is not None:
        sets.append(f"run.t_end={_setting(float(t_end))}")
    with tempfile.TemporaryDirectory(prefix="eulerdisk-run-") as scratch:
        folder = Path(out) if out is not None else Path(scratch)
        raw = _native.run(
            name,
            toml,
            sets,
            str(folder),
            _progress(progress),
            out is not None,
            figures and out is not None,
        )
        return _run_result(raw, folder, Path(out) if out is not None else None)


def _run_result(raw: Mapping[str, Any], folder: Path, out: Path | None) -> RunResult:
    columns: dict[str, npt.NDArray[Any]] = dict(_columns(raw["columns"]))
    names = np.array(raw["mode_names"] or ["rolling"], dtype=object)
    codes = np.frombuffer(raw["mode_codes"], dtype=np.uint8)
    columns = {"t": columns.pop("t"), "mode": names[codes], **columns}
    events = _read_csv(folder / "events.csv")
    stop_rows = [r for r in events if r.get("to") == "stop"]
    transitions = [r for r in events if r.get("to") != "stop"]
    event_names = ["t_s", "from", "to", "trigger", "value", "value_meaning", "slip_direction_rad"]
    stop_row = stop_rows[-1] if stop_rows else {}
    summary = json.loads((folder / "summary.json").read_text())
    provenance = summary.pop("produced_by", None) or json.loads(raw["provenance"] or "{}")
    return RunResult(
        trajectory=Table(columns),
        transitions=Table.from_rows(transitions, event_names),
        extrema=Table.read_csv(folder / "extrema.csv"),
        stop_reason=str(summary.get("stop_reason", stop_row.get("trigger", ""))),
        stop={
            "t_s": float(stop_row.get("t_s", "nan") or "nan"),
            "mode": stop_row.get("from", ""),
            "reason": stop_row.get("trigger", ""),
            "detail": stop_row.get("value_meaning", ""),
        },
        summary=summary,
        provenance=provenance,
        ending=str(raw["ending"]),
        out=out,
    )


@dataclass(frozen=True)
class Event:
    """One located event of :meth:`Model.solve`: its name, time, and every column there."""

    name: str
    t: float
    values: dict[str, float] = field(default_factory=dict)


@dataclass(frozen=True)
class Solution:
    """What :meth:`Model.solve` gives.

    Attributes:
        t: the recorded times.
        y: the states then the outputs at those times, by name.
        events: the located events, in order.
        stop: ``end_time``, or ``event NAME`` for a run a terminal event ended.
        stats: the integrator's work (``steps``, ``rejected``, ``rhs_evals``, ...).
        notes: remarks on the run (an accumulation of events, ...).
    """

    t: Array
    y: dict[str, Array]
    events: list[Event]
    stop: str
    stats: dict[str, int]
    notes: list[str]

    def __getitem__(self, name: str) -> Array:
        """A state's or output's values (``"t"``: the times)."""
        return self.t if name == "t" else self.y[name]

    def to_pandas(self) -> pd.DataFrame:
        """``t``, the states and the outputs as a ``pandas.DataFrame``."""
        return Table({"t": self.t, **self.y}).to_pandas()



def _sampling(t_eval: float | Iterable[float] | None) -> tuple[float | None, list[float] | None]:
    """``t_eval`` as the native call takes it: a sampling step, or sampling times."""
    if t_eval is None:
        return None, None
    if isinstance(t_eval, (int, float)):
        return float(t_eval), None
    return None, [float(t) for t in np.asarray(t_eval, dtype=float).ravel()]

class Model:
    """A model file of the DSL, compiled by the equation compiler and run by its interpreter.

    The same as ``eulerdisk model show|eval|solve FILE``: make one with :meth:`from_file` or
    :meth:`from_str`. In Jupyter it displays its solved equations.
    """

    def __init__(self, native: _native.NativeModel) -> None:
        """Wraps a compiled model; use :meth:`from_file` or :meth:`from_str`."""
        self._native = native

    @classmethod
    def from_file(cls, path: PathLike) -> Model:
        """Compiles the model file at ``path``.

        Raises:
            DslError: the file has errors; the message gives each as ``file:line:col``, with
                the line and a caret under the offending token.
        """
        return cls(_native.NativeModel.from_file(os.fspath(path)))

    @classmethod
    def from_str(cls, text: str, name: str = "<string>") -> Model:
        """Compiles a model given as text; ``name`` stands for the file in error messages.

        Raises:
            DslError: as :meth:`from_file`.
        """
        return cls(_native.NativeModel.from_text(name, text))

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
        state: Mapping[str, float] | None = None,
        params: Mapping[str, float] | None = None,
        *,
        t: float = 0.0,
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
            self._native.eval(chart, float(t), _assignments(state), _assignments(params))
        )
        return {"derivatives": raw["derivatives"], "outputs": raw["outputs"]}

    def solve(
        self,
        t_end: float,
        *,
        state: Mapping[str, float] | None = None,
        params: Mapping[str, float] | None = None,
        t0: float = 0.0,
        t_eval: float | Iterable[float] | None = None,
        events: Iterable[str] = (),
        method: str = "dop853",
        rtol: float = 1e-8,
        atol: float = 1e-10,
        chart: str | None = None,
    ) -> Solution:
        """Integrates the model from ``t0`` to ``t_end`` (``eulerdisk model solve``).

        Args:
            t_end: the end time.
            state: initial states by name, overriding the file's initial values
                (``states { x = 2 }``); a state given neither here nor there starts at zero.
            params: parameters by name (others: the file's defaults).
            t0: the start time.
            t_eval: a number: record every ``t_eval`` from ``t0`` (and at ``t_end``); a
                sequence (or NumPy array) of increasing times inside ``[t0, t_end]``: record at
                exactly those (a smooth model only), as ``solve_ivp``'s ``t_eval``; by default
                every accepted step.
            events: zero crossings to locate, as ``NAME[:up|:down][:stop]`` of a state or an
                output (a switched model declares its own in the file).
            method: ``dop853`` (default), ``dopri5`` or ``rodas4`` (stiff models).
            rtol: relative tolerance.
            atol: absolute tolerance.
            chart: solve the model in this chart of the file.

        Raises:
            ModelInputError: an unknown name or method, a bad event, an unusable setting.
            SolveError: the integration failed; the message says where and why.
            KeyboardInterrupt: Ctrl-C, raised once the integration has ended (a model file's
                solve has no cancellation yet; the GIL is released meanwhile).
        """
        raw = self._native.solve(
            chart,
            _assignments(state),
            _assignments(params),
            list(events),
            float(t0),
            float(t_end),
            *_sampling(t_eval),
            method,
            float(rtol),
            float(atol),
        )
        columns = _columns(raw["columns"])
        header: list[str] = raw["header"]
        found = [
            Event(name=name, t=row[0], values=dict(zip(header, row, strict=True)))
            for name, row in raw["events"]
        ]
        t = columns.pop("t")
        return Solution(
            t=t,
            y=columns,
            events=found,
            stop=raw["stop"],
            stats=dict(raw["stats"]),
            notes=list(raw["notes"]),
        )


@dataclass(frozen=True)
class SweepResult:
    """What :func:`sweep` gives: the sweep's table (``sweep.csv``) and the counts of its runs.

    Attributes:
        table: one row per point: the point, its axis values, its status and the summary's
            numbers; ``table.to_pandas()`` makes it a DataFrame.
        points: the sweep's points.
        ran: runs done by this call (failures and timeouts included).
        skipped: points already done in ``out`` (a resumed sweep).
        failed: runs that failed or timed out.
        out: the folder holding the sweep, or None when none was asked for.
    """

    table: Table
    points: int
    ran: int
    skipped: int
    failed: int
    out: Path | None = None

    def to_pandas(self) -> pd.DataFrame:
        """The table as a ``pandas.DataFrame``."""
        return self.table.to_pandas()


def sweep(
    sweep: str | PathLike | Mapping[str, Any],
    *,
    jobs: int | None = None,
    out: PathLike | None = None,
    set: Mapping[str, object] | None = None,
    progress: bool | None = None,
) -> SweepResult:
    """Runs a sweep, as ``eulerdisk sweep`` does, and returns its table.

    Args:
        sweep: a built-in sweep's name, a sweep file's path, or the sweep as nested dicts (an
            optional top-level ``"name"``; relative scene paths start from the current folder).
        jobs: runs at once (default: the sweep's ``jobs``, else the number of cores).
        out: the sweep's folder; a folder already holding some of its runs is resumed, as by
            the command line. By default a temporary folder, removed afterwards.
        set: overrides of every point's scene, as ``--set table.key=value``.
        progress: as for :func:`run`.

    Raises:
        SweepError: the sweep cannot be run; the message is the command line's.
        KeyboardInterrupt: Ctrl-C; finished runs are kept in ``out``, and running the same
            call again resumes the sweep.
    """
    if jobs is not None and jobs < 1:
        raise SweepError("jobs must be at least 1")
    if isinstance(sweep, Mapping):
        name = str(sweep.get("name", "python-sweep"))
        toml: str | None = _toml({k: v for k, v in sweep.items() if k != "name"})
        folder: str | None = os.getcwd()
    else:
        name, toml, folder = os.fspath(sweep), None, None
    with tempfile.TemporaryDirectory(prefix="eulerdisk-sweep-") as scratch:
        target = Path(out) if out is not None else Path(scratch)
        raw = _native.sweep(
            name, toml, folder, _assignments(set), str(target), jobs or 0, _progress(progress)
        )
        return SweepResult(
            table=Table.read_csv(Path(raw["table"])),
            points=int(raw["points"]),
            ran=int(raw["ran"]),
            skipped=int(raw["skipped"]),
            failed=int(raw["failed"]),
            out=Path(out) if out is not None else None,
        )
