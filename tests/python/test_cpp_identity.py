"""Every module call gives the C++ API's numbers bit for bit: the
derivative, the Jacobian, the energy, simulate with dopri5 and rosenbrock4,
and the ensemble (each case as C++ simulate() runs it)."""

import numpy as np
import pytest

import crane
import free_body
import spatial_arm
import spatial_arm_py
from conftest import as_array

MODULES = {"crane": crane, "spatial_arm": spatial_arm, "urdf_arm": spatial_arm_py, "free_body": free_body}


@pytest.mark.parametrize("name", sorted(MODULES))
def test_derivative_jacobian_energy(reference, name):
    m, ref = MODULES[name], reference[name]
    x = as_array(ref["x"])
    np.testing.assert_array_equal(m.derivative(0.25, x), as_array(ref["dxdt"]))
    np.testing.assert_array_equal(m.jacobian(0.25, x), as_array(ref["jacobian"]))
    assert m.energy(x)["total"] == ref["energy"]


@pytest.mark.parametrize("name", sorted(MODULES))
def test_batched_derivative_is_each_derivative(reference, name):
    m, ref = MODULES[name], reference[name]
    x = as_array(ref["x"])
    X = np.stack([x, x * 0.5, x])
    D = m.derivative(0.25, X)
    assert D.shape == X.shape
    for k in range(3):
        np.testing.assert_array_equal(D[k], m.derivative(0.25, X[k]))
    np.testing.assert_array_equal(D[0], as_array(ref["dxdt"]))


@pytest.mark.parametrize("name", sorted(MODULES))
@pytest.mark.parametrize("method", ["dopri5", "rosenbrock4"])
def test_simulate(reference, name, method):
    m, ref = MODULES[name], reference[name]
    tr = m.simulate(as_array(ref["x"]), as_array(ref["times"]), method=method, atol=ref["tolerance"])
    np.testing.assert_array_equal(tr.t, as_array(ref["times"]))
    np.testing.assert_array_equal(tr.x, as_array(ref[method]))
    if method == "dopri5":
        assert tr.steps == ref["dopri5_steps"]


@pytest.mark.parametrize("threads", [1, 0])
def test_ensemble_cases_are_simulate_runs(reference, threads):
    ref = reference["crane_ensemble"]
    x0 = as_array(reference["crane"]["x"])
    res = crane.ensemble({"controller.kp": ref["kp"]}, as_array(reference["crane"]["times"]), x0=x0,
                         atol=reference["crane"]["tolerance"], threads=threads)
    assert res.ok.all() and res.failed == 0
    np.testing.assert_array_equal(res.x, as_array(ref["x"]))
    np.testing.assert_array_equal(res.parameters["controller.kp"], as_array(ref["kp"]))
    assert res.parameters["m_load"].tolist() == [0.5] * 3


@pytest.mark.parametrize("threads", [1, 0])
def test_recorders_by_name_equal_the_cpp_recorders(reference, threads):
    ref = reference["crane_recorders"]
    x0 = as_array(reference["crane"]["x"])
    res = crane.ensemble({"controller.kp": reference["crane_ensemble"]["kp"]}, as_array(reference["crane"]["times"]),
                         x0=x0, atol=reference["crane"]["tolerance"], threads=threads,
                         recorders={"swing": ("max_abs", "pivot.q", -np.pi / 2), "down": ("crossing", "pivot.v", 0.0, -1),
                                    "settle": ("settling", "rail.q", -0.2, 0.05), "low": ("min", "rail.q"),
                                    "final": ("final", "rail.q"), "energy": ("max", "energy")})
    assert list(res.recorded) == ["swing", "down", "settle", "low", "final", "energy"]
    for name, values in res.recorded.items():
        np.testing.assert_array_equal(values, as_array(ref[name]), err_msg=name)
