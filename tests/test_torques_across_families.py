"""The user's torque and the attitude torques in every family that takes them, not only the
gyrostat Model: the Lagrange top (its right-hand side written here, gravity and an inertial
torque), the orthogonal-torque model with the attitude, the moving mass; and the refusals of the
models that cannot take them."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
import user_torques as user
from gyrostat import lagrange, orthogonal
from references import quaternion_rate, rotation


A, C, MU = 2.0, 1.2, 0.8
MI = np.array([0.05, -0.02, 0.03])           # inertial torque [N m]
DIPOLE, FIELD = np.array([0.1, 0.0, 0.2]), np.array([0.0, 0.3, -0.1])
Y0_TOP = np.concatenate([[0.1, -0.2, 4.0], np.array([0.95, 0.2, -0.1, 0.05]) / np.linalg.norm([0.95, 0.2, -0.1, 0.05])])


def top_reference(t_eval, torque):
    """The heavy top with the torque M(t, ω, R) written here: A ṗ = (A − C) q r + μ γ2 + M1,
    A q̇ = (C − A) p r − μ γ1 + M2, C ṙ = M3, γ the inertial vertical in body axes (Rᵀ ẑ)."""
    def rhs(t, y):
        w, q = y[:3], y[3:]
        R = rotation(q)
        gamma = R.T @ np.array([0.0, 0.0, 1.0])
        M = torque(t, w, R)
        p, qq, r = w
        return np.concatenate([[((A - C) * qq * r + MU * gamma[1] + M[0]) / A,
                                ((C - A) * p * r - MU * gamma[0] + M[1]) / A, M[2] / C], quaternion_rate(q, w)])

    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), Y0_TOP, method="DOP853", t_eval=t_eval, rtol=1e-12, atol=1e-14)
    assert sol.success
    return sol.y.T


def test_lagrange_top_with_attitude_torques_against_scipy():
    """An inertial torque and a magnetic dipole on the heavy top: against SciPy with the top's
    equations written here, 1e-8 (rtol 1e-11 over 10 s, ~6 nutation periods)."""
    t = np.linspace(0.0, 10.0, 11)
    top = lagrange.LagrangeTop(A, C, MU, [g.InertialTorque(MI), g.MagneticTorque(dipole=DIPOLE, field=FIELD)])
    sol = g.solve(top, Y0_TOP, (0.0, 10.0), t_eval=t, rtol=1e-11, atol=1e-13)
    ref = top_reference(t, lambda t, w, R: R.T @ MI + np.cross(DIPOLE, R.T @ FIELD))
    assert np.abs(sol.y[:, :3] - ref[:, :3]).max() < 1e-8
    assert max(np.abs(rotation(a) - rotation(b)).max() for a, b in zip(sol.y[:, 3:], ref[:, 3:])) < 1e-8


def test_lagrange_top_with_a_user_torque():
    """A Python torque f(t, ω, q) = R(q)ᵀ M_I equals the built-in InertialTorque on the top, to
    1e-10 (the same formula; rtol 1e-11), and both equal SciPy to 1e-8."""
    def inertial(t, omega, q):
        return rotation(q).T @ MI

    t = np.linspace(0.0, 10.0, 6)
    custom = g.solve(lagrange.LagrangeTop(A, C, MU, [g.CustomTorque(inertial, attitude=True)]), Y0_TOP, (0.0, 10.0),
                     t_eval=t, rtol=1e-11, atol=1e-13)
    builtin = g.solve(lagrange.LagrangeTop(A, C, MU, [g.InertialTorque(MI)]), Y0_TOP, (0.0, 10.0), t_eval=t,
                      rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(custom.y, builtin.y, atol=1e-10)
    ref = top_reference(t, lambda t, w, R: R.T @ MI)
    assert np.abs(custom.y[:, :3] - ref[:, :3]).max() < 1e-8


def test_averaged_top_refuses_a_user_and_an_attitude_torque():
    for torque in (g.CustomTorque(lambda t, w: -w), g.InertialTorque(MI)):
        with pytest.raises(ValueError, match=f"{type(torque).__name__}|'{torque.kind}'"):
            lagrange.LagrangeAveraged(A, C, MU, [torque])


BODY = g.Body([2.0, 3.0, 4.0])
W0 = np.array([0.3, -0.2, 0.5])


def test_orthogonal_model_with_the_attitude_takes_attitude_torques():
    """With L = 0 the servo adds nothing: the orthogonal model with a gravity gradient equals the
    gyrostat Model with it (itself checked against SciPy in test_attitude_torques), to 1e-10."""
    t = np.linspace(0.0, 20.0, 5)
    gravity = g.GravityGradient(0.3, orbit_normal=[0.2, 0.0, 1.0])
    a = g.solve(orthogonal.OrthogonalModel(BODY, 0.0, [gravity], attitude=True), W0, (0.0, 20.0), t_eval=t,
                rtol=1e-11, atol=1e-13)
    b = g.solve(g.Model(BODY, [gravity], attitude=True), W0, (0.0, 20.0), t_eval=t, rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y[:, :7], b.y, atol=1e-10)
    with pytest.raises(ValueError, match="GravityGradient"):
        orthogonal.OrthogonalModel(BODY, 0.1, [gravity], attitude=False)


@pytest.mark.parametrize("compiled", [False, True], ids=["python", "compiled"])
def test_orthogonal_model_with_a_user_torque(compiled):
    """The quadratic drag −0.05|ω|ω (tests/user_torques: a Python function and the same in C) beside
    the servo: equal to the servo with the drag written as a Python torque the other way, to
    rounding (1e-12), and the Python and compiled paths to each other."""
    drag = g.CustomTorque(user.compiled_drag() if compiled else user.quadratic_drag)
    law = orthogonal.harmonic(0.1, [0.1], [1.3])
    a = g.solve(orthogonal.OrthogonalModel(BODY, law, [drag]), W0, (0.0, 20.0), n_out=5, rtol=1e-11, atol=1e-13)

    def drag_here(t, w):
        return -0.05 * np.linalg.norm(w) * np.asarray(w) + np.array([0.0, 0.0, 0.02 * np.sin(t)])

    b = g.solve(orthogonal.OrthogonalModel(BODY, law, [g.CustomTorque(drag_here)]), W0, (0.0, 20.0), n_out=5,
                rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y, b.y, atol=1e-12)


def test_moving_mass_with_a_user_torque_equals_the_built_in():
    """M = −Dω as a Python torque and as LinearDamping on the moving-mass model: 1e-12 (the same
    numbers in another order), in solve and in an ensemble on 2 threads."""
    D = np.diag([0.01, 0.02, 0.015])
    kw = dict(mass=0.1, arm=0.5, frequency=3.0, damping=0.4)
    custom = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), **kw, torques=[g.CustomTorque(lambda t, w: -D @ w)])
    builtin = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), **kw, torques=[g.LinearDamping(matrix=D)])
    y0 = np.concatenate([[0.2, -0.1, 0.8], np.zeros(6)])
    a = g.solve(custom, y0, (0.0, 10.0), n_out=5, rtol=1e-11, atol=1e-13)
    b = g.solve(builtin, y0, (0.0, 10.0), n_out=5, rtol=1e-11, atol=1e-13)
    np.testing.assert_allclose(a.y, b.y, atol=1e-12)
    ens = g.solve_ensemble(custom, np.array([y0, 1.1 * y0]), (0.0, 10.0), n_out=5, threads=2, rtol=1e-11, atol=1e-13)
    np.testing.assert_array_equal(ens[0].y, a.y)  # one by one (never batched): bit for bit
