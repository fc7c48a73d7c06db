"""`eulerdisk.Model`: DSL files compiled and run by the interpreter, checked by closed forms."""

import math

import numpy as np
import pytest
from support import OSCILLATOR

import eulerdisk


def test_a_model_from_text_names_its_states_params_and_outputs():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    assert m.name == "oscillator"
    assert m.states == ["x", "v"]
    assert m.params == {"k": 4.0}
    assert m.outputs == ["energy"]
    assert m.modes == []
    assert "oscillator" in repr(m)


def test_eval_gives_the_derivatives_and_outputs():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    point = m.eval({"x": 0.5, "v": -1.0}, {"k": 2.0})
    assert point["derivatives"] == {"der(x)": -1.0, "der(v)": -1.0}
    assert point["outputs"]["energy"] == pytest.approx(0.5 + 0.25)


def test_solve_follows_the_closed_form_and_locates_events():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    s = m.solve(3.0, state={"x": 1.0}, t_eval=0.01, events=["x"], rtol=1e-10, atol=1e-12)
    assert len(s.t) == 301
    np.testing.assert_allclose(s["x"], np.cos(2 * s.t), atol=1e-8)
    np.testing.assert_allclose(s["v"], -2 * np.sin(2 * s.t), atol=1e-8)
    # x = cos 2t crosses zero at π/4 (falling) and 3π/4 (rising).
    assert [e.name for e in s.events] == ["x", "x"]
    assert [e.t for e in s.events] == pytest.approx([math.pi / 4, 3 * math.pi / 4], abs=1e-9)
    assert s.events[0].values["v"] == pytest.approx(-2.0, abs=1e-8)
    assert s.stop == "end_time"
    assert s.stats["steps"] > 0 and s.stats["rhs_evals"] > s.stats["steps"]
    frame = s.to_pandas()
    assert list(frame.columns) == ["t", "x", "v", "energy"]


def test_t_eval_times_are_recorded_exactly_as_given():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    times = np.sort(np.random.default_rng(7).uniform(0.0, 3.0, 57))
    s = m.solve(3.0, state={"x": 1.0}, t_eval=times, rtol=1e-10, atol=1e-12)
    np.testing.assert_array_equal(s.t, times)
    np.testing.assert_allclose(s["x"], np.cos(2 * times), atol=1e-8)
    for bad, words in [
        ([0.5, 0.2], "does not come after"),
        ([0.5, 4.0], "outside the run's span"),
        ([math.nan], "not finite"),
    ]:
        with pytest.raises(eulerdisk.ModelInputError, match=words):
            m.solve(3.0, state={"x": 1.0}, t_eval=bad)


def test_a_terminal_event_ends_the_solve_there():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    s = m.solve(3.0, state={"x": 1.0}, events=["x:down:stop"], method="dopri5")
    assert s.stop == "event x"
    assert s.t[-1] == pytest.approx(math.pi / 4, abs=1e-8)


DECAY = """
mod decay {
    params { k = 1.0 }
    states { x = 2.0, y = 3.0 }
    equations { der(x) = -k * x; der(y) = 0; }
}
"""


def test_solve_starts_at_the_initial_values_the_file_writes():
    m = eulerdisk.Model.from_str(DECAY)
    s = m.solve(1.0, rtol=1e-12, atol=1e-14, t_eval=0.25)
    assert np.allclose(s["x"], 2.0 * np.exp(-s.t), rtol=0, atol=1e-11)
    assert np.all(s["y"] == 3.0)
    # state= overrides the file's value; the other state keeps its own.
    s = m.solve(1.0, state={"x": 1.0}, rtol=1e-12, atol=1e-14)
    assert s["x"][-1] == pytest.approx(math.exp(-1.0), abs=1e-11)
    assert s["y"][-1] == 3.0
    assert m.eval()["derivatives"]["der(x)"] == -2.0


def test_the_heavy_top_starts_away_from_its_singular_point(dsl_examples):
    top = eulerdisk.Model.from_file(dsl_examples / "heavy_top.dsl")
    s = top.solve(0.5)
    assert s["theta"][0] == 0.3 and s["w_psi"][0] == 150.0
    assert np.all(np.isfinite(s["energy"]))


def test_the_heavy_top_keeps_its_energy_and_momenta(dsl_examples):
    top = eulerdisk.Model.from_file(dsl_examples / "heavy_top.dsl")
    assert top.states == ["phi", "theta", "psi", "w_phi", "w_theta", "w_psi"]
    s = top.solve(2.0, state={"theta": 0.3, "w_psi": 150.0, "w_phi": 2.0})
    for name in ["energy", "momentum_phi", "momentum_psi"]:
        drift = np.max(np.abs(s[name] - s[name][0]))
        assert drift <= 1e-7 * abs(s[name][0]) + 1e-12, (name, drift)


