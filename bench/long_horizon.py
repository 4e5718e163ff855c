"""Long horizons: error against t up to 1e7 for the exact free flow / splitting, Taylor and DOP853.

    PYTHONPATH=python python bench/long_horizon.py [--out bench/results] [--quick]
                                                   [--only torque-free|damped|forced|cavity ...]

Four problems, body I = (2, 3, 4), ω0 = (0.4, 0.9, −0.3), q0 = (0.8, 0.1, −0.5, 0.3)/|·|:

1. torque-free with attitude, t ≤ 1e9 for the exact flow (1e7 for the integrators). Reference:
   the closed form evaluated independently here in mpmath at 32 digits (Jacobi functions, Π by
   mpmath.ellippi; the formulas of cpp/include/gyrostat/model/torque_free.hpp re-derived in the
   bench; the phase ν t keeps 32 − 9 = 23 digits at t = 1e9), itself checked at t = 20 against an
   mpmath Taylor-series integration of Euler's equations and q̇ (32 digits).
2. weakly damped, ε = 1e-4: linear damping D = ε [[1, .1, 0], [0, 2, 0], [0, 0, 1.5]] (affine:
   Taylor applies). Reference: SciPy's DOP853 at rtol 1e-13 with the right-hand side written here
   (its own error, measured against rtol 1e-12, is printed as the reference's floor).
3. forced spin, ε = 1e-4: the same damping against a constant torque D ω*, ω* = (0, 0, 1): the
   body settles into a steady spin and keeps turning (Taylor's steps do not grow as in 2).
   Work-precision at t = 1e5 (1e4 with --quick) for splitting (orders 4 and 6, several steps),
   Taylor and DOP853; reference SciPy's DOP853 at rtol 1e-13, right-hand side written here.
4. the viscous cavity, κ = ε = 1e-4 (|G| conserved, energy dissipated): the drift of |G| over
   t = 1e6 (1e5 with --quick), splitting against DOP853.

Errors: max over ω (relative to |ω0|) and the quaternion (q and −q are one rotation). Prints the target ratios of issue 13 (measured in this one run) and writes
bench/results/long_horizon_*.svg and .png.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

import gyrostat as g

J = np.array([2.0, 3.0, 4.0])
W0 = np.array([0.4, 0.9, -0.3])
Q0 = np.array([0.8, 0.1, -0.5, 0.3]) / np.linalg.norm([0.8, 0.1, -0.5, 0.3])
EPS = 1e-4
D = EPS * np.array([[1.0, 0.1, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 1.5]])


# ------------------------------------------------------------------ references written here

def mp_closed_form(times, dps=32):
    """ω(t), q(t) of the free body in mpmath (an independent evaluation of the closed form)."""
    import mpmath as mp

    mp.mp.dps = dps
    Jm = [mp.mpf(x) for x in J]
    w0 = [mp.mpf(x) for x in W0]
    G2 = sum((Jm[i] * w0[i]) ** 2 for i in range(3))
    T2 = sum(Jm[i] * w0[i] ** 2 for i in range(3))
    G = mp.sqrt(G2)
    # ordering: G² ≥ 2TB → the polhode encircles the largest axis (index 2), else the smallest (0)
    largest = G2 - T2 * Jm[1] >= 0
    ax = (0, 1, 2) if largest else (2, 1, 0)
    s = 1 if largest else -1  # (2, 1, 0) is odd: e2' = −e_1 keeps the frame right-handed
    A, B, C = (Jm[i] for i in ax)
    w1, w2, w3 = (w0[i] for i in ax)
    w2 = s * w2
    across, along = T2 * C - G2, G2 - T2 * A
    a = mp.sqrt(across / (A * (C - A)))
    b = mp.sqrt(across / (B * (C - B)))
    c = mp.sqrt(along / (C * (C - A)))
    m = (B - A) * across / ((C - B) * along)
    sign3 = 1 if w3 >= 0 else -1
    # Euler in the right-handed primed frame: A ω̇1 = (B − C) ω2 ω3 → with ω1 = a cn, ω2 = s' b sn:
    # ν from dω1/dt at u0 compared with −a sn dn ν
    K = mp.ellipk(m)
    phi0 = mp.atan2(w2 / b, w1 / a)
    u0 = mp.ellipf(phi0, m)
    # ν: (−a sn dn) ν = (B − C) ω2 ω3 / A with ω2 = b sn, ω3 = sign3 c dn
    nu = -(B - C) * b * sign3 * c / (A * a)
    N = -C * (B - A) / (A * (C - B))

    def am(u):
        j = mp.nint(u / (2 * K))
        r = u - 2 * j * K
        sn, cn = mp.ellipfun("sn", r, m=m), mp.ellipfun("cn", r, m=m)
        return j * mp.pi + mp.atan2(sn, cn)

    def Pi(u):
        return mp.ellippi(N, am(u), m)

    def qmul(p, q):
        return [p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
                p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
                p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
                p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]]

    def qx(x):
        return [mp.cos(x / 2), mp.sin(x / 2), 0, 0]

    def qz(x):
        return [mp.cos(x / 2), 0, 0, mp.sin(x / 2)]

    def state(u):
        sn, cn, dn = (mp.ellipfun(f, u, m=m) for f in ("sn", "cn", "dn"))
        wp = [a * cn, b * sn, sign3 * c * dn]        # primed components (right-handed frame)
        gp = [Jp * x / G for Jp, x in zip((A, B, C), wp)]
        theta = mp.atan2(mp.sqrt(gp[0] ** 2 + gp[1] ** 2), gp[2])
        # ψ continuous: atan2(g1, g2) unwrapped along am(u)
        al = am(u)
        psi = mp.atan2(A * a * mp.cos(al), B * b * mp.sin(al))
        j = mp.floor((al + mp.pi / 2) / mp.pi)
        psi = mp.atan2(A * a * mp.cos(al - j * mp.pi), B * b * mp.sin(al - j * mp.pi)) - j * mp.pi
        return wp, theta, psi

    # body index of each primed axis and the sign of the axis
    def to_body(wp):
        w = [0, 0, 0]
        w[ax[0]], w[ax[1]], w[ax[2]] = wp[0], s * wp[1], wp[2]
        return w

    # q_S of the signed permutation x' = S x_body
    S = mp.matrix(3, 3)
    S[0, ax[0]], S[1, ax[1]], S[2, ax[2]] = 1, s, 1
    tr = S[0, 0] + S[1, 1] + S[2, 2]
    qs = _quat_from_matrix(mp, S, tr)
    _, th0, ps0 = state(u0)
    q0 = [mp.mpf(x) for x in Q0]
    conj = lambda q: [q[0], -q[1], -q[2], -q[3]]  # noqa: E731
    q_in = qmul(qmul(q0, conj(qs)), conj(qmul(qx(th0), qz(ps0))))
    Pi0 = Pi(u0)
    out = []
    for t in times:
        t = mp.mpf(t)
        u = nu * t + u0
        wp, th, ps = state(u)
        dphi = G / C * t + G * (C - A) / (C * A * nu) * (Pi(u) - Pi0)
        q = qmul(qmul(qmul(qmul(q_in, qz(dphi)), qx(th)), qz(ps)), qs)
        out.append([float(x) for x in to_body(wp)] + [float(x) for x in q])
    return np.array(out)


def _quat_from_matrix(mp, R, tr):
    w = mp.sqrt(max(1 + tr, 0)) / 2
    if w > mp.mpf("0.1"):
        return [w, (R[2, 1] - R[1, 2]) / (4 * w), (R[0, 2] - R[2, 0]) / (4 * w), (R[1, 0] - R[0, 1]) / (4 * w)]
    # largest diagonal
    i = max(range(3), key=lambda k: R[k, k])
    j, k = (i + 1) % 3, (i + 2) % 3
    x = mp.sqrt(1 + R[i, i] - R[j, j] - R[k, k]) / 2
    q = [0, 0, 0, 0]
    q[0] = (R[k, j] - R[j, k]) / (4 * x)
    q[1 + i] = x
    q[1 + j] = (R[j, i] + R[i, j]) / (4 * x)
    q[1 + k] = (R[k, i] + R[i, k]) / (4 * x)
    return q


def mp_taylor_check(t_end=20.0, dps=32, h=0.1, order=26):
    """An mpmath Taylor-series integration of Euler's equations and q̇ (40 digits): the check of
    the mpmath closed form above at t ≤ t_end."""
    import mpmath as mp

    mp.mp.dps = dps
    Jm = [mp.mpf(x) for x in J]
    y = [mp.mpf(x) for x in W0] + [mp.mpf(x) for x in Q0]

    def series(y):
        w = [[y[0]], [y[1]], [y[2]]]
        q = [[y[3]], [y[4]], [y[5]], [y[6]]]
        for n in range(order):
            def conv(a, b):
                return sum(a[i] * b[n - i] for i in range(n + 1))
            dw = [(Jm[1] - Jm[2]) * conv(w[1], w[2]) / Jm[0], (Jm[2] - Jm[0]) * conv(w[2], w[0]) / Jm[1],
                  (Jm[0] - Jm[1]) * conv(w[0], w[1]) / Jm[2]]
            p, qq, r = w
            qw, qx_, qy, qz_ = q
            dq = [-(conv(qx_, p) + conv(qy, qq) + conv(qz_, r)) / 2, (conv(qw, p) + conv(qy, r) - conv(qz_, qq)) / 2,
                  (conv(qw, qq) + conv(qz_, p) - conv(qx_, r)) / 2, (conv(qw, r) + conv(qx_, qq) - conv(qy, p)) / 2]
            for i in range(3):
                w[i].append(dw[i] / (n + 1))
            for i in range(4):
                q[i].append(dq[i] / (n + 1))
        return w + q

    hm = mp.mpf(h)
    for _ in range(int(round(t_end / h))):
        c = series(y)
        y = [sum(ci[k] * hm ** k for k in range(len(ci))) for ci in c]
    return np.array([float(x) for x in y])


def scipy_reference(times, rtol):
    from scipy.integrate import solve_ivp

    def rhs(t, y):
        w, q = y[:3], y[3:]
        dw = (-(D @ w) - np.cross(w, J * w)) / J
        qw, qx, qy, qz = q
        p, qq, r = w
        dq = 0.5 * np.array([-qx * p - qy * qq - qz * r, qw * p + qy * r - qz * qq, qw * qq + qz * p - qx * r,
                             qw * r + qx * qq - qy * p])
        return np.concatenate([dw, dq])

    sol = solve_ivp(rhs, (0.0, times[-1]), np.concatenate([W0, Q0]), method="DOP853", t_eval=times, rtol=rtol,
                    atol=1e-300)
    y = sol.y.T
    y[:, 3:] /= np.linalg.norm(y[:, 3:], axis=1)[:, None]
    return y


# ------------------------------------------------------------------ errors, runs

def errors(y, ref):
    """max(|ω − ω_ref| / |ω0|, |q − q_ref| with the sign of q aligned) at each time (ω against its
    initial size: in problem 2 ω decays by e^{-50} by t = 1e6, and a relative error of a decayed ω
    says nothing about the motion; the attitude, frozen once ω has decayed, keeps its error)."""
    w_err = np.linalg.norm(y[:, :3] - ref[:, :3], axis=1) / np.linalg.norm(W0)
    q = y[:, 3:] * np.sign(np.sum(y[:, 3:] * ref[:, 3:], axis=1))[:, None]
    q_err = np.linalg.norm(q - ref[:, 3:], axis=1)
    return np.maximum(w_err, q_err)


def run(model, times, **options):
    start = time.perf_counter()
    sol = g.solve(model, np.concatenate([W0, Q0]), (0.0, times[-1]), t_eval=times, max_steps=10**9, error_estimate=False, **options)
    elapsed = time.perf_counter() - start
    n = len(sol.t)
    return sol.y, elapsed, sol.status, n


def _axes():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(figsize=(6.4, 4.2))


def _finish(fig, ax, path: Path, title: str, xlabel: str, ylabel: str, floor=None):
    """Labels, the reference's floor, the legend; writes path.svg and path.png."""
    import matplotlib.pyplot as plt

    if floor is not None:
        ax.axhline(floor, color="grey", ls=":", lw=1, label="reference's own error")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    for suffix in (".svg", ".png"):
        fig.savefig(path.with_suffix(suffix), dpi=80)
    plt.close(fig)


