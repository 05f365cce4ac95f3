"""The module's calls, checked against closed forms and conservation laws:
names and sizes, initial_state's forms, run-time parameters, recover, energy."""

import math

import numpy as np
import pytest

import crane
import free_body
import spatial_arm


def test_names_and_sizes():
    assert (crane.n_q, crane.n_v, crane.n_state) == (2, 2, 4)
    assert crane.joints == ["rail", "pivot"]
    assert crane.state_names == ["rail.q", "pivot.q", "rail.v", "pivot.v"]
    assert crane.joint_layout["pivot"]["type"] == "Revolute"
    x = np.arange(4.0)
    assert x[crane.joint_layout["pivot"]["v"]].tolist() == [3.0]
    assert crane.parameters["controller.kp"] == 10.0 and crane.parameters["m_load"] == 0.5
    assert spatial_arm.parameters == {}
    # FreeMotion: r (3) and a quaternion (4); v and w (6). Spherical: a quaternion (4); w (3)
    assert (free_body.n_q, free_body.n_v) == (11, 9)
    assert free_body.joint_layout["ball"]["q"] == slice(7, 11, 1)
    assert "hand.frame_b" in spatial_arm.frames


def test_initial_state_by_name():
    x = crane.initial_state(rail={"q": -0.5, "v": 0.2}, pivot=-math.pi / 2)
    np.testing.assert_array_equal(x, [-0.5, -math.pi / 2, 0.2, 0.0])
    assert crane.initial_state().tolist() == [0.0] * 4


def _rpy(r, p, y):
    cx, sx, cy, sy, cz, sz = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    rx = np.array([[1, 0, 0], [0, cx, sx], [0, -sx, cx]])  # the paper's convention: R rotates world into frame
    ry = np.array([[cy, 0, -sy], [0, 1, 0], [sy, 0, cy]])
    rz = np.array([[cz, sz, 0], [-sz, cz, 0], [0, 0, 1]])
    return rx @ ry @ rz


def test_orientation_forms_agree():
    R = _rpy(0.1, 0.2, 0.3)
    by_rpy = free_body.initial_state(base={"R": {"rpy": [0.1, 0.2, 0.3]}})
    by_matrix = free_body.initial_state(base={"R": R})
    np.testing.assert_allclose(by_rpy, by_matrix, rtol=0, atol=1e-15)
    # the frame's rotation as recover gives it is the one set
    s = free_body.recover(0.0, by_rpy)
    np.testing.assert_allclose(s["frames"]["base.frame_b"]["R"], R, rtol=0, atol=1e-15)
    by_axis = free_body.initial_state(ball={"R": {"axis": [0, 0, 1], "angle": 0.4}})
    phi = 0.4
    Rz = np.array([[math.cos(phi), math.sin(phi), 0], [-math.sin(phi), math.cos(phi), 0], [0, 0, 1]])
    np.testing.assert_allclose(free_body.recover(0.0, by_axis)["frames"]["ball.frame_b"]["R"], Rz, atol=1e-15)


def test_centre_of_mass_velocity():
    # hull 3 kg with its centre of mass at 0.1 m; bob 1 kg 0.5 m out: the
    # centre of mass of both moves at v_cm (world coordinates: base.frame_a is the world's)
    v_cm = np.array([1.0, -2.0, 0.5])
    x = free_body.initial_state(base={"w": [0.0, 0.0, 3.0], "v_cm": v_cm}, ball={"w": [0.0, 1.0, 0.0]})
    s = free_body.recover(0.0, x)
    v = (3.0 * (s["frames"]["hull.frame_a"]["v"] + np.cross(s["frames"]["hull.frame_a"]["R"].T @ s["frames"]["hull.frame_a"]["w"],
                                                             s["frames"]["hull.frame_a"]["R"].T @ [0.1, 0, 0]))
         + 1.0 * s["frames"]["bob.frame_a"]["v"]) / 4.0
    np.testing.assert_allclose(v, v_cm, rtol=0, atol=1e-14)


def test_energy_is_conserved_on_the_free_body():
    x0 = free_body.initial_state(base={"w": [0.3, -0.2, 1.0], "v": [0.1, 0, 0]}, ball={"w": [0, 0, 2.0]})
    tr = free_body.simulate(x0, np.linspace(0, 2, 5), atol=1e-11)
    e = [free_body.energy(x)["total"] for x in tr.x]
    assert e[0] > 0
    # no gravity, no springs: the kinetic energy stays, to the tolerance's order
    assert max(abs(v - e[0]) for v in e) < 1e-8 * max(1.0, e[0])


