"""The user's torque, gyrostat.CustomTorque: a Python callable and a compiled function
(scipy.LowLevelCallable from ctypes) against SciPy with the right-hand side written here, against
each other, in solve, events, dense output, ensembles on 2 threads, a sweep and a scene; its
Jacobian; and its errors (the user's exception as raised, a wrong shape naming the torque)."""

from __future__ import annotations

import ctypes

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
import user_torques as user
from gyrostat.events import Event

J = np.array([1.0, 2.0, 2.5])
W0 = np.array([1.0, 0.5, -0.3])
T = np.linspace(0.0, 20.0, 41)


def scipy_reference(t_eval):
    """J ω̇ = M − ω × Jω with M = −0.05 |ω| ω + (0, 0, 0.02 sin t), written here."""
    def rhs(t, w):
        M = -0.05 * np.linalg.norm(w) * w + np.array([0.0, 0.0, 0.02 * np.sin(t)])
        return (M - np.cross(w, J * w)) / J
    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), W0, method="DOP853", t_eval=t_eval, rtol=1e-12, atol=1e-14)
    return sol.y.T


@pytest.fixture(scope="module")
def expected():
    return scipy_reference(T)


def python_model():
    return g.Model(g.Body(J), [g.CustomTorque(user.quadratic_drag)])


def compiled_model():
    return g.Model(g.Body(J), [g.CustomTorque(user.compiled_drag())])


@pytest.mark.parametrize("make", [python_model, compiled_model], ids=["python", "compiled"])
def test_against_scipy(make, expected):
    sol = g.solve(make(), W0, (0.0, 20.0), t_eval=T, method="dop853", rtol=1e-12, atol=1e-14)
    assert sol.success, sol.message
    error = np.abs(sol.y - expected).max()
    # both DOP853 at rtol 1e-12 over 20 s: measured 2.2e-15 (the two DOP853s take the same steps
    # here); the bound is the tolerance's level, which any valid step sequence meets
    assert error < 2e-12, f"max |omega - omega_scipy| = {error:.3g}"


def test_python_and_compiled_agree_to_rounding():
    a = g.solve(python_model(), W0, (0.0, 20.0), t_eval=T, rtol=1e-10, atol=1e-12)
    b = g.solve(compiled_model(), W0, (0.0, 20.0), t_eval=T, rtol=1e-10, atol=1e-12)
    # the same formula in NumPy and in C: |omega| may differ in the last bit (measured: equal)
    assert np.abs(a.y - b.y).max() < 1e-14
    assert a.stats["steps"] == b.stats["steps"]


def test_equals_the_built_in_linear_damping():
    """M = -c omega as a compiled user torque (c through user_data) and as LinearDamping(c I)."""
    c = 0.07
    custom = g.solve(g.Model(g.Body(J), [g.CustomTorque(user.compiled_linear(c))]), W0, (0.0, 20.0), t_eval=T,
                     rtol=1e-10, atol=1e-12)
    builtin = g.solve(g.Model(g.Body(J), [g.LinearDamping(c * np.eye(3))]), W0, (0.0, 20.0), t_eval=T,
                      rtol=1e-10, atol=1e-12)
    # -c omega_i against c omega_i + 0 omega_j + 0 omega_k subtracted from 0: the same numbers
    assert np.abs(custom.y - builtin.y).max() < 1e-14


def test_attitude_function_equals_the_inertial_torque():
    q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    y0 = np.concatenate([W0, q0])
    mine = g.Model(g.Body(J), [g.CustomTorque(user.inertial_moment, attitude=True)], attitude=True)
    builtin = g.Model(g.Body(J), [g.InertialTorque([0.1, -0.2, 0.05])], attitude=True)
    a = g.solve(mine, y0, (0.0, 10.0), t_eval=T[:21], rtol=1e-11, atol=1e-13)
    b = g.solve(builtin, y0, (0.0, 10.0), t_eval=T[:21], rtol=1e-11, atol=1e-13)
    # R(q)^T M_I in NumPy and in C++: rounding of a 3x3 product, carried over 10 s (measured 2.9e-15)
    assert np.abs(a.y - b.y).max() < 3e-14
    with pytest.raises(ValueError, match="CustomTorque depends on the attitude.*attitude=True"):
        g.Model(g.Body(J), [g.CustomTorque(user.inertial_moment, attitude=True)])


