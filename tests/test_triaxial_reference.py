"""Tests of the pure-Python triaxial averaging reference (tests/triaxial_reference.py; derivation in
docs/papers/triaxial_averaging.md). NumPy/SciPy/mpmath only: no library build needed."""
import math

import mpmath
import numpy as np
import pytest
from scipy.integrate import solve_ivp

import triaxial_reference as R

A = (3.0, 2.0, 1.0)
DAMPING = np.array([[0.3, 0.05, -0.02], [0.05, 0.5, 0.04], [-0.02, 0.04, 0.7]])  # off-diagonal: average 0
KAPPA = 0.1
MOMENT = np.array([0.1, -0.2, 0.3])
SIDES = ("largest", "smallest")


def euler(moments, torque=None):
    """Euler's equations J ω̇ = Jω × ω + M(ω), written here independently of the reference."""
    J = np.asarray(moments, float)

    def rhs(t, w):
        dw = np.cross(J * w, w)
        if torque is not None:
            dw = dw + torque(w)
        return dw / J

    return rhs


def relative(x, ref, scale):
    return abs(float(x) - float(ref)) / abs(float(scale))


@pytest.mark.parametrize("side", SIDES)
@pytest.mark.parametrize("branch", (1, -1))
def test_free_motion_solves_euler_and_phase_rate(side, branch):
    # ω(φ0 + φ̇ t) against DOP853 (rtol 1e-12) over one third of a period: 1e-9 is the integrator's
    # accumulated error with margin; the invariants hold to rounding (1e-14).
    G, T = R.invariants_at(A, 0.3, side=side)
    w0 = R.free_motion(A, G, T, 0.3, branch)
    J = np.asarray(A)
    assert abs(J * J @ (w0 * w0) - G * G) < 1e-14 * G * G and abs(J @ (w0 * w0) - 2 * T) < 1e-14 * T
    t1 = R.period(A, G, T) / 3
    sol = solve_ivp(euler(A), (0, t1), w0, method="DOP853", rtol=1e-12, atol=1e-14)
    w1 = R.free_motion(A, G, T, 0.3 + R.phase_rate(A, G, T) * t1, branch)
    assert np.max(np.abs(sol.y[:, -1] - w1)) < 1e-9


def rates_all(G, T, n, mp, branch=1):
    """Quadrature and mpmath closed forms (dps 30) for damping, cavity and constant torque."""
    quad = [R.averaged_rates_quadrature(A, G, T, lambda w: -np.dot(DAMPING, w), n,
                                        branch, mp),
            R.averaged_rates_quadrature(A, G, T, lambda w: R.cavity_torque(w, A, KAPPA), n, branch, mp),
            R.averaged_rates_quadrature(A, G, T, lambda w: MOMENT[:, None] + 0 * w, n, branch, mp)]
    with mpmath.workdps(30):
        closed = [R.averaged_rates_closed_form_linear_damping(A, DAMPING, G, T, mp=True),
                  R.averaged_rates_closed_form_cavity(A, KAPPA, G, T, mp=True),
                  R.averaged_rates_closed_form_constant(A, MOMENT, G, T, branch, mp=True)]
    return quad, closed


@pytest.mark.parametrize("side", SIDES)
@pytest.mark.parametrize("m", (1e-6, 0.5, 1 - 1e-6))
def test_closed_forms_match_quadrature(side, m):
    # Relative to the scale G²·max|D|/A, T·κ|ω|²... (the rates' natural sizes): 1e-12. The closed
    # forms are evaluated in mpmath at 30 digits (S2 = (2(1 + k²)S1 − 1)/(3k²) cancels in double at
    # small k²); the quadrature is double-precision SciPy (n = 64) away from the separatrix and
    # mpmath (n = 256, 30 digits) at k'² = 1e-6, where SciPy's ellipj (which takes k², not k'²) is
    # good to 3e-12 only. The off-diagonal damping and the transverse constant torque components
    # are in both: their averages vanish.
    G, T = R.invariants_at(A, m, side=side)
    mp = m > 0.9
    with mpmath.workdps(30):
        quad, closed = rates_all(G, T, 256 if mp else 64, mp, branch=-1)
    w2 = 2 * T / min(A)  # bound of |ω|²
    scales = [(G * G * 0.7 / min(A), T * 0.7 / min(A)), (KAPPA * G * G * w2, KAPPA * w2 * w2),
              (G * max(A) * 0.4, 0.4 * math.sqrt(w2))]
    for q, c, s in zip(quad, closed, scales):
        assert relative(q[0], c[0], s[0]) < 1e-12 and relative(q[1], c[1], s[1]) < 1e-12


