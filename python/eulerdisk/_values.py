"""Numbers and arrays as the native calls take them, from Python or NumPy.

A value the command line spells ``NAME=VALUE`` is converted by what it is, never by its
``repr()`` (which NumPy 2 spells ``np.float64(0.5)``): a boolean as TOML's ``true``/``false``,
an integer of any kind (``int``, a NumPy integer, a 0-d integer array) with
:func:`operator.index`, any other real number (``float``, a NumPy float of any width, a 0-d
array) with :func:`float`, written back exactly (``repr`` of a Python ``float``).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from ._native import MAX_SAMPLES, ModelInputError


def scalar(value: object) -> object:
    """A NumPy scalar or 0-d array as the Python scalar it holds; anything else unchanged."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        value = value[()]
    if isinstance(value, np.generic):
        return value.item()
    return value


def setting(value: object) -> str:
    """One value as the command line's ``--set`` writes it (TOML's spelling)."""
    value = scalar(value)
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return value
    if isinstance(value, np.ndarray):
        raise TypeError(f"a setting takes one number, not an array of shape {value.shape}")
    try:
        return str(operator.index(value))
    except TypeError:
        pass
    try:
        return repr(float(value))  # type: ignore[arg-type]
    except (TypeError, ValueError):
        return str(value)


def assignments(values: Mapping[str, object] | None) -> list[str]:
    """``{"a.b": 1}`` as ``["a.b=1"]``: the command line's ``NAME=VALUE`` arguments."""
    return [f"{key}={setting(value)}" for key, value in (values or {}).items()]


def initial_states(
    names: Sequence[str], state: Mapping[str, object] | None, y0: object | None
) -> dict[str, object] | None:
    """The initial states by name, from ``state=`` or from ``y0=`` in the model's order."""
    if y0 is None:
        return dict(state) if state is not None else None
    if state is not None:
        raise ModelInputError("give the initial state as `state=` (by name) or `y0=`, not both")
    values = np.asarray(y0, dtype=float)
    if values.shape != (len(names),):
        raise ModelInputError(
            f"y0 has shape {values.shape}; the model has {len(names)} states, in this order: "
            + ", ".join(names)
        )
    return dict(zip(names, values.tolist(), strict=True))


def tolerance(name: str, value: object) -> float:
    """A tolerance: a positive, finite number."""
    number = float(value)  # type: ignore[arg-type]
    if not (math.isfinite(number) and number > 0.0):
        raise ModelInputError(f"{name} = {number}: a tolerance must be positive and finite")
    return number


def step(name: str, value: object | None) -> float | None:
    """``first_step`` or ``max_step``: None, or a positive number (``max_step`` may be inf)."""
    if value is None:
        return None
    number = float(value)  # type: ignore[arg-type]
    if not number > 0.0 or (name == "first_step" and math.isinf(number)):
        raise ModelInputError(f"{name} = {number}: a step size must be positive")
    return None if math.isinf(number) else number


def sampling(t_eval: object | None) -> tuple[float | None, bytes | None]:
    """``t_eval`` as the native call takes it: a sampling step, or the sampling times as the
    bytes of native ``f64``. The count is checked before any array is made."""
    if t_eval is None:
        return None, None
    if np.ndim(t_eval) == 0:  # type: ignore[arg-type]
        return float(scalar(t_eval)), None  # type: ignore[arg-type]
    count = int(np.size(t_eval))  # type: ignore[arg-type]
    if count > MAX_SAMPLES:
        raise ModelInputError(
            f"t_eval has {count} times: at most {MAX_SAMPLES} are recorded "
            "(a step, t_eval=dt, records every dt)"
        )
    times = np.ascontiguousarray(t_eval, dtype=np.float64).ravel()
    return None, times.tobytes()


def event_specs(events: Iterable[str]) -> list[str]:
    """The events as a list of ``NAME[:up|:down][:stop]`` strings (a lone string is refused:
    it would be read as one event per character)."""
    if isinstance(events, str | bytes):
        raise TypeError(f"events must be a sequence of names, e.g. [{events!r}], not a string")
    specs = list(events)
    for spec in specs:
        if not isinstance(spec, str):
            raise TypeError(f"an event is a string NAME[:up|:down][:stop], not {spec!r}")
    return specs


def method(name: str) -> str:
    """The integrator called ``name``: ours, or SciPy's name for the same method."""
    lowered = name.lower()
    known = {"rk45": "dopri5", "dopri5": "dopri5", "dop853": "dop853", "rodas4": "rodas4"}
    if lowered in known:
        return known[lowered]
    if lowered in {"radau", "bdf", "lsoda"}:
        raise ModelInputError(
            f"method `{name}`: not available; for a stiff model use `rodas4` (a Rosenbrock "
            "method, implicit like Radau and BDF); RK45 (dopri5) and DOP853 are the explicit ones"
        )
    raise ModelInputError(
        f"method `{name}`: expected one of dopri5 (RK45), dop853 (DOP853), rodas4"
    )
