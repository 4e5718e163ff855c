"""The triaxial averaged model (C++ model/averaged_triaxial.hpp, euler_poinsot.hpp; Python
gyrostat.TriaxialAveragedModel) against independent references: the pure-Python derivation of
tests/triaxial_reference.py (closed forms in mpmath at 30 digits), its own quadrature through a
user's torque (the trapezoidal path) against the closed forms, the symmetric (a, r) model in the
symmetric limit, and the full model integrated by DOP853 (O(ε) with the order measured)."""
import math

import mpmath
import numpy as np
import pytest

import gyrostat as g
import triaxial_reference as R
from references import cavity_torque, damper_torque_series

A = (3.0, 2.0, 1.0)
DAMPING = np.diag([0.3, 0.5, 0.7])
KAPPA = 0.1
MOMENT = np.array([0.1, -0.2, 0.3])
DENSITY, VISCOSITY = 100.0, 100.0  # κ = ρ P0 / ν = P0; ν large: Reynolds number |ω| b²/ν ≪ 1


def cavity(kappa=KAPPA):
    return g.ViscousCavity(density=DENSITY, viscosity=VISCOSITY, p0=kappa)


def state_at(moments, m, side, branch=1.0, phase=0.7):
    """(|G|², p_b, s, φ) exactly (mpmath, rounded once) of the motion with k² = m on a side."""
    mpmath.mp.dps = 40
    G, T = R.invariants_at(moments, m, side=side)
    lo, mid, hi = sorted(moments)
    G2 = mpmath.mpf(G) ** 2
    # k'² = (A_a − A_c) p_b / ((A_a − A_b) p_a) solved for p_b from m, in mpmath (no cancellation)
    Aa, Ac = (hi, lo) if side == "largest" else (lo, hi)
    m1 = 1 - mpmath.mpf(m)
    # p_a = (G²(A_b − A_c) + p_b A_c)/A_b: p_b = m1 (A_a − A_b) G² (A_b − A_c) / ((A_a − A_c) A_b − m1 (A_a − A_b) A_c)
    pb = m1 * (Aa - mid) * G2 * (mid - Ac) / ((Aa - Ac) * mid - m1 * (Aa - mid) * Ac)
    return np.array([float(G2), float(pb), branch, phase])


def reference_rates(moments, y, closed_form):
    """(d|G|²/dt, dp_b/dt) of the reference's closed form at the state y, in mpmath at 30 digits."""
    mpmath.mp.dps = 30
    G2, pb = mpmath.mpf(y[0]), mpmath.mpf(y[1])
    Ab = sorted(moments)[1]
    G, T = mpmath.sqrt(G2), (G2 - pb) / (2 * Ab)
    dG2, dT = closed_form(G, T)
    return float(dG2), float(dG2 - 2 * Ab * dT)


def model_rates(model, y):
    rates = np.asarray(model._core.rhs(0.0, y))
    return rates[0], rates[1]


MODULI = [(1e-6, "largest"), (0.09, "largest"), (0.5, "largest"), (1 - 1e-6, "largest"), (1e-6, "smallest"), (0.5, "smallest"),
          (1 - 1e-6, "smallest")]


@pytest.mark.parametrize("m,side", MODULI)
def test_rates_of_the_closed_forms_equal_the_mpmath_reference(m, side):
    # The model's closed forms (damping, cavity, constant torque on both branches) against the
    # reference's formulas evaluated in mpmath at 30 digits at the same double state. 1e-11 relative
    # to the rates' scale: double rounding of α², K and S1 (~1e-15) amplified next to the separatrix
    # by ~1/(k'² L²) in the rates' slope (measured 1e-13 at k'² = 1e-6); plus 1e-15/k²: next to the
    # permanent rotation (k² → 0) p_c = 2T A_a − G² is formed from the state (|G|², p_b) by a
    # difference that loses log10(1/k²) digits, and the cavity's rates are proportional to it
    # (measured 2.8e-11 at k² = 1e-6).
    tolerance = 1e-11 + 1e-15 / m
    body = g.Body(list(A))
    for branch in (1.0, -1.0):
        y = state_at(A, m, side, branch)
        cases = [
            (g.LinearDamping(DAMPING), lambda G, T: R.averaged_rates_closed_form_linear_damping(A, DAMPING, G, T, mp=True)),
            (cavity(), lambda G, T: R.averaged_rates_closed_form_cavity(A, KAPPA, G, T, mp=True)),
            (g.ConstantTorque(MOMENT),
             lambda G, T: R.averaged_rates_closed_form_constant(A, MOMENT, G, T, branch=int(branch), mp=True)),
        ]
        for torque, closed in cases:
            model = g.TriaxialAveragedModel(body, [torque])
            got = model_rates(model, y)
            want = reference_rates(A, y, closed)
            scale = max(abs(want[0]), abs(want[1]), 1e-300)
            assert abs(got[0] - want[0]) <= tolerance * scale, (torque, m, side, branch, got, want)
            assert abs(got[1] - want[1]) <= tolerance * scale, (torque, m, side, branch, got, want)


