"""`Model.solve` returns what a SciPy user reads off `solve_ivp`'s result."""

import math

import numpy as np
import pytest
from support import OSCILLATOR

import eulerdisk

STIFF = """
mod stiff {
    params { lam = 1000.0 }
    states { x = 1.0 }
    equations { der(x) = -lam * (x - cos(t)); }
}
"""


@pytest.fixture
def oscillator():
    return eulerdisk.Model.from_str(OSCILLATOR)


def test_y_is_states_by_times_and_the_status_is_scipys(oscillator):
    s = oscillator.solve(3.0, state={"x": 1.0}, t_eval=0.01)
    assert s.y.shape == (2, len(s.t)) and s.states == ["x", "v"]
    np.testing.assert_array_equal(s.y[0], s["x"])
    np.testing.assert_array_equal(s.y[1], s["v"])
    assert "energy" in s.columns and "energy" not in s.states
    assert s.success and s.status == 0
    assert s.message == "The solver successfully reached the end of the integration interval."
    assert s.nfev == s.stats["rhs_evals"] > 0
    assert s.njev == 0 and s.nlu == 0
    stopped = oscillator.solve(3.0, state={"x": 1.0}, events=["x:down:stop"])
    assert stopped.status == 1 and stopped.message == "A termination event occurred."


def test_an_implicit_method_counts_jacobians_and_decompositions():
    s = eulerdisk.Model.from_str(STIFF).solve(1.0, method="rodas4")
    assert s.njev > 0 and s.nlu > 0


def test_t_events_and_y_events_follow_the_events_asked_for(oscillator):
    # x = cos 2t: down at pi/4, up at 3pi/4; v = -2 sin 2t: up at pi/2.
    s = oscillator.solve(
        3.0, state={"x": 1.0}, events=["x:up", "v", "x:down"], rtol=1e-10, atol=1e-12
    )
    assert len(s.t_events) == 3 and s.event_names == ["x", "v", "x"]
    np.testing.assert_allclose(s.t_events[0], [3 * math.pi / 4], atol=1e-9)
    np.testing.assert_allclose(s.t_events[1], [math.pi / 2], atol=1e-9)
    np.testing.assert_allclose(s.t_events[2], [math.pi / 4], atol=1e-9)
    assert s.y_events[0].shape == (1, 2)
    np.testing.assert_allclose(s.y_events[0][0], [0.0, 2.0], atol=1e-8)
    none = oscillator.solve(0.1, state={"x": 1.0}, events=["x"])
    assert none.t_events[0].shape == (0,) and none.y_events[0].shape == (0, 2)


def test_a_switched_models_events_are_grouped_by_name(dsl_examples):
    ball = eulerdisk.Model.from_file(dsl_examples / "bouncing_ball.dsl")
    s = ball.solve(10.0, t_eval=0.01, dense_output=True)
    assert s.event_names[0] == "impact"
    # The dense output follows the modes: free fall h = 1 - g t^2 / 2 until the impact.
    fall = np.linspace(0.0, 0.4, 9)
    np.testing.assert_allclose(s.sol(fall)[0], 1.0 - 9.81 * fall**2 / 2, atol=1e-9)
    assert s.t_events[0][0] == pytest.approx(math.sqrt(2 / 9.81), abs=1e-9)
    assert len(s.t_events[0]) == sum(e.name == "impact" for e in s.events)


@pytest.mark.parametrize(
    ("scipy", "ours"),
    [
        ("RK45", "dopri5"),
        ("rk45", "dopri5"),
        ("DOP853", "dop853"),
        ("Dopri5", "dopri5"),
        ("RODAS4", "rodas4"),
    ],
)
def test_scipys_method_names_mean_ours(oscillator, scipy, ours):
    a = oscillator.solve(1.0, state={"x": 1.0}, method=scipy)
    b = oscillator.solve(1.0, state={"x": 1.0}, method=ours)
    np.testing.assert_array_equal(a.t, b.t)
    np.testing.assert_array_equal(a.y, b.y)


