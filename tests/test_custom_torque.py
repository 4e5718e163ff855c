"""The user's torque, gyrostat.CustomTorque: a Python callable and a compiled function
(scipy.LowLevelCallable from ctypes) against SciPy with the right-hand side written here, against
each other, in solve, events, dense output, ensembles on 2 threads, a sweep and a scene; its
Jacobian; and its errors (the user's exception as raised, a wrong shape naming the torque)."""

from __future__ import annotations

import ctypes
import signal
import time

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


RETURNS = {  # what a user's M = -c omega may be returned as; the first three are read in place (read_flat)
    "float64 array": lambda c, w: -c * w,
    "tuple of floats": lambda c, w: tuple(float(-c * x) for x in w),
    "tuple of NumPy float64 scalars": lambda c, w: (-c * w[0], -c * w[1], -c * w[2]),
    "list of floats": lambda c, w: [float(-c * x) for x in w],
    "strided float64 view": lambda c, w: np.repeat(-c * w, 2)[::2],
    "float32 array": lambda c, w: (-c * w).astype(np.float32),
    "list with an int": lambda c, w: [0, float(-c * w[1]), float(-c * w[2])],
}


@pytest.mark.parametrize("kind", list(RETURNS))
def test_every_form_of_a_returned_torque_gives_the_same_run(kind):
    """The values a Python torque returns are read in place when they are a float64 array or a tuple
    or list of floats, and converted otherwise: every form gives the run the built-in LinearDamping
    gives to rounding (1e-14: the same -c omega_i; float32 rounds M to ~6e-8 relative, the integer
    0 replaces M_1 and is compared with its own reference)."""
    c = 0.07
    make = RETURNS[kind]
    run = g.solve(g.Model(g.Body(J), [g.CustomTorque(lambda t, w: make(c, w))]), W0, (0.0, 20.0), t_eval=T,
                  rtol=1e-10, atol=1e-12)
    diagonal = [0.0, c, c] if kind == "list with an int" else [c, c, c]
    builtin = g.solve(g.Model(g.Body(J), [g.LinearDamping(diagonal=diagonal)]), W0, (0.0, 20.0), t_eval=T,
                      rtol=1e-10, atol=1e-12)
    tolerance = 1e-6 if kind == "float32 array" else 1e-14
    assert np.abs(run.y - builtin.y).max() < tolerance, kind


@pytest.mark.parametrize("value", [(1.0, 2.0), [1.0, 2.0, 3.0, 4.0], np.zeros(4), np.zeros((3, 1)), ("a", 1.0, 2.0)])
def test_a_returned_torque_of_the_wrong_shape_is_refused_by_name(value):
    with pytest.raises(ValueError, match="CustomTorque 'shaped' returned a value that, as M in body axes, must be 3 "
                                         "numbers, got"):
        g.solve(g.Model(g.Body(J), [g.CustomTorque(lambda t, w: value, name="shaped")]), W0, (0.0, 1.0))


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
    solutions, _, _ = runner.solve_scene(scenes.load(path, allow_import=["user_torques"]), progress=False)
    (main,) = solutions.values()
    # the factory's drag with c = 0.05, a = 0.02 is the reference's: as in test_against_scipy
    assert np.abs(main.y[:, :3] - expected).max() < 2e-11


def test_sweep_over_a_scene_with_a_user_torque(tmp_path):
    """A sweep of the initial spin: each member equals its own solve (the sweep's ensemble calls
    the Python torque on the GIL, the members one at a time)."""
    from gyrostat import scene as scenes
    path = tmp_path / "user.toml"
    path.write_text(SCENE.format(sweep=""))
    ds = g.sweep(scenes.load(path, allow_import="user_torques"), {"initial.omega[0]": [0.8, 1.0, 1.2]}, progress=False,
                 threads=2)
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
    with pytest.raises(SceneError, match=r"\[torques\[0\]\] function = 'user_torques:nothing_here'.*has no attribute"):
        scenes.load(path, allow_import=["user_torques"])
    path.write_text(SCENE.format(sweep="").replace("user_torques:drag_factory", "no_such_module_x:f"))
    with pytest.raises(SceneError, match="cannot import module 'no_such_module_x'"):
        scenes.load(path, allow_import=["no_such_module_x"])


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


