"""The exact free-body flow with attitude and the splitting integrators built on it.

References written here, independent of the library: Euler's equations and q̇ = ½ q ⊗ (0, ω)
integrated by SciPy's DOP853 at rtol 1e-13; the rotation matrix of a quaternion; the invariants
(the inertial angular momentum R(q) J ω, |G|, T).
"""

import math

import warnings

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
from gyrostat.events import Event
from references import cavity_torque

J = np.array([2.0, 3.0, 4.0])
SPLIT_SCENE_ERROR = 5.1e-14  # measured: splitting order 6, h = 0.1, scene of test_scene_with_splitting
SPLIT_TOP_SCENE_ERROR = 1.6e-12  # measured: order 6, h = 0.02, the Lagrange scene below
W0 = np.array([0.4, 0.9, -0.3])
Q0 = np.array([0.8, 0.1, -0.5, 0.3]) / np.linalg.norm([0.8, 0.1, -0.5, 0.3])


def rhs(t, y, moments, rotor=(0.0, 0.0, 0.0), torque=None):
    w, q = y[:3], y[3:]
    moments, rotor = np.asarray(moments), np.asarray(rotor)
    m = np.zeros(3) if torque is None else torque(t, w)
    dw = (m - np.cross(w, moments * w + rotor)) / moments
    qw, qx, qy, qz = q
    p, qq, r = w
    dq = 0.5 * np.array([-qx * p - qy * qq - qz * r, qw * p + qy * r - qz * qq, qw * qq + qz * p - qx * r,
                         qw * r + qx * qq - qy * p])
    return np.concatenate([dw, dq])


def reference(moments, w0, t, q0=Q0, rotor=(0.0, 0.0, 0.0), torque=None):
    y0 = np.concatenate([w0, q0])
    sol = solve_ivp(rhs, (t[0], t[-1]), y0, method="DOP853", t_eval=t, rtol=1e-13, atol=1e-14,
                    args=(moments, rotor, torque))
    y = sol.y.T
    y[:, 3:] /= np.linalg.norm(y[:, 3:], axis=1)[:, None]
    return y


def rotation(q):
    w, x, y, z = q / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
                     [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
                     [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]])


def same_sign(q, ref):
    """q and −q are one rotation: align each row of q with the reference's sign."""
    return q * np.sign(np.sum(q * ref, axis=1))[:, None]


def exact(moments, w0, t, q0=Q0, rotor=(0.0, 0.0, 0.0)):
    model = g.TorqueFreeModel(g.Body(moments, rotor), attitude=True)
    return g.solve(model, np.concatenate([w0, q0]), (t[0], t[-1]), t_eval=t)


def energy_ordering(moments, w0):
    """+1: the polhode encircles the largest axis (G² > 2TB), −1: the smallest."""
    moments, w0 = np.asarray(moments), np.asarray(w0)
    return np.sign(np.sum(moments * (moments - moments[1]) * w0 ** 2))


CASES = {
    # name: (moments, ω0); the orderings checked in the test
    "largest_axis": ([2.0, 3.0, 4.0], [0.4, 0.9, -0.3]),
    "smallest_axis": ([2.0, 3.0, 4.0], [1.0, 0.3, 0.2]),
    "relabelled_odd": ([3.0, 4.0, 2.0], [0.2, -0.3, 1.1]),
    "relabelled_cyclic": ([4.0, 2.0, 3.0], [-0.5, 0.8, 0.6]),
}


@pytest.mark.parametrize("name", CASES)
def test_exact_attitude_against_integrated_quaternion(name):
    moments, w0 = CASES[name]
    t = np.linspace(0.0, 60.0, 301)
    ref = reference(moments, w0, t)
    sol = exact(moments, w0, t)
    # SciPy's DOP853 at rtol 1e-13 over ~10 periods: ~1e-11; the closed form: rounding
    assert np.max(np.abs(sol.y[:, :3] - ref[:, :3])) < 1e-9
    assert np.max(np.abs(same_sign(sol.y[:, 3:], ref[:, 3:]) - ref[:, 3:])) < 1e-9
    # the closed form's quaternion is continuous in t (no jumps between q and −q)
    assert np.max(np.linalg.norm(np.diff(sol.y[:, 3:], axis=0), axis=1)) < 0.2


def test_both_energy_orderings_are_covered():
    assert energy_ordering(*CASES["largest_axis"]) == 1
    assert energy_ordering(*CASES["smallest_axis"]) == -1


@pytest.mark.parametrize("name", CASES)
def test_inertial_angular_momentum_is_constant_at_any_horizon(name):
    """Basilisk's convention check: with q rotating body into inertial axes, R(q) J ω is fixed.
    |G| and T exact to rounding at any t (the closed form's cost does not depend on t), and so is
    R(q) J ω (its phases formed in double-double)."""
    moments, w0 = CASES[name]
    moments = np.asarray(moments)
    t = np.array([0.0, 1.0, 1e3, 1e5, 1e7, 1e9])
    sol = exact(moments, w0, t)
    g_in = np.array([rotation(q) @ (moments * w) for w, q in zip(sol.y[:, :3], sol.y[:, 3:])])
    G = np.linalg.norm(moments * np.asarray(w0))
    # the phases in double-double: rounding of the double evaluation only, at every horizon
    # (measured ≤ 9e-16 relative up to t = 1e9; with double phases it was 2e-7 at 1e9)
    assert np.max(np.abs(g_in - g_in[0])) < 1e-14 * G
    # |G| and T: relative rounding only, at every horizon
    assert np.max(np.abs(sol["angular_momentum_norm"] / G - 1)) < 1e-14
    T = 0.5 * np.sum(moments * np.asarray(w0) ** 2)
    assert np.max(np.abs(sol["kinetic_energy"] / T - 1)) < 1e-14


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_near_the_separatrix(side):
    """ω0 within 1e-6 (relative) of the separatrix G² = 2TB, on either side."""
    moments = np.array([2.0, 3.0, 4.0])
    # on the separatrix: A(A−B) p² + C(C−B) r² = 0 → p² = 2 r²
    r = 0.5
    w0 = np.array([np.sqrt(2.0) * r * (1.0 + side * 1e-6), 0.05, r])
    assert energy_ordering(moments, w0) == -side
    t = np.linspace(0.0, 40.0, 201)
    ref = reference(moments, w0, t)
    sol = exact(moments, w0, t)
    # the separatrix amplifies errors (Lyapunov growth ~e^{λt} on the homoclinic loop);
    # SciPy's DOP853 at rtol 1e-13 is good to ~1e-10 here: 1e-8 allowed
    assert np.max(np.abs(sol.y[:, :3] - ref[:, :3])) < 1e-8
    assert np.max(np.abs(same_sign(sol.y[:, 3:], ref[:, 3:]) - ref[:, 3:])) < 1e-8


