"""The torques of papers 000–002 against formulas written in the tests, full models against
SciPy reference runs, and input validation."""

import numpy as np
import pytest

import gyrostat as g
from references import cavity_torque, damper_torque_series, damper_torque_symmetric, euler_rhs, scipy_reference

RNG = np.random.default_rng(7)


def test_cavity_torque_formula_and_invariants():
    cavity = g.ViscousCavity(1.3, 20.0, 0.7)
    for _ in range(20):
        w, J = RNG.normal(size=3), RNG.uniform(1, 2, 3)
        M = cavity(0.0, w, J)
        np.testing.assert_allclose(M, cavity_torque(w, J, cavity.kappa), rtol=1e-13, atol=1e-15)
        assert abs(np.dot(J * w, M)) < 1e-13 * np.linalg.norm(J * w) * np.linalg.norm(M) + 1e-300  # keeps |Jω|
        assert np.dot(w, M) <= 1e-15  # dissipates
    assert g.ViscousCavity.sphere(1.0, 1.0, 2.0).p0 == pytest.approx(8 * np.pi * 2.0**7 / 525, rel=1e-15)


def test_damper_torque_symmetric_and_triaxial():
    damper = g.MovingMassDamper(0.3, 1.7, np.sqrt(50.0), 7.0)
    for _ in range(10):
        w = RNG.normal(size=3)
        A, B, C = RNG.uniform(0.5, 3, 3)
        expected = damper_torque_symmetric(w, A, C, 0.3 * 1.7**2, 50.0, 7.0)
        np.testing.assert_allclose(damper(0.0, w, [A, A, C]), expected, rtol=1e-12, atol=1e-14)
        # triaxial: the closed form against the independent series evaluation of the reduction
        series = damper_torque_series(w, [A, B, C], 1.7, 0.3, 50.0, 7.0)
        np.testing.assert_allclose(damper(0.0, w, [A, B, C]), series, rtol=1e-10, atol=1e-12 * np.abs(series).max())
    assert damper.S(1.5, 1.0) == pytest.approx(0.3 * 1.7**2 * 7.0 / 50.0**2 * (1.5 - 1.0) / 1.5**4, rel=1e-14)


def test_resistive_medium_polynomial_in_time():
    D0, D1 = np.diag([0.1, 0.1, 0.2]), np.array([[0.01, 0.002, 0], [0, 0.01, 0], [0, 0, 0.03]])
    medium = g.ResistiveMedium([D0, D1])
    w = np.array([1.0, -2.0, 0.5])
    np.testing.assert_allclose(medium(3.0, w, [1, 1, 1]), -(D0 + 3.0 * D1) @ w, rtol=1e-15)
    a_dot, r_dot = medium.averaged(3.0, 2.0, 0.5, 1.5, 1.0)
    D = D0 + 3.0 * D1
    assert (a_dot, r_dot) == pytest.approx((-(D[0, 0] + D[1, 1]) * 2.0 / 3.0, -D[2, 2] * 0.5 / 1.0), rel=1e-14)


def test_full_model_with_new_torques_against_scipy():
    J, cav = [1.0, 1.4, 1.9], g.ViscousCavity(1.0, 10.0, 0.4)
    medium = g.ResistiveMedium([0.05 * np.eye(3), 0.001 * np.diag([1.0, 2.0, 3.0])])
    damper = g.MovingMassDamper(0.2, 1.0, 8.0, 3.0)
    torques = [cav, medium, damper, g.ConstantTorque([0.01, 0.0, 0.02])]

    def torque(t, w):
        D = 0.05 * np.eye(3) + 0.001 * np.diag([1.0, 2.0, 3.0]) * t
        return (cavity_torque(w, J, cav.kappa) - D @ w + damper_torque_series(w, J, 1.0, 0.2, 64.0, 3.0)
                + np.array([0.01, 0.0, 0.02]))

    t = np.linspace(0, 30, 61)
    ref = scipy_reference(J, [0, 0, 0], torque, [0.7, 0.4, 1.1], t, rtol=1e-11, atol=1e-13)
    for method in ("dop853", "cvode_bdf", "arkode_fehlberg8"):
        sol = g.solve(g.Model(g.Body(J), torques), [0.7, 0.4, 1.1], (0, 30), t_eval=t, method=method, rtol=1e-11,
                      atol=1e-13)
        # reference ~1e-10; CVODE's global error at rtol 1e-11 over 30 s ~1e-8 (docs/integrators.md)
        assert np.max(np.abs(sol.y - ref)) < (1e-7 if method == "cvode_bdf" else 1e-8), method


