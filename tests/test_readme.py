"""Every Python snippet of the README runs as written (each block in a fresh namespace), and the
results of the first three are checked against references written in the tests."""

import functools
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parent.parent / "README.md"
BLOCKS = re.findall(r"```python\n(.*?)```", README.read_text(), flags=re.S)


def test_readme_has_snippets():
    assert len(BLOCKS) >= 3


@pytest.mark.parametrize("index", range(len(BLOCKS)))
def test_readme_snippet_runs(index):
    _namespace(index)


@functools.lru_cache(maxsize=None)  # each block runs once; its results are checked below
def _namespace(index):
    namespace = {"__name__": "readme"}
    exec(compile(BLOCKS[index], f"README.md python block {index}", "exec"), namespace)
    return namespace


def test_readme_results_against_references():
    """The README's results, not only that its snippets run: block 0's forced gyrostat (ω and q)
    against SciPy on Euler's and the quaternion's equations (tests/references.py) and its closed
    form against the test's elliptic functions; block 2's full model against SciPy with the cavity
    torque written in tests/references.py; block 3's top against (3.3), r = r0 exp(−(ε/C)∫b dt),
    and the servo torque's exact integrals |G| and ω·Jω (paper 004 (5), (6))."""
    import numpy as np

    from references import cavity_torque, euler_poinsot, scipy_reference

    ns = _namespace(0)
    sol = ns["sol"]
    J, k, M, D = np.array([1.0, 2.0, 2.5]), np.array([0.0, 0.0, 0.1]), np.array([0, 0, 0.05]), np.diag([0.05, 0.04, 0.03])
    t = sol.t[::50]
    ref = scipy_reference(J, k, lambda s, w: M - D @ w, sol.y[0], t)
    # rtol 1e-10 over t = 200: measured 4.5e-10; 10× it (q: same sign branch, both continuous)
    assert np.max(np.abs(sol.y[::50] - ref)) < 4.5e-9, np.max(np.abs(sol.y[::50] - ref))
    exact = ns["exact"]
    # the closed form (GSL) against SciPy's ellipj: rounding of the phase over 100 s, measured 5.0e-14
    assert np.max(np.abs(exact.y - euler_poinsot([1, 2, 3], [1.0, 0.5, -0.3], exact.t))) < 5e-13

    ns = _namespace(2)  # block 1: user and attitude torques (tests/test_custom_torque.py, test_attitude_torques.py)
    full = ns["full"]
    D0, D1 = np.diag([0.02, 0.02, 0.01]), np.diag([1e-3, 1e-3, 5e-4])
    kappa = 1260 * 0.48 / 1000
    ref = scipy_reference([8.0, 8.0, 4.0], [0, 0, 0],
                          lambda s, w: cavity_torque(w, [8.0, 8.0, 4.0], kappa) + [0, 0, -0.01] - (D0 + D1 * s) @ w,
                          [1.0, 0.0, 1.0], full.t)
    # default rtol (1e-8) over t = 60: measured 8.5e-9; 10× it
    assert np.max(np.abs(full.y - ref)) < 8.5e-8, np.max(np.abs(full.y - ref))

    ns = _namespace(3)
    full, eps = ns["full"], 0.01
    tau = eps * full.t
    r_exact = 1.7 * np.exp(-(tau + tau**2 / 2) / 1.0)  # (3.3), b = 1 + τ, C = 1
    # r is decoupled and its equation linear: rounding only, measured 6.7e-16; 10× it
    assert np.max(np.abs(full.y[:, 2] - r_exact)) < 7e-15, np.max(np.abs(full.y[:, 2] - r_exact))
    servo = ns["sol"]
    Jo, ko = np.array([2.0, 3.0, 4.0]), np.array([0.3, -0.2, 0.5])
    G = np.linalg.norm(servo.omega * Jo + ko, axis=1)
    h = np.einsum("ni,i,ni->n", servo.omega, Jo, servo.omega)
    # exact integrals of the servo torque: the integration error at rtol 1e-10 over t = 60,
    # measured 1.4e-10 and 2.5e-10 (relative); 10× it
    assert np.max(np.abs(G / G[0] - 1)) < 1.4e-9 and np.max(np.abs(h / h[0] - 1)) < 2.5e-9, (np.ptp(G), np.ptp(h))


