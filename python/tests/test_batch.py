"""`Model.solve_many`: a parameter array or a batch of initial states, solved on the local
cores and stacked."""

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
