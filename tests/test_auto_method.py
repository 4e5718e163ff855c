"""method="auto": DOP853 while the problem is not stiff, CVODE BDF while it is, switching along the
run on the measured stiffness. References are SciPy's Radau at rtol 1e-12 with the right-hand
sides written here (independent of the C++ code)."""

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g

# The gyrostat whose stiffness changes along the run: a resistive medium D(t) = c t (T − t) I
# (zero at both ends, c T²/4 = 1000 at T/2) under a constant torque M. Its Jacobian's dominant
# eigenvalue ≈ −D(t)/A1: DOP853 is held by stability in the middle of the span only.
MOMENTS = np.array([1.0, 2.0, 3.0])
TORQUE = np.array([0.5, -0.3, 1.0])
C, T = 40.0, 10.0
OMEGA0 = [1.0, 0.5, -0.3]


def changing_model():
    eye = np.eye(3)
    return g.Model(g.Body(list(MOMENTS)), [g.ConstantTorque(list(TORQUE)),
                                           g.ResistiveMedium([0 * eye, C * T * eye, -C * eye])])


def changing_rhs(t, w):
    """Euler's equations A ω̇ = M − D(t) ω − ω × (A ω), D(t) = c t (T − t)."""
    return (TORQUE - C * t * (T - t) * w - np.cross(w, MOMENTS * w)) / MOMENTS


# Paper 001's explicit moving mass in its stiff setting (bench/stiff_radau.py): Ω = 100, λ = 2e4.
MM_MOMENTS = np.array([4.0, 4.0, 2.0])
MASS, ARM, FREQ, DAMP = 1.0, 1.0, 100.0, 2e4


def moving_mass_rhs(t, y):
    """d = ρ e3 + u, s = ω × d + v, K = J_B ω + μ d × s, R = −2 ω × v − ω × (ω × d) − Ω² u − λ v,
    J_B ω̇ = −ω × K − μ [2 (d·v) ω − v (d·ω) − d (v·ω)] − μ d × R, u̇ = v, v̇ = R − ω̇ × d,
    J_B = diag(A1 − μρ², A2 − μρ², A3)."""
    w, u, v = y[:3], y[3:6], y[6:]
    carrier = MM_MOMENTS - np.array([MASS * ARM**2, MASS * ARM**2, 0.0])
    d = np.array([0.0, 0.0, ARM]) + u
    s = np.cross(w, d) + v
    K = carrier * w + MASS * np.cross(d, s)
    R = -2 * np.cross(w, v) - np.cross(w, np.cross(w, d)) - FREQ**2 * u - DAMP * v
    f = -np.cross(w, K) - MASS * (2 * d.dot(v) * w - v * d.dot(w) - d * v.dot(w)) - MASS * np.cross(d, R)
    a = f / carrier
    return np.concatenate([a, v, R - np.cross(a, d)])


def test_changing_stiffness_switches_to_bdf_and_back_and_matches_radau():
    t_eval = np.linspace(0, T, 201)
    sol = g.solve(changing_model(), OMEGA0, (0, T), method="auto", t_eval=t_eval, rtol=1e-8, atol=1e-10)
    assert sol.success, sol.message
    reference = solve_ivp(changing_rhs, (0, T), OMEGA0, method="Radau", t_eval=t_eval, rtol=1e-12, atol=1e-14)
    # 2e-6 = 200 rtol: BDF's global error at rtol 1e-8 accumulated over the stiff middle part
    # (measured ~1e-7); the DOP853 parts are ~100 times better
    assert np.max(np.abs(sol.omega - reference.y.T)) < 2e-6
    np.testing.assert_array_equal(sol.t, t_eval)  # each output time once, in order, across switches
    switches = sol.method_switches
    assert [m for _, m, _ in switches[:2]] == ["cvode_bdf", "dop853"]
    assert 0 < switches[0][0] < T / 2 < switches[1][0] < T  # on either side of the peak of D(t)
    assert all(isinstance(t, float) and "h·|λ|" in why for t, _, why in switches)
    # back to DOP853 as the medium thins: BDF's steps no longer pay (h_BDF·|λ| < 3 × 6.1: DOP853's held
    # step is more than a third of BDF's) before it is not stiff at all (h·|λ| ≤ 1.5)
    assert "stiff" in switches[0][2] and ("not stiff" in switches[1][2] or "BDF does not pay" in switches[1][2])
    assert sol.methods_used == ("dop853", "cvode_bdf")
    assert sol.method == "auto"
    attrs = sol.to_xarray().attrs
    assert attrs["methods_used"] == "dop853, cvode_bdf" and "cvode_bdf" in attrs["method_switches"]


