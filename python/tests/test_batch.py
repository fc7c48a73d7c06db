"""`Model.solve_many`: a parameter array or a batch of initial states, solved on the local
cores and stacked."""

import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest
from support import OSCILLATOR

import eulerdisk


@pytest.fixture
def oscillator():
    return eulerdisk.Model.from_str(OSCILLATOR)


def test_a_parameter_array_gives_stacked_solves_equal_to_single_ones(oscillator):
    ks = np.linspace(1.0, 4.0, 5)
    batch = oscillator.solve_many(
        2.0, params={"k": ks}, t_eval=0.1, method="RK45", state={"x": 1.0}
    )
    assert len(batch) == 5 and batch.y.shape == (5, 2, 21) and batch.t.shape == (21,)
    assert batch["energy"].shape == (5, 21)
    for k, y in zip(ks, batch.y, strict=True):
        np.testing.assert_array_equal(
            y, oscillator.solve(2.0, params={"k": k}, t_eval=0.1, method="RK45", state={"x": 1.0}).y
        )
    np.testing.assert_allclose(batch.y[:, 0, -1], np.cos(np.sqrt(ks) * 2.0), atol=1e-7)


def test_a_batch_of_initial_states_with_shared_params(oscillator):
    y0 = np.array([[1.0, 0.0], [0.0, 1.0], [2.0, -1.0]])
    batch = oscillator.solve_many(1.0, y0=y0, params={"k": 1.0}, t_eval=[0.0, 0.5, 1.0], workers=2)
    np.testing.assert_array_equal(batch.y[:, :, 0], y0)
    t = 1.0
    expected = y0[:, 0] * np.cos(t) + y0[:, 1] * np.sin(t)
    np.testing.assert_allclose(batch.y[:, 0, -1], expected, atol=1e-7)


def test_bad_batches_are_refused(oscillator):
    with pytest.raises(eulerdisk.ModelInputError, match="one length"):
        oscillator.solve_many(1.0, params={"k": [1.0, 2.0], "x": [1.0]}, t_eval=0.1)
    with pytest.raises(eulerdisk.ModelInputError, match="as many"):
        oscillator.solve_many(1.0, params={"k": [1.0, 2.0]}, y0=np.zeros((3, 2)), t_eval=0.1)
    with pytest.raises(eulerdisk.ModelInputError, match="other times"):
        oscillator.solve_many(
            2.0,
            y0=[[1.0, 0.0], [0.5, 0.0]],
            params={"k": [4.0, 1.0]},
            t_eval=0.1,
            events=["x:down:stop"],
        )


def test_the_solves_run_at_the_same_time(oscillator):
    # Each solve releases the GIL: on two workers the two solves overlap in time.
    spans = []
    solve = oscillator.solve

    def timed(*args, **kwargs):
        start = time.monotonic()
        try:
            return solve(*args, **kwargs)
        finally:
            spans.append((start, time.monotonic()))

    oscillator.solve = timed
    oscillator.solve_many(
        5e3,
        params={"k": [1.0, 2.0]},
        state={"x": 1.0},
        t_eval=1.0,
        rtol=1e-13,
        atol=1e-15,
        workers=2,
    )
    (a0, a1), (b0, b1) = spans
    overlap = min(a1, b1) - max(a0, b0)
    assert overlap > 0.5 * min(a1 - a0, b1 - b0), spans


def test_ctrl_c_stops_every_solve_of_a_batch_within_a_second(tmp_path):
    # SIGINT reaches the main thread only: there it sets the batch's token, which the solves
    # on the pool's threads watch. In a process of its own, as a terminal sends it; each
    # solve alone would take half a minute.
    script = textwrap.dedent(
        f"""
        import eulerdisk
        model = eulerdisk.Model.from_str({OSCILLATOR!r})
        print("solving", flush=True)
        try:
            model.solve_many(
                1e5, params={{"k": [1.0, 2.0, 3.0, 4.0]}}, state={{"x": 1.0}}, t_eval=1.0,
                rtol=1e-13, atol=1e-15, workers=2,
            )
        except KeyboardInterrupt:
            print("interrupted", flush=True)
        """
    )
    # From another folder, for the reason test_session's exit test gives.
    child = subprocess.Popen(
        [sys.executable, "-c", script],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
    )
    try:
        assert child.stdout is not None
        assert child.stdout.readline().strip() == "solving"
        time.sleep(0.5)
        sent = time.monotonic()
        child.send_signal(signal.SIGINT)
        said = child.stdout.readline().strip()
        elapsed = time.monotonic() - sent
        _, err = child.communicate(timeout=30)
    finally:
        child.kill()
    assert said == "interrupted", f"exit status {child.returncode}, stderr: {err!r}"
    assert elapsed < 1.0
    assert child.returncode == 0, err


def test_a_failed_solve_stops_the_others_at_once(oscillator):
    # The second row cannot start (NaN); the first alone would take half a minute.
    start = time.monotonic()
    with pytest.raises(eulerdisk.ModelInputError, match="finite"):
        oscillator.solve_many(
            1e5, y0=[[1.0, 0.0], [np.nan, 0.0]], t_eval=1.0, rtol=1e-13, atol=1e-15, workers=2
        )
    assert time.monotonic() - start < 1.0
