"""A body given by its inertia tensor in a frame other than its principal axes.

The references never diagonalise: SciPy integrates Euler's equations with the full tensor in the
user's frame, I ω̇ = M − ω × (I ω + k), q̇ = ½ q ⊗ (0, ω), right-hand side written here. The same
motion given in principal axes (ω_p = R0ᵀ ω, torques rotated by hand) must agree with the
tensor's run converted by R0. Every family that takes a tensor is run, through solve, events,
dense output, the ensemble (batched and not, 2 threads) and a scene; the families that cannot take
one refuse it by name."""

from __future__ import annotations

import math
import tomllib

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
from gyrostat import attitude as att
from gyrostat.events import Event
from gyrostat.runner import solve_scene
from gyrostat.scene import Scene
from gyrostat.schema import SceneError
from references import quaternion_rate, rotation


def axis_angle(axis, angle):
    """The rotation matrix by `angle` about `axis` (Rodrigues)."""
    a = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


# The body: principal moments (3, 2, 1.2) turned by R0 into the user's frame.
R0 = axis_angle([0.3, -0.5, 0.8], 0.7)
MOMENTS = np.array([3.0, 2.0, 1.2])
INERTIA = R0 @ np.diag(MOMENTS) @ R0.T
ROTOR = np.array([0.05, -0.02, 0.08])  # user frame
D = np.array([[0.1, 0.02, -0.01], [0.01, 0.08, 0.0], [0.0, 0.03, 0.12]])  # damping, user frame
M0 = np.array([0.01, -0.02, 0.03])  # constant body torque, user frame
OMEGA0 = np.array([0.3, -0.2, 0.9])
Q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])


def tensor_reference(I, k, torque, y0, t_eval, rtol=1e-12):
    """SciPy DOP853 on I ω̇ = M(t, ω, R(q)) − ω × (I ω + k), q̇ = ½ q ⊗ (0, ω) (no diagonalising)."""
    I_inv = np.linalg.inv(I)

    def rhs(t, y):
        w = y[:3]
        M = torque(t, w, rotation(y[3:]) if len(y) == 7 else None)
        dw = I_inv @ (M - np.cross(w, I @ w + k))
        if len(y) == 3:
            return dw
        return np.concatenate([dw, quaternion_rate(y[3:], w)])

    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), y0, method="DOP853", t_eval=t_eval, rtol=rtol, atol=1e-14)
    assert sol.success
    return sol.y.T


def same_rotation(q, q_ref):
    """max |R(q) − R(q_ref)| over rows of quaternions."""
    return max(np.abs(rotation(a) - rotation(b)).max() for a, b in zip(q, q_ref))


# ------------------------------------------------------------------ the Body
def test_body_from_tensor_diagonalises_it():
    body = g.Body(inertia=INERTIA, rotor=ROTOR)
    R = body.principal_axes
    assert not body.principal
    # R is a rotation and diagonalises the tensor: to rounding (1e-14 of the moments)
    np.testing.assert_allclose(R.T @ R, np.eye(3), atol=1e-14)
    assert abs(np.linalg.det(R) - 1.0) < 1e-14
    np.testing.assert_allclose(R @ np.diag(body.moments) @ R.T, INERTIA, atol=1e-14)
    np.testing.assert_allclose(np.sort(body.moments), np.sort(np.linalg.eigvalsh(INERTIA)), rtol=1e-14)
    np.testing.assert_allclose(body.inertia, INERTIA, atol=1e-14)
    np.testing.assert_allclose(body.rotor, ROTOR, atol=1e-15)  # returned in the user's frame
    np.testing.assert_allclose(body.principal_rotor, R.T @ ROTOR, atol=1e-15)
    # the rotation closest to the identity: no relabelling of R's columns with det +1 has a larger trace
    import itertools
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product([1, -1], repeat=3):
            P = R[:, perm] * np.array(signs)
            if np.linalg.det(P) > 0:
                assert np.trace(P) <= np.trace(R) + 1e-12


