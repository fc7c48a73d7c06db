"""The package in a real session: interpreter exit, Ctrl-C, process pools, bad arguments."""

import concurrent.futures
import importlib.metadata
import multiprocessing
import pickle
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
from support import OSCILLATOR, seconds_to_interrupt

import eulerdisk


def test_the_interpreter_exits_cleanly_with_runs_in_flight(tmp_path):
    # Daemon threads inside `run`, `Model.solve` and `Model.solve_many` when the interpreter
    # exits: CPython ends such threads as they take the GIL back, which used to abort the
    # process (rc 134); a batch's own threads are daemons too, or the exit would wait for them.
    script = textwrap.dedent(
        f"""
        import threading, time
        import eulerdisk
        model = eulerdisk.Model.from_str({OSCILLATOR!r})
        solve = lambda: model.solve(1e6, state={{"x": 1.0}}, rtol=1e-12, atol=1e-14)
        run = lambda: eulerdisk.run("tangent-toy", t_end=100.0, progress=False)
        many = lambda: model.solve_many(
            1e6, params={{"k": [1.0, 2.0]}}, state={{"x": 1.0}}, t_eval=1.0,
            rtol=1e-12, atol=1e-14, workers=2,
        )
        for work in (solve, run, many):
            threading.Thread(target=work, daemon=True).start()
        time.sleep(0.5)
        print("leaving")
        """
    )
    # From another folder: `python -c` puts its working folder first on the path, and the
    # tests run in python/, where `eulerdisk/` is the package's source without its native part.
    start = time.monotonic()
    done = subprocess.run(
        [sys.executable, "-c", script],
        capture_output=True,
        text=True,
        timeout=120,
        cwd=tmp_path,
    )
    # Without waiting for the work (minutes): no thread of the package holds the exit.
    assert time.monotonic() - start < 20.0
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "leaving"
    assert "FATAL" not in done.stderr


def test_ctrl_c_stops_a_solve_within_a_second():
    model = eulerdisk.Model.from_str(OSCILLATOR)
    solve = lambda: model.solve(1e5, state={"x": 1.0}, rtol=1e-13, atol=1e-15, t_eval=1.0)  # noqa: E731
    assert seconds_to_interrupt(solve) < 1.0


def test_errors_and_models_pickle():
    for error in (eulerdisk.ModelInputError("bad"), eulerdisk.SolveError("failed")):
        back = pickle.loads(pickle.dumps(error))
        assert type(back) is type(error) and str(back) == str(error)
    with pytest.raises(eulerdisk.SceneError) as caught:
        eulerdisk.run("tangent-toy", set={"run.no_such_key": 1}, progress=False)
    back = pickle.loads(pickle.dumps(caught.value))
    assert type(back) is eulerdisk.SceneError and back.key == "run.no_such_key"
    for cls in (eulerdisk.SceneError, eulerdisk.DslError, eulerdisk.SweepError):
        assert cls.__module__ == "eulerdisk"
    token = eulerdisk._native.Cancel()
    token.set()
    # A cancel token crosses to another process as a fresh one (that process cannot see it).
    assert not pickle.loads(pickle.dumps(token)).is_set()
    model = eulerdisk.Model.from_str(OSCILLATOR, "osc.dsl")
    again = pickle.loads(pickle.dumps(model))
    assert again.states == model.states
    np.testing.assert_array_equal(again.solve(1.0).y, model.solve(1.0).y)


def test_a_process_pool_solves_and_reports_errors(dsl_examples):
    model = eulerdisk.Model.from_file(dsl_examples / "heavy_top.dsl")
    spawn = multiprocessing.get_context("spawn")
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=spawn) as pool:
        spins = [100.0, 150.0]
        futures = [pool.submit(model.solve, 0.2, state={"w_psi": w}) for w in spins]
        solved = [f.result() for f in futures]
        failed = pool.submit(model.solve, 0.2, method="euler")
        with pytest.raises(eulerdisk.ModelInputError, match="euler"):
            failed.result()
    for w, s in zip(spins, solved, strict=True):
        np.testing.assert_array_equal(s.y, model.solve(0.2, state={"w_psi": w}).y)


def test_t_eval_too_long_is_refused_before_anything_is_allocated():
    model = eulerdisk.Model.from_str(OSCILLATOR)
    huge = np.broadcast_to(np.float64(0.5), (200_000_000,))  # a view: no memory
    start = time.monotonic()
    with pytest.raises(eulerdisk.ModelInputError, match="200000000 times"):
        model.solve(1.0, t_eval=huge)
    with pytest.raises(eulerdisk.ModelInputError, match="too many"):
        model.solve(1.0, t_eval=1e-9)
    assert time.monotonic() - start < 1.0


def test_events_must_be_a_sequence_of_names():
    model = eulerdisk.Model.from_str(OSCILLATOR)
    with pytest.raises(TypeError, match=r"\['x'\]"):
        model.solve(1.0, events="x")
    assert len(model.solve(1.0, events=("x",)).t_events) == 1


@pytest.mark.parametrize("tolerances", [{"rtol": 0.0}, {"atol": 0.0}, {"rtol": float("nan")}])
def test_tolerances_must_be_positive(tolerances):
    model = eulerdisk.Model.from_str(OSCILLATOR)
    with pytest.raises(eulerdisk.ModelInputError, match="positive"):
        model.solve(1.0, **tolerances)


def test_the_version_is_the_packages():
    assert eulerdisk.__version__ == importlib.metadata.version("eulerdisk")


def test_repr_counts_the_transitions_the_summary_counts():
    r = eulerdisk.run("tangent-toy", t_end=1.0, progress=False)
    assert r.transitions["trigger"][0] == "initial_friction"
    assert f"{r.summary['transitions']} transitions" in repr(r)
