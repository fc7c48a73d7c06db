"""Type stubs of the compiled half of the package (``eulerdisk._native``)."""

from typing import Any

__version__: str
MAX_SAMPLES: int
"""The most times a solve records at."""
DENSE_NODES: int
"""The nodes at which each step's dense output is kept."""

class SceneError(ValueError):
    """A scene that cannot be run; ``key`` is the scene key it is about, or None."""

    key: str | None

class DslError(ValueError):
    """A model file with errors, each located as ``file:line:col`` with a caret."""

class ModelInputError(ValueError):
    """An unusable argument of ``Model.eval`` or ``Model.solve``."""

class SolveError(RuntimeError):
    """A model that could not be evaluated or integrated."""

class SweepError(ValueError):
    """A sweep that cannot be run."""

class RunError(RuntimeError):
    """A run whose outputs could not be written."""

class Cancel:
    """A flag that stops a call running on another thread at its next step (it pickles as a
    fresh token)."""

    def set(self) -> None:
        """Stops the calls that watch this token."""

    def is_set(self) -> bool:
        """Whether the token was set."""

def run(
    scene: str,
    toml: str | None,
    sets: list[str],
    out_dir: str,
    progress: bool,
    trajectory_file: bool,
    figures: bool,
) -> dict[str, Any]:
    """Runs a scene as ``eulerdisk run`` does; the columns as bytes of ``f64``."""

def default_scene() -> str:
    """The scene ``eulerdisk run`` runs when none is given."""

def sweep(
    sweep: str,
    toml: str | None,
    folder: str | None,
    sets: list[str],
    out: str,
    jobs: int,
    progress: bool,
    shard: tuple[int, int] | None = None,
    cancel: Cancel | None = None,
) -> dict[str, Any]:
    """Runs a sweep (or shard ``(index, count)`` of it) into ``out``; the path of its table
    and the counts of its runs. ``cancel`` set stops it as Ctrl-C does."""

def merge_sweep(dirs: list[str], out: str) -> dict[str, Any]:
    """Joins sweep folders (shards) into ``out``; its table and the counts of points, rows,
    missing and duplicated points."""

class NativeModel:
    """A compiled model file."""

    @staticmethod
    def from_file(path: str, cache: bool = True) -> NativeModel:
        """Compiles the model file at ``path`` (through the cache of compiled models when
        ``cache``)."""

    @staticmethod
    def from_text(name: str, text: str, cache: bool = True) -> NativeModel:
        """Compiles a model given as text (through the cache when ``cache``)."""

    @property
    def cache_hit(self) -> bool:
        """Whether the compiled models came from the cache."""

    @property
    def name(self) -> str:
        """The model's name."""

    @property
    def states(self) -> list[str]:
        """The states."""

    @property
    def params(self) -> list[tuple[str, float | None]]:
        """The parameters and their defaults."""

    @property
    def outputs(self) -> list[str]:
        """The outputs."""

    @property
    def charts(self) -> list[str]:
        """The charts' names."""

    @property
    def modes(self) -> list[str]:
        """The modes' names."""

    def show(self, latex: bool) -> str:
        """The solved equations."""

    def eval(self, chart: str | None, t: float, state: list[str], sets: list[str]) -> str:
        """Derivatives and outputs at one point, as JSON."""

    def solve(
        self,
        chart: str | None,
        state: list[str],
        sets: list[str],
        events: list[str],
        t0: float,
        t_end: float,
        dt: float | None,
        times: bytes | None,
        method: str,
        rtol: float,
        atol: float,
        first_step: float | None,
        max_step: float | None,
        dense: bool,
        cancel: Cancel | None = None,
    ) -> dict[str, Any]:
        """Integrates the model; ``times`` as the bytes of native ``f64``; ``cancel`` set
        stops it at its next step (its stop then ``interrupted``)."""