def test_symmetric_body_and_axial_rotor():
    t = np.linspace(0.0, 50.0, 201)
    for moments, rotor in (([2.0, 2.0, 3.5], [0.0, 0.0, 0.0]), ([2.0, 2.0, 3.5], [0.0, 0.0, 0.7]),
                           ([3.0, 2.0, 2.0], [-0.4, 0.0, 0.0]), ([2.5, 2.5, 2.5], [0.3, -0.2, 0.5])):
        ref = reference(moments, W0, t, rotor=rotor)
        sol = exact(moments, W0, t, rotor=rotor)
        # SciPy at rtol 1e-13 over ~10 turns: ~1e-11
        assert np.max(np.abs(sol.y[:, :3] - ref[:, :3])) < 1e-9, (moments, rotor)
        assert np.max(np.abs(same_sign(sol.y[:, 3:], ref[:, 3:]) - ref[:, 3:])) < 1e-9, (moments, rotor)


def test_gyrostat_without_closed_form_is_refused():
    with pytest.raises(ValueError, match="closed form here only.*rotor k = \\(0.1, 0, 0.2\\)"):
        g.TorqueFreeModel(g.Body([2.0, 3.0, 4.0], [0.1, 0.0, 0.2]), attitude=True)
    model = g.Model(g.Body([2.0, 3.0, 4.0], [0.1, 0.0, 0.2]))
    with pytest.raises(ValueError, match="closed form here only"):
        g.solve(model, W0, (0, 1), method="splitting", step=0.1)


# --- splitting ----------------------------------------------------------------------------------

EPS = 0.05


def linear_case():
    D = EPS * np.array([[1.0, 0.2, 0.0], [0.0, 0.5, 0.1], [0.3, 0.0, 2.0]])
    M0 = EPS * np.array([0.1, -0.2, 0.05])
    torques = [g.LinearDamping(D), g.ConstantTorque(M0)]
    return torques, (lambda t, w: M0 - D @ w)


