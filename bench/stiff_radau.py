"""The stiff explicit moving-mass model (paper 001): gyrostat's cvode_bdf (exact Jacobian) against
SciPy's Radau at equal error, with the Newton statistics.

Run:  .venv/bin/python bench/stiff_radau.py      (or: bash run.sh bench)

The case: body moments (4, 4, 2) with the mass at rest, m = 1 at ρ = 1 on a spring Ω = 100 with a
damper λ = 2e4, ω0 = (1, 0, 1), the mass on its quasi-static motion, t = 0..20. Its (u, v) block
has eigenvalues ≈ −λ/2 ± √(λ²/4 − Ω²) ≈ −0.5 and −2e4: stiff. SciPy's Radau integrates the same
equations written out here in NumPy (independently of the C++ code), with its own finite-difference
Jacobian, as a user would call it. The reference is Radau at rtol 1e-12 (independent code). Each
method runs over a range of tolerances; its error at t = 20 against the reference and its time
(best of 3) give a work-precision curve, and the ratio is read at equal error (log-log
interpolation of each curve at the errors both reach).
"""

from __future__ import annotations

import time

import numpy as np
from scipy.integrate import solve_ivp

import gyrostat as g

MOMENTS = np.array([4.0, 4.0, 2.0])
MASS, ARM, OMEGA, LAMBDA = 1.0, 1.0, 100.0, 2e4
T1 = 20.0


def rhs(t, y):
    """Paper 001's explicit model (docs/papers/001_moving_mass.md §C), written out again:
    d = ρ e3 + u, s = ω × d + v, K = J_B ω + μ d × s, R = −2 ω × v − ω × (ω × d) − Ω² u − λ v,
    J_B ω̇ = −ω × K − μ [2 (d·v) ω − v (d·ω) − d (v·ω)] − μ d × R,  u̇ = v,  v̇ = R − ω̇ × d,
    with J_B = diag(A1 − μρ², A2 − μρ², A3)."""
    w, u, v = y[:3], y[3:6], y[6:]
    carrier = MOMENTS - np.array([MASS * ARM**2, MASS * ARM**2, 0.0])
    d = np.array([0.0, 0.0, ARM]) + u
    s = np.cross(w, d) + v
    K = carrier * w + MASS * np.cross(d, s)
    R = -2 * np.cross(w, v) - np.cross(w, np.cross(w, d)) - OMEGA**2 * u - LAMBDA * v
    f = -np.cross(w, K) - MASS * (2 * d.dot(v) * w - v * d.dot(w) - d * v.dot(w)) - MASS * np.cross(d, R)
    a = f / carrier
    return np.concatenate([a, v, R - np.cross(a, d)])


def timed(call, repeats=3):
    best, result = float("inf"), None
    for _ in range(repeats):
        started = time.perf_counter()
        result = call()
        best = min(best, time.perf_counter() - started)
    return best, result


def at_equal_error(errors_a, times_a, errors_b, times_b):
    """Time ratio b/a at the errors both curves cover (log-log interpolation), as (error, ratio)."""
    la, lb = np.log(errors_a), np.log(errors_b)
    low, high = max(la.min(), lb.min()), min(la.max(), lb.max())
    if low > high:
        return []
    rows = []
    for level in np.linspace(low, high, 4):
        ta = np.exp(np.interp(level, la[np.argsort(la)], np.log(times_a)[np.argsort(la)]))
        tb = np.exp(np.interp(level, lb[np.argsort(lb)], np.log(times_b)[np.argsort(lb)]))
        rows.append((float(np.exp(level)), tb / ta))
    return rows


def main() -> None:
    model = g.MovingMassModel(g.Body(list(MOMENTS)), mass=MASS, arm=ARM, frequency=OMEGA, damping=LAMBDA)
    y0 = model.quasi_static_state([1.0, 0.0, 1.0])
    reference = solve_ivp(rhs, (0.0, T1), y0, method="Radau", rtol=1e-12, atol=1e-14).y[:, -1]
    print("Stiff explicit moving mass (paper 001: Omega = 100, lambda = 2e4, t = 0..20); error at t = 20 "
          "against Radau at rtol 1e-12")
    print(f"{'method':12s} {'rtol':>8s} {'error':>10s} {'time [ms]':>10s} {'steps':>7s} {'f evals':>8s} "
          f"{'J evals':>8s} {'Newton fails':>12s}")
    curves = {}
    for name in ("cvode_bdf", "Radau"):
        errors, times = [], []
        for rtol in (1e-5, 1e-6, 1e-7, 1e-8, 1e-9):
            atol = rtol * 1e-2
            if name == "cvode_bdf":
                seconds, sol = timed(lambda: g.solve(model, y0, (0.0, T1), method="cvode_bdf", rtol=rtol, atol=atol,
                                                      n_out=2, progress=False, error_estimate=False))
                error = np.max(np.abs(sol.y[-1] - reference))
                s = sol.stats
                row = (s["steps"], s["rhs_evals"], s["jacobian_evals"], s["nonlinear_conv_failures"])
            else:
                seconds, sol = timed(lambda: solve_ivp(rhs, (0.0, T1), y0, method="Radau", rtol=rtol, atol=atol),
                                     repeats=1)
                error = np.max(np.abs(sol.y[:, -1] - reference))
                row = (len(sol.t) - 1, sol.nfev, sol.njev, "-")
            errors.append(error)
            times.append(seconds)
            print(f"{name:12s} {rtol:8.0e} {error:10.2e} {seconds * 1e3:10.2f} {row[0]:7d} {row[1]:8d} {row[2]:8d} "
                  f"{row[3]!s:>12s}")
        curves[name] = (np.array(errors), np.array(times))
    print("Radau time / cvode_bdf time at equal error (target: at least 50):")
    for error, ratio in at_equal_error(*curves["cvode_bdf"], *curves["Radau"]):
        print(f"  error {error:8.2e}: {ratio:7.1f}x")


if __name__ == "__main__":
    main()