@pytest.mark.parametrize("name", ["Radau", "BDF", "LSODA"])
def test_scipys_stiff_methods_point_to_rodas4(oscillator, name):
    with pytest.raises(eulerdisk.ModelInputError, match="rodas4"):
        oscillator.solve(1.0, method=name)


@pytest.mark.parametrize("method", ["dop853", "dopri5", "rodas4"])
def test_dense_output_is_the_integrators_own_interpolant(oscillator, method):
    s = oscillator.solve(3.0, state={"x": 1.0}, method=method, dense_output=True)
    assert s.sol is not None and s.sol.t_min == 0.0 and s.sol.t_max == 3.0
    # At the recorded steps, the interpolant gives the steps' own states.
    np.testing.assert_allclose(s.sol(s.t), s.y, rtol=0, atol=1e-12)
    # Between them, the same values as sampling at those times during the run.
    times = np.linspace(0.0, 3.0, 301)
    sampled = oscillator.solve(3.0, state={"x": 1.0}, method=method, t_eval=times)
    np.testing.assert_allclose(s.sol(times), sampled.y, rtol=0, atol=1e-12)
    assert s.sol(1.0).shape == (2,)
    # And the closed form, to the tolerance.
    np.testing.assert_allclose(s.sol(times)[0], np.cos(2 * times), atol=1e-6)


def test_without_dense_output_sol_is_none(oscillator):
    assert oscillator.solve(1.0).sol is None


def test_dense_output_of_a_run_without_steps_is_its_start(oscillator):
    s = oscillator.solve(0.0, state={"x": 1.0}, dense_output=True)
    assert s.sol is not None and s.sol.t_min == s.sol.t_max == 0.0
    np.testing.assert_array_equal(s.sol([0.0, 0.5]), [[1.0, 1.0], [0.0, 0.0]])


def test_max_step_and_first_step_shape_the_steps(oscillator):
    free = oscillator.solve(3.0, state={"x": 1.0})
    bounded = oscillator.solve(3.0, state={"x": 1.0}, max_step=0.01)
    assert np.max(np.diff(bounded.t)) <= 0.01 + 1e-12 < np.max(np.diff(free.t))
    first = oscillator.solve(3.0, state={"x": 1.0}, first_step=np.float64(1e-6))
    assert first.t[1] == pytest.approx(1e-6)
    for bad in [{"max_step": 0.0}, {"first_step": -1.0}, {"first_step": math.inf}]:
        with pytest.raises(eulerdisk.ModelInputError, match="step"):
            oscillator.solve(1.0, **bad)


DECAY = "mod decay { states { y } equations { der(y) = -y; } }"


def on_cosine(t0: float) -> dict[str, float]:
    """The oscillator's state on x = cos 2t at t0."""
    return {"x": math.cos(2 * t0), "v": -2 * math.sin(2 * t0)}


def test_a_t_end_before_t0_integrates_backward_to_the_closed_form(oscillator):
    # y' = -y from y(1) = 1/e back to t = 0: y(0) = 1.
    decay = eulerdisk.Model.from_str(DECAY)
    back = decay.solve(0.0, t0=1.0, state={"y": math.exp(-1.0)}, rtol=1e-10, atol=1e-12)
    assert back.t[0] == 1.0 and back.t[-1] == 0.0 and np.all(np.diff(back.t) < 0)
    assert back["y"][-1] == pytest.approx(1.0, abs=1e-9)
    np.testing.assert_allclose(back["y"], np.exp(-back.t), rtol=1e-9)
    # The oscillator from t = 3 back to 0 lands on x = 1, v = 0.
    s = oscillator.solve(0.0, t0=3.0, state=on_cosine(3.0), rtol=1e-10, atol=1e-12)
    assert s.success and s.status == 0
    np.testing.assert_allclose(s.y[:, -1], [1.0, 0.0], atol=1e-8)
    np.testing.assert_allclose(s["x"], np.cos(2 * s.t), atol=1e-8)