def split_run(model, y0, t_span, **options):
    """A splitting run that may doubt its own answer: an AccuracyWarning is expected exactly when
    its own error estimate exceeds rtol (or its step was clamped to the span)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always", g.AccuracyWarning)
        sol = g.solve(model, y0, t_span, method="splitting", **options)
    said = [str(w.message) for w in caught if issubclass(w.category, g.AccuracyWarning)]
    rtol = options.get("rtol", g.Options().rtol)
    assert any("exceeds rtol" in m for m in said) == (sol.error_estimate > rtol), (said, sol.error_estimate)
    assert all(m in sol.notes for m in said)
    return sol


def honest(sol, error):
    """The splitting's error estimate has the measured error's order of magnitude: at least a third
    of it (measured 0.58 on the Lagrange top at order 2 over t = 4, where phase errors grow
    faster than the linear sum of local errors) and at most 100 times it (measured 10-60 on the
    rigid body: the local errors of an oscillating solution partly cancel, which the linear sum
    does not assume); at the rounding floor only the lower bound is asked."""
    assert error <= 3 * sol.error_estimate, (error, sol.error_estimate)
    assert error < 1e-12 or sol.error_estimate <= 100 * error, (error, sol.error_estimate)


def cavity_case():
    cavity = g.ViscousCavity(EPS, 1.0, 1.0)  # κ = ρ P0 / ν = ε
    return [cavity], None


@pytest.mark.parametrize("order", [2, 4, 6])
def test_order_of_splitting_with_exact_perturbation_flow(order):
    torques, torque = linear_case()
    model = g.Model(g.Body(J), torques, attitude=True)
    t = np.array([0.0, 8.0])
    ref = reference(J, W0, np.linspace(0, 8.0, 3), torque=torque)[-1]
    steps = {2: (0.4, 0.2), 4: (0.8, 0.4), 6: (1.6, 0.8)}[order]
    errors = []
    for h in steps:
        sol = split_run(model, np.concatenate([W0, Q0]), (0, 8.0), t_eval=t, step=h, splitting_order=order)
        y = sol.y[-1]
        y[3:] *= np.sign(y[3:] @ ref[3:])
        errors.append(np.max(np.abs(y - ref)))
        honest(sol, errors[-1])
    measured = np.log2(errors[0] / errors[1])
    # the error ratio at halved step is 2^order asymptotically; ±0.5 for the pre-asymptotic range
    assert abs(measured - order) < 0.5, (errors, measured)


def test_order_of_splitting_with_the_cavity():
    """The cavity's perturbation flow is one 8th-order step per sub-step: the composition keeps
    its order (measured against SciPy with the cavity torque written here from the paper)."""
    torques, _ = cavity_case()
    model = g.Model(g.Body(J), torques, attitude=True)
    # the torque of paper 002 eq. (1), written in tests/references.py; ViscousCavity(ε, 1, 1): κ = ρ P0/ν = ε
    torque = lambda t, w: cavity_torque(w, J, EPS)  # noqa: E731
    # the written-out torque is internal: G·M = 0
    m = torque(0.0, W0)
    assert abs(np.dot(J * W0, m)) < 1e-15
    t_end = 8.0
    ref = reference(J, W0, np.array([0.0, t_end]), torque=torque)[-1]
    for order, steps in ((2, (0.4, 0.2)), (4, (0.8, 0.4))):
        errors = []
        for h in steps:
            sol = split_run(model, np.concatenate([W0, Q0]), (0, t_end), t_eval=[0, t_end], step=h, splitting_order=order)
            y = sol.y[-1]
            y[3:] *= np.sign(y[3:] @ ref[3:])
            errors.append(np.max(np.abs(y - ref)))
            honest(sol, errors[-1])
        measured = np.log2(errors[0] / errors[1])
        assert abs(measured - order) < 0.5, (order, errors, measured)


def test_splitting_keeps_G_when_the_perturbation_does():
    """The cavity conserves |G| (an internal torque): both sub-flows keep it, so the splitting
    keeps it to rounding over a long run (no secular drift), while T decays."""
    torques, _ = cavity_case()
    model = g.Model(g.Body(J), torques)
    sol = split_run(model, W0, (0, 2e4), step=0.5, splitting_order=4, n_out=11)
    G = sol["angular_momentum_norm"]
    # each step ends projected on |Jω| = |G(0)| (splitting.hpp): rounding of that projection
    # only, never accumulated (without it: 1e-13 here, 2.6e-11 over 2e6 steps, a drift)
    assert np.max(np.abs(G / G[0] - 1)) < 1e-15
    assert sol["kinetic_energy"][-1] < 0.99 * sol["kinetic_energy"][0]
    # the projection keeps |G| whatever the sub-flows do: the sub-flows themselves are checked
    # by the whole ω against SciPy with the cavity torque written in tests/references.py, over
    # t ≤ 200 (T falls from 1.555 to 1.18): order 4 at h = 0.5, measured 2.0e-6; 10× it
    t = np.linspace(0, 200, 5)
    short = split_run(model, W0, (0, 200), step=0.5, splitting_order=4, t_eval=t)
    ref = solve_ivp(lambda s, w: (cavity_torque(w, J, EPS) - np.cross(w, J * w)) / J, (0, 200), W0, method="DOP853",
                    rtol=1e-12, atol=1e-14, t_eval=t).y.T
    assert np.max(np.abs(short.y - ref)) < 2e-5, np.max(np.abs(short.y - ref))


def test_torque_free_splitting_is_the_exact_flow():
    model = g.Model(g.Body(J), attitude=True)
    t = np.linspace(0, 100, 11)
    split = g.solve(model, np.concatenate([W0, Q0]), (0, 100), t_eval=t, method="splitting", step=3.0)
    closed = exact(J, W0, t)
    # composition of exact flows: rounding per sub-flow
    assert np.max(np.abs(split.y[:, :3] - closed.y[:, :3])) < 1e-12
    assert np.max(np.abs(same_sign(split.y[:, 3:], closed.y[:, 3:]) - closed.y[:, 3:])) < 1e-11


def test_events_dense_output_and_ensembles_with_splitting():
    torques, torque = linear_case()
    model = g.Model(g.Body(J), torques)
    opts = dict(method="splitting", step=0.05, splitting_order=6)
    sol = g.solve(model, W0, (0, 20), events=Event("q", 0.0),
                  dense_output=True, n_out=5, **opts)
    ref = solve_ivp(lambda t, w: rhs(t, np.concatenate([w, Q0]), J, torque=torque)[:3], (0, 20), W0, method="DOP853",
                    rtol=1e-13, atol=1e-14, events=lambda t, w: w[1], dense_output=True)
    # order-6 splitting at h = 0.05 with ε = 0.05: ~1e-10; events located to a few ulps on it
    assert np.allclose(sol.t_events[0], ref.t_events[0], atol=1e-8, rtol=0)
    # the kept dense output is cubic Hermite: O(h⁴ |ω⁽⁴⁾|) ≈ 1e-6
    tt = np.linspace(0.3, 19.7, 37)
    assert np.max(np.abs(np.array([sol(x) for x in tt]) - ref.sol(tt).T)) < 1e-5
    members = g.solve_ensemble(model, np.array([W0, 1.1 * W0]), (0, 20), n_out=5, **opts)
    assert np.array_equal(members[0].y, g.solve(model, W0, (0, 20), n_out=5, **opts).y)


def test_splitting_progress_and_interrupt(ctrl_c):
    import threading
    import time

    model = g.Model(g.Body(J), [g.LinearDamping(np.eye(3) * 1e-4)])
    seen = []
    timer = threading.Timer(0.3, ctrl_c)
    timer.start()
    started = time.perf_counter()
    # at most 6e6 steps, ~10 s (~6e5 steps a second): a lost signal fails the test instead of waiting for minutes
    with pytest.warns(RuntimeWarning, match="interrupted"):
        sol = g.solve(model, W0, (0, 1e8), method="splitting", step=0.1, max_steps=6 * 10**6, n_out=1001,
                      progress=seen.append)
    timer.join()
    # stopped within the poll interval (0.1 s) plus the signal's delay; progress was reported
    assert time.perf_counter() - started < 2.0
    assert sol.status == "interrupted" and 1 <= len(sol) < 1001 and seen and 0 <= seen[-1] < 1


@pytest.mark.parametrize("step", [0.0, -1.0, float("nan")])
def test_bad_splitting_step(step):
    model = g.Model(g.Body(J))
    with pytest.raises(ValueError, match="step = "):
        g.solve(model, W0, (0, 1), method="splitting", step=step)


# issue 44: a body (1, 2, 3) under M0 = (0.02, 0, -0.03) and D = diag(0.05, 0.02, 0.03) from
# (0.7, -0.4, 0.9) over (0, 100). Its composite steps err by a floor of ~7e-15 each (the
# sub-flows' constants recomputed from the state round alike step after step), which adds up
# linearly: counted as a random walk, the estimate read 7.6e-13 at order 4, rtol 1e-11, where the
# error was 3.2e-10 (order 2 at 1e-9: 6.3e-12 against 6.1e-9; order 6 at 1e-10: 3.9e-13 against
# 5.2e-11), and a smaller step did not take the error below ~1e-10.
FLOOR_J, FLOOR_W0 = np.array([1.0, 2.0, 3.0]), np.array([0.7, -0.4, 0.9])
FLOOR_M, FLOOR_D = np.array([0.02, 0.0, -0.03]), np.diag([0.05, 0.02, 0.03])


@pytest.fixture(scope="module")
def floor_reference():
    def euler(t, w):  # A ω̇ = (A ω) × ω + M0 − D ω, written here
        return (np.cross(FLOOR_J * w, w) + FLOOR_M - FLOOR_D @ w) / FLOOR_J
    return solve_ivp(euler, (0.0, 100.0), FLOOR_W0, method="DOP853", rtol=1e-13, atol=1e-15, dense_output=True).sol


@pytest.mark.parametrize("order, rtol", [(4, 1e-11), (2, 1e-9), (6, 1e-10)])
def test_the_splitting_estimate_sees_its_rounding_floor(order, rtol, floor_reference):
    """The estimate lies within [1/2, 30] x the error measured against SciPy (the error floored at
    1e-10, the contract's "near rounding" floor: SciPy's own error at rtol 1e-13 over t = 100 is
    ~1e-12), and the run warns exactly when its estimate exceeds rtol, naming the steps' rounding
    when that is what dominates (no smaller step would help)."""
    model = g.Model(g.Body(FLOOR_J), [g.ConstantTorque(FLOOR_M), g.LinearDamping(FLOOR_D)])
    sol = split_run(model, FLOOR_W0, (0.0, 100.0), splitting_order=order, rtol=rtol, n_out=101)
    truth = floor_reference(sol.t).T
    error = np.abs(sol.y - truth).max() / np.abs(truth).max()
    assert 0.5 * error <= sol.error_estimate <= 30 * max(error, 1e-10), (error, sol.error_estimate)
    if error > rtol:  # the run missed rtol: it must have said so, with the number
        assert any("exceeds rtol" in note for note in sol.notes), (error, sol.notes)


@pytest.mark.parametrize("rtol", [1e-6, 1e-10])
def test_splitting_chooses_its_step_from_rtol(rtol):
    """step left out: h from the splitting's own probe at t0, so that the run meets rtol (against
    SciPy with the damping written here; the estimate is conservative, so the error lands below
    rtol, and the step is no smaller than needed by more than the estimate's factor (≤ 100)^(1/4)
    ≈ 3.2 against the h that would just meet rtol)."""
    torques, torque = linear_case()
    model = g.Model(g.Body(J), torques, attitude=True)
    ref = reference(J, W0, np.array([0.0, 8.0]), torque=torque)[-1]
    sol = split_run(model, np.concatenate([W0, Q0]), (0, 8.0), t_eval=[0, 8.0], rtol=rtol, atol=1e-3 * rtol)
    y = sol.y[-1]
    y[3:] *= np.sign(y[3:] @ ref[3:])
    error = np.max(np.abs(y - ref))
    assert error <= rtol and sol.error_estimate <= rtol, (error, sol.error_estimate)
    assert any("chosen from rtol" in note for note in sol.notes)
    h = sol.stats["last_step"]
    # order 4: the error with 3.2x the step would be ~100x larger; it must not still meet rtol/10
    coarser = split_run(model, np.concatenate([W0, Q0]), (0, 8.0), t_eval=[0, 8.0], step=3.2 * h, rtol=0.5)
    y = coarser.y[-1]
    y[3:] *= np.sign(y[3:] @ ref[3:])
    assert np.max(np.abs(y - ref)) > 0.1 * error, (h, error)


def test_a_step_above_the_span_is_clamped_and_estimated():
    """The issue's case: step = 10 over (0, 5) returned success with a 9.1 % error. Now: one step of
    5 with a warning saying so, and the estimate of that step's error above rtol with a warning."""
    torques, torque = linear_case()
    model = g.Model(g.Body(J), torques)
    ref = reference(J, W0, np.array([0.0, 5.0]), q0=Q0, torque=torque)[-1, :3]
    with pytest.warns(g.AccuracyWarning) as caught:
        sol = g.solve(model, W0, (0, 5), method="splitting", step=10.0, n_out=2)
    said = " ".join(str(w.message) for w in caught)
    assert "exceeds the span" in said and "exceeds rtol" in said and sol.stats["steps"] == 1
    honest(sol, np.max(np.abs(sol.y[-1] - ref)))