def work_precision_chart(path: Path, rows, floor):
    """Error against time, one line per method (rows: (method, setting, error, seconds))."""
    fig, ax = _axes()
    for method in dict.fromkeys(r[0] for r in rows):
        mine = [r for r in rows if r[0] == method]
        ax.loglog([r[3] for r in mine], [max(r[2], 1e-17) for r in mine], marker="o", ms=4, label=method)
        for r in mine:
            ax.annotate(r[1], (r[3], max(r[2], 1e-17)), fontsize=6, xytext=(3, 3), textcoords="offset points")
    _finish(fig, ax, path, f"forced spin (ε = {EPS:g}), I = (2, 3, 4), with attitude: work-precision",
            "time [s] (one solve, Python included)", "error at the horizon (|Δω|/|ω0|, |Δq|)", floor)


def chart(path: Path, title: str, curves: dict, floor=None, ylabel="error (|Δω|/|ω0|, |Δq|)"):
    fig, ax = _axes()
    for label, (t, e) in curves.items():
        ax.loglog(t[: len(e)], np.maximum(e, 1e-17), marker="o", ms=3, label=label)
    _finish(fig, ax, path, title, "t", ylabel, floor)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default="bench/results")
    parser.add_argument("--quick", action="store_true", help="horizons to 1e5 only (a smoke run)")
    parser.add_argument("--only", nargs="+", choices=PROBLEMS, default=list(PROBLEMS),
                        help="run these problems only (all by default; 'damped' takes minutes)")
    parser.add_argument("--torque-free-only", action="store_true", help="the same as --only torque-free")
    args = parser.parse_args(argv)
    chosen = {"torque-free"} if args.torque_free_only else set(args.only)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    horizon = 1e5 if args.quick else 1e7
    far = 1e5 if args.quick else 1e9  # the exact flow's horizon (its cost does not depend on t)

    def grid(end):
        return np.concatenate([[0.0], np.logspace(0, math.log10(end), int(2 * math.log10(end)) + 1)])

    times, times_far = grid(horizon), grid(far)
    print(f"# {' '.join(['python'] + sys.argv)}")

    if "torque-free" in chosen:
        torque_free(out, times, times_far, horizon, far)
    if "damped" in chosen:
        damped(out, times, horizon)
    if "forced" in chosen:
        rows, floor = forced_spin(1e4 if args.quick else 1e5)
        work_precision_chart(out / "long_horizon_forced_spin", rows, floor)
        taylor = [r for r in rows if r[0] == "taylor" and r[1] == "rtol 1e-14"][0]
        best = min((r for r in rows if r[0].startswith("splitting")), key=lambda r: r[2])
        print(f"TARGET forced spin: splitting's smallest error {best[2]:.2e} ({best[0]}, {best[1]}, {best[3]:.3f} s) "
              f"vs taylor rtol 1e-14 {taylor[2]:.2e} (bounded by the reference's {floor:.1e}) in {taylor[3]:.3f} s: "
              f"time ratio {best[3] / taylor[3]:.1f} (target <= 0.33) at >= {best[2] / taylor[2]:.0f}x the error (target <= 1)")
    if "cavity" in chosen:
        drift = cavity_G_drift(1e5 if args.quick else 1e6)
        chart(out / "long_horizon_cavity_G", f"viscous cavity (κ = ε = {EPS:g}): relative drift of |G|", drift,
              ylabel="|ΔG|/G (zero drawn at 1e-17)")
        print("TARGET cavity: no secular drift of |G| under splitting: max |ΔG|/G "
              f"{np.max(drift['splitting order 4, h = 0.5'][1]):.1e} (DOP853 rtol 1e-12: "
              f"{np.max(drift['dop853 rtol 1e-12'][1]):.1e})")


