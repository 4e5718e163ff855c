"""The torques of papers 000–002 against formulas written in the tests, full models against
SciPy reference runs, and input validation."""

import numpy as np
import pytest

import gyrostat as g
from references import (cavity_torque, damper_torque_series, damper_torque_symmetric, euler_rhs, moving_mass_rhs,
                        scipy_reference)

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


def test_damper_in_a_model_uses_the_coefficients_made_for_its_body():
    # A model prepares the damper's monomial coefficients once for its body's principal moments
    # (TorqueSet::in_principal_axes); evaluated at other moments the torque makes them on the call.
    # Both against the independent series of the reduction, on a triaxial body and on the same body
    # given by a rotated inertia tensor (the model runs in its principal axes: ω' = Rᵀω).
    damper = g.MovingMassDamper(0.3, 1.7, np.sqrt(50.0), 7.0)
    J = np.array([1.3, 2.1, 2.9])
    model = g.Model(g.Body(list(J)), [damper])
    angle = 0.7
    R = np.array([[np.cos(angle), -np.sin(angle), 0.0], [np.sin(angle), np.cos(angle), 0.0], [0.0, 0.0, 1.0]])
    tensor_model = g.Model(g.Body(inertia=R @ np.diag(J) @ R.T), [damper])
    for _ in range(5):
        w = RNG.normal(size=3)
        torque = damper_torque_series(w, J, 1.7, 0.3, 50.0, 7.0)
        euler = (torque - np.cross(w, J * w)) / J  # Euler's equations with the series' torque
        scale = np.abs(euler).max()
        np.testing.assert_allclose(model.rhs(0.0, w), euler, rtol=1e-10, atol=1e-12 * scale)  # (the series' truncation)
        np.testing.assert_allclose(damper(0.0, w, 1.01 * J), damper_torque_series(w, 1.01 * J, 1.7, 0.3, 50.0, 7.0),
                                   rtol=1e-10, atol=1e-12 * np.abs(torque).max())
        # the tensor's model: the same motion written in the user's frame (ω_user = R ω_principal)
        np.testing.assert_allclose(tensor_model.rhs(0.0, R @ w), R @ euler, rtol=1e-10, atol=1e-12 * scale)


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
    f = moving_mass_rhs([A, A, C], mu, rho, omega2, lam, I)
    for _ in range(10):
        y = RNG.normal(size=9) * 0.3
        expected = f(0.0, y)
        np.testing.assert_allclose(model.rhs(0.0, y), expected, rtol=1e-13, atol=1e-14)


def test_averaged_rhs_is_the_phase_average_of_the_torques_written_here():
    """First-order averaging over the symmetric Euler–Poinsot motion p = a cos φ, q = a sin φ,
    r = const: ȧ = ⟨p M_p + q M_q⟩/(A a), ṙ = ⟨M_r⟩/C, the mean over φ of the torques written in
    tests/references.py (papers 002 (1) and 001 (2)–(3)) and here (−Dω, M0), by the trapezoid
    rule on 64 points (exact for these trigonometric polynomials of degree ≤ 6). Each
    contribution alone and the model's sum; several (a, r), both signs of r and of A − C."""
    D = np.array([[0.1, 0.02, 0.0], [-0.01, 0.07, 0.03], [0.0, 0.02, 0.05]])
    M0 = np.array([0.1, 0.2, 0.05])
    cavity, damper = g.ViscousCavity(1.0, 5.0, 0.3), g.MovingMassDamper(0.2, 1.0, 8.0, 3.0)
    phi = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    for A, C in ((1.5, 1.0), (1.0, 1.7)):
        J = np.array([A, A, C])
        written = {"cavity": (cavity, lambda w: cavity_torque(w, J, cavity.kappa)),
                   "damper": (damper, lambda w: damper_torque_symmetric(w, A, C, 0.2 * 1.0**2, 64.0, 3.0)),
                   "linear": (g.LinearDamping(D), lambda w: -D @ w),
                   "constant": (g.ConstantTorque(M0), lambda w: M0)}
        model = g.AveragedModel(g.Body(J), [pair[0] for pair in written.values()])
        for a, r in ((0.8, -0.6), (1.3, 0.4), (0.2, 2.1)):
            total = np.zeros(2)
            for name, (torque, formula) in written.items():
                M = np.array([formula(np.array([a * np.cos(f), a * np.sin(f), r])) for f in phi])
                mean = np.array([np.mean(a * np.cos(phi) * M[:, 0] + a * np.sin(phi) * M[:, 1]) / (A * a),
                                 np.mean(M[:, 2]) / C])
                # sums of 64 O(1) terms: rounding, 1e-14 of the largest term
                np.testing.assert_allclose(torque.averaged(0.0, a, r, A, C), mean, rtol=0,
                                           atol=1e-14 * max(1.0, np.abs(M).max()), err_msg=f"{name} A={A} C={C}")
                total += mean
            np.testing.assert_allclose(model.rhs(0.0, [a, r]), total, rtol=0, atol=1e-13, err_msg=f"A={A} C={C}")


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