def test_a_diagonal_tensor_keeps_its_axes_and_order():
    body = g.Body(inertia=np.diag([1.0, 3.0, 2.5]))
    assert body.principal
    np.testing.assert_array_equal(body.moments, [1.0, 3.0, 2.5])
    np.testing.assert_array_equal(body.principal_axes, np.eye(3))


@pytest.mark.parametrize("inertia, message", [
    ([[2.0, 0.1, 0.0], [0.2, 2.0, 0.0], [0.0, 0.0, 1.0]], "not symmetric: I[0][1] = 0.1 but I[1][0] = 0.2"),
    ([[2.0, 0.0, 0.0], [0.0, float("nan"), 0.0], [0.0, 0.0, 1.0]], "(1, 1) = nan is not finite"),
    ([[1.0, 2.0, 0.0], [2.0, 1.0, 0.0], [0.0, 0.0, 1.0]], "must be positive"),  # eigenvalue −1
    ([[5.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.0]], "triangle inequality"),
])
def test_bad_tensors_are_refused_naming_the_value(inertia, message):
    with pytest.raises(ValueError, match=message.replace("[", r"\[").replace("]", r"\]").replace("(", r"\(").replace(")", r"\)")):
        g.Body(inertia=inertia)


def test_moments_or_inertia_not_both():
    with pytest.raises(TypeError, match="either moments"):
        g.Body([1.0, 2.0, 2.5], inertia=np.eye(3))
    with pytest.raises(TypeError, match="either moments"):
        g.Body()


# ------------------------------------------------------------------ the gyrostat Model
def user_torque(t, w, R):
    return M0 - D @ w


@pytest.mark.parametrize("attitude, method", [(False, "dop853"), (True, "dop853"), (False, "cvode_bdf"),
                                               (True, "cvode_bdf"), (False, "taylor"), (True, "splitting")])
def test_model_against_the_tensor_reference(attitude, method):
    """Euler's equations with the full tensor in the user's frame; tolerance 1e-7: the runs at
    rtol 1e-10 (splitting: its own error estimate at 1e-10) over 20 s, a few hundred steps.
    Splitting's exact free flow needs a rigid body: no rotor there."""
    rotor = np.zeros(3) if method == "splitting" else ROTOR
    body = g.Body(inertia=INERTIA, rotor=rotor)
    model = g.Model(body, [g.ConstantTorque(M0), g.LinearDamping(matrix=D)], attitude=attitude)
    t = np.linspace(0.0, 20.0, 11)
    y0 = np.concatenate([OMEGA0, Q0]) if attitude else OMEGA0
    sol = g.solve(model, y0, (0.0, 20.0), t_eval=t, method=method, rtol=1e-10, atol=1e-12)
    ref = tensor_reference(INERTIA, rotor, user_torque, y0, t)
    assert np.abs(sol.y[:, :3] - ref[:, :3]).max() < 1e-7, np.abs(sol.y[:, :3] - ref[:, :3]).max()
    if attitude:
        assert same_rotation(sol.y[:, 3:], ref[:, 3:]) < 1e-7


def test_same_motion_in_principal_axes():
    """The tensor's run, converted by R0, equals the run given in principal axes with the torques
    rotated by hand (v_p = R0ᵀ v, D_p = R0ᵀ D R0, q_p = q ⊗ q_R0): to 1e-9 (rtol 1e-11)."""
    user = g.Model(g.Body(inertia=INERTIA, rotor=ROTOR), [g.ConstantTorque(M0), g.LinearDamping(matrix=D)],
                   attitude=True)
    principal = g.Model(g.Body(MOMENTS, rotor=R0.T @ ROTOR),
                        [g.ConstantTorque(R0.T @ M0), g.LinearDamping(matrix=R0.T @ D @ R0)], attitude=True)
    t = np.linspace(0.0, 15.0, 7)
    a = g.solve(user, np.concatenate([OMEGA0, Q0]), (0.0, 15.0), t_eval=t, rtol=1e-11, atol=1e-13)
    qp0 = att.quaternion_from_matrix(rotation(Q0) @ R0)
    b = g.solve(principal, np.concatenate([R0.T @ OMEGA0, qp0]), (0.0, 15.0), t_eval=t, rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y[:, :3], b.y[:, :3] @ R0.T, atol=1e-9)
    assert max(np.abs(rotation(qa) - rotation(qb) @ R0.T).max() for qa, qb in zip(a.y[:, 3:], b.y[:, 3:])) < 1e-9
    # the outputs are the principal axes': |G|, T and the nutation angle agree as they are
    for name in ("angular_momentum_norm", "kinetic_energy", "nutation_angle"):
        np.testing.assert_allclose(a.outputs[name], b.outputs[name], rtol=1e-9, atol=1e-12)