def test_splitting_needs_a_model_that_splits():
    with pytest.raises(ValueError, match="splitting_order = 3"):
        g.solve(g.Model(g.Body(J)), W0, (0, 1), method="splitting", step=0.1, splitting_order=3)
    averaged = g.AveragedModel(g.Body([2.0, 2.0, 1.0]))
    with pytest.raises(ValueError, match="'averaged_symmetric' model does not split"):
        g.solve(averaged, [1.0, 0.5], (0, 1), method="splitting", step=0.1)
    # a gyrostat whose free flow has no closed form: the body and its rotor are named
    rotor = g.Body(J, [0.3, -0.2, 0.5])
    for model in (g.Model(rotor, [g.LinearDamping(1e-3 * np.eye(3))]), g.orthogonal.OrthogonalModel(rotor, 0.1)):
        with pytest.raises(ValueError, match=r"closed form.*rotor k = \(0.3, -0.2, 0.5\)"):
            g.solve(model, W0, (0, 1), method="splitting", step=0.1)


def test_auto_scene_picks_the_exact_flow_with_attitude():
    from gyrostat.scene import Scene

    doc = {"body": {"moments": [2, 3, 4]}, "initial": {"omega": list(W0), "attitude": list(Q0)},
           "integration": {"t_span": [0, 50]}}
    scene = Scene.from_dict(doc)
    assert scene.model_choice == "closed_form" and "attitude included" in scene.model_reason
    run = scene.runs[0]
    sol = g.solve(run.model, run.y0, run.t_span, t_eval=[0.0, 50.0])
    ref = reference(J, W0, np.array([0.0, 50.0]))
    assert np.max(np.abs(same_sign(sol.y[:, 3:], ref[:, 3:]) - ref[:, 3:])) < 1e-9