def test_parameters_per_call_and_per_scene():
    x = crane.initial_state(rail=0.3, pivot=-math.pi / 2)
    # the cart's force is kp·(target − s) − kd·ṡ, the buffer pulls it back by c·(its stretch): the buffer
    # runs from −(s0 + 0.5) = −1.5 m to the cart at 0.3 m, 0.8 m beyond s0 = 1 m. With the rope vertical
    # and at rest, the load's equation (L·θ̈ + s̈ = 0) cancels its share: m_cart·s̈ = f, θ̈ = −s̈/L
    for kp in (10.0, 25.0):
        d = crane.Scene(**{"controller.kp": kp}).derivative(0.0, x)
        f = kp * (1.0 - 0.3) - 40.0 * 0.8
        assert d[2] == pytest.approx(f / 1.0, rel=1e-13)
        assert d[3] == pytest.approx(-f / 1.0, rel=1e-13)
    np.testing.assert_array_equal(crane.derivative(0.0, x), crane.Scene().derivative(0.0, x))
    a = crane.simulate(x, [0.0, 1.0], params={"controller.kp": 25.0})
    b = crane.Scene(**{"controller.kp": 25.0}).simulate(x, [0.0, 1.0])
    np.testing.assert_array_equal(a.x, b.x)
    c = crane.simulate(x, [0.0, 1.0])
    assert not np.array_equal(a.x, c.x)
    assert crane.Scene(m_load=2.0).parameters["m_load"] == 2.0


def test_recover_frames_and_internals():
    x = spatial_arm.initial_state()
    s = spatial_arm.recover(0.0, x)
    # straight out along x: 0.5 + 0.4 + 0.1 m
    np.testing.assert_allclose(s["frames"]["hand.frame_b"]["r"], [1.0, 0, 0], atol=1e-15)
    assert s["internals"]["elbow.phi"] == 0.0
    x = spatial_arm.initial_state(elbow={"q": 0.6, "v": -1.5})
    s = spatial_arm.recover(0.0, x)
    assert s["internals"]["elbow.phi"] == 0.6
    assert s["v"][1] == -1.5
    # the joint's cut torque about its axis is what its PD law applies: 150·(−0.8 − 0.6) − 20·(−1.5)
    np.testing.assert_allclose(s["vdot"], spatial_arm.derivative(0.0, x)[3:], rtol=0, atol=0)
    assert s["energy"]["total"] == spatial_arm.energy(x)["total"]


def test_out_argument_writes_in_place():
    x = spatial_arm.initial_state(elbow=0.6)
    out = np.empty(6)
    r = spatial_arm.derivative(0.0, x, out)
    assert r is out or np.shares_memory(r, out)
    np.testing.assert_array_equal(out, spatial_arm.derivative(0.0, x))


def test_ensemble_failures_are_recorded_per_case():
    x0 = crane.initial_state(rail=-0.5, pivot=-math.pi / 2)
    # a negative load mass is refused at construction: that case fails, the others run
    res = crane.ensemble({"m_load": [0.5, -1.0, 1.0]}, np.linspace(0, 1, 3), x0=x0)
    assert res.ok.tolist() == [True, False, True]
    assert "mass" in res.reason[1] and res.reason[0] == ""
    assert np.isnan(res.x[1]).all() and not np.isnan(res.x[0]).any()
    # a spent budget: recorded with its time and last state
    res = crane.ensemble({"controller.kp": [10.0, 20.0]}, np.linspace(0, 1, 3), x0=x0, max_rhs_evals=60)
    assert not res.ok.any()
    assert all("budget" in r for r in res.reason)
    assert (res.fail_time > 0).all() and np.isfinite(res.fail_state).all()


def test_bodies_and_momentum_conserved_on_the_free_body():
    bodies = {b["name"]: b for b in free_body.bodies()}
    assert bodies["hull"]["m"] == 3.0 and bodies["bob"]["m"] == 1.0
    np.testing.assert_array_equal(bodies["hull"]["r_cm"], [0.1, 0, 0])
    np.testing.assert_array_equal(np.diag(bodies["hull"]["J"]), [0.2, 0.3, 0.4])
    x0 = free_body.initial_state(base={"w": [0.3, -0.2, 1.0], "v": [0.1, 0, 0.2]}, ball={"w": [0, 1.0, 2.0]})
    tr = free_body.simulate(x0, np.linspace(0, 2, 5), atol=1e-11)
    h = [free_body.momentum(x) for x in tr.x]
    # no external force: both are constant, to the tolerance's order
    for k in ("linear", "angular"):
        assert np.abs(h[0][k]).max() > 0.1
        assert max(np.abs(e[k] - h[0][k]).max() for e in h) < 1e-8