def test_stiff_moving_mass_goes_to_bdf_early_and_matches_radau():
    model = g.MovingMassModel(g.Body(list(MM_MOMENTS)), mass=MASS, arm=ARM, frequency=FREQ, damping=DAMP)
    y0 = model.quasi_static_state([1.0, 0.0, 1.0])
    t_eval = np.linspace(0, 2.0, 21)
    sol = g.solve(model, y0, (0, 2.0), method="auto", t_eval=t_eval, rtol=1e-8, atol=1e-10)
    bdf = g.solve(model, y0, (0, 2.0), method="cvode_bdf", t_eval=t_eval, rtol=1e-8, atol=1e-10)
    reference = solve_ivp(moving_mass_rhs, (0, 2.0), y0, method="Radau", t_eval=t_eval, rtol=1e-12, atol=1e-14)
    assert sol.success and len(sol.method_switches) == 1
    t_switch, to, why = sol.method_switches[0]
    assert to == "cvode_bdf" and t_switch < 0.02 and "h·|λ|" in why  # the stiffness (λ ≈ −2e4) is there from t = 0
    # ω to 1e-6 = 100 rtol, as cvode_bdf itself: BDF's global error at rtol 1e-8, measured 9e-8
    # for cvode_bdf and 3e-7 for auto (whose BDF segment restarts at order 1 at t ≈ 0.005)
    assert np.max(np.abs(sol.omega - reference.y[:3].T)) < 1e-6
    assert np.max(np.abs(bdf.omega - reference.y[:3].T)) < 1e-6
    # far fewer steps than DOP853 alone, which is held at h ≈ 6/2e4
    dop = g.solve(model, y0, (0, 2.0), method="dop853", t_eval=t_eval, rtol=1e-8, atol=1e-10)
    assert sol.stats["steps"] < dop.stats["steps"] / 5


def test_mildly_stiff_at_a_loose_tolerance_goes_back_to_dop853_where_bdf_does_not_pay():
    """Paper 001's moving mass with a mild damper (Ω = 10, λ = 98; bench/accuracy_cost.py's scene)
    at rtol 3.8e-6: DOP853 is held at its stability boundary, but BDF at this tolerance takes steps
    only ~2x DOP853's, each costing ~5 of DOP853's (alone: 2.6x DOP853's time, and 100x its error).
    So the run goes back to DOP853 at BDF's second check, saying why, and does not switch again (the
    held step does not shrink): against SciPy's LSODA at rtol 1e-11 on the right-hand side
    written in tests/references.py, its error is a fraction of BDF's alone. (LSODA, ODEPACK's
    Adams/BDF switching: 3.0e-9 from SciPy's DOP853 at rtol 1e-12, four orders below the errors
    compared, in 0.6 s where that DOP853 run, held at the damper's stability boundary with this
    Python right-hand side, took 29 s: 186 293 evaluations.)"""
    from references import moving_mass_rhs as explicit_rhs

    model = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=98.0)
    y0 = model.quasi_static_state([1.0, 0.0, 1.0])
    t_eval = np.linspace(0.0, 40.0, 201)
    rtol, atol = 3.8e-6, 3.8e-9 * np.max(np.abs(y0))
    sol = g.solve(model, y0, (0.0, 40.0), method="auto", t_eval=t_eval, rtol=rtol, atol=atol, error_estimate=False)
    dop = g.solve(model, y0, (0.0, 40.0), method="dop853", t_eval=t_eval, rtol=rtol, atol=atol, error_estimate=False)
    reference = solve_ivp(explicit_rhs([4.0, 4.0, 2.0], 1.0, 1.0, 100.0, 98.0), (0.0, 40.0), y0, method="LSODA",
                          t_eval=t_eval, rtol=1e-11, atol=1e-14)
    assert sol.success and [to for _, to, _ in sol.method_switches] == ["cvode_bdf", "dop853"], sol.method_switches
    assert "BDF does not pay" in sol.method_switches[1][2], sol.method_switches[1][2]
    bdf = g.solve(model, y0, (0.0, 40.0), method="cvode_bdf", t_eval=t_eval, rtol=rtol, atol=atol,
                  error_estimate=False)
    size = np.max(np.abs(reference.y))
    error, bdf_error = (np.max(np.abs(s.y - reference.y.T)) / size for s in (sol, bdf))
    # BDF alone: 6.5e-5 (its global error at this rtol, over the whole span); auto: BDF's error over
    # its 100 steps before the check that sends the run back, 2.1e-5 measured, then DOP853's (~1e-8)
    assert error < 0.5 * bdf_error, (error, bdf_error)
    # the steps DOP853 takes from there: at most 1.3x DOP853 alone's right-hand sides (measured 0.8x)
    assert sol.stats["rhs_evals"] <= 1.3 * dop.stats["rhs_evals"], (sol.stats["rhs_evals"], dop.stats["rhs_evals"])