def test_scene_with_splitting():
    from gyrostat.scene import Scene, SceneError

    doc = {"body": {"moments": [2, 3, 4]}, "initial": {"omega": list(W0)},
           "torques": [{"type": "linear_damping", "matrix": (1e-3 * np.eye(3)).tolist()}],
           "integration": {"t_span": [0, 10], "method": "splitting", "step": 0.1, "splitting_order": 6, "n_out": 3}}
    run = Scene.from_dict(doc).runs[0]
    assert run.options["step"] == 0.1 and run.options["splitting_order"] == 6
    sol = g.solve(run.model, run.y0, run.t_span, **run.options)
    t_out = np.linspace(*run.t_span, 3)
    ref = solve_ivp(lambda t, w: rhs(t, np.r_[w, Q0], J, torque=lambda t, w: -1e-3 * w)[:3], run.t_span, W0,
                    method="DOP853", t_eval=t_out, rtol=1e-13, atol=1e-14).y.T  # M = −1e-3 ω written here
    # order 6, h = 0.1, ε = 1e-3: measured SPLIT_SCENE_ERROR; 10× it
    assert np.max(np.abs(sol.y - ref)) < 10 * SPLIT_SCENE_ERROR, np.max(np.abs(sol.y - ref))
    del doc["integration"]["step"]  # left out: chosen from rtol
    run = Scene.from_dict(doc).runs[0]
    sol = g.solve(run.model, run.y0, run.t_span, **run.options)
    assert any("chosen from rtol" in note for note in sol.notes)
    assert np.max(np.abs(sol.y - ref)) < run.options["rtol"]
    doc["integration"]["step"] = 100.0  # the scene: one step over [0, 10], 2.8 % off, exit 0
    run = Scene.from_dict(doc).runs[0]
    with pytest.warns(g.AccuracyWarning) as caught:
        sol = g.solve(run.model, run.y0, run.t_span, **run.options)
    said = " ".join(str(w.message) for w in caught)
    assert "clamped to one step of 10" in said and "exceeds rtol" in said
    honest(sol, np.max(np.abs(sol.y - ref)))
    with pytest.raises(SceneError, match="step"):
        doc["integration"]["step"] = -1.0
        Scene.from_dict(doc).runs


def test_splitting_step_budget():
    sol = g.solve(g.Model(g.Body(J)), W0, (0, 10), method="splitting", step=0.1, max_steps=20, n_out=11)
    # 20 steps of 0.1 reach t = 2: outputs at 0, 1, 2 are kept
    assert sol.status == "max_steps_reached" and "needs 100 steps" in sol.message
    assert np.allclose(sol.t, [0.0, 1.0, 2.0])


def test_exact_flow_of_a_decayed_rate():
    """ω(t; s ω0) = s ω(s t; ω0) and q(t; s ω0) = q(s t; ω0): at s = 1e-160 (ω² would underflow)
    the flow keeps all its digits (it works with ω0/max|ω0_i| and the time s t)."""
    t = np.linspace(0.0, 30.0, 31)
    ref = exact(J, W0, t)
    tiny = exact(J, 1e-160 * W0, t * 1e160)
    # the same formulas on the same unit vector: rounding only
    assert np.max(np.abs(tiny.y[:, :3] * 1e160 - ref.y[:, :3])) < 1e-13
    assert np.max(np.abs(tiny.y[:, 3:] - ref.y[:, 3:])) < 1e-12


