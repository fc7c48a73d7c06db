"""NumPy numbers and arrays go wherever a number or an array goes, as Python's do."""

import math

import numpy as np
import pytest
from support import OSCILLATOR

import eulerdisk

# One number, in every spelling a NumPy session produces.
HALF = [
    0.5,
    np.float64(0.5),
    np.float32(0.5),
    np.float16(0.5),
    np.array(0.5),
    np.array(0.5, dtype=np.float32),
    np.longdouble(0.5),
]
TWO = [2, np.int64(2), np.int32(2), np.uint8(2), np.array(2), np.array(2, dtype=np.int16)]


@pytest.mark.parametrize("k", HALF + TWO, ids=lambda v: f"{type(v).__name__}:{v!r}")
def test_params_and_state_take_numpy_scalars_and_0d_arrays(k):
    m = eulerdisk.Model.from_str(OSCILLATOR)
    s = m.solve(1.0, state={"x": k}, params={"k": k}, rtol=1e-10, atol=1e-12)
    w = math.sqrt(float(k))
    assert s["x"][-1] == pytest.approx(float(k) * math.cos(w), abs=1e-8)
    point = m.eval({"x": k, "v": k}, {"k": k}, t=np.float32(0))
    assert point["derivatives"]["der(v)"] == pytest.approx(-float(k) * float(k))


def test_a_parameter_loop_over_linspace_runs():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    ends = [
        m.solve(np.float64(1.0), state={"x": 1.0}, params={"k": k})["x"][-1]
        for k in np.linspace(1.0, 4.0, 4)
    ]
    assert ends == pytest.approx([math.cos(math.sqrt(k)) for k in [1.0, 2.0, 3.0, 4.0]], abs=1e-6)


@pytest.mark.parametrize(
    "dt", [0.1, np.float64(0.1), np.float32(0.1), np.array(0.1)], ids=lambda v: type(v).__name__
)
def test_t_eval_as_a_numpy_number_is_a_step(dt):
    m = eulerdisk.Model.from_str(OSCILLATOR)
    s = m.solve(1.0, state={"x": 1.0}, t_eval=dt)
    assert len(s.t) == 11
    assert s.t[1] == pytest.approx(float(dt))


def test_y0_is_every_state_in_the_models_order():
    m = eulerdisk.Model.from_str(OSCILLATOR)
    by_array = m.solve(1.0, y0=np.array([1.0, -0.5]), t_eval=0.25)
    by_name = m.solve(1.0, state={"x": 1.0, "v": -0.5}, t_eval=0.25)
    np.testing.assert_array_equal(by_array.y, by_name.y)
    np.testing.assert_array_equal(m.solve(1.0, y0=[1, 0]).y[:, 0], [1.0, 0.0])
    with pytest.raises(eulerdisk.ModelInputError, match="2 states"):
        m.solve(1.0, y0=[1.0, 2.0, 3.0])
    with pytest.raises(eulerdisk.ModelInputError, match="not both"):
        m.solve(1.0, y0=[1.0, 2.0], state={"x": 1.0})


# 0.25 is exact in every float width, so each spelling asks for the same end time.
@pytest.mark.parametrize(
    "value",
    [0.25, np.float64(0.25), np.float32(0.25), np.array(0.25)],
    ids=lambda v: type(v).__name__,
)
def test_run_takes_numpy_numbers_in_t_end_and_set(value):
    r = eulerdisk.run(
        "tangent-toy", t_end=value, set={"run.sample_rate": np.int64(100)}, progress=False
    )
    assert len(r["t"]) == 26
    assert r.provenance["overrides"][-1] == f"run.t_end={float(value)!r}"
    by_set = eulerdisk.run("tangent-toy", set={"run.t_end": value, "run.sample_rate": 100})
    np.testing.assert_array_equal(by_set["theta"], r["theta"])


def test_a_scene_dict_takes_numpy_numbers(root):
    import tomllib

    table = tomllib.loads((root / "scenes" / "tangent-toy.toml").read_text())
    table["run"] = {**table.get("run", {}), "t_end": np.float64(0.2), "sample_rate": np.int32(50)}
    r = eulerdisk.run(table, progress=False)
    assert len(r["t"]) == 11


def test_a_numpy_array_in_set_is_refused_with_its_shape():
    with pytest.raises(TypeError, match="shape"):
        eulerdisk.run("tangent-toy", set={"run.t_end": np.array([1.0, 2.0])}, progress=False)