@pytest.mark.parametrize("m,side", MODULI)
def test_quadrature_for_a_users_torque_equals_the_closed_forms(m, side):
    # The same torques given as Python functions (CustomTorque: no closed form, so the model takes the
    # trapezoidal rule in the phase with nodes for 1e-13) against the built-in torques' closed forms:
    # 1e-12 relative to the rates' scale (the issue's bar; the rule's own error is ~1e-13).
    body = g.Body(list(A))
    for branch in (1.0, -1.0):
        y = state_at(A, m, side, branch)
        pairs = [
            (g.LinearDamping(DAMPING), g.CustomTorque(lambda t, w: -DAMPING @ w, name="damping")),
            (cavity(), g.CustomTorque(lambda t, w: cavity_torque(w, A, KAPPA), name="cavity")),
            (g.ConstantTorque(MOMENT), g.CustomTorque(lambda t, w: MOMENT.copy(), name="constant")),
            (g.ResistiveMedium([DAMPING, 0.1 * DAMPING]),
             g.CustomTorque(lambda t, w: -(DAMPING + 0.1 * t * DAMPING) @ w, name="medium")),
        ]
        for closed, user in pairs:
            for t in (0.0, 2.0):
                want = np.asarray(g.TriaxialAveragedModel(body, [closed])._core.rhs(t, y))
                got = np.asarray(g.TriaxialAveragedModel(body, [user])._core.rhs(t, y))
                scale = max(abs(want[0]), abs(want[1]))
                assert np.all(np.abs(got[:2] - want[:2]) <= 1e-12 * scale), (closed, m, side, branch, got, want)
                assert got[3] == want[3] and got[2] == 0.0  # the phase rate depends on the slow variables only


def test_the_off_diagonal_damping_averages_to_zero():
    # ⟨ω_i ω_j⟩ = 0 for i ≠ j: a full damping matrix has the rates of its diagonal (by quadrature,
    # 1e-12: the rule's error).
    body = g.Body(list(A))
    full = np.array([[0.3, 0.05, -0.02], [0.05, 0.5, 0.04], [-0.02, 0.04, 0.7]])
    y = state_at(A, 0.4, "smallest")
    with_matrix = np.asarray(g.TriaxialAveragedModel(body, [g.CustomTorque(lambda t, w: -full @ w)])._core.rhs(0.0, y))
    diagonal = np.asarray(g.TriaxialAveragedModel(body, [g.LinearDamping(np.diag(np.diag(full)))])._core.rhs(0.0, y))
    assert np.allclose(with_matrix[:2], diagonal[:2], rtol=1e-12, atol=0)