def mp_free_body_largest_axis(t, dps=40):
    """ω(t), q(t) of the free body I = J, ω0 = W0, q0 = Q0 in mpmath at `dps` digits, written here
    independently of the library: no relabelling (C = J[2] is the axis the polhode encircles for
    this ω0, checked), ω = (a cn u, b sn u, ±c dn u), u = ν t + u0 (Landau & Lifshitz §37) by
    mpmath's ellipfun; R(t) = R_in Rz(φ) Rx(θ) Rz(ψ) with θ, ψ the z-x-z angles of g = Jω/|G| and
    φ = ∫ φ̇ dt, φ̇ = |G| (2T − C ω3²)/(G² − C² ω3²), by QUADRATURE (mpmath.quad): n times the
    integral over one period P = 4K/|ν| plus the rest (not the library's Π(N | m) / Carlson R_J)."""
    import mpmath as mp

    with mp.workdps(dps):
        A, B, C = (mp.mpf(x) for x in J)
        w = [mp.mpf(x) for x in W0]
        G2 = (A * w[0]) ** 2 + (B * w[1]) ** 2 + (C * w[2]) ** 2
        T2 = A * w[0] ** 2 + B * w[1] ** 2 + C * w[2] ** 2
        G = mp.sqrt(G2)
        assert G2 > T2 * B  # the polhode encircles the largest axis C
        a = mp.sqrt((T2 * C - G2) / (A * (C - A)))
        b = mp.sqrt((T2 * C - G2) / (B * (C - B)))
        c = mp.sqrt((G2 - T2 * A) / (C * (C - A)))
        m = (B - A) * (T2 * C - G2) / ((C - B) * (G2 - T2 * A))
        sign3 = 1 if w[2] >= 0 else -1
        nu = (C - B) * b * c * sign3 / (A * a)  # A ω̇1 = (B − C) ω2 ω3 with ω1 = a cn, ω2 = b sn
        u0 = mp.ellipf(mp.atan2(w[1] / b, w[0] / a), m)
        period = 4 * mp.ellipk(m) / abs(nu)

        def omega(s):
            u = nu * s + u0
            return [a * mp.ellipfun("cn", u, m=m), b * mp.ellipfun("sn", u, m=m), sign3 * c * mp.ellipfun("dn", u, m=m)]

        def phi_rate(s):
            w3 = omega(s)[2]
            return G * (T2 - C * w3 ** 2) / (G2 - C ** 2 * w3 ** 2)

        def qmul(p, q):
            return [p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
                    p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
                    p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
                    p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]]

        def euler(wv):  # q_x(θ) ⊗ q_z(ψ), g = (sin θ sin ψ, sin θ cos ψ, cos θ)
            g = [A * wv[0] / G, B * wv[1] / G, C * wv[2] / G]
            theta, psi = mp.acos(g[2]), mp.atan2(g[0], g[1])
            return qmul([mp.cos(theta / 2), mp.sin(theta / 2), 0, 0], [mp.cos(psi / 2), 0, 0, mp.sin(psi / 2)])

        e0 = euler(omega(0))
        q_in = qmul([mp.mpf(x) for x in Q0], [e0[0], -e0[1], -e0[2], -e0[3]])
        per_period = mp.quad(phi_rate, mp.linspace(0, period, 9))
        out = []
        for tk in t:
            tk = mp.mpf(tk)
            n = mp.floor(tk / period)
            rest = tk - n * period
            dphi = n * per_period + (mp.quad(phi_rate, mp.linspace(0, rest, 9)) if rest > 0 else 0)
            wv = omega(tk)
            q = qmul(qmul(q_in, [mp.cos(dphi / 2), 0, 0, mp.sin(dphi / 2)]), euler(wv))
            out.append([float(x) for x in wv] + [float(x) for x in q])
        return np.array(out)


def test_exact_flow_at_long_horizons_against_mpmath():
    """Issue 13's target: ω and q within 1e-12 at t = 1e6 and 1e7. The reference (above) keeps
    40 − 7 = 33 digits in its phases at t = 1e7; the flow forms its phases in double-double and
    evaluates the reduced arguments in double (~1e-15). 1e-12 is the target; with the constants
    in double (before) the error was 9e-10 at 1e7, ~1e-16·|ω|·t, and this test failed."""
    t = np.array([0.0, 12.5, 1e6, 1e7])
    ref = mp_free_body_largest_axis(t)
    sol = exact(J, W0, t)
    assert np.max(np.abs(sol.y[:, :3] - ref[:, :3])) < 1e-12 * np.linalg.norm(W0)
    assert np.max(np.abs(same_sign(sol.y[:, 3:], ref[:, 3:]) - ref[:, 3:])) < 1e-12


def test_symmetric_flow_at_long_horizons_against_mpmath():
    """The symmetric body with an axial rotor and the spherical gyrostat at t = 1e7 and 1e9, against
    ω(t) = exp(t [λ]×) ω0, q(t) = q_rot(t G_in/A) ⊗ q0 ⊗ q_rot(−t λ) (λ = ((C − A) ω·e + k·e)/A e,
    or k/A for the sphere) evaluated here in mpmath at 40 digits. The flow forms the angles |λ| t,
    |G| t/A in double-double and reduces them modulo 4π: rounding only (1e-12 allowed, the issue's
    target; with the angles in double the error was ~1e-16·|λ|·t, 1e-7 at t = 1e9)."""
    import mpmath as mp

    t = np.array([0.0, 1e7, 1e9])
    for moments, rotor in (([2.0, 2.0, 3.5], [0.0, 0.0, 0.7]), ([2.5, 2.5, 2.5], [0.3, -0.2, 0.5])):
        sol = exact(moments, W0, t, rotor=rotor)
        with mp.workdps(40):
            Jm, k, w0 = ([mp.mpf(x) for x in v] for v in (moments, rotor, W0))
            A = Jm[0]
            lam = [x / A for x in k] if moments[2] == moments[0] else [0, 0, ((Jm[2] - A) * w0[2] + k[2]) / A]
            qw, qx, qy, qz = (x / mp.sqrt(sum(mp.mpf(y) ** 2 for y in Q0)) for x in map(mp.mpf, Q0))
            R0 = mp.matrix([[1 - 2 * (qy ** 2 + qz ** 2), 2 * (qx * qy - qw * qz), 2 * (qx * qz + qw * qy)],
                            [2 * (qx * qy + qw * qz), 1 - 2 * (qx ** 2 + qz ** 2), 2 * (qy * qz - qw * qx)],
                            [2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx ** 2 + qy ** 2)]])
            G_in = R0 * mp.matrix([Jm[i] * w0[i] + k[i] for i in range(3)])  # |G_in| = |G_b| to 40 digits

            def q_rot(v):
                angle = mp.sqrt(sum(x ** 2 for x in v))
                s = mp.sin(angle / 2) / angle
                return [mp.cos(angle / 2)] + [s * x for x in v]

            def qmul(p, q):
                return [p[0] * q[0] - p[1] * q[1] - p[2] * q[2] - p[3] * q[3],
                        p[0] * q[1] + p[1] * q[0] + p[2] * q[3] - p[3] * q[2],
                        p[0] * q[2] - p[1] * q[3] + p[2] * q[0] + p[3] * q[1],
                        p[0] * q[3] + p[1] * q[2] - p[2] * q[1] + p[3] * q[0]]

            for tk, y in zip(t[1:], sol.y[1:]):
                tk = mp.mpf(tk)
                ql = q_rot([tk * x for x in lam])
                w = qmul(qmul(ql, [0] + w0), [ql[0], -ql[1], -ql[2], -ql[3]])[1:]
                q = qmul(qmul(q_rot([tk * x / A for x in G_in]), [mp.mpf(x) for x in Q0]),
                         [ql[0], -ql[1], -ql[2], -ql[3]])
                ref_w, ref_q = np.array([float(x) for x in w]), np.array([float(x) for x in q])
                assert np.max(np.abs(y[:3] - ref_w)) < 1e-12, (moments, rotor, tk)
                assert np.max(np.abs(y[3:] * np.sign(y[3:] @ ref_q) - ref_q)) < 1e-12, (moments, rotor, tk)