PROBLEMS = ("torque-free", "damped", "forced", "cavity")


def torque_free(out: Path, times, times_far, horizon: float, far: float):
    """Problem 1: the torque-free body, the exact flow against Taylor and DOP853."""
    check_t = 20.0
    ref_check = mp_taylor_check(check_t)
    ref_far = mp_closed_form(np.concatenate([times_far, [check_t]]))
    agreement = errors(ref_far[-1:], ref_check[None, :])[0]
    ref_far = ref_far[:-1]
    ref = ref_far[: len(times)]
    print(f"torque-free reference: mpmath closed form vs mpmath Taylor integration at t = {check_t:g}: {agreement:.1e}")
    curves = {}
    free = g.TorqueFreeModel(g.Body(J), attitude=True)
    full = g.Model(g.Body(J), attitude=True)
    y, el, status, n = run(free, times_far)
    e_far = errors(y, ref_far)
    e_exact = e_far[: len(times)]
    curves[f"exact flow ({el * 1e3:.2f} ms)"] = (times_far, e_far)
    # cost independent of t: one evaluation at t = 1e3 and at the horizon
    per = {}
    for t_end in (1e3, horizon):
        start = time.perf_counter()
        for _ in range(200):
            g.solve(free, np.concatenate([W0, Q0]), (0.0, t_end), t_eval=[t_end], error_estimate=False)
        per[t_end] = (time.perf_counter() - start) / 200
    # and per output, the flow built once: 20000 outputs just after t = 1e3 and after the horizon
    per_output = {}
    for t_end in (1e3, horizon):
        t_out = t_end + 1e-3 * np.arange(20000)
        start = time.perf_counter()
        g.solve(free, np.concatenate([W0, Q0]), (0.0, t_out[-1]), t_eval=t_out, error_estimate=False)
        per_output[t_end] = (time.perf_counter() - start) / len(t_out)
    for rtol in (1e-12, 1e-14):
        y, el, status, n = run(full, times, method="taylor", rtol=rtol, atol=1e-16)
        curves[f"taylor rtol {rtol:g} ({el:.2f} s)"] = (times, errors(y, ref[:n]))
    y, el, status, n = run(full, times, method="dop853", rtol=1e-12, atol=1e-16)
    curves[f"dop853 rtol 1e-12 ({el:.2f} s)"] = (times, errors(y, ref[:n]))
    chart(out / "long_horizon_torque_free", "torque-free body with attitude, I = (2, 3, 4)", curves, agreement)
    for label, (tc, e) in curves.items():
        print(f"  {label:34s} max error {np.max(e):.2e}   at t = {tc[len(e) - 1]:.0e}: {e[-1]:.2e}")
    print(f"TARGET torque-free: max error of the exact flow over t <= {horizon:g}: {np.max(e_exact):.2e} "
          f"(target 1e-12); cost of one evaluation at t = 1e3: {per[1e3] * 1e6:.1f} us, at t = {horizon:g}: "
          f"{per[horizon] * 1e6:.1f} us (ratio {per[horizon] / per[1e3]:.2f}; one solve each, Python included); "
          f"per output: {per_output[1e3] * 1e6:.2f} us vs {per_output[horizon] * 1e6:.2f} us "
          f"(ratio {per_output[horizon] / per_output[1e3]:.2f})")
    print(f"  exact flow beyond: max error over t <= {far:g}: {np.max(e_far):.2e}; "
          + ", ".join(f"t = {t:.0e}: {e:.1e}" for t, e in zip(times_far, e_far) if t > horizon))