@pytest.mark.parametrize("side", ("largest", "smallest"))
def test_quadrature_and_the_medium_equal_a_time_average_of_euler_written_here(side):
    # The torques without a closed form here (the moving-mass damper: the model's trapezoidal rule in
    # the phase) and the resistive medium's closed form at t = 2 (D(t) = D0 + t D1) against a
    # brute-force time average written here: P_i = ⟨ω_i M_i⟩ over one period of Euler's torque-free
    # equations integrated by SciPy (DOP853, rtol 1e-12, 128 samples of the dense output: periodic
    # trapezoid), M from tests/references.py (the damper's independent series; −D(t)ω), then
    # d|G|²/dt = 2 Σ A_i P_i, dp_b/dt = d|G|²/dt − 2 A_b Σ P_i. Bound 1e-8 of the rates' scale: the
    # damper's series truncation (measured 8.4e-10 and 5.4e-10 on the two sides; the medium 4e-14);
    # a 1 % error in a contribution is 1e-2 (a wrong factor in either fails here: tools/mutation_check.py).
    from scipy.integrate import solve_ivp

    J = np.asarray(A)
    Ab = sorted(A)[1]
    D0, D1 = np.diag([0.3, 0.5, 0.7]), np.diag([0.02, -0.01, 0.04])
    G, T = R.invariants_at(A, 0.5, side=side)
    G, T = float(G), float(T)
    period = float(R.period(A, G, T))
    w0 = np.asarray(R.free_motion(A, G, T, 0.0, 1), float)
    sol = solve_ivp(lambda t, w: np.cross(J * w, w) / J, (0.0, period), w0, method="DOP853", rtol=1e-12, atol=1e-14,
                    dense_output=True)
    w = sol.sol(period * np.arange(128) / 128).T
    y = np.array([G * G, G * G - 2 * Ab * T, 1.0, 0.0])
    cases = [(g.MovingMassDamper(mass=0.1, arm=0.5, frequency=30.0, damping=2.0),
              lambda w: damper_torque_series(w, J, 0.5, 0.1, 900.0, 2.0)),
             (g.ResistiveMedium([D0, D1]), lambda w: -(D0 + 2.0 * D1) @ w)]
    for torque, written in cases:
        P = np.mean([wi * written(wi) for wi in w], axis=0)
        want = np.array([2 * J.dot(P), 2 * J.dot(P) - 2 * Ab * P.sum()])
        got = np.asarray(g.TriaxialAveragedModel(g.Body(list(A)), [torque])._core.rhs(2.0, y))[:2]
        scale = np.abs(want).max()
        assert np.all(np.abs(got - want) <= 1e-8 * scale), \
            f"{torque} {side}: rates {got}, time average {want} (bound 1e-8 of the scale: the series' truncation)"


@pytest.mark.parametrize("moments", [(4.0, 4.0, 1.5), (2.5, 2.5, 4.0)], ids=["oblate", "prolate"])
def test_symmetric_limit_equals_the_a_r_model(moments):
    # In the symmetric limit (k² = 0) the rates of (|G|², p_b) are those the (a, r) model gives:
    # d|G|²/dt = 2(A² a ȧ + C² r ṙ), dT/dt = A a ȧ + C r ṙ, p_b = G² − 2T A. Both are closed forms of the
    # same averages: 1e-12 relative (rounding); plus 1e-20 absolute for the moving-mass damper, which
    # has no closed form here: its d|G|²/dt (0: an internal damper) is the trapezoidal rule's sum of
    # terms A_i ω_i M_i up to 3.5e-6 that cancel, whose rounding (8 nodes · 2.2e-16 · 3.5e-6 ≈ 6e-21;
    # measured 1e-22 … 6.5e-22 with the nodes summed in different orders) is ~1e-12 of d p_b/dt here.
    body = g.Body(list(moments))
    A_, C_ = moments[0], moments[2]
    for torques in ([g.LinearDamping(np.diag([0.2, 0.2, 0.5]))], [cavity()], [g.ConstantTorque([0.0, 0.0, 0.3])],
                    [g.MovingMassDamper(mass=0.1, arm=0.5, frequency=30.0, damping=2.0)]):
        triaxial = g.TriaxialAveragedModel(body, torques)
        symmetric = g.AveragedModel(body, torques)
        for a, r in ((0.3, 1.2), (0.8, -0.4)):
            da, dr = np.asarray(symmetric._core.rhs(0.0, [a, r]))
            y = np.asarray(triaxial._core.initial_state([a, 0.0, r]))
            dG2, dpb = model_rates(triaxial, y)
            want_dG2 = 2 * (A_**2 * a * da + C_**2 * r * dr)
            want_dpb = want_dG2 - 2 * A_ * (A_ * a * da + C_ * r * dr)
            scale = max(abs(want_dG2), abs(want_dpb))
            bound = 1e-12 * scale + 1e-20
            assert abs(dG2 - want_dG2) <= bound and abs(dpb - want_dpb) <= bound, (torques, a, r)
            assert math.isclose(triaxial._core.outputs_at(0.0, y)[list(triaxial.output_names).index("fast_frequency")],
                                abs((C_ - A_) * r / A_), rel_tol=1e-13)


