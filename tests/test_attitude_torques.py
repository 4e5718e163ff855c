"""Torques that depend on the attitude (gravity gradient, a magnetic dipole in a constant or a
planet's tilted dipole field, a torque fixed in inertial space): each against SciPy with the
right-hand side written here (Euler's equations and the quaternion kinematics), the inertial
torque against its closed form, the gravity gradient's averaged precession against the full
model, the libration scene against the linearised pitch frequency, and the refusals of the
models and methods that cannot take them."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g


# ------------------------------------------------------------------ the reference, written here
def rotation(q):
    """R(q): body → inertial, q = (w, x, y, z) normalised first."""
    w, x, y, z = np.asarray(q, float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def orbit_position(t, n, normal=(0.0, 0.0, 1.0), phase=0.0):
    """ĉ(t) = cos(nt + φ) e1 + sin(nt + φ) e2, e1 = ẑ × N/|ẑ × N| (x̂ when N ∥ ẑ), e2 = N × e1."""
    N = np.asarray(normal, float) / np.linalg.norm(normal)
    node = np.cross([0.0, 0.0, 1.0], N)
    e1 = node / np.linalg.norm(node) if np.linalg.norm(node) > 1e-12 else np.array([1.0, 0.0, 0.0])
    e2 = np.cross(N, e1)
    return math.cos(n * t + phase) * e1 + math.sin(n * t + phase) * e2


def reference(J, torque, y0, t_eval, rtol=1e-12):
    """SciPy DOP853 on J ω̇ = M(t, ω, R) − ω × Jω, q̇ = ½ q ⊗ (0, ω)."""
    J = np.asarray(J, float)

    def rhs(t, y):
        w, q = y[:3], y[3:]
        M = torque(t, w, rotation(q))
        qw, qx, qy, qz = q
        p, r2, r3 = w
        dq = 0.5 * np.array([-(qx * p + qy * r2 + qz * r3), qw * p + qy * r3 - qz * r2,
                             qw * r2 + qz * p - qx * r3, qw * r3 + qx * r2 - qy * p])
        return np.concatenate([(M - np.cross(w, J * w)) / J, dq])

    sol = solve_ivp(rhs, (t_eval[0], t_eval[-1]), y0, method="DOP853", t_eval=t_eval, rtol=rtol, atol=1e-14)
    assert sol.success
    return sol.y.T


J = np.array([1.0, 2.0, 2.5])
Q0 = np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
Y0 = np.concatenate([[0.3, -0.2, 0.5], Q0])


def gravity(n, normal, phase):
    return lambda t, w, R: 3 * n * n * np.cross(R.T @ orbit_position(t, n, normal, phase),
                                                 J * (R.T @ orbit_position(t, n, normal, phase)))


def dipole_field(t, b0, n, axis, normal, phase):
    c = orbit_position(t, n, normal, phase)
    d = np.asarray(axis, float) / np.linalg.norm(axis)
    return b0 * (3 * d.dot(c) * c - d)


CASES = {
    "gravity_gradient": (g.GravityGradient(0.4, orbit_normal=[0.3, -0.2, 1.0], phase=0.4),
                         gravity(0.4, [0.3, -0.2, 1.0], 0.4)),
    "gravity_gradient_default_orbit": (g.GravityGradient(0.7), gravity(0.7, [0, 0, 1], 0.0)),
    "magnetic": (g.MagneticTorque(dipole=[0.2, -0.1, 0.3], field=[0.5, 0.2, -0.4]),
                 lambda t, w, R: np.cross([0.2, -0.1, 0.3], R.T @ np.array([0.5, 0.2, -0.4]))),
    "dipole_field": (g.DipoleFieldTorque(dipole=[0.2, -0.1, 0.3], field_strength=0.8, orbit_rate=0.5,
                                         dipole_axis=[0.17, 0.0, -1.0], orbit_normal=[0.0, -0.5, 1.0], phase=1.0),
                     lambda t, w, R: np.cross([0.2, -0.1, 0.3],
                                              R.T @ dipole_field(t, 0.8, 0.5, [0.17, 0, -1], [0, -0.5, 1], 1.0))),
    "inertial": (g.InertialTorque([0.1, -0.2, 0.05]), lambda t, w, R: R.T @ np.array([0.1, -0.2, 0.05])),
}


@pytest.mark.parametrize("case", sorted(CASES))
@pytest.mark.parametrize("method", ["dop853", "cvode_bdf"])
def test_attitude_torque_against_scipy(case, method):
    torque, written = CASES[case]
    t = np.linspace(0.0, 20.0, 41)
    expected = reference(J, written, Y0, t)
    rtol = 1e-12 if method == "dop853" else 1e-10
    sol = g.solve(g.Model(g.Body(J), [torque], attitude=True), Y0, (0.0, 20.0), t_eval=t, method=method,
                  rtol=rtol, atol=1e-14)
    assert sol.success, sol.message
    error = np.abs(sol.y - expected).max()
    # dop853 at rtol 1e-12 over ~3 rotations: measured ≤ 1.1e-12 against SciPy at the same tolerance;
    # cvode_bdf at rtol 1e-10 (its Jacobian leaves out ∂M/∂q, the answer does not; BDF's global
    # error grows most in the fastest case, n = 0.7): measured 4e-9 to 2.9e-7
    bound = 1e-11 if method == "dop853" else 1e-6
    assert error < bound, f"{case} {method}: max |y - y_scipy| = {error:.3g} (bound {bound:g})"


@pytest.mark.parametrize("case", sorted(CASES))
def test_torque_value_against_the_written_formula(case):
    torque, written = CASES[case]
    w = np.array([0.3, -0.2, 0.5])
    for t in (0.0, 1.3, 7.9):
        expected = written(t, w, rotation(Q0))
        # one evaluation of the same formula in another order of operations: rounding only (measured ≤ 1.5e-16)
        assert np.allclose(torque(t, w, J, quaternion=Q0), expected, rtol=0, atol=1e-15), case


def test_inertial_torque_grows_the_inertial_momentum_linearly():
    """G_I(t) = G_I(0) + M_I t exactly (dG_I/dt = M_I): an invariant no right-hand side restates."""
    M = np.array([0.1, -0.2, 0.05])
    t = np.linspace(0.0, 30.0, 7)
    sol = g.solve(g.Model(g.Body(J), [g.InertialTorque(M)], attitude=True), Y0, (0.0, 30.0), t_eval=t,
                  method="dop853", rtol=1e-12, atol=1e-14)
    G = np.array([rotation(q) @ (J * w) for w, q in zip(sol.omega, sol.quaternion)])
    G0 = rotation(Q0) @ (J * Y0[:3])
    error = np.abs(G - (G0 + np.outer(t, M))).max()
    # rtol 1e-12 over 30 s (|G| ~ 2): measured 1.05e-12
    assert error < 1e-11, f"|G_I - (G_I(0) + M_I t)| = {error:.3g}"


def test_gravity_gradient_precession_matches_the_classical_rate():
    """A fast-spinning oblate body (A, A, C) with its spin axis 30° from the orbit normal: G
    precesses about the normal at Ω = -3 n² (C - A)(3 cos²ϑ - 1) cos i / (4 |G|) (ϑ = 0 here:
    -(3/2)(n²/ω3)((C - A)/C) cos i). Measured over 10 orbits against the full model."""
    n, spin = 0.01, 1.0
    body = g.Body([1.0, 1.0, 2.0])
    tilt = math.radians(30.0)
    q0 = np.array([math.cos(tilt / 2), math.sin(tilt / 2), 0.0, 0.0])  # body z tilted about x by 30°
    torque = g.GravityGradient(n)
    omega0 = np.array([0.0, 0.0, spin])
    rate = torque.precession_rate(body.moments, omega0, q0)
    expected = -1.5 * n * n / spin * (2.0 - 1.0) / 2.0 * math.cos(tilt)
    assert rate == pytest.approx(expected, rel=1e-14)  # the same formula at ϑ = 0, rounding only
    period = 2 * math.pi / n
    t = np.linspace(0.0, 10 * period, 201)
    sol = g.solve(g.Model(body, [torque], attitude=True), np.concatenate([omega0, q0]), (0.0, t[-1]), t_eval=t,
                  method="dop853", rtol=1e-10, atol=1e-12)
    G = np.array([rotation(q) @ (body.moments * w) for w, q in zip(sol.omega, sol.quaternion)])
    angle = np.unwrap(np.arctan2(G[:, 1], G[:, 0]))  # G's node angle about the orbit normal ẑ
    slope = np.polyfit(t, angle - angle[0], 1)[0]
    # first-order averaging errs by O(n / ω3) = 1e-2 relative (the bound), plus the twice-per-orbit
    # wobble the fit sees over 10 orbits: measured 0.12 %
    assert slope == pytest.approx(rate, rel=0.01), f"measured {slope:.6g} rad/s, classical {rate:.6g}"


def test_models_without_the_attitude_refuse_attitude_torques():
    torque = g.GravityGradient(0.01)
    with pytest.raises(ValueError, match="GravityGradient depends on the attitude.*attitude=True"):
        g.Model(g.Body(J), [torque])
    with pytest.raises(ValueError, match="InertialTorque.*averaged model does not carry"):
        g.AveragedModel(g.Body([1.0, 1.0, 2.0]), [g.InertialTorque([0, 0, 1])])
    with pytest.raises(ValueError, match="depends on the attitude"):
        torque(0.0, [0, 0, 1], J)


def test_taylor_refuses_and_splitting_freezes_the_attitude():
    model = g.Model(g.Body(J), [g.GravityGradient(0.4, phase=0.4)], attitude=True)
    with pytest.raises(ValueError, match="taylor"):
        g.solve(model, Y0, (0.0, 1.0), method="taylor")
    t = np.linspace(0.0, 10.0, 11)
    expected = reference(J, gravity(0.4, [0, 0, 1], 0.4), Y0, t)
    split = g.solve(model, Y0, (0.0, 10.0), t_eval=t, method="splitting", step=0.01)
    assert split.success, split.message
    error = np.abs(split.y - expected).max()
    # the splitting with the attitude frozen over each perturbation sub-step (step 0.01; the torque,
    # 3 n² |J| ~ 1, is slow against the free flow, which is exact): measured 5.4e-11
    assert error < 5e-10, f"splitting against SciPy: {error:.3g}"


def test_ensemble_on_two_threads_equals_single_solves():
    models = [g.Model(g.Body(J), [g.GravityGradient(0.4 + 0.1 * k)], attitude=True) for k in range(4)]
    y0s = np.array([Y0] * 4)
    runs = g.solve_ensemble(models, y0s, (0.0, 5.0), n_out=11, threads=2, rtol=1e-10, atol=1e-12)
    for model, run in zip(models, runs):
        alone = g.solve(model, Y0, (0.0, 5.0), n_out=11, rtol=1e-10, atol=1e-12)
        assert np.array_equal(run.y, alone.y)  # not batched (not affine): the same code path, bit for bit


def test_orbit_normal_must_not_be_zero():
    with pytest.raises(ValueError, match=r"orbit_normal = \[0, 0, 0\] must not be zero"):
        g.GravityGradient(0.1, orbit_normal=[0, 0, 0])
    with pytest.raises(ValueError, match="orbit rate n = -1 must be finite and positive"):
        g.GravityGradient(-1.0)


def test_libration_scene_librates_at_the_linearised_pitch_frequency():
    """The shipped scene gravity_gradient_libration: a satellite at rest in the orbit frame (LVLH:
    x along track, y minus the orbit normal, z nadir), 0.1 rad off in pitch (about y). B θ̈ =
    -3 n² (A - C) sin θ cos θ: small oscillations at n sqrt(3 (A - C)/B), lengthened by the
    amplitude as a pendulum in 2θ, by (2 θ0)²/16 = 0.25 %. The pitch rate θ' = ω_y + n is read
    from the state (not from the model's orbit-frame outputs)."""
    from gyrostat import runner
    from gyrostat import scene as scenes
    scene = scenes.load(scenes.SCENES / "gravity_gradient_libration.toml")
    solutions, _, _ = runner.solve_scene(scene, progress=False)
    (sol,) = solutions.values()
    n, (A, B, C) = 0.001, scene.runs[0].model.body.moments
    r = sol.omega[:, 1] + n
    up = np.flatnonzero((r[:-1] < 0) & (r[1:] >= 0))
    crossings = sol.t[up] - r[up] * (sol.t[up + 1] - sol.t[up]) / (r[up + 1] - r[up])
    period = np.diff(crossings).mean()
    expected = 2 * math.pi / (n * math.sqrt(3 * (A - C) / B)) * (1 + (2 * 0.1) ** 2 / 16)
    # linear interpolation of the crossings between outputs 15.7 s apart, and the next term of the
    # pendulum's series (~1e-5): measured 5.7e-6 relative; without the amplitude term it would be 2.5e-3 off
    assert abs(np.max(np.abs(sol["pitch"])) - 0.1) < 1e-6  # the promised libration, in the orbit frame
    assert np.max(np.abs(sol["roll"])) < 1e-12 and np.max(np.abs(sol["yaw"])) < 1e-12  # planar: rounding only
    assert period == pytest.approx(expected, rel=5e-5), f"period {period:.2f} s, expected {expected:.2f} s"