def test_rhs_initial_state_and_identity_attitude_are_the_users():
    body = g.Body(inertia=INERTIA, rotor=ROTOR)
    model = g.Model(body, [g.LinearDamping(matrix=D)], attitude=True)
    y0 = model.initial_state(OMEGA0)  # the identity attitude: the user's axes along inertial axes
    np.testing.assert_allclose(y0, np.concatenate([OMEGA0, [1, 0, 0, 0]]), atol=1e-15)
    dy = model.rhs(0.0, np.concatenate([OMEGA0, Q0]))
    w = OMEGA0
    expected = np.linalg.solve(INERTIA, -D @ w - np.cross(w, INERTIA @ w + ROTOR))
    np.testing.assert_allclose(dy[:3], expected, atol=1e-14)


def test_attitude_torques_on_a_tensor():
    """Gravity gradient M = 3n² ĉ × (I ĉ) with the user's tensor, a magnetic dipole m given in the
    user's frame and an inertial torque: against the tensor reference, 1e-8 (rtol 1e-11)."""
    n, m_dip, B, MI = 0.5, np.array([0.2, -0.1, 0.3]), np.array([0.4, 0.1, -0.3]), np.array([0.0, 0.01, 0.02])

    def torque(t, w, R):
        c = R.T @ np.array([math.cos(n * t), math.sin(n * t), 0.0])
        return 3 * n * n * np.cross(c, INERTIA @ c) + np.cross(m_dip, R.T @ B) + R.T @ MI

    model = g.Model(g.Body(inertia=INERTIA), [g.GravityGradient(n), g.MagneticTorque(dipole=m_dip, field=B),
                                              g.InertialTorque(MI)], attitude=True)
    t = np.linspace(0.0, 12.0, 7)
    y0 = np.concatenate([OMEGA0, Q0])
    sol = g.solve(model, y0, (0.0, 12.0), t_eval=t, rtol=1e-11, atol=1e-13)
    ref = tensor_reference(INERTIA, np.zeros(3), torque, y0, t)
    assert np.abs(sol.y[:, :3] - ref[:, :3]).max() < 1e-8
    assert same_rotation(sol.y[:, 3:], ref[:, 3:]) < 1e-8


def test_custom_torque_sees_the_users_frame():
    """A Python torque f(t, ω, q) is called with the user's ω and q and returns M in the user's
    frame: it equals the built-in torques it writes out, to 1e-10 (rtol 1e-11)."""
    seen = []

    def f(t, omega, q):
        seen.append(np.array(omega))
        return M0 - D @ np.asarray(omega)

    custom = g.Model(g.Body(inertia=INERTIA), [g.CustomTorque(f, attitude=True)], attitude=True)
    builtin = g.Model(g.Body(inertia=INERTIA), [g.ConstantTorque(M0), g.LinearDamping(matrix=D)], attitude=True)
    y0 = np.concatenate([OMEGA0, Q0])
    a = g.solve(custom, y0, (0.0, 5.0), n_out=5, rtol=1e-11, atol=1e-13)
    b = g.solve(builtin, y0, (0.0, 5.0), n_out=5, rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y, b.y, atol=1e-10)
    np.testing.assert_allclose(seen[0], OMEGA0, atol=1e-15)  # the first call is at the user's ω(0)