def damped(out: Path, times, horizon: float):
    """Problem 2: weakly damped (linear damping, ε = 1e-4); ω decays by e^{-50} over 1e6."""
    damped = g.Model(g.Body(J), [g.LinearDamping(D)], attitude=True)
    t_ref = times[times <= min(horizon, 1e7)]
    ref2 = scipy_reference(t_ref, 1e-13)
    floor = np.max(errors(scipy_reference(t_ref, 1e-12), ref2))
    print(f"damped reference: SciPy DOP853 rtol 1e-13; |rtol 1e-12 − rtol 1e-13| = {floor:.1e}")
    curves = {}
    results = {}
    for label, opts in (("splitting order 4, h = 2", dict(method="splitting", step=2.0, splitting_order=4)),
                        ("splitting order 6, h = 4", dict(method="splitting", step=4.0, splitting_order=6)),
                        ("taylor rtol 1e-14", dict(method="taylor", rtol=1e-14, atol=1e-300)),
                        ("taylor rtol 1e-12", dict(method="taylor", rtol=1e-12, atol=1e-300)),
                        ("dop853 rtol 1e-12", dict(method="dop853", rtol=1e-12, atol=1e-300))):
        y, el, status, n = run(damped, t_ref, **opts)
        e = errors(y, ref2[:n])
        results[label] = (e, el)
        curves[f"{label} ({el:.2f} s)"] = (t_ref, e)
        print(f"  {label:34s} {el:7.2f} s  max error {np.max(e):.2e}  ({status})")
    chart(out / "long_horizon_damped", f"weakly damped (linear, ε = {EPS:g}), I = (2, 3, 4), with attitude", curves,
          floor)
    t6 = 1e6 if horizon >= 1e6 else horizon
    k6 = int(np.searchsorted(t_ref, t6))
    taylor_e, taylor_t = results["taylor rtol 1e-14"]
    for label in ("splitting order 4, h = 2", "splitting order 6, h = 4"):
        e, el = results[label]
        # time to t6 ≈ the run's time × t6/horizon is not linear (ω decays): runs to t6 alone
        print(f"TARGET damped ({label}): error at t = {t6:g}: {np.max(e[:k6 + 1]):.2e} vs taylor 1e-14 "
              f"{np.max(taylor_e[:k6 + 1]):.2e} (ratio {np.max(e[:k6 + 1]) / np.max(taylor_e[:k6 + 1]):.2f}, target <= 1)")
    for label, opts in (("splitting order 4, h = 2", dict(method="splitting", step=2.0, splitting_order=4)),
                        ("splitting order 6, h = 4", dict(method="splitting", step=4.0, splitting_order=6))):
        _, el_s, _, _ = run(damped, np.array([0.0, t6]), **opts)
        _, el_t, _, _ = run(damped, np.array([0.0, t6]), method="taylor", rtol=1e-14, atol=1e-300)
        print(f"TARGET damped ({label}): time to t = {t6:g}: {el_s:.3f} s vs taylor 1e-14 {el_t:.3f} s "
              f"(ratio {el_s / el_t:.2f}, target <= 0.33)")


