"""Sensitivities to the parameters a user writes (a CustomTorque's own, through its factory) and to
an inertia tensor's entries (whose principal axes turn with the entry), against SciPy runs of
variational equations written here in the user's frame, their derivatives by complex steps
(exact to rounding: an independent route from the library's central differences and frames)."""

import numpy as np
import pytest
import user_torques
from scipy.integrate import solve_ivp

import gyrostat as g

TENSOR = np.array([[2.0, 0.1, -0.05], [0.1, 1.5, 0.08], [-0.05, 0.08, 1.2]])
OMEGA0 = np.array([0.3, -0.2, 1.0])
T_OUT = np.linspace(0.0, 15.0, 6)


def _quaternion_rate(q, w):
    """½ q ⊗ (0, ω), q = (w, x, y, z)."""
    return 0.5 * np.array([-q[1] * w[0] - q[2] * w[1] - q[3] * w[2],
                           q[0] * w[0] + q[2] * w[2] - q[3] * w[1],
                           q[0] * w[1] + q[3] * w[0] - q[1] * w[2],
                           q[0] * w[2] + q[1] * w[1] - q[2] * w[0]])


def _reference(rate, y0, n_p, p0, direction, s0=None):
    """y and ∂y/∂p along `direction` in p (the parameters' vector) by SciPy's DOP853 on the state and
    its sensitivity, S' = Im f(y + i h S, p + i h e)/h with h = 1e-30 (the complex step: no
    truncation, no cancellation)."""
    n = len(y0)
    h = 1e-30

    def augmented(t, Y):
        y, S = Y[:n], Y[n:]
        value = rate(t, y.astype(complex), p0.astype(complex))
        moved = rate(t, y + 1j * h * S, p0 + 1j * h * direction)
        return np.concatenate([value.real, moved.imag / h])
    Y0 = np.concatenate([y0, np.zeros(n) if s0 is None else s0])
    sol = solve_ivp(augmented, (T_OUT[0], T_OUT[-1]), Y0, method="DOP853", t_eval=T_OUT, rtol=1e-12, atol=1e-14)
    assert sol.success
    return sol.y[:n].T, sol.y[n:].T


def _drag(t, w, c, a):
    """user_torques.drag_factory's torque, written for complex arguments (|ω| = sqrt(ω·ω))."""
    return -c * np.sqrt(w @ w) * w + np.array([0.0, 0.0, a * np.sin(t)])


@pytest.mark.parametrize("name, index", [("CustomTorque.c", 0), ("torques[0].a", 1)])
def test_a_custom_torques_parameters(name, index):
    """A CustomTorque made by its factory offers the factory's arguments: ∂y/∂c and ∂y/∂a agree with
    the reference (ours at rtol 1e-11, the reference at 1e-12: within 1e-8 of each vector's size;
    ∂M/∂c is a central difference quotient here, ~1e-11, and the notes say so)."""
    J = np.array([1.0, 2.0, 2.5])
    torque = g.CustomTorque(user_torques.drag_factory, parameters={"c": 0.05, "a": 0.02}, name="drag")
    model = g.Model(g.Body(J), [torque])
    assert {"CustomTorque.c", "CustomTorque.a", "torques[0].c"} <= set(g.sensitivity.parameter_names(model))
    sol = g.solve(model, [1.0, 0.5, -0.3], (0.0, 15.0), t_eval=T_OUT, rtol=1e-11, atol=1e-13, sensitivities=[name])

    def rate(t, w, p):
        return (np.cross(J * w, w) + _drag(t, w, p[0], p[1])) / J
    y, S = _reference(rate, np.array([1.0, 0.5, -0.3]), 2, np.array([0.05, 0.02]), np.eye(2)[index])
    assert np.abs(sol.y - y).max() < 1e-9, "the state itself (rtol 1e-11 over 15 s)"
    scale = np.abs(S).max(axis=1)[1:]
    error = np.abs(sol.sensitivity(name) - S).max(axis=1)[1:]
    assert np.all(error <= 1e-8 * scale), (name, error / scale)
    assert any("difference quotient of the torques its factory made" in note for note in sol.notes), sol.notes
    assert 0 < sol.sensitivity_errors[name] < 1e-7, "measured, and near the truth (~1e-10)"


