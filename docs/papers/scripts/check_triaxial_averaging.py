#!/usr/bin/env python3
"""Numbers quoted in docs/papers/triaxial_averaging.md, from the pure-Python reference
tests/triaxial_reference.py (NumPy/SciPy/mpmath). Run from the repository root:
    OMP_NUM_THREADS=1 python3 docs/papers/scripts/check_triaxial_averaging.py
"""
import math
import os
import sys

os.environ.setdefault("OMP_NUM_THREADS", "1")
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "..", "..", "tests"))
import mpmath  # noqa: E402
import numpy as np  # noqa: E402
from scipy import special  # noqa: E402
from scipy.integrate import solve_ivp  # noqa: E402

import triaxial_reference as R  # noqa: E402

A = (3.0, 2.0, 1.0)
D = np.diag([0.3, 0.5, 0.7])


def mp_ref(G, T):
    with mpmath.workdps(30):
        return [float(x) for x in R.averaged_rates_closed_form_linear_damping(A, D, G, T, mp=True)]


def err(G, T, n, ref):
    q = R.averaged_rates_quadrature(A, G, T, lambda w: -D @ w, n)
    return max(abs(q[i] - ref[i]) / abs(ref[i]) for i in range(2))


print("== nodes: minimal even n with relative error < tol (double quadrature, linear damping, major side)")
print("k'^2      K       K'     pi K'/(2K)  fitted rate/node  n(1e-8) rule  n(1e-10) rule  n(1e-12) rule")
for m1 in (0.5, 1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6):
    G, T = R.invariants_at(A, 1 - m1)
    ref = mp_ref(G, T)
    K, Kp = float(special.ellipkm1(m1)), float(special.ellipk(m1))
    errs = {n: err(G, T, n, ref) for n in range(4, 400, 2)}
    row = []
    for tol in (1e-8, 1e-10, 1e-12):
        n = next((n for n, e in errs.items() if e < tol), None)
        row.append(f"{n!s:>5} {R.nodes_for(m1, tol):>5}")
    big = [n for n, e in errs.items() if 1e-10 < e < 1e-3]
    rate = -np.polyfit(big, np.log([errs[n] for n in big]), 1)[0] if len(big) > 2 else float("nan")
    print(f"{m1:7.0e} {K:7.3f} {Kp:7.4f} {math.pi * Kp / (2 * K):9.4f} {rate:12.4f}      " + "  ".join(row))

print("\n== closed form (double, Carlson) and quadrature (n = nodes_for(1e-13)) against mpmath 30 digits")
for side in ("largest", "smallest"):
    for m in (1e-6, 0.5, 1 - 1e-6):
        G, T = R.invariants_at(A, m, side=side)
        ref = mp_ref(G, T)
        cf = R.averaged_rates_closed_form_linear_damping(A, D, G, T)
        e_cf = max(abs(cf[i] - ref[i]) / abs(ref[i]) for i in range(2))
        n = R.nodes_for(R.parameters(A, G, T)["m1"], 1e-13)
        with mpmath.workdps(30):
            qm = R.averaged_rates_quadrature(A, G, T, lambda w: -np.dot(D, w), n, mp=True)
        e_qm = max(abs(float(qm[i]) - ref[i]) / abs(ref[i]) for i in range(2))
        print(f"{side:8s} k^2 = {m:<10.7g} closed(double) {e_cf:.1e}  quad(double, n={n}) {err(G, T, n, ref):.1e}"
              f"  quad(mpmath) {e_qm:.1e}")

print("\n== near the separatrix: <w_b^2>/alpha_b^2 = S1 against 1 - 1/L, L = ln(4/k')")
for m1 in (1e-2, 1e-4, 1e-8, 1e-16):
    with mpmath.workdps(40):
        m1m = mpmath.mpf(m1)
        _, S1, _ = R.sn_moments(1 - m1m, m1m, mp=True)
        L = mpmath.log(4 / mpmath.sqrt(m1m))
        print(f"k'^2 = {m1:.0e}: S1 = {float(S1):.10f}, 1 - 1/L = {float(1 - 1 / L):.10f},"
              f" (1 - S1) L = {float((1 - S1) * L):.6f}")

print("\n== averaged vs full, M = -eps diag(1,2,3) w, k^2(0) = 0.3 (major side), t = 1/eps")
d = np.array([1.0, 2.0, 3.0])
G0, T0 = R.invariants_at(A, 0.3)
w0 = R.free_motion(A, G0, T0, 0.0)
errors, epss = [], (3e-2, 1e-2, 3e-3, 1e-3, 3e-4)
for eps in epss:
    t = np.linspace(0, 1 / eps, 200)
    J = np.asarray(A)
    full = solve_ivp(lambda s, w: (np.cross(J * w, w) - eps * d * w) / J, (0, t[-1]), w0, method="DOP853",
                     rtol=1e-11, atol=1e-13, t_eval=t)
    Jw = J[:, None] * full.y
    Gf, Tf = np.sqrt(np.sum(Jw * Jw, axis=0)), 0.5 * np.sum(Jw * full.y, axis=0)
    avg = solve_ivp(lambda s, y: R.averaged_rates_closed_form_linear_damping(A, eps * np.diag(d), math.sqrt(y[0]),
                                                                             y[1]),
                    (0, t[-1]), (G0 * G0, T0), method="DOP853", rtol=1e-11, atol=1e-15, t_eval=t)
    e = max(np.max(np.abs(np.sqrt(avg.y[0]) - Gf) / Gf), np.max(np.abs(avg.y[1] - Tf) / Tf))
    k2_end = R.parameters(A, math.sqrt(avg.y[0][-1]), avg.y[1][-1])["m"]
    errors.append(e)
    print(f"eps = {eps:.0e}: max rel error of |G|, T = {e:.3e}, error/eps = {e / eps:.3f}, k^2(end) = {k2_end:.4f}")
print("fitted slope:", np.polyfit(np.log(epss), np.log(errors), 1)[0])