# ------------------------------------------------------------------ 3. forced spin, 4. cavity

def forced_spin_rhs(t, y):
    """Problem 3 written here: J ω̇ = ε D'(ω* − ω) − ω × Jω, q̇ = ½ q ⊗ (0, ω)."""
    w, q = y[:3], y[3:]
    dw = (D @ (W_SPIN - w) - np.cross(w, J * w)) / J
    qw, qx, qy, qz = q
    p, qq, r = w
    dq = 0.5 * np.array([-qx * p - qy * qq - qz * r, qw * p + qy * r - qz * qq, qw * qq + qz * p - qx * r,
                         qw * r + qx * qq - qy * p])
    return np.concatenate([dw, dq])


W_SPIN = np.array([0.0, 0.0, 1.0])  # problem 3's steady spin ω* (about the largest axis)


def forced_spin(t_end: float):
    """Problem 3: the weakly damped body driven by a constant torque ε D'ω* (a spin-up motor
    against friction): it settles into a steady spin ω* about its largest axis and keeps turning,
    so Taylor must follow the rotation over the whole horizon (in problem 2 ω decays and Taylor's
    steps grow). Work-precision at t = t_end, reference SciPy DOP853 at rtol 1e-13."""
    from scipy.integrate import solve_ivp

    model = g.Model(g.Body(J), [g.ConstantTorque(D @ W_SPIN), g.LinearDamping(D)], attitude=True)
    y0 = np.concatenate([W0, Q0])
    refs = []
    for rtol in (1e-13, 1e-12):
        sol = solve_ivp(forced_spin_rhs, (0.0, t_end), y0, method="DOP853", rtol=rtol, atol=1e-300)
        refs.append(sol.y[:, -1] / np.r_[1.0, 1.0, 1.0, [np.linalg.norm(sol.y[3:, -1])] * 4])
    ref, floor = refs[0], errors(refs[1][None, :], refs[0][None, :])[0]
    print(f"forced spin (ε = {EPS:g}, t = {t_end:g}) reference: SciPy DOP853 rtol 1e-13; "
          f"|rtol 1e-12 − rtol 1e-13| = {floor:.1e}")
    rows = []
    configs = [("taylor", dict(method="taylor", rtol=r, atol=1e-300), f"rtol {r:g}") for r in (1e-10, 1e-12, 1e-14)]
    configs += [("dop853", dict(method="dop853", rtol=r, atol=1e-300), f"rtol {r:g}") for r in (1e-10, 1e-12)]
    configs += [(f"splitting order {o}", dict(method="splitting", step=h, splitting_order=o), f"h = {h:g}")
                for o, hs in ((4, (1.0, 0.5, 0.25)), (6, (2.0, 1.0, 0.5))) for h in hs]
    for name, opts, setting in configs:
        y, el, status, _ = run(model, np.array([0.0, t_end]), **opts)
        e = errors(y[-1:], ref[None, :])[0]
        rows.append((name, setting, e, el))
        print(f"  {name:20s} {setting:12s} {el:8.3f} s  error {e:.2e}  ({status})")
    return rows, floor


def cavity_G_drift(t_end: float):
    """Problem 4: the viscous cavity (κ = ε), an internal torque: |G| is conserved exactly while
    the energy decays. The relative drift of |G| over t_end: splitting against DOP853 (Taylor does
    not apply: the cavity's torque is cubic in ω)."""
    model = g.Model(g.Body(J), [g.ViscousCavity(EPS, 1.0, 1.0)])
    out = {}
    for label, opts in (("splitting order 4, h = 0.5", dict(method="splitting", step=0.5, splitting_order=4)),
                        ("dop853 rtol 1e-12", dict(method="dop853", rtol=1e-12, atol=1e-300))):
        start = time.perf_counter()
        sol = g.solve(model, W0, (0.0, t_end), n_out=101, max_steps=10**9, error_estimate=False, **opts)
        el = time.perf_counter() - start
        G = sol["angular_momentum_norm"]
        T = sol["kinetic_energy"]
        out[label] = (sol.t, np.abs(G / G[0] - 1))
        print(f"  cavity {label:28s} {el:7.2f} s  max |ΔG|/G {np.max(out[label][1]):.1e}  "
              f"T(t_end)/T(0) = {T[-1] / T[0]:.6f}  ({sol.status})")
    return out


if __name__ == "__main__":
    main()