def test_what_a_custom_torque_does_not_offer():
    plain = g.Model(g.Body([1.0, 2.0, 2.5]), [g.CustomTorque(lambda t, w: -0.1 * w)])
    assert not any(name.startswith(("CustomTorque", "torques[")) for name in g.sensitivity.parameter_names(plain))
    with pytest.raises(ValueError, match="no parameter or state component 'CustomTorque.c'"):
        g.solve(plain, [1.0, 0.5, -0.3], (0.0, 1.0), sensitivities=["CustomTorque.c"])
    with pytest.raises(TypeError, match="with parameters, give a factory"):
        g.CustomTorque(user_torques.compiled("quadratic_drag"), parameters={"c": 0.1})
    named = g.Model(g.Body([1.0, 2.0, 2.5]), [g.CustomTorque(user_torques.compiled, parameters={"name": "quadratic_drag"})])
    assert "CustomTorque.name" not in g.sensitivity.parameter_names(named), "a factory's argument that is no number"


def test_a_custom_torques_parameters_through_an_ensemble_and_a_scene(tmp_path):
    """solve_ensemble gives each member its single run's sensitivities (bit for bit: the same code on
    the same data); a scene's custom torque with `parameters` offers them by name in its outputs."""
    from gyrostat import runner
    from gyrostat import scene as scenes
    torque = g.CustomTorque(user_torques.drag_factory, parameters={"c": 0.05, "a": 0.02})
    model = g.Model(g.Body([1.0, 2.0, 2.5]), [torque])
    y0s = np.array([[1.0, 0.5, -0.3], [0.9, 0.5, -0.3]])
    members = g.solve_ensemble(model, y0s, (0.0, 5.0), n_out=4, rtol=1e-10, sensitivities=["CustomTorque.c"])
    single = g.solve(model, y0s[1], (0.0, 5.0), n_out=4, rtol=1e-10, sensitivities=["CustomTorque.c"])
    assert np.array_equal(members[1].sensitivity("CustomTorque.c"), single.sensitivity("CustomTorque.c"))
    from test_custom_torque import SCENE  # the user's drag named in a scene, with its factory's parameters
    scene = SCENE.format(sweep="").replace("n_out = 41", 'n_out = 41\nsensitivities = ["CustomTorque.c"]')
    path = tmp_path / "user.toml"
    path.write_text(scene)
    solutions, _, _ = runner.solve_scene(scenes.load(path, allow_import=["user_torques"]), progress=False)
    (main,) = solutions.values()
    direct = g.solve(model, [1.0, 0.5, -0.3], (0.0, 20.0), n_out=41, method="dop853", rtol=1e-12, atol=1e-14,
                     sensitivities=["CustomTorque.c"])
    assert np.array_equal(main.sensitivity("CustomTorque.c"), direct.sensitivity("CustomTorque.c"))


def _tensor_rate(damping, rotor, attitude):
    """The user's-frame equations: I ω' = (Iω + k) × ω − D ω, q' = ½ q ⊗ (0, ω); p = I's 6 entries
    (upper triangle, symmetric)."""
    def rate(t, y, p):
        I = np.array([[p[0], p[1], p[2]], [p[1], p[3], p[4]], [p[2], p[4], p[5]]])
        w = y[:3]
        dw = np.linalg.solve(I, np.cross(I @ w + rotor, w) - damping @ w)
        return np.concatenate([dw, _quaternion_rate(y[3:], w)]) if attitude else dw
    return rate


UPPER = [(0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)]