def test_eval_of_the_heavy_top_matches_its_equations_in_numpy(dsl_examples):
    top = eulerdisk.Model.from_file(dsl_examples / "heavy_top.dsl")
    m, g, arm, i1, i3 = 0.5, 9.81, 0.04, 0.0012, 0.0009
    phi, th, psi, wphi, wth, wpsi = 0.1, 0.7, 0.2, 3.0, 1.5, 120.0
    got = top.eval(dict(zip(top.states, [phi, th, psi, wphi, wth, wpsi], strict=True)))
    w3 = wpsi + wphi * math.cos(th)
    s, c = math.sin(th), math.cos(th)
    dwth = (i1 * wphi**2 * s * c - i3 * w3 * wphi * s + m * g * arm * s) / i1
    assert got["derivatives"]["der(w_theta)"] == pytest.approx(dwth, rel=1e-12)
    # Conserved p_phi = I1 w_phi sin²θ + I3 ω3 cosθ: its derivative vanishes.
    dth, dwphi = wth, got["derivatives"]["der(w_phi)"]
    dwpsi = got["derivatives"]["der(w_psi)"]
    dw3 = dwpsi + dwphi * c - wphi * s * dth
    dpphi = i1 * (dwphi * s * s + 2 * wphi * s * c * dth) + i3 * (dw3 * c - w3 * s * dth)
    assert dpphi == pytest.approx(0.0, abs=1e-9)


def test_a_switched_model_bounces_and_comes_to_rest(dsl_examples):
    ball = eulerdisk.Model.from_file(dsl_examples / "bouncing_ball.dsl")
    assert ball.modes == ["flying", "resting"]
    s = ball.solve(10.0, t_eval=0.01)
    first = s.events[0]
    assert first.name == "impact"
    assert first.t == pytest.approx(math.sqrt(2 * 1.0 / 9.81), abs=1e-9)
    assert any(e.name == "impact accumulates" for e in s.events)
    # Rest at the accumulation: the flight times form a geometric series of ratio e = 0.8.
    t1 = math.sqrt(2 / 9.81)
    rest = t1 + 2 * t1 * 0.8 / (1 - 0.8)
    accumulated = next(e for e in s.events if e.name == "impact accumulates")
    assert accumulated.t == pytest.approx(rest, rel=1e-6)
    assert np.all(s["h"] >= -1e-9)
    assert s["h"][-1] == 0.0 and s["v"][-1] == 0.0
    assert s.notes and "accumulate" in s.notes[0]


def test_the_rich_display_shows_the_solved_equations(dsl_examples):
    top = eulerdisk.Model.from_file(dsl_examples / "heavy_top.dsl")
    assert "der(" in top._repr_markdown_()
    latex = top._repr_latex_()
    assert "\\" in latex and latex != top._repr_markdown_()
    ball = eulerdisk.Model.from_file(dsl_examples / "bouncing_ball.dsl")
    assert "impact" in ball.markdown()


def test_dsl_errors_are_located_with_a_caret():
    with pytest.raises(eulerdisk.DslError) as caught:
        eulerdisk.Model.from_str(
            OSCILLATOR.replace("der(v) = -k * x;", "der(v) = -k * ;"), "osc.dsl"
        )
    message = str(caught.value)
    assert isinstance(caught.value, ValueError)
    assert "osc.dsl:" in message
    line = next(n for n, text in enumerate(OSCILLATOR.splitlines(), 1) if "der(v)" in text)
    assert f"osc.dsl:{line}:" in message
    assert "^" in message


def test_a_missing_file_is_a_dsl_error_naming_it(tmp_path):
    with pytest.raises(eulerdisk.DslError, match="cannot read"):
        eulerdisk.Model.from_file(tmp_path / "absent.dsl")


@pytest.mark.parametrize(
    ("call", "said"),
    [
        (lambda m: m.solve(1.0, state={"y": 1.0}), "`y`"),
        (lambda m: m.solve(1.0, params={"q": 1.0}), "`q`"),
        (lambda m: m.solve(1.0, method="euler"), "method `euler`"),
        (lambda m: m.solve(1.0, events=["nothing"]), "nothing"),
        (lambda m: m.solve(1.0, rtol=-1.0), "tol"),
        (lambda m: m.solve(1.0, chart="polar"), "polar"),
        (lambda m: m.eval({"w": 1.0}), "`w`"),
    ],
)
def test_bad_arguments_raise_model_input_errors(call, said):
    m = eulerdisk.Model.from_str(OSCILLATOR)
    with pytest.raises(eulerdisk.ModelInputError) as caught:
        call(m)
    assert said in str(caught.value)


def test_a_singular_model_raises_a_solve_error():
    singular = eulerdisk.Model.from_str(
        "mod singular { params { a = 0.0 } states { x } equations { a * der(x) = 1; } }"
    )
    with pytest.raises(eulerdisk.SolveError):
        singular.eval({"x": 0.0})


def test_a_second_load_comes_from_the_cache_and_cache_false_bypasses_it(dsl_examples, cache_home):
    path = dsl_examples / "heavy_top.dsl"
    models = cache_home / "eulerdisk" / "models"
    uncached = eulerdisk.Model.from_file(path, cache=False)
    assert not uncached.cache_hit
    assert not models.exists(), "cache=False writes no entry"
    first = eulerdisk.Model.from_file(path)
    assert not first.cache_hit
    assert len(list(models.iterdir())) == 1
    second = eulerdisk.Model.from_file(path)
    assert second.cache_hit
    # The entry is keyed by the text: the same text given by value (a model unpickled in a
    # worker) finds it; cache=False compiles it again.
    assert eulerdisk.Model.from_str(path.read_text(encoding="utf-8"), name="top").cache_hit
    assert not eulerdisk.Model.from_file(path, cache=False).cache_hit
    assert len(list(models.iterdir())) == 1
    # What the cache gives solves as what was compiled, to the bit.
    solved = [m.solve(0.5).y for m in (uncached, second)]
    np.testing.assert_array_equal(solved[0], solved[1])