# ----------------------------------------------------------------------------------------------
# The heavy (Lagrange) top and the orthogonal servo torque split too
# ----------------------------------------------------------------------------------------------
TOP_A, TOP_C, TOP_MU = 1.5, 1.0, 0.5
TOP_Y0 = g.lagrange.initial_state([0.3, -0.2, 3.0], 0.6)


def top_rhs(torque):
    """The heavy top written here: A ṗ = (A − C) q r + μ γ2 + M1, A q̇ = (C − A) p r − μ γ1 + M2,
    C ṙ = M3, Q̇ = ½ Q ⊗ (0, ω), γ (upward vertical in body axes) = third row of R(Q)."""
    J_top = np.array([TOP_A, TOP_A, TOP_C])

    def f(t, y):
        p, q, r = y[:3]
        gamma = rotation(y[3:])[2]
        free_and_gravity = np.array([(TOP_A - TOP_C) * q * r + TOP_MU * gamma[1],
                                     (TOP_C - TOP_A) * p * r - TOP_MU * gamma[0], 0.0])
        dy = rhs(t, y, J_top)  # for Q̇ (its ω part is replaced below)
        dy[:3] = (free_and_gravity + torque(t, y[:3])) / J_top
        return dy
    return f


def top_cases():
    """(torques, M(t, ω) written here): constant + linear (the exact perturbation flow) and the
    paper's resistive medium M = −ε(a(τ) p, a(τ) q, b(τ) r), a = b = 1 + τ, τ = ε t (the
    8th-order sub-step)."""
    D = np.diag([0.05, 0.05, 0.02])
    M0 = np.array([0.0, 0.01, 0.03])
    eps = 0.05
    return {"affine": ([g.ConstantTorque(M0), g.LinearDamping(D)], lambda t, w: M0 - D @ w),
            "medium": ([g.lagrange.paper_torque(eps)], lambda t, w: -eps * (1 + eps * t) * w)}


@pytest.mark.parametrize("case", ["affine", "medium"])
def test_order_of_splitting_for_the_lagrange_top(case):
    torques, torque = top_cases()[case]
    top = g.lagrange.LagrangeTop(TOP_A, TOP_C, TOP_MU, torques)
    t_end = 4.0
    sol = solve_ivp(top_rhs(torque), (0, t_end), TOP_Y0, method="DOP853", rtol=1e-13, atol=1e-14)
    ref = sol.y[:, -1] / np.r_[np.ones(3), [np.linalg.norm(sol.y[3:, -1])] * 4]
    # the engine's right-hand side is the one written here (the split is of the same equations)
    assert np.max(np.abs(top.rhs(0.7, TOP_Y0) - top_rhs(torque)(0.7, TOP_Y0))) < 1e-14
    for order, steps in ((2, (0.04, 0.02)), (4, (0.16, 0.08)), (6, (0.32, 0.16))):
        errors = []
        for h in steps:
            sol = split_run(top, TOP_Y0, (0, t_end), t_eval=[0, t_end], step=h, splitting_order=order)
            y = sol.y[-1]
            y[3:] *= np.sign(y[3:] @ ref[3:])
            errors.append(np.max(np.abs(y - ref)))
            honest(sol, errors[-1])
        measured = np.log2(errors[0] / errors[1])
        # 2^order at halved step asymptotically; ±0.5 for the pre-asymptotic range
        assert abs(measured - order) < 0.5, (case, order, errors, measured)


def test_lagrange_top_splitting_keeps_Gz_and_r():
    """Without torques the free top keeps the inertial G and r, and the gravity kick is a
    horizontal torque with no axial part: G_z and r are kept to rounding at any step; H, not
    kept by either sub-flow, stays bounded (a symplectic composition), no drift."""
    top = g.lagrange.LagrangeTop(TOP_A, TOP_C, TOP_MU)
    sol = split_run(top, TOP_Y0, (0, 2000), step=0.1, splitting_order=4, n_out=201)
    Gz, H, r = sol["G_z"], sol["H"], sol.y[:, 2]
    # rounding only: measured 1.2e-13 relative over 2e4 steps (1.3e-12 over 2e5: ~6e-18 a step),
    # where DOP853 at rtol 1e-12 drifts by 1e-10; r exactly
    assert np.max(np.abs(Gz - Gz[0])) < 1e-12 * abs(Gz[0])
    assert np.max(np.abs(r - r[0])) < 1e-15 * abs(r[0])
    dH = np.abs(H / H[0] - 1)
    # order-4 energy error at h = 0.1: measured 1.9e-7, the same in both halves of the run; 10× it
    assert np.max(dH) < 2e-6 and np.max(dH[100:]) < 2 * np.max(dH[:101]), np.max(dH)


def orthogonal_rhs(moments, L, delta_eta=1e-3):
    """The orthogonal servo torque written here (rigid body): J ω̇ = −(1 − L/n) Q, Q = ω × Jω,
    τ̇ = 1 − L/n, n = |Q| above δ = η|ω||G| and (|Q|² + δ²)/(2δ) below; q̇ = ½ q ⊗ (0, ω)."""
    def f(t, y):
        w = y[:3]
        G = moments * w
        Q = np.cross(w, G)
        d = delta_eta * np.linalg.norm(w) * np.linalg.norm(G)
        n = np.linalg.norm(Q)
        g_rate = 1.0 - L(t) / (n if n >= d else (n * n + d * d) / (2 * d))
        dy = rhs(t, y[:7], moments)
        dy[:3] = -g_rate * Q / moments
        return np.concatenate([dy, [g_rate]])
    return f