@pytest.mark.parametrize("entry", [(0, 1), (1, 2), (2, 2)])
@pytest.mark.parametrize("attitude", [False, True])
def test_an_inertia_tensors_entries(entry, attitude):
    """∂(ω, q)/∂I_ij of a body given by its tensor (both I_ij and I_ji moved): the model runs in its
    principal axes and the entry turns them; the reference runs in the user's frame. Within 1e-8 of
    each vector's size (ours at rtol 1e-11: ~1e-10; the entry's central difference ~1e-11). The
    kinetic energy's derivative follows from T = ½ ω·Iω (below), to the same bound."""
    rotor = np.array([0.05, 0.0, 0.1])
    damping = np.array([[0.02, 0.005, 0.0], [0.0, 0.03, 0.0], [0.0, 0.0, 0.01]])
    body = g.Body(inertia=TENSOR, rotor=rotor)
    model = g.Model(body, [g.LinearDamping(matrix=damping)], attitude=attitude)
    name = f"inertia[{entry[0]},{entry[1]}]"
    assert name in g.sensitivity.parameter_names(model) and "moments[0]" not in g.sensitivity.parameter_names(model)
    sol = g.solve(model, OMEGA0, (0.0, 15.0), t_eval=T_OUT, rtol=1e-11, atol=1e-13, sensitivities=[name])
    p0 = np.array([TENSOR[i, j] for i, j in UPPER])
    y0 = np.concatenate([OMEGA0, [1.0, 0.0, 0.0, 0.0]]) if attitude else OMEGA0
    y, S = _reference(_tensor_rate(damping, rotor, attitude), y0, 6, p0, np.eye(6)[UPPER.index(entry)])
    assert np.abs(sol.y - y).max() < 1e-9, "the state itself, in the user's frame"
    scale = np.abs(S).max(axis=1)[1:]
    error = np.abs(sol.sensitivity(name) - S).max(axis=1)[1:]
    assert np.all(error <= 1e-8 * scale), error / scale
    # T = ½ ω·Iω in any frame: ∂T/∂I_ij = (Iω)·S_ω + ω_i ω_j (the symmetric pair: ½ (ω_i ω_j + ω_j ω_i))
    i, j = entry
    expected = np.einsum("tk,kl,tl->t", S[:, :3], TENSOR, y[:, :3]) + y[:, i] * y[:, j] * (1.0 if i != j else 0.5)
    got = sol.sensitivity(name, of="kinetic_energy")
    assert np.abs(got - expected).max() <= 1e-8 * np.abs(expected).max(), (got, expected)


def test_an_inertia_tensor_with_equal_moments():
    """A tilted axisymmetric body (moments 2, 2, 3): its principal axes in the symmetric plane are
    arbitrary, and the moved tensors' eigenvectors may turn far within it; the derivative, taken
    through the user's frame, does not depend on them (same bound and reason as above)."""
    c, s = np.cos(0.4), np.sin(0.4)
    R = np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])
    tensor = R @ np.diag([2.0, 2.0, 3.0]) @ R.T
    model = g.Model(g.Body(inertia=tensor), [g.LinearDamping(diagonal=[0.01, 0.02, 0.03])])
    sol = g.solve(model, OMEGA0, (0.0, 15.0), t_eval=T_OUT, rtol=1e-11, atol=1e-13, sensitivities=["inertia[0,1]"])
    p0 = np.array([tensor[i, j] for i, j in UPPER])
    y, S = _reference(_tensor_rate(np.diag([0.01, 0.02, 0.03]), np.zeros(3), False), OMEGA0, 6, p0, np.eye(6)[1])
    scale = np.abs(S).max(axis=1)[1:]
    error = np.abs(sol.sensitivity("inertia[0,1]") - S).max(axis=1)[1:]
    assert np.all(error <= 1e-8 * scale), error / scale


def test_an_inertia_tensors_entry_by_taylor_is_refused():
    """The Taylor recursion differences the moved models' coefficients in their own principal axes,
    which an inertia tensor's entry turns: refused by name, as are the other methods it lacks."""
    model = g.Model(g.Body(inertia=TENSOR), [g.LinearDamping(diagonal=[0.01, 0.02, 0.03])])
    with pytest.raises(ValueError, match="taylor.*turns the body's principal axes.*use dop853 or cvode_bdf"):
        g.solve(model, OMEGA0, (0.0, 1.0), method="taylor", sensitivities=["inertia[0,1]"])
    by_taylor = g.solve(model, OMEGA0, (0.0, 5.0), method="taylor", rtol=1e-12, n_out=3, sensitivities=["p"])
    by_dop853 = g.solve(model, OMEGA0, (0.0, 5.0), rtol=1e-12, n_out=3, sensitivities=["p"])
    # an initial component needs no moved model: Taylor takes it on a tensor body (rtol 1e-12, 5 s)
    assert np.abs(by_taylor.sensitivity("p") - by_dop853.sensitivity("p")).max() < 1e-9