def test_events_and_dense_output_in_the_users_frame():
    """An event on the user's ω_x and the dense output: the crossing time against SciPy's event
    on the tensor reference (1e-8 s), the dense state against the reference (1e-8)."""
    model = g.Model(g.Body(inertia=INERTIA, rotor=ROTOR), [g.LinearDamping(matrix=D)])
    sol = g.solve(model, OMEGA0, (0.0, 30.0), events=[Event("p")], dense_output=True,
                  rtol=1e-11, atol=1e-13)
    I_inv = np.linalg.inv(INERTIA)

    def rhs(t, w):
        return I_inv @ (-D @ w - np.cross(w, INERTIA @ w + ROTOR))

    def px(t, w):
        return w[0]

    ref = solve_ivp(rhs, (0.0, 30.0), OMEGA0, method="DOP853", rtol=1e-12, atol=1e-14, events=px, dense_output=True)
    assert len(ref.t_events[0]) > 0
    np.testing.assert_allclose(sol.t_events[0][: len(ref.t_events[0])], ref.t_events[0], atol=1e-8)
    np.testing.assert_allclose(sol.y_events[0][:, 0], 0.0, atol=1e-9)
    np.testing.assert_allclose(sol(13.7), ref.sol(13.7), atol=1e-8)
    # the dense output keeps the body's rotation, not the model: it outlives the model
    del model
    import gc
    gc.collect()
    np.testing.assert_allclose(sol(21.3), ref.sol(21.3), atol=1e-8)


# ------------------------------------------------------------------ the other families
def symmetric_tensor():
    R = axis_angle([1.0, 2.0, -0.5], 0.4)
    return R, R @ np.diag([2.0, 2.0, 1.2]) @ R.T


def test_averaged_model_takes_omega_in_the_users_frame():
    """(a, r) from the user's ω are the principal ones; the averaged run equals the principal
    body's (same moments, torques rotated by hand) to rounding."""
    R, I = symmetric_tensor()
    Dsym = np.diag([0.002, 0.002, 0.005])
    D_user = R @ Dsym @ R.T
    user = g.AveragedModel(g.Body(inertia=I), [g.LinearDamping(matrix=D_user)])
    principal = g.AveragedModel(g.Body([2.0, 2.0, 1.2]), [g.LinearDamping(matrix=Dsym)])
    body = g.Body(inertia=I)
    w_user = np.array([0.2, -0.1, 0.8])
    w_p = body.principal_axes.T @ w_user
    np.testing.assert_allclose(user.initial_state(w_user), [math.hypot(w_p[0], w_p[1]), w_p[2]], atol=1e-15)
    a = g.solve(user, w_user, (0.0, 50.0), n_out=3)
    b = g.solve(principal, w_p, (0.0, 50.0), n_out=3)
    # the principal axes of a symmetric tensor are fixed only up to a turn about its axis, and the
    # user's damping rotated back is Dsym in any of them: equal to rounding (1e-13)
    np.testing.assert_allclose(a.y, b.y, atol=1e-13)
    # lifting back to the full model gives the user's frame: |ω| and ω's axial part are kept
    lifted = user._core.full_state(a.y[-1], 0.3)
    assert abs(np.linalg.norm(lifted) - np.hypot(*a.y[-1])) < 1e-14
    assert abs(lifted @ body.principal_axes[:, 2] - a.y[-1][1]) < 1e-14


def test_torque_free_model_closed_form_in_the_users_frame():
    model = g.TorqueFreeModel(g.Body(inertia=INERTIA), attitude=True)
    t = np.linspace(0.0, 30.0, 7)
    sol = g.solve(model, np.concatenate([OMEGA0, Q0]), (0.0, 30.0), t_eval=t)
    ref = tensor_reference(INERTIA, np.zeros(3), lambda t, w, R: np.zeros(3), np.concatenate([OMEGA0, Q0]), t)
    assert np.abs(sol.y[:, :3] - ref[:, :3]).max() < 1e-9
    assert same_rotation(sol.y[:, 3:], ref[:, 3:]) < 1e-9
    with pytest.raises(ValueError, match="closed form is written in principal axes"):
        g.TorqueFreeSolution(g.Body(inertia=INERTIA), OMEGA0)