@pytest.mark.parametrize("side", ("largest", "smallest"))
@pytest.mark.parametrize("branch", (1.0, -1.0))
@pytest.mark.parametrize("m", (1e-6, 0.5, 1 - 1e-8))
def test_lift_and_projection_are_inverse_and_match_the_reference_motion(side, branch, m):
    # ω = full_state(y) is the reference's free motion at the same phase (1e-12 of |ω|; SciPy's
    # ellipj takes k², which floors at ~1e-8 next to the separatrix: compared in mpmath there), and
    # initial_state(ω) gives y back (|G|², p_b to 1e-13 relative to |G|², the phase to 1e-9 rad: the
    # argument of sn/cn/dn read back at the separatrix's K ≈ 10).
    body = g.Body(list(A))
    model = g.TriaxialAveragedModel(body)
    y = state_at(A, m, side, branch, phase=2.1)
    w = np.asarray(model._core.full_state(y, 0.0))
    mpmath.mp.dps = 30
    G2, pb = mpmath.mpf(y[0]), mpmath.mpf(y[1])
    G, T = mpmath.sqrt(G2), (G2 - pb) / (2 * sorted(A)[1])
    want = np.array([float(x) for x in R.free_motion(A, G, T, mpmath.mpf(2.1), int(branch), mp=True)])
    assert np.allclose(w, want, rtol=0, atol=1e-12 * np.linalg.norm(want)), (w, want)
    back = np.asarray(model._core.initial_state(w))
    assert abs(back[0] - y[0]) <= 1e-13 * y[0] and abs(back[1] - y[1]) <= 1e-13 * y[0]
    assert back[2] == branch and abs(back[3] - 2.1) <= 1e-9


def test_a_body_given_by_its_inertia_tensor_averages_in_its_principal_axes():
    # The same body rotated: the states (|G|², p_b, s, φ) do not depend on the frame, ω lifts into the
    # user's frame. 1e-13 (rounding of the rotation).
    c, s = math.cos(0.4), math.sin(0.4)
    R_ = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    tilted = g.Body(inertia=R_ @ np.diag(A) @ R_.T)
    principal = g.Body(list(A))
    D = np.diag([0.3, 0.5, 0.7])
    m_t = g.TriaxialAveragedModel(tilted, [g.LinearDamping(R_ @ D @ R_.T)])
    m_p = g.TriaxialAveragedModel(principal, [g.LinearDamping(D)])
    w_p = np.array([0.9, 0.3, 0.2])
    y_t = np.asarray(m_t._core.initial_state(R_ @ w_p))
    y_p = np.asarray(m_p._core.initial_state(w_p))
    assert np.allclose(y_t, y_p, rtol=1e-13, atol=1e-13)
    assert np.allclose(m_t._core.rhs(0.0, y_t), m_p._core.rhs(0.0, y_p), rtol=1e-13, atol=1e-16)
    assert np.allclose(m_t._core.full_state(y_t, 0.0), R_ @ np.asarray(m_p._core.full_state(y_p, 0.0)), atol=1e-13)


def full_and_averaged(eps, t1, n=2001):
    """M = −ε diag(1, 2, 3) ω on A = (3, 2, 1) from k² = 0.3 on the major side (the reference's case)."""
    body = g.Body(list(A))
    torque = [g.LinearDamping(eps * np.diag([1.0, 2.0, 3.0]))]
    G, T = R.invariants_at(A, 0.3, side="largest")
    w0 = np.asarray(R.free_motion(A, G, T, 0.0, 1), float)
    times = np.linspace(0.0, t1, n)
    full = g.solve(g.Model(body, torque), w0, (0.0, t1), method="dop853", rtol=1e-12, atol=1e-14, t_eval=times)
    averaged = g.solve(g.TriaxialAveragedModel(body, torque), w0, (0.0, t1), rtol=1e-12, atol=1e-14, t_eval=times)
    return full, averaged


def test_error_of_G_and_T_is_first_order_in_epsilon():
    # Max relative error of |G| and T over [0, 1/ε] against the full model, at ε = 1e-2, 3e-3, 1e-3:
    # the fitted slope in log ε must be 1 ± 0.2 (first-order averaging: the reference measured 1.006),
    # and the error itself below 0.3 ε (the reference's constant is 0.22).
    errors = []
    epsilons = (1e-2, 3e-3, 1e-3)
    for eps in epsilons:
        full, averaged = full_and_averaged(eps, 1.0 / eps)
        worst = 0.0
        for name in ("angular_momentum_norm", "kinetic_energy"):
            worst = max(worst, float(np.max(np.abs(averaged[name] - full[name]) / full[name])))
        assert worst <= 0.3 * eps, (eps, worst)
        errors.append(worst)
    slope = np.polyfit(np.log(epsilons), np.log(errors), 1)[0]
    assert 0.8 <= slope <= 1.2, (errors, slope)