def test_events_and_dense_output(expected):
    sol = g.solve(python_model(), W0, (0.0, 20.0), events=[Event("q", 0.0)], dense_output=True, rtol=1e-12,
                  atol=1e-14)
    dense = np.asarray(sol(T))
    dense = dense.T if dense.shape[0] == 3 else dense
    # DOP853's 7th-order continuous extension at rtol 1e-12: measured 2.2e-15 against SciPy's
    # (the same steps); the bound is the tolerance's level
    assert np.abs(dense - expected).max() < 2e-12
    # each crossing of q = 0 located on the continuous extension: q there is zero to the tolerance
    crossings = sol.t_events[0]
    assert len(crossings) >= 2
    assert np.abs(scipy_reference(np.concatenate([[0.0], crossings]))[1:, 1]).max() < 1e-12  # measured 8.4e-14


@pytest.mark.parametrize("make", [python_model, compiled_model], ids=["python", "compiled"])
def test_ensemble_on_two_threads_equals_single_solves(make):
    models = [make() for _ in range(4)]
    y0s = W0 * np.linspace(0.8, 1.2, 4)[:, None]
    runs = g.solve_ensemble(models, y0s, (0.0, 10.0), n_out=11, threads=2, rtol=1e-10, atol=1e-12)
    for model, y0, run in zip(models, y0s, runs):
        alone = g.solve(model, y0, (0.0, 10.0), n_out=11, rtol=1e-10, atol=1e-12)
        assert run.success and np.array_equal(run.y, alone.y)  # one member, one code path: bit for bit


@pytest.mark.parametrize("method", ["cvode_bdf"])
def test_user_jacobian_and_difference_quotients(method, expected):
    with_jacobian = g.Model(g.Body(J), [g.CustomTorque(user.quadratic_drag, user.quadratic_drag_jacobian)])
    compiled = g.Model(g.Body(J), [g.CustomTorque(user.compiled_drag(), user.compiled_drag_jacobian())])
    for model in (python_model(), with_jacobian, compiled):
        sol = g.solve(model, W0, (0.0, 20.0), t_eval=T, method=method, rtol=1e-10, atol=1e-12)
        assert sol.success, sol.message
        assert sol.stats["jacobian_evals"] > 0
        # BDF at rtol 1e-10 over 20 s: measured 5.2e-9 with either Jacobian (11 Jacobians)
        assert np.abs(sol.y - expected).max() < 5e-8


def test_the_users_exception_propagates_as_raised():
    model = g.Model(g.Body(J), [g.CustomTorque(user.failing)])
    for method in ("dop853", "cvode_bdf", "arkode_fehlberg8", "splitting"):
        with pytest.raises(ZeroDivisionError, match="the user's torque failed"):
            g.solve(model, W0, (0.0, 5.0), method=method, **({"step": 0.01} if method == "splitting" else {}))
    with pytest.raises(ZeroDivisionError, match="the user's torque failed"):
        g.solve_ensemble([model] * 3, np.array([W0] * 3), (0.0, 5.0), threads=2)


def test_errors_name_the_torque():
    with pytest.raises(ValueError, match="CustomTorque 'wrong_shape' returned a value that.*3"):
        g.solve(g.Model(g.Body(J), [g.CustomTorque(user.wrong_shape)]), W0, (0.0, 1.0))
    with pytest.raises(TypeError, match="CustomTorque 'int': the function must be a Python callable.*got 3"):
        g.CustomTorque(3)
    bad = user.library().quadratic_drag
    bad.restype, bad.argtypes = ctypes.c_double, [ctypes.c_double]
    from scipy import LowLevelCallable
    with pytest.raises(ValueError, match=r"signature is 'double \(double\)'"):
        g.CustomTorque(LowLevelCallable(bad))
    with pytest.raises(RuntimeError, match="CustomTorque 'failing': the compiled function returned 3 at t = "):
        g.solve(g.Model(g.Body(J), [g.CustomTorque(user.compiled("failing"))]), W0, (0.0, 5.0))
    with pytest.raises(ValueError, match="CustomTorque.*no contribution to the \\(a, r\\) system"):
        g.AveragedModel(g.Body([1.0, 1.0, 2.0]), [g.CustomTorque(user.quadratic_drag)])
    with pytest.raises(ValueError, match="taylor"):
        g.solve(python_model(), W0, (0.0, 1.0), method="taylor")


