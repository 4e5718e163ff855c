"""Events and dense output, for every integrator and every model family.

References written here: the torque-free body's closed form (tests/references.py, SciPy's
ellipj) with its zero crossings found by SciPy's brentq; SciPy solve_ivp events on right-hand
sides written in this file; paper 003's exact r(t) = r0 exp(−∫b/C)."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

import gyrostat as g
from gyrostat import averaged, lagrange, orthogonal
from gyrostat.events import Event
from references import attitude_reference, euler_poinsot, quaternion_distance

J = np.array([1.0, 2.0, 3.0])
W0 = np.array([1.0, 0.5, -0.3])
INTEGRATORS = ["dop853", "taylor", "cvode_bdf", "cvode_adams", "arkode_fehlberg8", "auto"]


def exact_zeros(component, t1):
    """Times where ω_component of the torque-free body crosses zero on (0, t1]: sign changes of
    the closed form on a fine grid, refined by brentq to 1e-14."""
    grid = np.linspace(0.0, t1, 20001)
    values = euler_poinsot(J, W0, grid)[:, component]
    f = lambda t: euler_poinsot(J, W0, [t])[0, component]  # noqa: E731
    return np.array([brentq(f, grid[i], grid[i + 1], xtol=1e-14, rtol=1e-15)
                     for i in np.nonzero(np.sign(values[:-1]) * np.sign(values[1:]) < 0)[0]])


@pytest.mark.parametrize("method", INTEGRATORS + ["closed_form"])
def test_torque_free_zero_crossings_are_exact(method):
    t1 = 40.0
    exact = exact_zeros(1, t1)  # q = b sn(u): crosses zero twice a period
    model = g.TorqueFreeModel(g.Body(J)) if method == "closed_form" else g.Model(g.Body(J))
    sol = g.solve(model, W0, (0, t1), method=None if method == "closed_form" else method, rtol=1e-11, atol=1e-13,
                  n_out=5, events=Event("q"))
    found = sol.t_events[0]
    assert found.shape == exact.shape, (found, exact)
    # |q̇| ≥ 0.3 at these crossings, so a state error e moves a root by ≲ 3e: the methods' global
    # errors at rtol 1e-11 over 40 s are ≤ 1e-9 (cvode ≤ 1e-8): 1e-7 bounds them all; the
    # closed form is exact to rounding of the root search (a few ulps of t)
    bound = 1e-12 if method == "closed_form" else 1e-7
    assert np.max(np.abs(found - exact)) < bound, np.max(np.abs(found - exact))
    # y_events hold the state there: q = 0 to the root's precision, p, r the closed form's
    np.testing.assert_allclose(sol.y_events[0][:, 1], 0.0, atol=1e-9)
    np.testing.assert_allclose(sol.y_events[0][:, [0, 2]], euler_poinsot(J, W0, exact)[:, [0, 2]], atol=1e-7)


def forced_rhs(t, y):
    """J ω̇ = −ω × (Jω + k) + M0 − D ω (written here)."""
    k = np.array([0.1, -0.2, 0.3])
    M0 = np.array([0.0, 0.0, 0.05])
    D = np.array([[0.05, 0.01, 0.0], [0.0, 0.04, 0.005], [0.0, 0.0, 0.03]])
    w = y[:3]
    return (M0 - D @ w - np.cross(w, J * w + k)) / J


def forced_model():
    D = np.array([[0.05, 0.01, 0.0], [0.0, 0.04, 0.005], [0.0, 0.0, 0.03]])
    return g.Model(g.Body(J, [0.1, -0.2, 0.3]), [g.ConstantTorque([0, 0, 0.05]), g.LinearDamping(D)])


@pytest.mark.parametrize("method", INTEGRATORS)
def test_events_against_scipy(method):
    def q_crossing(t, y):
        return y[1] - 0.2

    q_crossing.direction = -1
    ref = solve_ivp(forced_rhs, (0, 60), W0, method="DOP853", rtol=1e-12, atol=1e-14,
                    events=[lambda t, y: y[2], q_crossing])
    sol = g.solve(forced_model(), W0, (0, 60), method=method, rtol=1e-11, atol=1e-13, n_out=3,
                  events=[Event("r"), Event("q", 0.2, direction=-1)])
    for k in range(2):
        assert sol.t_events[k].shape == ref.t_events[k].shape
        # both runs ~1e-10 accurate, |ṙ|, |q̇| ~ 0.1–1 at the crossings: 1e-7
        assert np.max(np.abs(sol.t_events[k] - ref.t_events[k])) < 1e-7
    # a Python callable (the slow path) finds the same crossings as the built-in event
    slow = g.solve(forced_model(), W0, (0, 60), method=method, rtol=1e-11, atol=1e-13, n_out=3,
                   events=[lambda t, y: y[2]])
    np.testing.assert_allclose(slow.t_events[0], sol.t_events[0], rtol=0, atol=1e-12)


def test_terminal_event_ends_the_run():
    sol = g.solve(forced_model(), W0, (0, 60), rtol=1e-11, atol=1e-13, n_out=601,
                  events=Event("r", terminal=True))
    ref = solve_ivp(forced_rhs, (0, 60), W0, method="DOP853", rtol=1e-12, atol=1e-14, events=[lambda t, y: y[2]])
    first = ref.t_events[0][0]
    assert sol.success and sol.terminal_event == 0 and "terminal event 0" in sol.message
    assert abs(sol.t_events[0][-1] - first) < 1e-7 and len(sol.t_events[0]) == 1
    assert sol.t[-1] <= first + 1e-7 and sol.t[-1] > first - 0.1  # outputs up to the event only
    # stop at the second crossing
    second = g.solve(forced_model(), W0, (0, 60), rtol=1e-11, atol=1e-13, events=Event("r", terminal=2))
    assert len(second.t_events[0]) == 2 and abs(second.t_events[0][1] - ref.t_events[0][1]) < 1e-7


def test_terminal_event_in_an_ensemble_leaves_the_others_unchanged():
    model = forced_model()
    starts = np.array([W0, [0.2, 0.1, 2.0], [1.0, -0.5, 0.4]])
    event = Event("r", value=-0.25, terminal=True)
    runs = g.solve_ensemble(model, starts, (0, 30), rtol=1e-10, n_out=31, events=event, threads=2)
    plain = [g.solve(model, w, (0, 30), rtol=1e-10, n_out=31) for w in starts]
    stopped = [r.terminal_event == 0 for r in runs]
    assert any(stopped) and not all(stopped)
    for run, alone, w in zip(runs, plain, starts):
        single = g.solve(model, w, (0, 30), rtol=1e-10, n_out=31, events=event)
        assert np.array_equal(run.y, single.y) and np.array_equal(run.t_events[0], single.t_events[0])
        if run.terminal_event is None:  # events do not change a trajectory
            assert np.array_equal(run.y, alone.y)
        else:
            assert np.array_equal(run.y, alone.y[:len(run)])


def test_paper_003_r_reaches_half_at_the_exact_time():
    # r(t) = r0 exp(−(b0 τ + b1 τ²/2)/C), τ = εt: r = r0/2 where b1 τ²/2 + b0 τ = C ln 2
    A, C, mu, eps, b = 1.5, 1.0, 0.5, 0.01, (1.0, 1.0)
    torque = lagrange.paper_torque(eps, (1.0, 1.0), b)
    y0 = lagrange.initial_state([0.0, 0.0, math.sqrt(3.0)], math.radians(60))
    tau = (-b[0] + math.sqrt(b[0] ** 2 + 2 * b[1] * C * math.log(2))) / b[1]
    t_exact = tau / eps
    half = Event("r", math.sqrt(3.0) / 2)
    for model in (lagrange.LagrangeTop(A, C, mu, [torque]), lagrange.LagrangeAveraged(A, C, mu, [torque])):
        sol = g.solve(model, y0, (0, 80), rtol=1e-11, atol=1e-13, n_out=3, events=half, check_validity=False)
        # r obeys C ṙ = −ε b(τ) r exactly in both models; |ṙ| ≈ 0.01: the root to ~1e-11/0.01
        assert abs(sol.t_events[0][0] - t_exact) < 1e-7 * t_exact, (type(model).__name__, sol.t_events[0])


def test_nutation_turning_points_reach_the_roots():
    # unperturbed top: cos θ oscillates between u1 and u2; at each turning point it is one of them
    top = lagrange.LagrangeTop(1.5, 1.0, 0.5)
    y0 = lagrange.initial_state([0.3, -0.2, 1.2], math.radians(40), math.radians(30))
    sol = g.solve(top, y0, (0, 30), rtol=1e-12, atol=1e-14, n_out=3, events=lagrange.turning_points())
    u1, u2 = sol["u1"][0], sol["u2"][0]
    cos_theta = lagrange.vertical(sol.y_events[0])[:, 2]
    assert len(cos_theta) >= 4
    distance = np.minimum(np.abs(cos_theta - u1), np.abs(cos_theta - u2))
    # a turning point is a double root in t: cos θ − u_i ~ (t − t*)², so 1e-9 in t gives ~1e-18;
    # the integration error of cos θ (rtol 1e-12) dominates: 1e-9
    assert np.max(distance) < 1e-9


def test_orthogonal_g_zero_against_scipy():
    A, K = np.array([2.0, 3.0, 4.0]), np.array([0.3, -0.2, 0.5])

    def rhs(t, y):  # the test's own: A ω̇ = −(1 − L/|Q|) Q, τ̇ = 1 − L/|Q| (|Q| stays ≫ δ here)
        w = y[:3]
        Q = np.cross(w, A * w + K)
        rate = 1 - (0.3 + 0.2 * np.sin(1.3 * t)) / np.linalg.norm(Q)
        return np.r_[-rate * Q / A, rate]

    def g_of(t, y):
        Q = np.cross(y[:3], A * y[:3] + K)
        return 1 - (0.3 + 0.2 * np.sin(1.3 * t)) / np.linalg.norm(Q)

    ref = solve_ivp(rhs, (0, 60), np.r_[1.0, 0.5, -0.8, 0.0], method="DOP853", rtol=1e-12, atol=1e-13, events=g_of)
    model = orthogonal.OrthogonalModel(g.Body(A, K), orthogonal.harmonic(0.3, [0.2], [1.3]))
    sol = g.solve(model, [1.0, 0.5, -0.8], (0, 60), rtol=1e-11, atol=1e-13, n_out=61, events=orthogonal.g_zero())
    report = orthogonal.tau_report(model, sol)
    crossings = np.array([c["t"] for c in report["crossings"]])
    assert crossings.shape == ref.t_events[0].shape
    assert np.max(np.abs(crossings - ref.t_events[0])) < 1e-7  # both ~1e-10; |ġ| = O(1)
    directions = [c["direction"] for c in report["crossings"]]
    assert directions[0] == "down" and all(a != b for a, b in zip(directions, directions[1:]))


def test_averaged_r_zero_and_validity_events():
    # paper 000's scene A = 8, C = 4 with the misprint-corrected sign: r passes through zero
    body = g.Body([8.0, 8.0, 4.0])
    torques = [g.ViscousCavity(1260.0, 1000.0, 0.48), g.ConstantTorque([0.0, 0.0, -0.01])]
    full = g.solve(g.Model(body, torques), [1.0, 0.0, 1.0], (0, 60), rtol=1e-10, n_out=3,
                   events=averaged.r_zero())
    slow = g.solve(g.AveragedModel(body, torques), [1.0, 1.0], (0, 60), rtol=1e-10, n_out=3,
                   events=[averaged.r_zero(), averaged.averaging_fails(0.5)], check_validity=False)
    assert len(full.t_events[0]) == 1 and len(slow.t_events[0]) == 1
    # the (a, r) reduction is exact for this symmetric scene: the same crossing to the tolerance
    assert abs(full.t_events[0][0] - slow.t_events[0][0]) < 1e-6
    # the averaging's assumption (slow/fast ≪ 1; 0.15 at the start here) fails before r reaches 0,
    # where the fast frequency vanishes: slow/fast rises through 0.5 first
    assert len(slow.t_events[1]) == 1 and slow.t_events[1][0] < slow.t_events[0][0]
    assert slow.y_events[1].shape == (1, 2) and slow.y_events[1][0, 1] > 0.0


# measured max |q − q_ref| at 2000 random times over [0, 50], rtol 1e-10 (ARKODE: its degree-5 Hermite interpolant)
DENSE_QUATERNION_ERROR = {"dop853": 5.1e-10, "taylor": 1.1e-11, "cvode_bdf": 1.3e-8, "cvode_adams": 3.0e-9, "arkode_fehlberg8": 2.5e-7}


@pytest.mark.parametrize("method, bound", [("dop853", 1e-8), ("taylor", 1e-8), ("cvode_bdf", 1e-6),
                                           ("cvode_adams", 1e-6), ("arkode_fehlberg8", 2e-6)])
def test_dense_output_between_steps(method, bound):
    t1 = 50.0
    sol = g.solve(g.Model(g.Body(J), attitude=True), W0, (0, t1), method=method, rtol=1e-10, atol=1e-12, n_out=2,
                  dense_output=True)
    t = np.sort(np.random.default_rng(7).uniform(0, t1, 2000))
    y = sol(t)
    exact = euler_poinsot(J, W0, t)
    # DOP853's, Taylor's and CVODE's continuous extensions have the method's order, so between
    # steps the error stays at the level of the global error at rtol 1e-10 (measured over 50 s:
    # dop853/taylor ~1e-9, CVODE ~1e-7); ARKODE's Hermite interpolant has degree 5 < 8, the
    # order of Fehlberg's table (measured 2.5e-7). The bounds leave a margin of ~5-10
    assert np.max(np.abs(y[:, :3] - exact)) < bound
    np.testing.assert_allclose(np.linalg.norm(y[:, 3:7], axis=1), 1.0, rtol=0, atol=4e-16)  # a unit quaternion
    # and the right one: against q̇ = ½ q ⊗ (0, ω) integrated here (no normalisation in the run);
    # measured DENSE_QUATERNION_ERROR between steps, bound 10× it
    ref = attitude_reference(J, (0, 0, 0), lambda t, w: (0.0, 0.0, 0.0), W0, sol.y[0, 3:7], np.r_[0.0, t])[1:]
    error = quaternion_distance(y[:, 3:7], ref[:, 3:])
    assert error < 10 * DENSE_QUATERNION_ERROR[method], f"{method}: {error:.2e}"
    assert sol(t[5]).shape == (7,) and np.array_equal(sol(t[5]), y[5])
    with pytest.raises(ValueError, match="outside the span"):
        sol(t1 + 1.0)


def test_dense_output_of_every_family():
    """Between the outputs, against references written here: the elliptic solution (closed
    form), SciPy on paper 000's averaged cavity (a, r) equations, SciPy on the servo torque's
    equations (J ω̇ = −(1 − L/|Q|) Q, τ̇ = 1 − L/|Q|, Q = ω × Jω); measured at the 10 midpoints
    3.0e-15, 9.0e-11, 1.1e-10 (rtol 1e-10); bounds 10× these."""
    kappa, Jo = 1260 * 0.48 / 1000, np.array([2.0, 3.0, 4.0])

    def averaged_cavity(t, y):
        a, r = y
        return [kappa * 4.0 * (8.0 - 4.0) * r * r * a / 8.0**3, kappa * (4.0 - 8.0) * a * a * r / (8.0 * 4.0)]

    def servo(t, y):
        w = y[:3]
        Q = np.cross(w, Jo * w)
        rate = 1 - 0.15 / np.linalg.norm(Q)
        return np.concatenate([-rate * Q / Jo, [rate]])

    def scipy(f, y0):
        return lambda t: solve_ivp(f, (0, 10), y0, method="DOP853", rtol=1e-13, atol=1e-14, t_eval=t).y.T

    middle = np.arange(10) + 0.5
    for model, y0, reference, measured in (
            (g.TorqueFreeModel(g.Body(J)), W0, lambda t: euler_poinsot(J, W0, t), 3.0e-15),
            (g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48)]), [1.0, 1.0],
             scipy(averaged_cavity, [1.0, 1.0]), 9.0e-11),
            (orthogonal.OrthogonalModel(g.Body([2.0, 3.0, 4.0]), 0.15), [1.0, 0.5, -0.8],
             scipy(servo, [1.0, 0.5, -0.8, 0.0]), 1.1e-10)):
        sol = g.solve(model, y0, (0, 10), rtol=1e-10, atol=1e-12, n_out=11, dense_output=True, check_validity=False)
        # at the output times the dense output and the recorded outputs are the same polynomial
        np.testing.assert_allclose(sol(sol.t), sol.y, rtol=0, atol=1e-12)
        error = np.max(np.abs(sol(middle) - reference(middle)))
        assert error < 10 * measured, (model, error)
    plain = g.solve(g.Model(g.Body(J)), W0, (0, 1), n_out=2)
    with pytest.raises(ValueError, match="dense_output=True"):
        plain(0.5)


def test_bad_events_name_the_problem():
    with pytest.raises(ValueError, match="'theta' is neither a state component .* nor an output"):
        g.solve(g.Model(g.Body(J)), W0, (0, 1), events=Event("theta"))
    with pytest.raises(ValueError, match="direction = 2"):
        Event("p", direction=2)
    with pytest.raises(TypeError, match="must be a gyrostat.events.Event or a callable"):
        g.solve(g.Model(g.Body(J)), W0, (0, 1), events=[3.0])

    def broken(t, y):
        raise ZeroDivisionError("inside the event")

    with pytest.raises(ZeroDivisionError, match="inside the event"):
        g.solve(g.Model(g.Body(J)), W0, (0, 1), events=broken)