def test_orthogonal_torque_model_on_a_tensor():
    """The servo's torque is orthogonal to G in any frame: the tensor's run converted by R0
    equals the principal one, 1e-9."""
    from gyrostat import orthogonal
    law = 0.05
    a = g.solve(orthogonal.OrthogonalModel(g.Body(inertia=INERTIA), law), OMEGA0, (0.0, 10.0), n_out=5,
                rtol=1e-11, atol=1e-13)
    b = g.solve(orthogonal.OrthogonalModel(g.Body(MOMENTS), law), R0.T @ OMEGA0, (0.0, 10.0), n_out=5,
                rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y[:, :3], b.y[:, :3] @ R0.T, atol=1e-9)
    np.testing.assert_allclose(a.y[:, 3], b.y[:, 3], atol=1e-9)  # τ is a scalar


def test_moving_mass_model_on_a_tensor():
    """ω, the mass's displacement u and its rate v are body vectors: converted by R0 they equal the
    principal run's, 1e-9."""
    R, I = symmetric_tensor()
    Rb = g.Body(inertia=I).principal_axes
    kw = dict(mass=0.1, arm=0.5, frequency=3.0, damping=0.4)
    a = g.solve(g.MovingMassModel(g.Body(inertia=I), **kw), np.concatenate([[0.2, -0.1, 0.8], np.zeros(6)]),
                (0.0, 10.0), n_out=5, rtol=1e-11, atol=1e-13)
    w_p = Rb.T @ np.array([0.2, -0.1, 0.8])
    b = g.solve(g.MovingMassModel(g.Body([2.0, 2.0, 1.2]), **kw), np.concatenate([w_p, np.zeros(6)]), (0.0, 10.0),
                n_out=5, rtol=1e-11, atol=1e-13)
    for k in range(3):
        np.testing.assert_allclose(a.y[:, 3 * k:3 * k + 3], b.y[:, 3 * k:3 * k + 3] @ Rb.T, atol=1e-9)


# ------------------------------------------------------------------ ensembles and scenes
def scene_text(title: str, rotor: bool = False) -> str:
    """A rigid_body scene of the tensor body under the damping D, 10 s, 3 outputs."""
    rotor_line = f"rotor = {ROTOR.tolist()}\n" if rotor else ""
    return f"""
title = "{title}"
[body]
inertia = {INERTIA.tolist()}
{rotor_line}[[torques]]
type = "linear_damping"
matrix = {D.tolist()}
[initial]
omega = {OMEGA0.tolist()}
[integration]
t_span = [0.0, 10.0]
n_out = 3
rtol = 1e-10
atol = 1e-12
"""


@pytest.mark.parametrize("batch", [True, False])
def test_ensemble_equals_single_runs(batch):
    """Members on a tensor body in an ensemble on 2 threads: batched (SIMD lanes, to the
    tolerance: 1e-8 at rtol 1e-10) or one by one (bit for bit)."""
    model = g.Model(g.Body(inertia=INERTIA, rotor=ROTOR), [g.LinearDamping(matrix=D)])
    rng = np.random.default_rng(3)
    y0s = OMEGA0 + 0.1 * rng.standard_normal((6, 3))
    ens = g.solve_ensemble(model, y0s, (0.0, 10.0), n_out=3, threads=2, batch=batch, rtol=1e-10, atol=1e-12)
    for i, y0 in enumerate(y0s):
        single = g.solve(model, y0, (0.0, 10.0), n_out=3, rtol=1e-10, atol=1e-12)
        member = ens[i]
        if batch:
            np.testing.assert_allclose(member.y, single.y, atol=1e-8)
        else:
            np.testing.assert_array_equal(member.y, single.y)
        ref = tensor_reference(INERTIA, ROTOR, lambda t, w, R: -D @ w, y0, single.t)
        assert np.abs(member.y - ref).max() < 1e-7


def test_scene_with_an_inertia_tensor():
    """A scene's [body] takes inertia = [[...], ...] instead of moments; its run equals solve's."""
    text = scene_text("tensor", rotor=True)
    scene = Scene.from_dict(tomllib.loads(text), name="tensor")
    solutions, _, _ = solve_scene(scene, progress=False)
    model = g.Model(g.Body(inertia=INERTIA, rotor=ROTOR), [g.LinearDamping(matrix=D)])
    single = g.solve(model, OMEGA0, (0.0, 10.0), n_out=3, rtol=1e-10, atol=1e-12)
    (run,) = solutions.values()
    np.testing.assert_allclose(run.y[-1], single.y[-1], atol=1e-12)
    bad = text.replace("[body]\n", "[body]\nmoments = [1.0, 2.0, 2.5]\n")
    with pytest.raises(SceneError, match="moments.*inertia|inertia.*moments"):
        Scene.from_dict(tomllib.loads(bad), name="bad")