@pytest.mark.parametrize("side", SIDES)
@pytest.mark.parametrize("m1, tol", ((0.5, 1e-15), (1e-2, 1e-15), (1e-6, 1e-11)))
def test_double_closed_form_linear_damping(side, m1, tol):
    # The double fast path (S1 = R_D/(3R_F), K from k'²) against mpmath at 30 digits from the same
    # double (G, T): 1e-15 away from the separatrix; at k'² = 1e-6 the input's own conditioning
    # (G² − 2T A_b carries a relative error ~1e-16/k'²) limits both to ~1e-12.
    G, T = R.invariants_at(A, 1 - m1, side=side)
    d = R.averaged_rates_closed_form_linear_damping(A, DAMPING, G, T)
    with mpmath.workdps(30):
        ref = R.averaged_rates_closed_form_linear_damping(A, DAMPING, G, T, mp=True)
    assert relative(d[0], ref[0], ref[0]) < tol and relative(d[1], ref[1], ref[1]) < tol


@pytest.mark.parametrize("side", SIDES)
def test_quadrature_matches_time_average_of_euler(side):
    # The phase average against a brute-force time average of a DOP853 run (rtol 1e-12) over one
    # period: 128 samples of the dense output, periodic trapezoid (spectrally accurate), so the
    # 1e-9 bound is the dense interpolant's error with margin.
    G, T = R.invariants_at(A, 0.7, side=side)
    P = R.period(A, G, T)
    w0 = R.free_motion(A, G, T, 0.0)
    sol = solve_ivp(euler(A), (0, P), w0, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    w = sol.sol(P * np.arange(128) / 128)
    for torque in (lambda w: -DAMPING @ w, lambda w: R.cavity_torque(w, A, KAPPA)):
        M = torque(w)
        brute = (2 * np.mean(np.sum(np.asarray(A)[:, None] * w * M, axis=0)), np.mean(np.sum(w * M, axis=0)))
        quad = R.averaged_rates_quadrature(A, G, T, torque, 64)
        assert abs(brute[0] - quad[0]) < 1e-9 * G * G and abs(brute[1] - quad[1]) < 1e-9 * T


@pytest.mark.parametrize("moments", ((2.0, 2.0, 1.0), (1.0, 1.0, 2.0)))
def test_symmetric_limit_is_the_a_r_model(moments):
    # A1 = A2 = A, A3 = C: k² = 0 exactly, and (d|G|²/dt, dT/dt) from the library's (a, r) rates
    # (linear_damping.hpp, viscous_cavity.hpp `averaged`) through |G|² = A²a² + C²r²,
    # T = (A a² + C r²)/2. Rounding only: 1e-14.
    Am, C = moments[0], moments[2]
    a, r = 0.7, 1.3
    G, T = math.sqrt(Am * Am * a * a + C * C * r * r), 0.5 * (Am * a * a + C * r * r)
    assert R.parameters(moments, G, T)["m"] == 0.0
    D = np.diag([0.3, 0.5, 0.7])
    k = KAPPA
    for (da, dr), closed in (
            ((-(D[0, 0] + D[1, 1]) * a / (2 * Am), -D[2, 2] * r / C),
             R.averaged_rates_closed_form_linear_damping(moments, D, G, T)),
            ((k * C * (Am - C) * r * r * a / Am**3, k * (C - Am) * a * a * r / (Am * C)),
             R.averaged_rates_closed_form_cavity(moments, k, G, T))):
        expected = (2 * (Am * Am * a * da + C * C * r * dr), Am * a * da + C * r * dr)
        assert abs(closed[0] - expected[0]) < 1e-14 * G * G and abs(closed[1] - expected[1]) < 1e-14 * T
    M = np.array([0.1, -0.2, 0.3])  # constant.hpp: (ȧ, ṙ) = (0, M3/C) on the branch sign ω3 = sign r
    closed = R.averaged_rates_closed_form_constant(moments, M, G, T, branch=1)
    assert abs(closed[0] - 2 * C * C * r * M[2] / C) < 1e-14 * G * G and abs(closed[1] - r * M[2]) < 1e-14 * T
    quad = R.averaged_rates_quadrature(moments, G, T, lambda w: -D @ w, 16)
    assert abs(quad[1] - (Am * a * (-(D[0, 0] + D[1, 1]) * a / (2 * Am)) - D[2, 2] * r * r)) < 1e-14 * T


def test_averaged_against_full_motion_is_first_order():
    # M = −ε diag(1, 2, 3) ω from k² = 0.3 about the major axis (the motion stays there: k² falls)
    # over t = 1/ε, ε = 1e-2, 3e-3, 1e-3. The averaged (|G|², T) by the double closed form; both
    # runs DOP853 at rtol 1e-10. Max relative error of |G| and T over 50 times: error/ε must be
    # O(1) and the fitted slope in ε within 0.8–1.2 (measured: see the paper page).
    d = np.array([1.0, 2.0, 3.0])
    G0, T0 = R.invariants_at(A, 0.3, side="largest")
    w0 = R.free_motion(A, G0, T0, 0.0)
    errors = []
    for eps in (1e-2, 3e-3, 1e-3):
        t = np.linspace(0, 1 / eps, 50)
        full = solve_ivp(euler(A, lambda w: -eps * d * w), (0, t[-1]), w0, method="DOP853", rtol=1e-10,
                         atol=1e-12, t_eval=t)
        Jw = np.asarray(A)[:, None] * full.y
        G_full, T_full = np.sqrt(np.sum(Jw * Jw, axis=0)), 0.5 * np.sum(Jw * full.y, axis=0)

        def slow(s, y):
            return R.averaged_rates_closed_form_linear_damping(A, eps * np.diag(d), math.sqrt(y[0]), y[1])

        avg = solve_ivp(slow, (0, t[-1]), (G0 * G0, T0), method="DOP853", rtol=1e-10, atol=1e-14, t_eval=t)
        err = max(np.max(np.abs(np.sqrt(avg.y[0]) - G_full) / G_full), np.max(np.abs(avg.y[1] - T_full) / T_full))
        errors.append(err)
        assert err / eps < 1.0
    slope = np.polyfit(np.log([1e-2, 3e-3, 1e-3]), np.log(errors), 1)[0]
    assert 0.8 < slope < 1.2, (errors, slope)


@pytest.mark.parametrize("side", SIDES)
def test_period_against_mpmath_at_both_ends(side):
    # k² = 1e-6: P = 4K/λ, K = (π/2)(1 + k²/4 + 9k⁴/64 + ...) to 1e-15. k'² = 1e-6: the double
    # period (K from k'² by SciPy's ellipkm1) against mpmath at 30 digits from the same (G, T), to
    # the input's conditioning: G² − 2T A_b = 5e-7 out of G² = 4 has a relative rounding error
    # ~1e-9, and δK/K = δk'²/(2k'² K) ~ 6e-11 (bound 1e-10); and mpmath against the asymptotic
    # K = ln(4/k') + (k'²/4)(ln(4/k') − 1) + O(k'⁴ ln k') (1e-12 relative).
    for m in (1e-6, 1 - 1e-6):
        G, T = R.invariants_at(A, m, side=side)
        with mpmath.workdps(30):
            ref = R.period(A, G, T, mp=True)
            P = R.parameters(A, G, T, mp=True)
            if m < 0.5:
                approx = 4 * (mpmath.pi / 2) * (1 + P["m"] / 4 + 9 * P["m"] ** 2 / 64) / P["lam"]
                assert abs(approx - ref) / ref < 1e-15
            else:
                L = mpmath.log(4 / mpmath.sqrt(P["m1"]))
                approx = 4 * (L + P["m1"] / 4 * (L - 1)) / P["lam"]
                assert abs(approx - ref) / ref < 1e-12
        assert relative(R.period(A, G, T), ref, ref) < (1e-15 if m < 0.5 else 1e-10)


@pytest.mark.parametrize("m1", (1e-2, 1e-4, 1e-6))
def test_nodes_rule_near_the_separatrix(m1):
    # nodes_for(k'², tol) = 2K ln(1e3/tol)/(πK') reaches tol = 1e-10 (error ~exp(−πK'n/(2K)));
    # half as many nodes does not (the rule is within 2× of the minimum). Against mpmath closed
    # forms; double quadrature suffices at 1e-10 (SciPy's ellipj floor is ~3e-12 at k'² = 1e-6).
    G, T = R.invariants_at(A, 1 - m1, side="largest")
    with mpmath.workdps(30):
        ref = R.averaged_rates_closed_form_linear_damping(A, DAMPING, G, T, mp=True)
    n = R.nodes_for(R.parameters(A, G, T)["m1"], 1e-10)

    def err(n):
        q = R.averaged_rates_quadrature(A, G, T, lambda w: -DAMPING @ w, n)
        return max(relative(q[i], ref[i], ref[i]) for i in range(2))

    assert err(n) < 1e-10 < err(n // 2)