SCENE = """
title = "user torque"
description = "a user's drag torque named in the scene"
[body]
moments = [1.0, 2.0, 2.5]
[[torques]]
type = "custom"
function = "user_torques:drag_factory"
parameters = {{ c = 0.05, a = 0.02 }}
[initial]
omega = [1.0, 0.5, -0.3]
[integration]
model = "full"
method = "dop853"
rtol = 1e-12
atol = 1e-14
t_span = [0.0, 20.0]
n_out = 41
[outputs]
plots = []
{sweep}
"""


def test_scene_names_the_torque_by_import(tmp_path, expected):
    from gyrostat import runner
    from gyrostat import scene as scenes
    path = tmp_path / "user.toml"
    path.write_text(SCENE.format(sweep=""))
    solutions, _, _ = runner.solve_scene(scenes.load(path), progress=False)
    (main,) = solutions.values()
    # the factory's drag with c = 0.05, a = 0.02 is the reference's: as in test_against_scipy
    assert np.abs(main.y[:, :3] - expected).max() < 2e-11


def test_sweep_over_a_scene_with_a_user_torque(tmp_path):
    """A sweep of the initial spin: each member equals its own solve (the sweep's ensemble calls
    the Python torque on the GIL, the members one at a time)."""
    from gyrostat import scene as scenes
    path = tmp_path / "user.toml"
    path.write_text(SCENE.format(sweep=""))
    ds = g.sweep(scenes.load(path), {"initial.omega[0]": [0.8, 1.0, 1.2]}, progress=False, threads=2)
    for k, p0 in enumerate([0.8, 1.0, 1.2]):
        alone = g.solve(python_model(), [p0, 0.5, -0.3], (0.0, 20.0), n_out=41, method="dop853", rtol=1e-12,
                        atol=1e-14)
        member = ds.isel(member=k) if "member" in ds.dims else ds.sel({list(ds.sizes)[0]: p0})
        values = np.column_stack([member[name].values for name in ("p", "q", "r")])
        assert np.abs(values - alone.y).max() < 1e-14


def test_scene_errors_name_the_key(tmp_path):
    from gyrostat import scene as scenes
    from gyrostat.schema import SceneError
    path = tmp_path / "user.toml"
    path.write_text(SCENE.format(sweep="").replace("user_torques:drag_factory", "user_torques:nothing_here"))
    with pytest.raises(SceneError, match="function = 'user_torques:nothing_here'.*has no attribute"):
        scenes.load(path)
    path.write_text(SCENE.format(sweep="").replace("user_torques:drag_factory", "no_such_module_x:f"))
    with pytest.raises(SceneError, match="cannot import module 'no_such_module_x'"):
        scenes.load(path)


def test_an_ensemble_with_a_python_torque_runs_on_one_thread():
    """Python torques serialise on the GIL, so more threads only pass it back and forth (measured
    18.7 µs a call on 2 threads, 1.0 µs on one): the ensemble runs them on one thread, whatever
    `threads` asks. The calls' thread ids say so (2 of them before), and the results are the
    single runs' bit for bit."""
    import threading

    idents = set()

    def drag(t, omega):
        idents.add(threading.get_ident())
        return user.quadratic_drag(t, omega)

    model = g.Model(g.Body(J), [g.CustomTorque(drag)])
    y0s = W0 * np.linspace(0.8, 1.2, 6)[:, None]
    runs = g.solve_ensemble(model, y0s, (0.0, 5.0), n_out=3, threads=2)
    assert len(idents) == 1, idents
    for y0, run in zip(y0s, runs):
        assert np.array_equal(run.y, g.solve(model, y0, (0.0, 5.0), n_out=3).y)