class StopsOnCall:
    """quadratic_drag that stops on its n-th call: raising KeyboardInterrupt itself, or (sigint)
    sending SIGINT to this process from inside the call, so that Python's default handler raises
    KeyboardInterrupt in the callback's own code (the signal arrives while Python code runs in it)."""

    def __init__(self, n, sigint=False):
        self.calls, self.n, self.sigint = 0, n, sigint

    def __call__(self, t, omega):
        self.calls += 1
        if self.calls == self.n:
            if not self.sigint:
                raise KeyboardInterrupt
            signal.raise_signal(signal.SIGINT)  # the handler runs before the next line, in this call
        return user.quadratic_drag(t, omega)


@pytest.mark.parametrize("sigint", [False, True], ids=["KeyboardInterrupt", "SIGINT"])
@pytest.mark.parametrize("method", ["dop853", "cvode_bdf", "arkode_fehlberg8", "splitting", "auto"])
def test_ctrl_c_in_the_users_function_ends_the_run_interrupted(method, sigint, ctrl_c):
    """Ctrl-C while the user's Python torque runs ends the run as Ctrl-C between two steps does:
    status interrupted, the outputs computed up to there kept (the uninterrupted run's, bit for
    bit: the same steps), t_last and y_last to continue from. The run is short (at most 20 s of
    model time, ~1 s of wall time), so a lost interruption ends it, with status success."""
    options = dict(t_eval=T, method=method, rtol=1e-10, atol=1e-12, **({"step": 0.01} if method == "splitting" else {}))
    counted = StopsOnCall(None)
    model = g.Model(g.Body(J), [g.CustomTorque(counted)])
    whole = g.solve(model, W0, (0.0, 20.0), **options, error_estimate=False)  # the calls of the run alone
    stops = StopsOnCall(counted.calls // 2, sigint)  # Ctrl-C half-way through the run
    started = time.perf_counter()
    with pytest.warns(RuntimeWarning, match="interrupted"):
        part = g.solve(g.Model(g.Body(J), [g.CustomTorque(stops)]), W0, (0.0, 20.0), **options)
    assert time.perf_counter() - started < 30.0
    assert part.status == "interrupted" and "interrupted at t =" in part.message, part.message
    assert stops.calls == stops.n, stops.calls  # stopped at the call that saw Ctrl-C, nothing called after
    assert 1 <= len(part) < len(T) and np.array_equal(part.y, whole.y[:len(part)])
    assert part.t[-1] <= part.t_last < 20.0 and np.all(np.isfinite(part.y_last))
    # continued from (t_last, y_last) to the uninterrupted answer: within the two runs' global
    # errors at rtol 1e-10 (CVODE restarts at order 1; measured ≤ 4e-9)
    rest = g.solve(model, part, (part.t_last, 20.0), **{**options, "t_eval": T[T > part.t_last]})
    assert rest.success and np.max(np.abs(rest.y[-1] - whole.y[-1])) < 1e-7, np.max(np.abs(rest.y[-1] - whole.y[-1]))


@pytest.mark.parametrize("sigint", [False, True], ids=["KeyboardInterrupt", "SIGINT"])
def test_ctrl_c_in_the_users_function_interrupts_an_ensemble(sigint, ctrl_c):
    """In solve_ensemble (one thread: the torque holds the GIL) the member running ends
    interrupted with its outputs so far, the members before it are whole, those after it are
    not started; no KeyboardInterrupt reaches the caller."""
    whole = g.solve(python_model(), W0, (0.0, 20.0), t_eval=T)
    stops = StopsOnCall(None, sigint)
    first = g.solve_ensemble(g.Model(g.Body(J), [g.CustomTorque(stops)]), [W0] * 3, (0.0, 20.0), t_eval=T,
                             error_estimate=False)  # the calls of the runs alone
    per_member = stops.calls // 3
    stops.calls, stops.n = 0, per_member + per_member // 2  # Ctrl-C half-way through member 1
    runs = g.solve_ensemble(g.Model(g.Body(J), [g.CustomTorque(stops)]), [W0] * 3, (0.0, 20.0), t_eval=T, threads=2)
    assert [r.status for r in first] == ["success"] * 3
    assert [r.status for r in runs] == ["success", "interrupted", "interrupted"], [r.message for r in runs]
    assert np.array_equal(runs[0].y, whole.y)
    assert 1 <= len(runs[1]) < len(T) and np.array_equal(runs[1].y, whole.y[:len(runs[1])])
    assert len(runs[2]) == 0 and "not started" in runs[2].message


# --- The vectorised signature: n members at once, structure of arrays --------------------------
# int f(int n, const double *t, const double *omega, const double *quaternion, double *moment,
# void *user_data): the ensembles' SIMD batches call it once per stage for their lanes (n =
# g.simd_lanes), every other path with n = 1. drag.c's *_lanes functions record the widest n.

def lanes_model():
    return g.Model(g.Body(J), [g.CustomTorque(user.compiled_drag_lanes())])


def test_the_vectorised_signature_is_recognised():
    assert g.CustomTorque(user.compiled_drag_lanes()).vectorised
    assert not g.CustomTorque(user.compiled_drag()).vectorised
    assert not g.CustomTorque(user.quadratic_drag).vectorised


def test_vector_and_scalar_compiled_agree_in_solve_events_and_dense_output(expected):
    user.reset_widest_call()
    options = dict(t_eval=T, method="dop853", rtol=1e-12, atol=1e-14)
    scalar = g.solve(compiled_model(), W0, (0.0, 20.0), **options)
    vector = g.solve(lanes_model(), W0, (0.0, 20.0), **options)
    assert user.widest_call() == 1  # a single solve calls the vectorised form with n = 1
    # the same C operations on the same numbers (n = 1): equal to rounding (measured: bit for bit)
    assert np.abs(vector.y - scalar.y).max() < 1e-15
    # against SciPy on the test's own equations: as test_against_scipy
    assert np.abs(vector.y - expected).max() < 2e-12
    a = g.solve(compiled_model(), W0, (0.0, 20.0), events=[Event("q", 0.0)], dense_output=True, rtol=1e-12,
                atol=1e-14)
    b = g.solve(lanes_model(), W0, (0.0, 20.0), events=[Event("q", 0.0)], dense_output=True, rtol=1e-12,
                atol=1e-14)
    assert len(b.t_events[0]) >= 2
    # the same steps (equal right-hand sides): the same crossings and continuous extension to rounding
    assert np.abs(np.asarray(b.t_events[0]) - np.asarray(a.t_events[0])).max() < 1e-13
    assert np.abs(np.asarray(b(T)) - np.asarray(a(T))).max() < 1e-15


def test_vector_torque_in_stiff_integrators_with_and_without_its_jacobian(expected):
    for jacobian in (None, user.compiled_drag_jacobian()):
        model = g.Model(g.Body(J), [g.CustomTorque(user.compiled_drag_lanes(), jacobian)])
        sol = g.solve(model, W0, (0.0, 20.0), t_eval=T, method="cvode_bdf", rtol=1e-10, atol=1e-12)
        assert sol.success and sol.stats["jacobian_evals"] > 0, sol.message
        # BDF at rtol 1e-10 over 20 s: as test_user_jacobian_and_difference_quotients (measured 5.2e-9)
        assert np.abs(sol.y - expected).max() < 5e-8


def _ensemble(model, y0s, batch, **options):
    """The ensemble run alone (no estimate: its companion runs may batch a subset of the members,
    e.g. those that cross a separatrix, whose lanes then call the user's torque differently)."""
    options.setdefault("error_estimate", False)
    return g.solve_ensemble(model, y0s, (0.0, 10.0), n_out=11, threads=2, batch=batch, method="dop853", rtol=1e-10,
                            atol=1e-12, **options)


def test_vector_torque_runs_in_simd_batches_and_equals_the_built_in_damping():
    """M = -c omega three ways on 13 members (a full batch and a partial one) on 2 threads:
    LinearDamping, the scalar compiled torque, the vectorised one; batched and not."""
    c = 0.07
    y0s = np.random.default_rng(3).normal(size=(13, 3))
    builtin = g.Model(g.Body(J), [g.LinearDamping(c * np.eye(3))])
    scalar = g.Model(g.Body(J), [g.CustomTorque(user.compiled_linear(c))])
    vector = g.Model(g.Body(J), [g.CustomTorque(user.compiled_linear(c, vectorised=True))])
    user.reset_widest_call()
    unbatched = _ensemble(vector, y0s, batch=False)
    assert user.widest_call() == 1  # one member at a time: n = 1
    batched = _ensemble(vector, y0s, batch=True)
    assert user.widest_call() == g.simd_lanes  # the batches call once for their lanes
    builtin_batched = _ensemble(builtin, y0s, batch=True)
    for y0, b, u, s, bb in zip(y0s, batched, unbatched, _ensemble(scalar, y0s, batch=False),
                               builtin_batched):
        alone = g.solve(builtin, y0, (0.0, 10.0), n_out=11, method="dop853", rtol=1e-10, atol=1e-12)
        assert b.success and u.success
        # unbatched: one member, one code path, and -c omega = 0 - (c omega + 0 + 0) in IEEE
        # arithmetic: the built-in's single run bit for bit, and the scalar signature's
        assert np.array_equal(u.y, alone.y) and np.array_equal(s.y, alone.y)
        # batched, against the built-in's batch: r + (0 + (-c w)) against r - (c w + 0 w + 0 w),
        # equal up to the plugin's fused multiply-adds (measured: bit for bit)
        assert np.abs(b.y - bb.y).max() <= 1e-14 * np.abs(bb.y).max()
        # batched against the single run: the lanes evaluate Euler's equations in their affine form
        # (another rounding), carried over 10 s at rtol 1e-10 (measured 4.4e-13 relative): within
        # 100 rtol, as tests/test_batch.py
        assert np.abs(b.y - alone.y).max() <= 100 * 1e-10 * np.abs(alone.y).max()


def test_a_vector_torque_member_is_the_same_whichever_members_share_its_batch():
    """Lanes whose user torques differ (another user_data, or none) are called one by one with
    n = 1; a member's result is its result in a batch of its own kind, bit for bit."""
    fast, slow = user.compiled_linear(0.07, vectorised=True), user.compiled_linear(0.03, vectorised=True)
    body = g.Body(J)
    same = g.Model(body, [g.CustomTorque(fast)])
    others = [g.Model(body, [g.CustomTorque(slow)]), g.Model(body, [g.LinearDamping(0.03 * np.eye(3))])]
    y0s = np.random.default_rng(4).normal(size=(2 * g.simd_lanes, 3))
    uniform = _ensemble(same, y0s, batch=True)
    mixed_models = [same if k % 2 == 0 else others[(k // 2) % 2] for k in range(len(y0s))]
    user.reset_widest_call()
    mixed = _ensemble(mixed_models, y0s, batch=True)
    assert user.widest_call() == 1  # mixed batches call lane by lane
    for k in range(0, len(y0s), 2):
        assert np.array_equal(mixed[k].y, uniform[k].y)
    for k in range(1, len(y0s), 2):
        alone = g.solve(mixed_models[k], y0s[k], (0.0, 10.0), n_out=11, method="dop853", rtol=1e-10, atol=1e-12)
        assert np.abs(mixed[k].y - alone.y).max() <= 100 * 1e-10 * np.abs(alone.y).max()  # as above


def test_vector_attitude_torque_equals_the_inertial_torque_in_batches():
    """R(q)^T M_I vectorised in C (the quaternion's 4n numbers, structure of arrays) against the
    built-in InertialTorque, in solve and in a batched ensemble on 2 threads."""
    mine = g.Model(g.Body(J), [g.CustomTorque(user.compiled("inertial_moment_lanes"), attitude=True)], attitude=True)
    builtin = g.Model(g.Body(J), [g.InertialTorque([0.1, -0.2, 0.05])], attitude=True)
    rng = np.random.default_rng(5)
    q0s = rng.normal(size=(g.simd_lanes + 3, 4))
    y0s = np.hstack([rng.normal(size=(len(q0s), 3)), q0s / np.linalg.norm(q0s, axis=1)[:, None]])
    a = g.solve(mine, y0s[0], (0.0, 10.0), n_out=11, rtol=1e-11, atol=1e-13)
    b = g.solve(builtin, y0s[0], (0.0, 10.0), n_out=11, rtol=1e-11, atol=1e-13)
    # R(q)^T M_I in C and in C++: rounding of a 3x3 product, carried over 10 s by this faster
    # tumbling start (measured 1.4e-13); the bound stays below the run's rtol 1e-11
    assert np.abs(a.y - b.y).max() < 1e-12
    user.reset_widest_call()
    runs = _ensemble(mine, y0s, batch=True)
    assert user.widest_call() == g.simd_lanes
    for y0, run in zip(y0s, runs):
        alone = g.solve(builtin, y0, (0.0, 10.0), n_out=11, method="dop853", rtol=1e-10, atol=1e-12)
        # the batch's affine form and the C product against the scalar C++ path: within 100 rtol
        assert np.abs(run.y - alone.y).max() <= 100 * 1e-10 * np.abs(alone.y).max()


def test_a_body_given_by_its_inertia_tensor_runs_its_vector_torque_alone():
    """The batches do not rotate the user's frame: such members run one at a time (n = 1), equal
    to their single runs bit for bit, and to the built-in damping given in the same frame."""
    tilted = g.Body(inertia=[[2.0, 0.1, 0.0], [0.1, 1.5, 0.0], [0.0, 0.0, 1.2]])
    mine = g.Model(tilted, [g.CustomTorque(user.compiled_linear(0.07, vectorised=True))])
    builtin = g.Model(tilted, [g.LinearDamping(0.07 * np.eye(3))])
    y0s = np.random.default_rng(6).normal(size=(g.simd_lanes + 1, 3))
    user.reset_widest_call()
    runs = _ensemble(mine, y0s, batch=True)
    assert user.widest_call() == 1
    for y0, run in zip(y0s, runs):
        options = dict(n_out=11, method="dop853", rtol=1e-10, atol=1e-12)
        assert np.array_equal(run.y, g.solve(mine, y0, (0.0, 10.0), **options).y)
        reference = g.solve(builtin, y0, (0.0, 10.0), **options).y
        # R^T(-c R w) against (R^T c I R) w: rounding of the rotations, carried over 10 s at rtol
        # 1e-10 (measured 8.3e-14 relative); the bound is 100 rtol
        assert np.abs(run.y - reference).max() <= 100 * 1e-10 * np.abs(reference).max()


def test_vector_torque_errors():
    from scipy import LowLevelCallable
    bad = user.library().quadratic_drag_lanes
    bad.restype, bad.argtypes = ctypes.c_int, [ctypes.c_int, ctypes.POINTER(ctypes.c_double)]
    # a wrong signature names both accepted ones
    with pytest.raises(ValueError, match=r"signature is 'int \(int, double \*\)'; a compiled torque is int \(double t.*"
                                         r"or vectorised over n members.*int \(int n, const double \*t"):
        g.CustomTorque(LowLevelCallable(bad))
    # the Jacobian keeps the scalar signature
    with pytest.raises(ValueError, match=r"Jacobian: the LowLevelCallable's signature is 'int \(int, double \*, "
                                         r"double \*, double \*, double \*, void \*\)'; a compiled Jacobian is int \(double t"):
        g.CustomTorque(user.compiled_drag_lanes(), user.compiled_drag_lanes())
    failing = g.Model(g.Body(J), [g.CustomTorque(user.compiled("failing_lanes"))])
    with pytest.raises(RuntimeError, match="CustomTorque 'failing_lanes': the compiled function returned 3 at t = 1"):
        g.solve(failing, W0, (0.0, 5.0), method="dop853")
    runs = _ensemble(failing, np.array([W0] * 3), batch=True)
    for run in runs:  # the batch's members end with the error, naming the torque
        assert not run.success
        assert "CustomTorque 'failing_lanes': the compiled function returned 3 at one of" in run.message, run.message


VECTOR_SCENE = SCENE.replace('function = "user_torques:drag_factory"', 'function = "user_torques:compiled"').replace(
    "parameters = {{ c = 0.05, a = 0.02 }}", 'parameters = {{ name = "quadratic_drag_lanes" }}')


def test_scene_and_sweep_with_a_vector_torque(tmp_path, expected):
    from gyrostat import runner
    from gyrostat import scene as scenes
    path = tmp_path / "lanes.toml"
    path.write_text(VECTOR_SCENE.format(sweep=""))
    loaded = scenes.load(path, allow_import=["user_torques"])
    solutions, _, _ = runner.solve_scene(loaded, progress=False)
    (main,) = solutions.values()
    # drag.c's quadratic_drag_lanes is the reference's torque: as test_against_scipy
    assert np.abs(main.y[:, :3] - expected).max() < 2e-11
    user.reset_widest_call()
    spins = [0.8, 1.0, 1.2]
    ds = g.sweep(loaded, {"initial.omega[0]": spins}, progress=False, threads=2)
    assert user.widest_call() == g.simd_lanes  # the sweep's ensemble ran the members in a batch
    for k, p0 in enumerate(spins):
        alone = g.solve(compiled_model(), [p0, 0.5, -0.3], (0.0, 20.0), n_out=41, method="dop853", rtol=1e-12,
                        atol=1e-14)
        member = ds.isel(member=k) if "member" in ds.dims else ds.sel({list(ds.sizes)[0]: p0})
        values = np.column_stack([member[name].values for name in ("p", "q", "r")])
        # the batch's affine form against the scalar compiled torque's single run: rounding
        # carried over 20 s at rtol 1e-12, within 100 rtol (as tests/test_batch.py)
        assert np.abs(values - alone.y).max() < 100 * 1e-12 * np.abs(alone.y).max()


def test_numba_cfunc_with_the_vector_signature(expected):
    """The docstring's recipe: a numba cfunc over carray (n, 3 rows of n) as the vectorised torque."""
    numba = pytest.importorskip("numba")
    from scipy import LowLevelCallable
    double_p = numba.types.CPointer(numba.types.double)

    @numba.cfunc(numba.types.intc(numba.types.intc, double_p, double_p, double_p, double_p, numba.types.voidptr))
    def drag(n, t, omega, quaternion, moment, user_data):
        w, m, times = numba.carray(omega, (3, n)), numba.carray(moment, (3, n)), numba.carray(t, (n,))
        for l in range(n):
            norm = np.sqrt(w[0, l] * w[0, l] + w[1, l] * w[1, l] + w[2, l] * w[2, l])
            for i in range(3):
                m[i, l] = -0.05 * norm * w[i, l]
            m[2, l] += 0.02 * np.sin(times[l])
        return 0

    torque = g.CustomTorque(LowLevelCallable(drag.ctypes))
    assert torque.vectorised
    model = g.Model(g.Body(J), [torque])
    sol = g.solve(model, W0, (0.0, 20.0), t_eval=T, method="dop853", rtol=1e-12, atol=1e-14)
    assert np.abs(sol.y - expected).max() < 2e-12  # as test_against_scipy
    y0s = W0 * np.linspace(0.8, 1.2, g.simd_lanes + 1)[:, None]
    for y0, run in zip(y0s, _ensemble(model, y0s, batch=True)):
        alone = g.solve(lanes_model(), y0, (0.0, 10.0), n_out=11, method="dop853", rtol=1e-10, atol=1e-12)
        # numba's and C's sqrt, sin and products, and the batch's affine form: within 100 rtol
        assert np.abs(run.y - alone.y).max() <= 100 * 1e-10 * np.abs(alone.y).max()


@pytest.mark.parametrize("isa", ["sse2", "avx2", "avx512"])
def test_vector_torque_in_every_form_of_the_batches(isa):
    """The vectorised tests above in a process that asked for each form of the batches (4 lanes
    in SSE2 pairs, AVX2 + FMA, AVX-512: n = 4, 4, 8), as tests/test_batch.py does for its own."""
    import os
    import subprocess
    import sys

    from test_batch import _runs, _session_form

    if isa != "sse2" and not _runs(isa):
        pytest.skip(f"this CPU does not run the {isa} batches, or their plugin is not installed")
    if _session_form(isa):
        pytest.skip(f"this session runs the {isa} batches: its own run of the tests above is that form's")
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", __file__, "-k",
                             "vector and not every_form"], env={**os.environ, "GYROSTAT_SIMD": isa},
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout[-3000:]