def test_sweep_over_a_product_of_inertia(tmp_path):
    """A sweep sets both I_xy and I_yx (one Parameter, two paths): each member equals its own
    solve to 1e-12 (the same run); setting only one entry makes every member's tensor
    non-symmetric, reported as invalid input naming the entries, not a wrong result."""
    text = scene_text("tensor sweep")
    path = tmp_path / "tensor.toml"
    path.write_text(text)
    values = [INERTIA[0, 1] - 0.05, INERTIA[0, 1] + 0.05]
    ds = g.sweep(path, [g.Parameter("Ixy", ["body.inertia[0][1]", "body.inertia[1][0]"], values=values)],
                 progress=False)
    assert list(ds.status.values) == ["success", "success"]
    for i, v in enumerate(values):
        I = INERTIA.copy()
        I[0, 1] = I[1, 0] = v
        single = g.solve(g.Model(g.Body(inertia=I), [g.LinearDamping(matrix=D)]), OMEGA0, (0.0, 10.0), n_out=3,
                         rtol=1e-10, atol=1e-12)
        np.testing.assert_allclose([ds.p.values[i, -1], ds.q.values[i, -1], ds.r.values[i, -1]], single.y[-1],
                                   atol=1e-12)
    one_sided = g.sweep(path, {"body.inertia[0][1]": [INERTIA[0, 1] + 0.05]}, progress=False)
    assert one_sided.status.values[0] == "invalid_input"
    assert "not symmetric" in one_sided.message.values[0]


@pytest.mark.parametrize("name", ["p001_explicit_moving_mass", "p004_triaxial"])
def test_shipped_scenes_of_other_families_given_by_a_tensor(name):
    """A moving-mass and an orthogonal-torque scene given again in a body frame turned by R0
    (inertia = R0 J R0ᵀ, rotor, ω0 and the damping rotated likewise): every run's ω, and the
    mass's u and v, equal R0 times the original scene's, τ equal; 1e-8 (rtol 1e-9…1e-10 over 5 s)."""
    from gyrostat.scene import SCENES
    doc = tomllib.loads((SCENES / f"{name}.toml").read_text())
    doc["integration"]["t_span"], doc["integration"]["n_out"] = [0.0, 5.0], 3
    doc.pop("expected_broken", None)
    R = axis_angle([1.0, 0.4, -0.3], 0.6)
    turned = tomllib.loads((SCENES / f"{name}.toml").read_text())
    turned.update({k: doc[k] for k in ("integration",)})
    turned.pop("expected_broken", None)
    body = turned["body"]
    body["inertia"] = (R @ np.diag(body.pop("moments")) @ R.T).tolist()
    if "rotor" in body:
        body["rotor"] = (R @ np.asarray(body["rotor"])).tolist()
    turned["initial"]["omega"] = (R @ np.asarray(turned["initial"]["omega"])).tolist()
    for torque in turned.get("torques", []):
        torque["matrix"] = (R @ np.diag(torque.pop("diagonal")) @ R.T).tolist()
    a, _, _ = solve_scene(Scene.from_dict(doc, name=name), progress=False)
    b, _, _ = solve_scene(Scene.from_dict(turned, name=name), progress=False)
    assert a.keys() == b.keys()
    for run in a:
        ya, yb = a[run].y, b[run].y
        for start in range(0, 9 if name.startswith("p001") else 3, 3):
            np.testing.assert_allclose(yb[:, start:start + 3], ya[:, start:start + 3] @ R.T, atol=1e-8)
        if "tau" in a[run].state_names:
            k = a[run].state_names.index("tau")
            np.testing.assert_allclose(yb[:, k], ya[:, k], atol=1e-8)