def test_order_of_splitting_for_the_orthogonal_torque():
    w0 = np.array([1.0, 0.5, -0.8])
    model = g.orthogonal.OrthogonalModel(g.Body(J), g.orthogonal.harmonic(0.1, [0.1], [1.3]), attitude=True)
    y0 = np.concatenate([w0, Q0, [0.0]])
    t_end = 6.0
    sol = solve_ivp(orthogonal_rhs(J, lambda t: 0.1 + 0.1 * np.sin(1.3 * t)), (0, t_end), y0, method="DOP853",
                    rtol=1e-13, atol=1e-14)
    ref = sol.y[:, -1]
    ref[3:7] /= np.linalg.norm(ref[3:7])
    for order, steps in ((2, (0.04, 0.02)), (4, (0.16, 0.08)), (6, (0.32, 0.16))):
        errors = []
        for h in steps:
            sol = split_run(model, y0, (0, t_end), t_eval=[0, t_end], step=h, splitting_order=order)
            y = sol.y[-1]
            y[3:7] *= np.sign(y[3:7] @ ref[3:7])
            errors.append(np.max(np.abs(y - ref)))  # ω, q and τ
            honest(sol, errors[-1])
        measured = np.log2(errors[0] / errors[1])
        assert abs(measured - order) < 0.5, (order, errors, measured)
    # the servo torque is along Q ⊥ G: |G| projected on, kept to rounding over 2e4 steps
    run = split_run(model, y0, (0, 2000), step=0.1, n_out=11)
    G = run["angular_momentum_norm"]
    assert np.max(np.abs(G / G[0] - 1)) < 1e-15
    # Q ⊥ ω too, so the quasi-energy ωᵀJω (paper 004 (6)) is kept by both sub-flows, and it is not
    # projected on: a test of the sub-flows themselves. Measured 9.8e-15 over the 2e4 steps; 10× it
    h = np.einsum("ni,i,ni->n", run.y[:, :3], J, run.y[:, :3])
    assert np.max(np.abs(h / h[0] - 1)) < 1e-13, np.max(np.abs(h / h[0] - 1))
    # with L = 0 the splitting is the exact flow and τ = t (rounding per step)
    free = g.orthogonal.OrthogonalModel(g.Body(J), 0.0, attitude=True)
    split = g.solve(free, y0, (0, 50), t_eval=[0, 50], method="splitting", step=0.5).y[-1]
    closed = exact(J, w0, np.array([0.0, 50.0])).y[-1]
    assert np.max(np.abs(split[:3] - closed[:3])) < 1e-13
    assert np.max(np.abs(same_sign(split[None, 3:7], closed[None, 3:]) - closed[3:])) < 1e-12
    assert abs(split[7] - 50.0) < 1e-12


def test_new_families_split_in_ensembles_and_scenes():
    from gyrostat.scene import Scene, SceneError

    top = g.lagrange.LagrangeTop(TOP_A, TOP_C, TOP_MU, top_cases()["medium"][0])
    opts = dict(method="splitting", step=0.05, n_out=5, rtol=1e-3)  # bit for bit, not accuracy, is checked
    y0s = [TOP_Y0, g.lagrange.initial_state([0.1, 0.2, 2.5], 1.0)]
    members = g.solve_ensemble(top, y0s, (0, 10), **opts)
    for y0, member in zip(y0s, members):  # the scalar path: the same numbers as one solve
        assert np.array_equal(member.y, g.solve(top, y0, (0, 10), **opts).y)
    servo = g.orthogonal.OrthogonalModel(g.Body(J), 0.1)
    assert np.array_equal(g.solve_ensemble(servo, [W0], (0, 10), **opts)[0].y, g.solve(servo, W0, (0, 10), **opts).y)
    # a Lagrange scene with splitting: the full top only, against DOP853 at rtol 1e-12
    doc = {"kind": "lagrange_top", "body": {"A": TOP_A, "C": TOP_C, "mu": TOP_MU},
           "torque": {"epsilon": 0.05, "a": [1.0, 1.0], "b": [1.0, 1.0]},
           "initial": {"omega": [0.3, -0.2, 3.0], "theta_deg": math.degrees(0.6)},
           "integration": {"model": "full", "method": "splitting", "step": 0.02, "splitting_order": 6,
                           "tau_end": 0.2, "n_out": 3}}
    run = Scene.from_dict(doc).runs[0]
    sol = g.solve(run.model, run.y0, run.t_span, **run.options)
    # the top's equations written here (top_rhs) with the paper's medium, ε = 0.05
    eps = 0.05
    ref = solve_ivp(top_rhs(lambda t, w: -eps * (1 + eps * t) * w), run.t_span, run.y0, method="DOP853",
                    t_eval=np.linspace(*run.t_span, 3), rtol=1e-13, atol=1e-14).y.T
    ref[:, 3:] = same_sign(ref[:, 3:] / np.linalg.norm(ref[:, 3:], axis=1)[:, None], sol.y[:, 3:])
    # order 6 at h = 0.02 over t = 4: measured SPLIT_TOP_SCENE_ERROR; 10× it
    assert np.max(np.abs(sol.y - ref)) < 10 * SPLIT_TOP_SCENE_ERROR, np.max(np.abs(sol.y - ref))
    doc["integration"]["model"] = "compare"
    with pytest.raises(SceneError, match="splits the full top only"):
        Scene.from_dict(doc).runs
    averaged = {"kind": "averaged", "body": {"moments": [2, 2, 1]}, "initial": {"a": 1.0, "r": 0.5},
                "integration": {"t_span": [0, 1], "method": "splitting"}}
    with pytest.raises(SceneError, match="not offered for averaged scenes"):
        Scene.from_dict(averaged).runs