def test_explicit_moving_mass_rhs_against_the_test_formula():
    """The explicit model's equations, written in vector form here (docs/papers/001 §C)."""
    A, C, mu, rho, omega2, lam = 1.5, 1.0, 0.3, 1.0, 100.0, 9.0
    I = 0.1 * np.diag([1.25, 1.25, 1.0])
    model = g.MovingMassModel(g.Body([A, A, C]), mu, rho, np.sqrt(omega2), lam, [g.LinearDamping(I)])
    JB = np.array([A - mu * rho**2, A - mu * rho**2, C])
    for _ in range(10):
        y = RNG.normal(size=9) * 0.3
        w, u, v = y[:3], y[3:6], y[6:]
        d = np.array([0, 0, rho]) + u
        K = JB * w + mu * np.cross(d, np.cross(w, d) + v)
        R = -2 * np.cross(w, v) - np.cross(w, np.cross(w, d)) - omega2 * u - lam * v
        wd = (-I @ w - np.cross(w, K) - mu * (2 * (d @ v) * w - v * (d @ w) - d * (v @ w)) - mu * np.cross(d, R)) / JB
        expected = np.concatenate([wd, v, R - np.cross(wd, d)])
        np.testing.assert_allclose(model.rhs(0.0, y), expected, rtol=1e-13, atol=1e-14)


def test_averaged_rhs_is_the_sum_of_the_contributions():
    torques = [g.ViscousCavity(1.0, 5.0, 0.3), g.ConstantTorque([0.1, 0.2, 0.05]), g.LinearDamping(0.1 * np.eye(3)),
               g.MovingMassDamper(0.2, 1.0, 8.0, 3.0)]
    model = g.AveragedModel(g.Body([1.5, 1.5, 1.0]), torques)
    expected = sum(np.asarray(t.averaged(0.0, 0.8, -0.6, 1.5, 1.0)) for t in torques)
    np.testing.assert_allclose(model.rhs(0.0, [0.8, -0.6]), expected, rtol=1e-15)


@pytest.mark.parametrize("make, message", [
    (lambda: g.ViscousCavity(1.0, -3.0, 0.5), r"kinematic viscosity ν = -3 must be finite and positive"),
    (lambda: g.ViscousCavity(np.nan, 3.0, 0.5), r"density ρ = nan"),
    (lambda: g.ViscousCavity.sphere(1.0, 3.0, 0.0), r"cavity radius b = 0"),
    (lambda: g.MovingMassDamper(0.0, 1.0, 10.0, 1.0), r"mass m = 0 must be finite and positive"),
    (lambda: g.MovingMassDamper(1.0, 1.0, 10.0, -1.0), r"damping lambda = -1"),
    (lambda: g.ResistiveMedium([]), r"at least one coefficient"),
    (lambda: g.MovingMassModel(g.Body([1.0, 1.0, 1.6]), 1.0, 1.2, 10.0, 1.0), r"carrier's moments"),
    (lambda: g.AveragedModel(g.Body([1.0, 1.0, 1.6], [0, 0, 0.1])), r"rotor"),
])
def test_bad_parameters(make, message):
    with pytest.raises(ValueError, match=message):
        make()


def test_taylor_refuses_non_polynomial_torques():
    with pytest.raises(ValueError, match="method 'taylor' covers constant and linear torques only"):
        g.solve(g.Model(g.Body([1, 2, 3]), [g.ViscousCavity(1.0, 5.0, 0.3)]), [1, 0, 0], (0, 1), method="taylor")