def test_the_steps_are_set_by_the_slow_variables_not_by_the_phase():
    # The phase is a quadrature (system.hpp: its rate depends on the slow variables, it feeds back into
    # none): the first step's heuristic and the step's error test leave it out (as CVODES leaves its
    # quadratures out of the error test by default). So a run started at the phase φ0 and one at
    # φ0 + 2π·1000 (the same motion) take the same steps, every one (to the rounding of t); with the
    # phase in the heuristic, φ0 ≈ 0 made h0 ~ 0.01 (atol + rtol |φ0|)/φ̇ and cost the ramp's steps
    # (13 against 7 at rtol 1e-6, ε = 1e-4), and in the error test its rounding near 0 held the first
    # steps' growth to ~5x (14 steps against 13 at rtol 1e-10).
    eps = 1e-4
    body = g.Body(list(A))
    model = g.TriaxialAveragedModel(body, [g.LinearDamping(eps * np.diag([1.0, 2.0, 3.0]))])
    G, T = R.invariants_at(A, 0.3, side="largest")
    start = np.asarray(model.initial_state(np.asarray(R.free_motion(A, G, T, 0.0, 1), float)))
    later = start + np.array([0.0, 0.0, 0.0, 2000.0 * math.pi])
    for rtol, most in ((1e-6, 8), (1e-10, 13)):
        runs = [g.solve(model, y0, (0.0, 1.0 / eps), rtol=rtol, atol=1e-12, every_step=True, t_eval=[0.0, 1.0 / eps],
                        check_validity=False) for y0 in (start, later)]
        steps = [np.diff(run.t) for run in runs]
        assert len(steps[0]) == len(steps[1]) <= most and np.allclose(steps[0], steps[1], rtol=1e-12, atol=0.0), steps


def test_the_phase_left_out_of_the_error_test_keeps_the_slow_variables_accuracy():
    # Its truncation error is its rate's, which the slow variables' control bounds: against a run at
    # rtol 1e-14, the phase's error relative to its largest size stays below the slow variables' own
    # (measured 0.041-0.050 of theirs at rtol 1e-6 ... 1e-10, ε = 1e-4 over 1/ε).
    eps = 1e-4
    model = g.TriaxialAveragedModel(g.Body(list(A)), [g.LinearDamping(eps * np.diag([1.0, 2.0, 3.0]))])
    G, T = R.invariants_at(A, 0.3, side="largest")
    y0 = np.asarray(model.initial_state(np.asarray(R.free_motion(A, G, T, 0.0, 1), float)))
    reference = g.solve(model, y0, (0.0, 1.0 / eps), rtol=1e-14, atol=1e-16, n_out=201, check_validity=False,
                        error_estimate=False)
    for rtol in (1e-6, 1e-8, 1e-10):
        run = g.solve(model, y0, (0.0, 1.0 / eps), rtol=rtol, atol=rtol * 1e-2, n_out=201, check_validity=False,
                      error_estimate=False)
        error = np.abs(run.y - reference.y).max(axis=0) / np.abs(reference.y).max(axis=0)
        slow, phase = max(error[0], error[1]), error[3]
        assert phase <= 0.5 * slow and slow <= 10 * rtol, (rtol, error)


def test_the_carried_phase_gives_omega_along_the_run():
    # ω(t) from the averaged run (outputs p, q, r: the free motion at the carried phase) against the
    # full model over [0, 1/ε] at ε = 1e-3: the phase's error is the integral of the O(ε) error of the
    # frequency, bounded by O(1) at t ~ 1/ε; here it stays within 1e-2 of |ω| (measured 1.4e-3, the
    # slow variables' own error), and is rounding at the start.
    full, averaged = full_and_averaged(1e-3, 1000.0)
    w_full = np.column_stack([full["p"], full["q"], full["r"]])
    w_avg = np.column_stack([averaged["p"], averaged["q"], averaged["r"]])
    error = np.linalg.norm(w_full - w_avg, axis=1) / np.linalg.norm(w_full, axis=1)
    assert error[0] <= 1e-12
    assert np.max(error) <= 1e-2, np.max(error)