def test_non_stiff_problem_stays_on_dop853_step_for_step():
    model = g.Model(g.Body([1, 2, 3]), [g.LinearDamping(0.01 * np.eye(3))])
    auto = g.solve(model, OMEGA0, (0, 50), method="auto", rtol=1e-10, atol=1e-12)
    dop = g.solve(model, OMEGA0, (0, 50), method="dop853", rtol=1e-10, atol=1e-12)
    assert auto.method_switches == [] and auto.methods_used == ("dop853",)
    np.testing.assert_array_equal(auto.y, dop.y)
    assert dop.methods_used == ("dop853",) and dop.method_switches == []


def test_events_and_dense_output_across_switches():
    model = changing_model()
    plain = g.solve(model, OMEGA0, (0, T), method="auto")
    t_switch = [t for t, _, _ in plain.method_switches]
    events = [(lambda ts: (lambda t, y: t - ts))(ts) for ts in t_switch] + [g.events.Event("r")]
    sol = g.solve(model, OMEGA0, (0, T), method="auto", events=events, dense_output=True)
    for i, ts in enumerate(t_switch):  # a crossing exactly at a switch: recorded once
        assert len(sol.t_events[i]) == 1 and abs(sol.t_events[i][0] - ts) < 1e-12 * T
    reference = solve_ivp(changing_rhs, (0, T), OMEGA0, method="Radau", rtol=1e-12, atol=1e-14,
                          events=lambda t, w: w[2], dense_output=True)
    # r = 0 crossings: the same ones, each once; times to 1e-6 (BDF's error over a slope ~1)
    np.testing.assert_allclose(sol.t_events[-1], reference.t_events[0], atol=1e-6)
    times = np.linspace(0, T, 333)
    assert np.max(np.abs(sol(times) - reference.sol(times).T)) < 2e-6  # dense output over every segment


def test_ensemble_members_have_their_own_switches():
    stiff = g.MovingMassModel(g.Body(list(MM_MOMENTS)), mass=MASS, arm=ARM, frequency=FREQ, damping=DAMP)
    models = [changing_model(), g.Model(g.Body([1, 2, 3])), stiff]
    y0s = [OMEGA0, OMEGA0, stiff.quasi_static_state([1.0, 0.0, 1.0])]
    runs = g.solve_ensemble(models, y0s, (0, 2.0), method="auto", n_out=11)
    assert [len(r.method_switches) for r in runs][1:] == [0, 1]
    assert runs[2].method_switches[0][1] == "cvode_bdf"
    for model, y0, run in zip(models, y0s, runs):
        single = g.solve(model, y0, (0, 2.0), method="auto", n_out=11)
        np.testing.assert_array_equal(single.y, run.y)
        assert single.method_switches == run.method_switches


def test_auto_is_a_method_and_bad_input_errors_are_unchanged():
    assert "auto" in g.METHODS and g.Options().method == "dop853"
    with pytest.raises(ValueError, match="unknown method 'Auto'.*auto"):
        g.solve(changing_model(), OMEGA0, (0, 1), method="Auto")
    with pytest.raises(ValueError, match="rtol"):
        g.solve(changing_model(), OMEGA0, (0, 1), method="auto", rtol=-1.0)
    with pytest.raises(ValueError, match="y0"):
        g.solve(changing_model(), [np.nan, 0, 0], (0, 1), method="auto")
    # the closed form stays closed form
    assert g.solve(g.TorqueFreeModel(g.Body([1, 2, 3])), OMEGA0, (0, 1), method="auto").method == "closed_form"
