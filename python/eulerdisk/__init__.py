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
:class:`KeyboardInterrupt` within a second (a run, a sweep or a solve stops at its next step).
"""

from __future__ import annotations

import csv
import json
import math
import os
import re
import sys
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from concurrent.futures import Executor
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt

from . import _native, _shards, _values
from ._batch import Batch
from ._model import Model, Real
from ._native import (
    DslError,
    ModelInputError,
    RunError,
    SceneError,
    SolveError,
    SweepError,
    __version__,
)
from ._solution import DenseOutput, Event, Solution

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "Batch",
    "DenseOutput",
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
    "__version__",
    "run",
    "sweep",
]

Array = npt.NDArray[np.float64]
PathLike = str | os.PathLike[str]


def _key(name: str) -> str:
    """A TOML key: bare (dotted keys nest, as in a file: ``run.t_end``), else quoted."""
    return name if re.fullmatch(r"[A-Za-z0-9_.-]+", name) else json.dumps(name)


def _toml(table: Mapping[str, Any]) -> str:
    """A scene or sweep given as nested dicts, written as the TOML file it stands for."""
    lines: list[str] = []

    def value(v: object) -> str:
        v = _values.scalar(v)
        if isinstance(v, bool | int | float):
            return _values.setting(v)
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
        # The mode changes after the start's decision, as the summary counts them.
        changes = sum(t != "initial_friction" for t in self.transitions.get("trigger", ()))
        return (
            f"RunResult(scene={self.summary.get('scene')!r}, {self.trajectory.rows} samples, "
            f"{changes} transitions, stop={self.stop_reason!r})"
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
    t_end: Real | None = None,
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
        progress: lines on standard error (the simulated time and the work done);
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
    sets = _values.assignments(set)
    if t_end is not None:
        sets.append(f"run.t_end={_values.setting(float(t_end))}")
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
    executor: Executor | None = None,
    shards: int | None = None,
) -> SweepResult:
    """Runs a sweep, as ``eulerdisk sweep`` does, and returns its table.

    On this machine's cores by default; with ``executor`` (any
    :class:`concurrent.futures.Executor`: the standard library's, or Dask's
    ``distributed.Client(...).get_executor()`` for a cluster), as ``shards`` tasks, each
    running its share of the points as ``eulerdisk sweep --shard i/n`` does, merged into
    ``out``'s table afterwards as ``eulerdisk sweep merge`` does. The executor's workers must
    see ``out`` (and a sweep file) at the same path: on one machine, or on a shared file
    system.

    Args:
        sweep: a built-in sweep's name, a sweep file's path, or the sweep as nested dicts (an
            optional top-level ``"name"``; relative scene paths start from the current folder).
        jobs: runs at once (default: the sweep's ``jobs``, else the number of cores); with
            an executor, runs at once in each task (default 1).
        out: the sweep's folder; a folder already holding some of its runs is resumed, as by
            the command line. By default a temporary folder, removed afterwards.
        set: overrides of every point's scene, as ``--set table.key=value``.
        progress: as for :func:`run`; with an executor, a line as each shard is done.
        executor: run the sweep's shards as this executor's tasks.
        shards: how many tasks (default: the number of cores here).

    Raises:
        SweepError: the sweep cannot be run; the message is the command line's.
        KeyboardInterrupt: Ctrl-C; finished runs are kept in ``out``, and running the same
            call again resumes the sweep. With an executor, the shards not started are
            cancelled and those on this process's threads stop at their next step; shards
            running elsewhere (other processes, a cluster's workers) finish into ``out``.
    """
    if jobs is not None and jobs < 1:
        raise SweepError("jobs must be at least 1")
    if shards is not None and shards < 1:
        raise SweepError("shards must be at least 1")
    if isinstance(sweep, Mapping):
        name = str(sweep.get("name", "python-sweep"))
        toml: str | None = _toml({k: v for k, v in sweep.items() if k != "name"})
        folder: str | None = os.getcwd()
    else:
        path = Path(sweep)
        name = str(path.resolve()) if path.is_file() else os.fspath(sweep)
        toml, folder = None, None
    sets = _values.assignments(set)
    with tempfile.TemporaryDirectory(prefix="eulerdisk-sweep-") as scratch:
        target = (Path(out) if out is not None else Path(scratch)).resolve()
        if executor is None:
            raw = _native.sweep(
                name, toml, folder, sets, str(target), jobs or 0, _progress(progress)
            )
        else:
            count = shards or os.cpu_count() or 1
            source = (name, toml, folder)
            raw, runs = _shards.on_executor(
                executor, source, sets, target, count, jobs or 1, _progress(progress)
            )
            raw.update(runs)
        return SweepResult(
            table=Table.read_csv(Path(raw["table"])),
            points=int(raw["points"]),
            ran=int(raw["ran"]),
            skipped=int(raw["skipped"]),
            failed=int(raw["failed"]),
            out=Path(out) if out is not None else None,
        )