def test_readme_torques_ladder_and_sweep_against_references():
    """The README's other blocks, against references: block 1's user drag and attitude torques
    against their formulas written here; block 4's averaged rung against a SciPy run of the (a, r)
    system written here (paper 000's cavity averaged over the phase, and the axial torque); block 5's sweep: a grid member
    and a dispersion member equal to their own solves (the sweep's promise)."""
    import math

    import numpy as np
    from scipy.integrate import solve_ivp

    import gyrostat as g
    from references import cavity_torque

    ns = _namespace(1)
    w, q = np.array([0.3, -0.2, 0.5]), np.array([0.9, 0.1, -0.3, 0.2]) / np.linalg.norm([0.9, 0.1, -0.3, 0.2])
    M_drag = ns["model"].torques[0](0.0, w, [1.0, 2.0, 2.5])
    assert np.allclose(M_drag, -0.05 * np.linalg.norm(w) * w, rtol=0, atol=1e-16)  # the same numbers
    wq, xq, yq, zq = q
    R = np.array([[1 - 2 * (yq * yq + zq * zq), 2 * (xq * yq - wq * zq), 2 * (xq * zq + wq * yq)],
                  [2 * (xq * yq + wq * zq), 1 - 2 * (xq * xq + zq * zq), 2 * (yq * zq - wq * xq)],
                  [2 * (xq * zq - wq * yq), 2 * (yq * zq + wq * xq), 1 - 2 * (xq * xq + yq * yq)]])
    gravity, magnetic, inertial = ns["orbit"].torques
    c = R.T @ np.array([math.cos(0.001 * 5.0), math.sin(0.001 * 5.0), 0.0])
    J = np.array([1.0, 2.0, 2.5])
    # 3 n² ĉ × Jĉ, m × Rᵀ B, Rᵀ M_I written here: the same formulas in another order, rounding only
    assert np.allclose(gravity(5.0, w, J, quaternion=q), 3e-6 * np.cross(c, J * c), rtol=1e-13, atol=1e-20)
    assert np.allclose(magnetic(0.0, w, J, quaternion=q), np.cross([0, 0, 1], R.T @ [2e-5, 0, 0]), rtol=1e-13, atol=1e-20)
    assert np.allclose(inertial(0.0, w, J, quaternion=q), R.T @ [0, 0, 1e-4], rtol=1e-13, atol=1e-20)
    # the tilted body: its principal axes diagonalise the tensor given (rounding), and the run's
    # gravity-gradient motion against Euler's equations with the full tensor written here
    tilted, I = ns["tilted"], np.array([[2.0, 0.1, 0.0], [0.1, 1.5, 0.0], [0.0, 0.0, 1.2]])
    P = tilted.principal_axes
    assert np.allclose(P @ np.diag(tilted.moments) @ P.T, I, rtol=0, atol=2e-15)  # a few ulps of 2

    def tensor_rhs(t, y):
        wv, (qw, qx, qy, qz) = y[:3], y[3:]
        Rq = np.array([[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)],
                       [2 * (qx * qy + qw * qz), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qw * qx)],
                       [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)]])
        cb = Rq.T @ np.array([math.cos(0.001 * t), math.sin(0.001 * t), 0.0])
        M = 3e-6 * np.cross(cb, I @ cb)
        p_, q_, r_ = wv
        dq = 0.5 * np.array([-(qx * p_ + qy * q_ + qz * r_), qw * p_ + qy * r_ - qz * q_,
                             qw * q_ + qz * p_ - qx * r_, qw * r_ + qx * q_ - qy * p_])
        return np.concatenate([np.linalg.solve(I, M - np.cross(wv, I @ wv)), dq])

    ref = solve_ivp(tensor_rhs, (0, 6000), [0, 0, 0.01, 1, 0, 0, 0], method="DOP853", rtol=1e-11, atol=1e-14)
    # the README's run at the default rtol 1e-8 over ~10 turns: 1e-7 relative to |ω| = 0.01
    assert np.abs(ns["sat"].y[-1, :3] - ref.y[:3, -1]).max() < 1e-9, ns["sat"].y[-1, :3] - ref.y[:3, -1]

    ns = _namespace(4)
    (averaged,) = [s for name, s in ns["solutions"].items() if s.state_names == ("a", "r")] or [None]
    assert averaged is not None, list(ns["solutions"])
    # the averaged (a, r) system written here: the cavity torque (tests/references.py) averaged over
    # p = a cos φ, q = a sin φ by the trapezoidal rule (exact: a trigonometric polynomial), plus M3
    phases = np.linspace(0.0, 2 * np.pi, 16, endpoint=False)
    moments, kappa = [8.0, 8.0, 4.0], 1260.0 * 0.48 / 1e6

    def slow(t, y):
        a, r = y
        M = np.array([cavity_torque([a * np.cos(f), a * np.sin(f), r], moments, kappa) for f in phases])
        along_a = np.mean(M[:, 0] * np.cos(phases) + M[:, 1] * np.sin(phases))
        return [along_a / 8.0, (np.mean(M[:, 2]) - 1e-5) / 4.0]

    ref = solve_ivp(slow, (0.0, averaged.t[-1]), [1.0, 1.0], t_eval=averaged.t, rtol=1e-11, atol=1e-13).y.T
    error = np.max(np.abs(averaged.y - ref))
    # the ladder's run at rtol 1e-10 against SciPy's at 1e-11: measured 4.6e-11
    assert error < 4e-10, error

    ns = _namespace(5)
    grid, mc, scene = ns["grid"], ns["mc"], ns["scene"]
    member = g.sweeps.Plan(scene, {"initial.omega[0]": g.Normal(1.0, 0.1),
                                   "torques[1].matrix[0][0]": g.LogUniform(1e-3, 1e-1)}, samples=200, seed=7).scene(42)
    sol = g.solve(member.runs[0].model, member.runs[0].y0, member.runs[0].t_span, **member.runs[0].options)
    # a dispersion member equals its own solve: the same model, options and code path
    assert mc["max_angular_momentum_norm"].values[42] == np.max(sol["angular_momentum_norm"])
    assert grid.sizes["body.moments[0]"] == 5 and grid.sizes["torques[0].moment[2]"] == 2


def test_readme_triaxial_averaged_block_against_scipy():
    """The last block's triaxial averaged run (linear damping and a quadratic drag written as a
    CustomTorque) against SciPy's DOP853 on Euler's equations with the same torques written here:
    |G| and T at t = 1000 agree to O(ε), ε ~ 1e-3 here: 5e-3 relative (measured 1e-3 and below)."""
    import numpy as np
    from scipy.integrate import solve_ivp

    ns = _namespace(len(BLOCKS) - 1)
    sol = ns["sol"]
    J, D = np.array([3.0, 2.0, 1.0]), 1e-3 * np.array([1.0, 2.0, 3.0])

    def euler(t, w):
        M = -D * w - 1e-3 * np.linalg.norm(w) * w
        return (np.cross(J * w, w) + M) / J

    ref = solve_ivp(euler, (0.0, 1000.0), [1.0, 0.2, 0.1], method="DOP853", rtol=1e-10, atol=1e-12).y[:, -1]
    G, T = np.linalg.norm(J * ref), 0.5 * ref @ (J * ref)
    assert abs(sol["angular_momentum_norm"][-1] - G) <= 5e-3 * G
    assert abs(sol["kinetic_energy"][-1] - T) <= 5e-3 * T