def test_a_tensor_bodys_rotor_by_every_method():
    """∂ω/∂k_1 on a body given by its tensor: the rotor moved keeps the body's axes bit for bit
    (Body.with_rotor); given again, the tensor's decomposition turned them by 1e-16, and taylor
    refused rotor[k] as "a parameter that turns the principal axes" (before 2026-11-29). Against
    central differences of plain runs at rtol 1e-13 (h = 1e-6 and 2e-6: at 1e-4 their truncation was
    2e-6 of the derivative)."""
    rotor = np.array([0.05, 0.02, 0.1])
    damping = [0.01, 0.02, 0.03]
    model = g.Model(g.Body(inertia=TENSOR, rotor=rotor), [g.LinearDamping(diagonal=damping)])

    def difference(h):
        ends = [g.solve(g.Model(g.Body(inertia=TENSOR, rotor=rotor + sign * h * np.eye(3)[1]),
                                [g.LinearDamping(diagonal=damping)]), OMEGA0, (0.0, 15.0), t_eval=T_OUT, rtol=1e-13,
                        atol=1e-15, error_estimate=False).y for sign in (1, -1)]
        return (ends[0] - ends[1]) / (2 * h)

    reference, coarse = difference(1e-6), difference(2e-6)
    spread = np.abs(reference - coarse).max() / np.abs(reference).max()
    assert spread < 1e-7, f"the reference's differences at h and 2h differ by {spread:.2e}: unusable"
    for method in ("dop853", "taylor", "cvode_bdf"):
        sol = g.solve(model, OMEGA0, (0.0, 15.0), t_eval=T_OUT, rtol=1e-11, atol=1e-13, method=method,
                      sensitivities=["rotor[1]"])
        assert sol.success, (method, sol.message)
        error = np.abs(sol.sensitivity("rotor[1]") - reference).max() / np.abs(reference).max()
        # 1e-6: the bound (measured 2e-10 … 3e-10 by each method)
        assert error < 1e-6, (method, error)
    with pytest.raises(ValueError, match="rotor momentum k"):
        g.Body(inertia=TENSOR).with_rotor([0.0, np.nan, 0.0])


def test_a_small_affine_parameter_does_not_hold_the_steps():
    """A damping entry of 0.01 on a body spinning at ~1 rad/s: its ∂f/∂p, a difference of right-hand
    sides moved by ε^(1/3)|p|, carried f's rounding at ~1e-9 of itself, and DOP853 chased that noise
    at rtol 1e-13 with 12x the plain run's steps (6993 against 574). Moved by the parameter's own
    size (exact: f is affine in it) the run takes 758 (bound 1.5x the plain run's), and agrees with
    the Taylor method's recursion (the derivative without a quotient of rates) within 1e-10."""
    D = [[0.05, 0.01, 0.0], [0.01, 0.08, 0.0], [0.0, 0.0, 0.03]]
    model = g.Model(g.Body([1.0, 1.4, 2.1], rotor=[0.05, -0.02, 0.1]),
                    [g.LinearDamping(matrix=D), g.ConstantTorque([0.01, -0.02, 0.005])], attitude=True)
    name = "LinearDamping.matrix[0,1]"
    options = dict(n_out=11, rtol=1e-13, atol=1e-16, error_estimate=False)
    plain = g.solve(model, [0.15, 0.3, 1.0], (0.0, 200.0), **options)
    sol = g.solve(model, [0.15, 0.3, 1.0], (0.0, 200.0), sensitivities=[name], **options)
    assert sol.stats["steps"] <= 1.5 * plain.stats["steps"], (sol.stats["steps"], plain.stats["steps"])
    taylor = g.solve(model, [0.15, 0.3, 1.0], (0.0, 200.0), method="taylor", sensitivities=[name], **options)
    scale = np.abs(taylor.sensitivity(name)).max()
    assert np.abs(sol.sensitivity(name) - taylor.sensitivity(name)).max() <= 1e-10 * scale
