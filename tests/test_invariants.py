"""Invariants: |G| and T conserved without torques; both decreasing under damping; |q| = 1."""

import contextlib

import numpy as np
import pytest

import gyrostat as g
from references import attitude_reference, quaternion_distance

BODY = g.Body([1.0, 2.0, 3.0])
OMEGA0 = [1.0, 0.5, -0.3]


# Measured max |I/I(0) − 1| of |G| and T over t ∈ [0, 500] at rtol 1e-10, atol 1e-13 (the run of
# test_torque_free_invariants_conserved). ARKODE's Verner table converges at order 3
# (docs/integrators.md); the splitting is the exact flow (rounding per step, step 0.5).
INVARIANT_DRIFT = {
    "dop853": {"angular_momentum_norm": 6.4e-10, "kinetic_energy": 1.0e-9},
    "cvode_bdf": {"angular_momentum_norm": 7.3e-8, "kinetic_energy": 1.3e-7},
    "cvode_adams": {"angular_momentum_norm": 3.6e-8, "kinetic_energy": 6.2e-8},
    "arkode_verner6": {"angular_momentum_norm": 2.0e-6, "kinetic_energy": 2.8e-6},
    "arkode_fehlberg8": {"angular_momentum_norm": 3.4e-11, "kinetic_energy": 6.1e-11},
    "taylor": {"angular_momentum_norm": 1.3e-11, "kinetic_energy": 1.7e-11},
    "splitting": {"angular_momentum_norm": 2.2e-16, "kinetic_energy": 3.2e-15},
    "auto": {"angular_momentum_norm": 6.4e-10, "kinetic_energy": 1.0e-9},
}
# Measured max |q − q_ref| (sign aligned) over t ∈ [0, 200] at rtol 1e-9 against the kinematics
# integrated here (references.attitude_reference: q̇ = ½ q ⊗ (0, ω), no normalisation in the run)
QUATERNION_ERROR = {"dop853": 1.2e-7, "taylor": 6.1e-9, "cvode_bdf": 3.3e-6, "arkode_fehlberg8": 2.7e-11}


def _maybe_warns(method):
    return pytest.warns(UserWarning) if method == "arkode_verner6" else contextlib.nullcontext()


@pytest.mark.parametrize("method", g.METHODS)
def test_torque_free_invariants_conserved(method):
    with _maybe_warns(method):
        sol = g.solve(g.Model(BODY), OMEGA0, (0, 500), method=method, rtol=1e-10, atol=1e-13,
                      step=0.5 if method == "splitting" else None)
    assert sol.success
    for name, values in sol.invariants.items():
        drift = np.max(np.abs(values / values[0] - 1))
        # measured relative drift over ~50 periods at rtol 1e-10 (INVARIANT_DRIFT); bound 10× it
        bound = 10 * INVARIANT_DRIFT[method][name]
        assert drift < bound, f"{name} drifts by {drift:.2e} (measured {bound / 10:.1e})"
    # independent recomputation of the invariants from the states
    G = np.linalg.norm(sol.omega * np.asarray(BODY.moments), axis=1)
    np.testing.assert_allclose(sol.invariants["angular_momentum_norm"], G, rtol=1e-15)


def test_damping_decreases_momentum_and_energy():
    # D symmetric positive definite and J D + D J positive definite:
    # dT/dt = −ω·Dω < 0 and d|G|²/dt = −2 (Jω)·Dω < 0.
    D = np.array([[0.05, 0.01, 0.0], [0.01, 0.04, 0.0], [0.0, 0.0, 0.03]])
    assert np.all(np.linalg.eigvalsh(np.diag(BODY.moments) @ D + D @ np.diag(BODY.moments)) > 0)
    sol = g.solve(g.Model(BODY, [g.LinearDamping(D)]), OMEGA0, (0, 100), rtol=1e-10)
    assert sol.success
    for name in ("angular_momentum_norm", "kinetic_energy"):
        assert np.all(np.diff(sol.invariants[name]) < 0), name
    # energy balance: T(t) − T(0) = −∫ ω·Dω dt (trapezoid on 1001 points: error ~1e-6 relative)
    w = sol.omega
    dissipation = np.einsum("ni,ij,nj->n", w, D, w)
    integral = np.concatenate([[0], np.cumsum(0.5 * (dissipation[1:] + dissipation[:-1]) * np.diff(sol.t))])
    T = sol.invariants["kinetic_energy"]
    np.testing.assert_allclose(T - T[0], -integral, atol=1e-5)


@pytest.mark.parametrize("method", ["dop853", "taylor", "cvode_bdf", "arkode_fehlberg8"])
def test_quaternion_norm_kept(method):
    sol = g.solve(g.Model(BODY, attitude=True), OMEGA0, (0, 200), method=method, rtol=1e-9)
    assert sol.success
    # normalised at every output (and after every step for the explicit methods): rounding only.
    # This checks the normalisation, not the kinematics: the attitude itself is checked next.
    assert np.max(np.abs(np.linalg.norm(sol.quaternion, axis=1) - 1)) < 4e-16
    ref = attitude_reference(BODY.moments, (0, 0, 0), lambda t, w: (0.0, 0.0, 0.0), OMEGA0, sol.quaternion[0], sol.t)
    error = quaternion_distance(sol.quaternion, ref[:, 3:])
    assert error < 10 * QUATERNION_ERROR[method], f"{method}: {error:.2e} (measured {QUATERNION_ERROR[method]:.1e})"


def test_attitude_keeps_inertial_momentum_fixed():
    """Without torque the inertial angular momentum R(q) J ω is constant: an independent check
    of the quaternion kinematics (a sign error in q̇ would rotate it)."""
    sol = g.solve(g.Model(BODY, attitude=True), OMEGA0, (0, 100), rtol=1e-12, atol=1e-14)
    G_body = sol.omega * np.asarray(BODY.moments)
    w, x, y, z = sol.quaternion.T
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                  [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                  [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])
    G_inertial = np.einsum("ijn,nj->ni", R, G_body)
    # rtol 1e-12 over ~10 periods: drift of the inertial vector ~1e-10
    assert np.max(np.abs(G_inertial - G_inertial[0])) < 1e-9