def test_a_compare_scene_reports_the_error_of_omega_at_the_carried_phase():
    # model = "compare" on a triaxial body: the report's averaged_vs_full holds, beside |G| and T,
    # the largest |ω_avg − ω_full| / |ω_full|. Recomputed here independently: ω_full from SciPy on
    # Euler's equations written below, ω_avg from the pure-Python reference's free motion at the
    # averaged run's (|G|, T, φ). Both integrations at rtol 1e-12 over 1e3 s: they agree to ~1e-9
    # of |ω|, so the two maxima (~1e-3, the phase error) agree to 1e-7. The phase error integrates
    # the frequency's O(ε) error, so it exceeds the slow variables' own.
    from scipy.integrate import solve_ivp

    from gyrostat.runner import solve_scene
    from gyrostat.scene import Scene

    eps, t1, n = 1e-3, 1000.0, 201
    G, T = R.invariants_at(A, 0.3, side="largest")
    w0 = np.asarray(R.free_motion(A, G, T, 0.0, 1), float)
    scene = Scene.from_dict({
        "title": "triaxial compare", "body": {"moments": list(A)},
        "torques": [{"type": "linear_damping", "matrix": (eps * np.diag([1.0, 2.0, 3.0])).tolist()}],
        "initial": {"omega": w0.tolist()},
        "integration": {"model": "compare", "method": "dop853", "rtol": 1e-12, "atol": 1e-14, "t_span": [0.0, t1],
                        "n_out": n},
        "outputs": {"plots": []}}, name="triaxial_compare")
    solutions, report, _ = solve_scene(scene, progress=False)
    reported = report["averaged_vs_full"]

    J, D = np.array(A), eps * np.diag([1.0, 2.0, 3.0])
    times = np.linspace(0.0, t1, n)
    euler = solve_ivp(lambda t, w: (-D @ w - np.cross(w, J * w)) / J, (0.0, t1), w0, method="DOP853", rtol=1e-12,
                      atol=1e-14, t_eval=times)
    avg = solutions["averaged"]
    Ab = sorted(A)[1]
    carried = np.array([R.free_motion(A, math.sqrt(G2), (G2 - pb) / (2 * Ab), phase, int(branch))
                        for G2, pb, branch, phase in avg.y]).astype(float)
    expected = np.max(np.linalg.norm(carried - euler.y.T, axis=1) / np.linalg.norm(euler.y.T, axis=1))
    assert abs(reported["max_relative_error_omega"] - expected) <= 1e-7, (reported, expected)
    assert 1e-4 <= expected <= 1e-2 and expected > reported["max_relative_error_kinetic_energy"], (reported, expected)
    assert f"max_relative_error_omega {reported['max_relative_error_omega']:.2g}" in report["agreement"]


def test_the_ladder_reports_an_estimate_of_omega_at_the_carried_phase_that_bounds_its_error():
    # model = "auto" at ε = 1e-4 over 1/ε: the ladder takes the triaxial rung on its |G|, T estimate,
    # and reports beside it (fast_motion) the error of ω at the carried phase, measured over the
    # same probe and extrapolated quadratically. Against the full model (Euler's equations, tested
    # against SciPy elsewhere) the run's ω error is 1.2e-4; the estimate must bound it without being
    # vacuous (within 10x; measured 2.4e-4: SAFETY 2 on the probe's O(ε) difference).
    from gyrostat import ladder
    from gyrostat.runner import solve_scene
    from gyrostat.scene import Scene

    eps, t1 = 1e-4, 1e4
    G, T = R.invariants_at(A, 0.3, side="largest")
    w0 = np.asarray(R.free_motion(A, G, T, 0.0, 1), float)
    damping = eps * np.diag([1.0, 2.0, 3.0])
    scene = Scene.from_dict({
        "title": "triaxial auto", "body": {"moments": list(A)},
        "torques": [{"type": "linear_damping", "matrix": damping.tolist()}], "initial": {"omega": w0.tolist()},
        "integration": {"model": "auto", "accuracy": 1e-2, "method": "dop853", "rtol": 1e-12, "atol": 1e-14,
                        "t_span": [0.0, t1], "n_out": 201},
        "outputs": {"plots": ["invariants"]}}, name="triaxial_auto")
    ladder.choosing._CHOICES.clear()
    solutions, report, _ = solve_scene(scene, progress=False)
    assert report["model"] == "averaged_triaxial", report["ladder"]["summary"]
    (entry,) = [e for e in report["ladder"]["rungs"] if e["rung"] == "averaged_triaxial"]
    estimate = entry["estimate"]["fast_motion"]["value"]
    averaged = solutions["averaged"]
    full = g.solve(g.Model(g.Body(list(A)), [g.LinearDamping(damping)]), w0, (0.0, t1), method="dop853", rtol=1e-12,
                   atol=1e-14, t_eval=averaged.t)
    carried = np.column_stack([averaged["p"], averaged["q"], averaged["r"]])
    measured = np.max(np.linalg.norm(carried - full.omega, axis=1)) / np.max(np.linalg.norm(full.omega, axis=1))
    assert measured <= estimate <= 10.0 * measured, (measured, estimate)


