"""Bad input raises a Python exception naming what is wrong (the closest
name for a misspelt one), never a crash or a silent NaN; a failed simulation
raises flange.SimulationError with the time, the state and the reason."""

import math

import numpy as np
import pytest

import crane
import flange
import free_body


X = crane.initial_state(rail=-0.5, pivot=-math.pi / 2)


def test_unknown_names_suggest_the_closest():
    with pytest.raises(KeyError, match='no joint named "rial"; did you mean "rail"'):
        crane.initial_state(rial=1.0)
    with pytest.raises(flange.UnknownNameError, match='no parameter "m_lod"; did you mean "m_load"'):
        crane.Scene(m_lod=1.0)
    with pytest.raises(KeyError, match='no parameter "controller.kq"; did you mean "controller.kp"'):
        crane.simulate(X, [0, 1], params={"controller.kq": 1.0})
    with pytest.raises(KeyError, match='has no state field "vv"; did you mean "v"'):
        crane.initial_state(rail={"vv": 1.0})
    with pytest.raises(KeyError, match='no state field "q"'):
        free_body.initial_state(base={"q": 1.0})


@pytest.mark.parametrize("x, what", [(np.zeros(5), r"shape \(5,\); the scene's states have shape \(4,\)"),
                                     (np.zeros((2, 3)), r"shape \(2, 3\)"),
                                     (np.zeros((2, 2, 4)), r"shape \(2, 2, 4\)"),
                                     (np.zeros(4, dtype=complex), "dtype complex128"),
                                     (np.array(["a", "b", "c", "d"]), "dtype <U1"),
                                     ("abcd", "not an array of numbers")])
def test_bad_states_are_value_errors(x, what):
    with pytest.raises(ValueError, match=what):
        crane.derivative(0.0, x)


def test_integers_are_numbers():
    np.testing.assert_array_equal(crane.derivative(0.0, np.zeros(4, dtype=int)), crane.derivative(0.0, np.zeros(4)))


def test_bad_out_and_times():
    with pytest.raises(ValueError, match="out"):
        crane.derivative(0.0, X, np.zeros(3))
    with pytest.raises(ValueError, match="out must be a C-contiguous float64"):
        crane.derivative(0.0, X, np.zeros(4, dtype=np.float32))
    with pytest.raises(ValueError, match="t = nan is not finite"):
        crane.derivative(math.nan, X)
    with pytest.raises(ValueError, match="output time 1 is inf"):
        crane.simulate(X, [0.0, math.inf])
    with pytest.raises(ValueError, match="strictly increasing"):
        crane.simulate(X, [0.0, 1.0, 0.5])
    with pytest.raises(ValueError, match='method "euler"'):
        crane.simulate(X, [0.0, 1.0], method="euler")
    with pytest.raises(ValueError, match="tolerance .* cannot be met in double precision"):
        crane.simulate(X, [0.0, 1.0], atol=1e-20)


def test_bad_parameters_name_the_component_and_value():
    with pytest.raises(flange.ParameterError, match='Body "load": mass m = -1'):
        crane.Scene(m_load=-1.0)
    with pytest.raises(ValueError, match='parameter "m_load" = nan is not finite'):
        crane.Scene(m_load=math.nan)
    with pytest.raises(ValueError, match="is not a number"):
        crane.Scene(m_load="heavy")


def test_non_finite_state_in_a_call():
    with pytest.raises(ValueError, match="x is not finite"):
        crane.derivative(0.0, np.full(4, math.nan))


def test_nan_start_raises_with_time_state_and_reason():
    x = X.copy()
    x[1] = math.nan
    with pytest.raises(flange.SimulationError) as e:
        crane.simulate(x, [0.0, 1.0])
    assert e.value.time == 0.0
    assert math.isnan(e.value.state[1]) and e.value.state[0] == -0.5
    assert e.value.reason == "the state is not finite"


def test_spent_budget_raises_with_time_state_and_reason():
    with pytest.raises(flange.SimulationError, match="budget of 50 derivative evaluations is spent") as e:
        crane.simulate(X, [0.0, 5.0], max_rhs_evals=50)
    assert 0 < e.value.time < 5
    assert e.value.state.shape == (4,) and np.isfinite(e.value.state).all()
    assert "budget" in e.value.reason
    assert isinstance(e.value, flange.Error) and not isinstance(e.value, ValueError)


def test_ensemble_input_errors():
    with pytest.raises(ValueError, match="one value per case"):
        crane.ensemble({"m_load": [1.0, 2.0], "controller.kp": [1.0]}, [0.0, 1.0], x0=X)
    with pytest.raises(ValueError, match="x0 has 3 states for 2 cases"):
        crane.ensemble({"m_load": [1.0, 2.0]}, [0.0, 1.0], x0=np.zeros((3, 4)))
    with pytest.raises(KeyError, match='did you mean "m_load"'):
        crane.ensemble({"mload": [1.0]}, [0.0, 1.0], x0=X)
    with pytest.raises(ValueError, match="an ensemble runs forward"):
        crane.ensemble({"m_load": [1.0]}, [1.0, 0.0], x0=X)


def test_bad_recorders():
    t = [0.0, 1.0]
    with pytest.raises(KeyError, match='no state entry "pivot.vv"; did you mean "pivot.v"'):
        crane.ensemble({"m_load": [1.0]}, t, x0=X, recorders={"a": ("max", "pivot.vv")})
    with pytest.raises(ValueError, match='no recorder kind "maximum"'):
        crane.ensemble({"m_load": [1.0]}, t, x0=X, recorders={"a": ("maximum", "pivot.q")})
    with pytest.raises(ValueError, match='"settling" takes the level it settles about and the band'):
        crane.ensemble({"m_load": [1.0]}, t, x0=X, recorders={"a": ("settling", "rail.q")})
    with pytest.raises(ValueError, match="direction 2 is not"):
        crane.ensemble({"m_load": [1.0]}, t, x0=X, recorders={"a": ("crossing", "rail.q", 0.0, 2)})
    with pytest.raises(ValueError, match="is a tuple"):
        crane.ensemble({"m_load": [1.0]}, t, x0=X, recorders={"a": "max"})


def test_a_python_without_numpy_is_told_which_python_to_run():
    """A module imported by an interpreter without numpy (a pyenv or
    virtualenv python3 first on PATH) says so, and which Python it is for;
    the launcher beside the modules runs that one with no PATH at all."""
    import os
    import subprocess
    import sys

    here = os.path.dirname(crane.__file__)
    hide_numpy = "import sys; sys.modules['numpy'] = None; import crane"
    r = subprocess.run([sys.executable, "-c", hide_numpy], capture_output=True, text=True)
    assert r.returncode != 0
    assert "flange scene modules need numpy, which this Python (" in r.stderr
    assert "run them with the Python they were built for" in r.stderr
    assert "the python3 beside the module" in r.stderr
    launcher = os.path.join(here, "python3")
    r = subprocess.run([launcher, "-c", "import crane; print(crane.joints)"], capture_output=True, text=True,
                       env={})
    assert r.returncode == 0, r.stderr
    assert r.stdout.strip() == str(crane.joints)