def test_forward_then_backward_returns_to_the_start(oscillator):
    start = np.array([0.3, -1.2])
    there = oscillator.solve(5.0, y0=start, rtol=1e-10, atol=1e-12)
    back = oscillator.solve(0.0, t0=5.0, y0=there.y[:, -1], rtol=1e-10, atol=1e-12)
    # Two runs of ~0.4 periods each way: a few hundred steps at local errors ~1e-10.
    np.testing.assert_allclose(back.y[:, -1], start, atol=1e-8)


@pytest.mark.parametrize("method", ["DOP853", "RK45", "rodas4"])
def test_dense_output_backward_is_the_closed_form(oscillator, method):
    s = oscillator.solve(
        0.0, t0=3.0, state=on_cosine(3.0), method=method, dense_output=True, rtol=1e-9, atol=1e-11
    )
    assert s.sol is not None and s.sol.t_min == 0.0 and s.sol.t_max == 3.0
    times = np.linspace(0.0, 3.0, 301)
    np.testing.assert_allclose(s.sol(times)[0], np.cos(2 * times), atol=1e-6)
    np.testing.assert_allclose(s.sol(s.t), s.y, rtol=0, atol=1e-12)
    assert s.sol(1.0).shape == (2,)


def test_events_backward_fire_as_the_run_proceeds(oscillator):
    # From t = 3 back to 0, x = cos 2t goes down through zero at 3 pi/4 and up at pi/4 as
    # t decreases (SciPy's direction is along the run; in t the slopes are the opposite).
    s = oscillator.solve(
        0.0, t0=3.0, state=on_cosine(3.0), events=["x:up", "x:down"], rtol=1e-10, atol=1e-12
    )
    np.testing.assert_allclose(s.t_events[0], [math.pi / 4], atol=1e-9)
    np.testing.assert_allclose(s.t_events[1], [3 * math.pi / 4], atol=1e-9)
    assert [e.t for e in s.events] == sorted((e.t for e in s.events), reverse=True)
    stopped = oscillator.solve(0.0, t0=3.0, state=on_cosine(3.0), events=["x:up:stop"])
    assert stopped.status == 1 and stopped.t[-1] == pytest.approx(math.pi / 4, abs=1e-8)


def test_t_eval_backward_decreases(oscillator):
    times = np.linspace(3.0, 0.0, 31)
    s = oscillator.solve(0.0, t0=3.0, state=on_cosine(3.0), t_eval=times)
    np.testing.assert_array_equal(s.t, times)
    np.testing.assert_allclose(s["x"], np.cos(2 * times), atol=1e-6)
    every = oscillator.solve(0.0, t0=3.0, state=on_cosine(3.0), t_eval=np.float32(0.5))
    np.testing.assert_array_equal(every.t, [3.0, 2.5, 2.0, 1.5, 1.0, 0.5, 0.0])
    with pytest.raises(eulerdisk.ModelInputError, match="decreasing times"):
        oscillator.solve(0.0, t0=3.0, t_eval=np.linspace(0.0, 3.0, 31))
    with pytest.raises(eulerdisk.ModelInputError, match="does not come after"):
        oscillator.solve(3.0, t_eval=times)


def test_max_step_and_first_step_are_lengths_backward(oscillator):
    s = oscillator.solve(0.0, t0=3.0, state=on_cosine(3.0), max_step=0.01, first_step=1e-6)
    assert np.max(np.abs(np.diff(s.t))) <= 0.01 + 1e-12
    assert s.t[1] == pytest.approx(3.0 - 1e-6)


def test_a_switched_model_is_refused_backward_saying_why(dsl_examples):
    ball = eulerdisk.Model.from_file(dsl_examples / "bouncing_ball.dsl")
    with pytest.raises(eulerdisk.ModelInputError, match=r"forward in time only.*inverse"):
        ball.solve(0.0, t0=1.0)