def test_a_damped_run_reaches_the_permanent_rotation_and_rest_without_error():
    # Over 20/ε the damping drives the body onto its permanent rotation about the major axis
    # (k² → 0, p_c = 2TA_a − G² → 0); the integrator's error pushes stage states past it (p_c < 0),
    # which the right-hand side takes as that rotation (this run failed with "outside" before).
    # There k² is rounding and T = G²/(2 A_max) to the integrator's tolerance (1e-6 relative).
    body = g.Body(list(A))
    model = g.TriaxialAveragedModel(body, [g.LinearDamping(1e-4 * np.diag([1.0, 2.0, 3.0]))])
    sol = g.solve(model, [1.0, 0.2, 0.1], (0.0, 2e5), rtol=1e-10, atol=1e-12, n_out=11, check_validity=False)
    assert sol.success, sol.message
    G, T = sol["angular_momentum_norm"][-1], sol["kinetic_energy"][-1]
    assert sol["modulus_squared"][-1] <= 1e-6 and abs(T - G * G / (2 * 3.0)) <= 1e-6 * T
    # Over 100/ε |G|² falls below the absolute tolerance and is stepped past 0: rest, all rates 0
    # (failed with "needs |G|^2 > 0" before), and the validity check says the averaging has ended.
    rest = g.solve(model, [1.0, 0.2, 0.1], (0.0, 1e6), rtol=1e-10, atol=1e-12, n_out=11, check_validity=False)
    assert rest.success and abs(rest["G2"][-1]) <= 1e-12
    assert not all(a.holds for a in model.check(rest))


def test_an_ensemble_equals_the_single_runs():
    # solve_ensemble on 2 threads against solve member by member: the same integrator on the same
    # model, so equal to rounding (1e-14).
    body = g.Body(list(A))
    model = g.TriaxialAveragedModel(body, [cavity(0.01), g.ConstantTorque([0.0, 0.0, 0.001])])
    starts = [[1.0, 0.2, 0.1], [-1.0, 0.3, 0.2], [0.1, 0.3, 1.5], [0.1, -0.2, -1.5]]
    ensemble = g.solve_ensemble(model, starts, (0.0, 50.0), n_out=5, threads=2)
    for start, member in zip(starts, ensemble):
        single = g.solve(model, start, (0.0, 50.0), n_out=5)
        assert np.allclose(member.y, single.y, rtol=1e-14, atol=1e-14)


def test_bad_input_is_refused_with_the_value_named():
    body = g.Body(list(A))
    with pytest.raises(ValueError, match="rotor"):
        g.TriaxialAveragedModel(g.Body([3.0, 2.0, 1.0], rotor=[0.0, 0.0, 0.1]))
    with pytest.raises(ValueError, match="spherical"):
        g.TriaxialAveragedModel(g.Body([2.0, 2.0, 2.0]))
    with pytest.raises(ValueError, match="GravityGradient"):
        g.TriaxialAveragedModel(body, [g.GravityGradient(orbit_rate=0.001)])
    model = g.TriaxialAveragedModel(body)
    with pytest.raises(ValueError, match="separatrix"):
        g.solve(model, [4.0, 0.0, 1.0, 0.0], (0.0, 1.0))
    with pytest.raises(ValueError, match="branch"):
        g.solve(model, [4.0, 1.0, 0.5, 0.0], (0.0, 1.0))
    with pytest.raises(ValueError, match="outside"):
        g.solve(model, [4.0, 3.9, 1.0, 0.0], (0.0, 1.0))  # T = 0.05 < G²/(2 A_max) = 0.67
    with pytest.raises(ValueError, match="separatrix"):
        g.solve(model, [0.0, 1.0, 0.0], (0.0, 1.0))  # ω along the middle axis: on the separatrix
