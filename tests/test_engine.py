"""One engine for every model family: each family through gyrostat.solve and
gyrostat.solve_ensemble, the Solution's names and guards, progress and Ctrl-C.

References written here: SciPy solve_ivp (DOP853, rtol 1e-12) on right-hand sides written in this
file, and the quantities each model records recomputed here from the recorded states."""

import math
import sys
import threading
import time

import numpy as np
import pytest
from scipy.integrate import solve_ivp

import gyrostat as g
from gyrostat import lagrange, orthogonal
from references import moving_mass_rhs

BODY = g.Body([1.0, 2.0, 3.0])
W0 = np.array([1.0, 0.5, -0.3])


def _families():
    """(name, model, y0, SciPy right-hand side written here for the state, or None)."""
    J = np.array([1.0, 2.0, 3.0])
    D = 0.05 * np.eye(3)

    def euler(t, y):  # J ω̇ = −ω × Jω − D ω
        w = y[:3]
        return (np.cross(J * w, w) - D @ w) / J

    def euler_attitude(t, y):
        w, q = y[:3], y[3:7]
        qw, qx, qy, qz = q
        p, qq, r = w
        dq = 0.5 * np.array([-qx * p - qy * qq - qz * r, qw * p + qy * r - qz * qq, qw * qq + qz * p - qx * r,
                             qw * r + qx * qq - qy * p])
        return np.concatenate([euler(t, y), dq])

    A, C, mu, eps = 1.5, 1.0, 0.5, 0.01
    torque = lagrange.paper_torque(eps, (1.0, 0.0), (1.0, 0.0))  # M = −ε(p, q, r)
    top0 = lagrange.initial_state([0.1, 0.0, 1.7], 0.4)

    def top(t, y):  # γ = third row of R(Q); A ṗ = (A − C) q r + μ γ2 − ε p, …
        p, q, r, qw, qx, qy, qz = y
        g1, g2 = 2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx)
        dq = 0.5 * np.array([-qx * p - qy * q - qz * r, qw * p + qy * r - qz * q, qw * q + qz * p - qx * r,
                             qw * r + qx * q - qy * p])
        return np.concatenate([[((A - C) * q * r + mu * g2 - eps * p) / A, ((C - A) * p * r - mu * g1 - eps * q) / A,
                                -eps * r / C], dq])

    def averaged_cavity(t, y):  # paper 000 (5) as derived: ȧ = κC(A − C)r²a/A³, ṙ = κ(C − A)a²r/(AC)
        a, r = y
        kappa, A8, C4 = 1260 * 0.48 / 1000, 8.0, 4.0
        return [kappa * C4 * (A8 - C4) * r * r * a / A8**3, kappa * (C4 - A8) * a * a * r / (A8 * C4)]

    Jo, k, L = np.array([2.0, 3.0, 4.0]), np.array([0.3, -0.2, 0.5]), 0.15

    def servo(t, y):  # J ω̇ = −(1 − L/|Q|) Q, τ̇ = 1 − L/|Q|, Q = ω × (Jω + k)
        w = y[:3]
        Q = np.cross(w, Jo * w + k)
        rate = 1 - L / np.linalg.norm(Q)
        return np.concatenate([-rate * Q / Jo, [rate]])

    return [
        ("gyrostat", g.Model(BODY, [g.LinearDamping(D)]), W0, euler),
        ("gyrostat_attitude", g.Model(BODY, [g.LinearDamping(D)], attitude=True),
         np.concatenate([W0, [1.0, 0, 0, 0]]), euler_attitude),
        ("torque_free", g.TorqueFreeModel(BODY), W0, lambda t, y: np.cross(J * y, y) / J),
        ("averaged", g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48)]),
         np.array([1.0, 1.0]), averaged_cavity),
        ("moving_mass", g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), 1, 1, 10, 98), None,
         moving_mass_rhs([4.0, 4.0, 2.0], 1.0, 1.0, 100.0, 98.0)),
        ("lagrange_top", lagrange.LagrangeTop(A, C, mu, [torque]), top0, top),
        ("lagrange_averaged", lagrange.LagrangeAveraged(A, C, mu, [torque]), top0, top),
        ("orthogonal", orthogonal.OrthogonalModel(g.Body(Jo, k), L), np.concatenate([[1.0, 0.5, -0.8], [0.0]]), servo),
    ]


FAMILIES = _families()
# measured max |y − y_SciPy| over t ∈ [0, 5] at rtol 1e-11 (cvode_bdf for the stiff moving mass)
REFERENCE_ERROR = {"gyrostat": 1.1e-11, "gyrostat_attitude": 4.7e-12, "torque_free": 6.5e-13, "averaged": 1.1e-11,
                   "moving_mass": 4.3e-10, "lagrange_top": 1.1e-11, "orthogonal": 7.9e-12}


@pytest.mark.parametrize("name, model, y0, reference", FAMILIES, ids=[f[0] for f in FAMILIES])
def test_every_family_solves_and_ensembles(name, model, y0, reference):
    if y0 is None:
        y0 = model.quasi_static_state([1.0, 0.0, 1.0])
    method = "cvode_bdf" if name == "moving_mass" else "dop853"
    options = dict(method=method, rtol=1e-11, atol=1e-13, n_out=21, check_validity=False)
    sol = g.solve(model, y0, (0.0, 5.0), **options)
    assert sol.success, sol.message
    assert sol.state_names == model.state_names and sol.y.shape == (21, model.dim)
    assert sol.output_names == model.output_names and all(sol[n].shape == (21,) for n in sol.output_names)
    if name == "lagrange_averaged":  # the averaged top against the full top written here
        A, C, mu, eps = 1.5, 1.0, 0.5, 0.01  # the family's top and torque (above)
        ref = solve_ivp(reference, (0.0, 5.0), y0, method="DOP853", rtol=1e-12, atol=1e-14, t_eval=sol.t).y.T
        p, q, r, qw, qx, qy, qz = ref.T
        g1, g2, g3 = 2 * (qx * qz - qw * qy), 2 * (qy * qz + qw * qx), 1 - 2 * (qx * qx + qy * qy)
        Gz, H = A * (p * g1 + q * g2) + C * r * g3, 0.5 * (A * (p * p + q * q) + C * r * r) + mu * g3
        # (3.3): r is exact, r0 exp(−εt/C) for b = 1; rounding and the tolerance
        np.testing.assert_allclose(sol.y[:, 2], 1.7 * np.exp(-eps * sol.t / C), rtol=0, atol=1e-11)
        # G_z and H: the full top's oscillate about the averaged ones by O(ε): measured 1.5e-3 and
        # 1.9e-3 (ε = 0.01, t ≤ 5) while they change by 0.070 and 0.146; 3× it (a wrong averaged
        # rate is off by the change itself)
        assert np.max(np.abs(sol.y[:, 0] - Gz)) < 4.5e-3, np.max(np.abs(sol.y[:, 0] - Gz))
        assert np.max(np.abs(sol.y[:, 1] - H)) < 6e-3, np.max(np.abs(sol.y[:, 1] - H))
    elif reference is not None:
        ref = solve_ivp(reference, (0.0, 5.0), model.initial_state(y0), method="DOP853", rtol=1e-12, atol=1e-14,
                        t_eval=sol.t)
        # both at tolerances ≤ 1e-11 over 5 time units: measured REFERENCE_ERROR[name]; 10× it
        error = np.max(np.abs(sol.y - ref.y.T))
        assert error < 10 * REFERENCE_ERROR[name], (name, error)
    # three members of the same family (different initial states): identical to single runs
    y0s = [np.asarray(y0, float) * s for s in (1.0, 0.9, 1.1)] if name != "lagrange_averaged" else [y0] * 3
    if "q_w" in model.state_names or name == "lagrange_averaged":  # keep the quaternion a rotation
        y0s = [y0, y0, y0]
    # (batch=False: SIMD batches equal single runs to the tolerance only; tests/test_batch.py)
    members = g.solve_ensemble(model, y0s, (0.0, 5.0), threads=2, batch=False, **options)
    batched = g.solve_ensemble(model, y0s, (0.0, 5.0), threads=2, **options)
    for y, member, in_batch in zip(y0s, members, batched):
        single = g.solve(model, y, (0.0, 5.0), **options)
        assert np.array_equal(member.y, single.y) and np.array_equal(member.outputs[sol.output_names[0]],
                                                                     single.outputs[sol.output_names[0]])
        # batched or not, at rtol 1e-10 the member agrees with its single run well within 1e-7
        np.testing.assert_allclose(in_batch.y, single.y, rtol=0, atol=1e-7 * max(1.0, np.abs(single.y).max()))


def test_ensemble_mixes_families():
    models = [f[1] for f in FAMILIES if f[2] is not None]
    y0s = [f[2] for f in FAMILIES if f[2] is not None]
    runs = g.solve_ensemble(models, y0s, (0.0, 2.0), n_out=5, rtol=1e-9, check_validity=False, batch=False)
    for model, y0, run in zip(models, y0s, runs):
        single = g.solve(model, y0, (0.0, 2.0), n_out=5, rtol=1e-9, check_validity=False)
        assert run.state_names == model.state_names and np.array_equal(run.y, single.y)


def test_recorded_outputs_are_the_physics():
    # The gyrostat with attitude: |G|, T from the recorded ω; Euler angles from the recorded q
    # through SciPy's Rotation (intrinsic "ZXZ" = Rz Rx Rz), rounding only: 1e-12.
    from scipy.spatial.transform import Rotation

    model = g.Model(g.Body([1.0, 2.0, 3.0], [0.0, 0.1, 0.2]), [g.ConstantTorque([0.0, 0.0, 0.1])], attitude=True)
    sol = g.solve(model, W0, (0, 20), n_out=101)
    J, k = np.array([1.0, 2.0, 3.0]), np.array([0.0, 0.1, 0.2])
    np.testing.assert_allclose(sol["angular_momentum_norm"], np.linalg.norm(sol.omega * J + k, axis=1), rtol=1e-14)
    np.testing.assert_allclose(sol["kinetic_energy"], 0.5 * np.sum(J * sol.omega**2, axis=1), rtol=1e-14)
    R = Rotation.from_quat(sol.quaternion[:, [1, 2, 3, 0]])
    back = Rotation.from_euler("ZXZ", sol.euler_angles())
    assert np.max((R.inv() * back).magnitude()) < 1e-12
    assert sol.euler_angles()[0].tolist() == [0.0, 0.0, 0.0]  # the identity (was ψ = π)
    # the orthogonal model: g = 1 − L/|Q|, |Q|, δ = η|ω||G| recomputed here (rounding: 1e-13)
    Jo, kk, L = np.array([2.0, 3.0, 4.0]), np.array([0.3, -0.2, 0.5]), orthogonal.harmonic(0.1, [0.1], [1.3])
    om = orthogonal.OrthogonalModel(g.Body(Jo, kk), L)
    s = g.solve(om, [1.0, 0.5, -0.8], (0, 30), n_out=61)
    G = s.omega * Jo + kk
    Q = np.linalg.norm(np.cross(s.omega, G), axis=1)
    law = 0.1 + 0.1 * np.sin(1.3 * s.t)
    np.testing.assert_allclose(s["Q_norm"], Q, rtol=1e-13)
    np.testing.assert_allclose(s["L"], law, rtol=0, atol=1e-15)
    np.testing.assert_allclose(s["g"], 1 - law / Q, rtol=0, atol=1e-13)
    np.testing.assert_allclose(s["delta"], 1e-3 * np.linalg.norm(s.omega, axis=1) * np.linalg.norm(G, axis=1),
                               rtol=1e-13)


def test_solution_guards_and_names():
    mm = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), 1, 1, 10, 98)
    sol = g.solve(mm, mm.quasi_static_state([1, 0, 1]), (0, 1), method="cvode_bdf", n_out=3)
    with pytest.raises(ValueError, match=r"no attitude: its state is \(p, q, r, u_1"):
        sol.quaternion
    with pytest.raises(KeyError, match="'psi' is neither a state component"):
        sol["psi"]
    assert sol["u_1"].shape == (3,) and "energy" in sol and sol.invariants.keys() == {"angular_momentum_norm"}
    averaged = g.solve(g.AveragedModel(g.Body([8.0, 8.0, 4.0])), [1.0, 1.0], (0, 1), n_out=3, check_validity=False)
    with pytest.raises(ValueError, match=r"no angular velocity in its state \(a, r\)"):
        averaged.omega


def test_bad_calls_name_what_is_wrong():
    with pytest.raises(TypeError, match="model must be a gyrostat model") as refused:
        g.solve("not a model", W0, (0, 1))
    named = set(str(refused.value).split("(", 1)[1].split(")", 1)[0].split(", "))  # from ModelBase's subclasses
    assert named >= {"Model", "AveragedModel", "TriaxialAveragedModel", "MovingMassModel", "TorqueFreeModel",
                     "LagrangeTop", "LagrangeAveraged", "OrthogonalModel"}
    with pytest.raises(TypeError, match="TriaxialAveragedModel"):
        g.solve_ensemble([object()], [W0], (0, 1))
    with pytest.raises(ValueError, match=r"initial state has 5 components; this model needs 7 \(p, q, r, q_w"):
        g.solve(g.Model(BODY, attitude=True), np.ones(5), (0, 1))
    with pytest.raises(ValueError, match=r"t_span must be \(t0, t1\)"):
        g.solve(g.Model(BODY), W0, (0, 1, 2))
    with pytest.raises(ValueError, match="t_span must be two numbers"):
        g.solve(g.Model(BODY), W0, ("zero", 1))
    with pytest.raises(ValueError, match=r"n_out = 2.7 must be a whole number"):
        g.solve(g.Model(BODY), W0, (0, 1), n_out=2.7)
    with pytest.raises(ValueError, match="quaternion .* is not a rotation"):
        g.solve(g.Model(BODY, attitude=True), [1, 0, 0, 0, 0, 0, 0], (0, 1))
    with pytest.raises(ValueError, match="amplitude a = .* must be >= 0; got a = -1"):
        g.solve(g.AveragedModel(g.Body([8.0, 8.0, 4.0])), [-1.0, 1.0], (0, 1))
    with pytest.raises(ValueError, match="unknown method 'rk4'"):
        g.solve(g.Model(BODY), W0, (0, 1), method="rk4")


def test_options_are_one_object_with_the_defaults():
    o = g.Options()
    assert (o.method, o.rtol, o.atol, o.n_out, o.max_steps) == ("dop853", 1e-8, 1e-10, 1001, 1_000_000)
    sol = g.solve(g.Model(BODY), W0, (0, 1))
    assert len(sol) == 1001 and sol.method == "dop853"
    o.rtol, o.n_out = 1e-12, 5
    tight = g.solve(g.Model(BODY), W0, (0, 1), options=o)
    assert len(tight) == 5 and g.Options().rtol == 1e-8  # a user's Options never changes the defaults


def test_the_option_names_are_written_once(monkeypatch):
    """``gyrostat.options.OPTIONS`` is the one list of integration options: it holds every option of
    the C++ ``Options`` (its scalars, ``t_eval``; events and dense output are keywords of their
    own), and the keywords that solve, solve_ensemble and ensemble_results spell out for their
    readers are exactly its names, so that a new option added to the list and not to a signature
    (or the other way round) fails here."""
    import inspect

    from gyrostat import accuracy, options
    from gyrostat.solve import ensemble_results

    assert set(options.OPTIONS) == set(g.Options().to_dict()) - {"dense_output"} | {"t_eval"}
    for name, kind in options.OPTIONS.items():
        if name != "t_eval":
            assert type(getattr(g.Options(), name)) is kind, name
    others = {"model", "models", "y0", "y0s", "t_span", "threads", "options", "events", "dense_output", "progress",
              "check_validity", "batch", "accuracy", "error_estimate", "compare", "sensitivities"}
    for function in (g.solve, g.solve_ensemble, ensemble_results):
        keywords = set(inspect.signature(function).parameters) - others
        assert keywords == set(options.OPTION_NAMES), function.__name__
    assert "_OPTION_NAMES" not in vars(accuracy)  # the companions copy the options by the one list
    # each function hands its option keywords on in the order of OPTIONS (solve names them for speed)
    seen = []

    def caught(opts, values, listed=None):
        seen.append(dict(zip(options.OPTION_NAMES, values)))
        raise KeyboardInterrupt

    distinct = {name: f"<{name}>" for name in options.OPTION_NAMES}
    for module in ("gyrostat.solve", "gyrostat.ensemble"):
        monkeypatch.setattr(sys.modules[module], "options_of", caught)
    for function in (g.solve, g.solve_ensemble, ensemble_results):
        with pytest.raises(KeyboardInterrupt):
            function(g.Model(BODY), [W0], (0, 1), **distinct)
    assert seen == [distinct] * 3
    with pytest.raises(TypeError, match="options are method, rtol, atol, t_eval, n_out"):
        options.make_options(tolerance=1e-9)


def test_t_eval_lists_reuse_their_options_and_keep_every_check():
    """t_eval given as a list is cached with its values and their types: the same
    list again gives the same output times, another list others, and every bad one is still
    refused on every call, naming the value."""
    model = g.Model(BODY)
    for _ in range(2):
        assert g.solve(model, W0, (0.0, 1.0), t_eval=[0.0, 0.5, 1.0]).t.tolist() == [0.0, 0.5, 1.0]
        assert g.solve(model, W0, (0.0, 1.0), t_eval=(0, 1)).t.tolist() == [0.0, 1.0]
        assert g.solve(model, W0, (0.0, 1.0), t_eval=[0.25]).t.tolist() == [0.25]
        with pytest.raises(ValueError, match=r"t_eval\[1\] = 2 lies outside"):
            g.solve(model, W0, (0.0, 1.0), t_eval=[0.0, 2.0])
        with pytest.raises(ValueError, match=r"t_eval must be output times .*got \[0\.0, 'a'\]"):  # the list given
            g.solve(model, W0, (0.0, 1.0), t_eval=[0.0, "a"])
        assert g.solve(model, W0, (0.0, 1.0), t_eval=[1.0]).t.tolist() == [1.0]  # kept; [True] == [1.0], refused:
        with pytest.raises(ValueError, match="t_eval must be output times"):
            g.solve(model, W0, (0.0, 1.0), t_eval=[True])  # True == 1, yet a boolean is no time
        with pytest.raises(ValueError, match="t_eval must be one-dimensional"):
            g.solve(model, W0, (0.0, 1.0), t_eval=[[0.0, 1.0]])
        with pytest.raises(ValueError, match="give t_eval or n_out, not both"):
            g.solve(model, W0, (0.0, 1.0), t_eval=[0.0, 1.0], n_out=2)
    assert g.solve(model, W0, (0.0, 1.0), t_eval=[1]).t.tolist() == [1.0]
    # a float array of the state is used as it is; others are converted (or refused) as before
    assert np.array_equal(g.solve(model, np.array(W0, np.float32), (0.0, 1.0), n_out=2).y[0], np.float32(W0))
    with pytest.raises(ValueError, match="y0 must be real numbers"):
        g.solve(model, np.array(["a", "b", "c"]), (0.0, 1.0))


def test_progress_is_reported_and_changes_nothing():
    from gyrostat import _core

    model = g.Model(BODY, [g.LinearDamping(1e-4 * np.eye(3))], attitude=True)
    fractions = []
    watched = g.solve(model, W0, (0, 3000), rtol=1e-10, n_out=101, progress=fractions.append)
    plain = g.solve(model, W0, (0, 3000), rtol=1e-10, n_out=101)
    assert np.array_equal(watched.y, plain.y) and watched.stats == plain.stats
    # the engine polls at most every `interval` seconds (0.1 from gyrostat.solve); with 0 it
    # reports every 64 steps: many reports, in order, and still the same trajectory
    options = g.Options()
    options.rtol, options.n_out = 1e-10, 101
    result = _core.solve(model._core, np.concatenate([W0, [1.0, 0, 0, 0]]), 0.0, 3000.0, options,
                         fractions.append, 0.0)
    assert len(fractions) > 10 and fractions == sorted(fractions) and 0 <= fractions[0] and fractions[-1] <= 1
    assert np.array_equal(np.asarray(result.y), plain.y)


def _interrupt_soon(ctrl_c, delay=0.3):
    timer = threading.Timer(delay, ctrl_c)
    timer.start()
    return timer


def test_ctrl_c_stops_a_solve_and_keeps_what_was_computed(ctrl_c):
    # a run that would take ~10 s (2e7 steps at ~2e6 a second, t up to 1e8 out of reach): a lost
    # signal fails the test (max_steps_reached) instead of waiting for minutes
    model = g.Model(BODY, attitude=True)
    timer = _interrupt_soon(ctrl_c)
    started = time.perf_counter()
    with pytest.warns(RuntimeWarning, match="interrupted"):
        sol = g.solve(model, W0, (0, 1e8), n_out=100001, max_steps=2 * 10**7)
    elapsed = time.perf_counter() - started
    timer.join()
    assert sol.status == "interrupted" and "interrupted at t =" in sol.message
    assert 1 < len(sol) < 100001 and np.all(np.isfinite(sol.y))
    assert elapsed < 2.0  # stopped within the poll interval (0.1 s) plus the signal's delay


def test_ctrl_c_stops_an_ensemble(ctrl_c):
    # 8 members of 1e7 steps on 2 threads: ~7 s uninterrupted (~6e6 steps a second a thread)
    model = g.Model(BODY)
    timer = _interrupt_soon(ctrl_c)
    started = time.perf_counter()
    runs = g.solve_ensemble(model, np.tile(W0, (8, 1)), (0, 1e8), n_out=11, max_steps=10**7, threads=2)
    timer.join()
    assert time.perf_counter() - started < 2.0
    assert {r.status for r in runs} == {"interrupted"}


def test_progress_callback_error_is_raised():
    def broken(fraction):
        raise ZeroDivisionError("from the callback")

    with pytest.raises(ZeroDivisionError, match="from the callback"):
        g.solve(g.Model(BODY, attitude=True), W0, (0, 1e8), n_out=11, max_steps=10**12, progress=broken)


def test_reprs_read():
    # numbers as their shortest round-trip text (Python's repr drops ".0" too, like format_value)
    assert repr(g.ConstantTorque([0, 0, 0.5])) == "ConstantTorque(moment=[0, 0, 0.5])"
    assert repr(g.MovingMassDamper(1, 1, 10, 98)) == "MovingMassDamper(mass=1, arm=1, frequency=10, damping=98)"
    assert repr(orthogonal.harmonic(0.1, [0.2], [1.3])) == \
        "MagnitudeLaw.harmonic(mean=0.1, amplitudes=[0.2], frequencies=[1.3], phases=[0])"
    assert "Model(" in repr(g.Model(BODY)) and "Options(method='dop853'" in repr(g.Options())


def test_wrong_shapes_are_value_errors_naming_the_value():
    # not pybind11's list of signatures: one line naming what was expected and what was given
    cases = [(lambda: g.Body([1, 2]), r"Body: moments must be 3 numbers, got \[1, 2\]"),
             (lambda: g.Body([1, 2, 3], rotor="k"), r"Body: rotor must be 3 numbers, got 'k'"),
             (lambda: g.ConstantTorque([0, 1]), r"ConstantTorque: moment must be 3 numbers"),
             (lambda: g.LinearDamping(np.eye(2)), r"LinearDamping: matrix must be 3x3 numbers"),
             (lambda: g.ResistiveMedium([np.eye(3), np.eye(2)]), r"ResistiveMedium: coefficient 1 must be 3x3")]
    for make, message in cases:
        with pytest.raises(ValueError, match=message) as error:
            make()
        assert "\n" not in str(error.value)
    with pytest.raises(ValueError, match=r"max_steps = 1180591620717411303424 is too large"):
        g.solve(g.Model(BODY), W0, (0, 1), max_steps=2**70)
    with pytest.raises(ValueError, match=r"threads = 1099511627776 must be a whole number of at most 4096"):
        g.solve_ensemble(g.Model(BODY), [W0], (0, 1), threads=2**40)


def test_edge_values_give_right_answers():
    # a table spanning the whole double range: the width overflows, its halves do not
    assert orthogonal.tabulated([-1e308, 1e308], [0.0, 1.0])(0.0) == 0.5
    assert orthogonal.tabulated([-1e308, 1e308], [-1e308, 1e308])(0.0) == 0.0
    # atol = 0 with a component that is exactly zero (and stays so: rotation about a principal
    # axis): 0/0 in the error scale is no error, not "the solution overflows"
    sol = g.solve(g.Model(BODY), [1.0, 0.0, 0.0], (0, 10), atol=0.0, n_out=3)
    assert sol.success and np.array_equal(sol.omega[-1], [1.0, 0.0, 0.0])


def test_unreachable_and_oversized_requests_are_refused():
    # (G_z, H, r) with H < C r²/2 − μ: p² + q² would be negative for every θ
    avg = lagrange.LagrangeAveraged(1.5, 1.0, 0.5)
    with pytest.raises(ValueError, match=r"\(G_z, H, r\) = \(0\.5, -10, 1\) is not a state of the top"):
        g.solve(avg, [0.5, -10.0, 1.0], (0, 1))
    # a reachable state on the separatrix-free side still solves (the paper's case 1 start)
    y0 = lagrange.initial_state([0.0, 0.0, math.sqrt(3.0)], math.radians(5))
    assert g.solve(avg, y0, (0, 1), n_out=3, check_validity=False).success
    # the memory the outputs would take is named before anything is allocated
    with pytest.raises(ValueError, match=r"n_out = 1000000000 output times would take at least 22\.35.* GiB"):
        g.solve(g.Model(BODY), W0, (0, 1), n_out=10**9)
    # 13 outputs: |G|, h, g, L, |Q|, δ, regularised, θ_G, φ_G, the nutation angle, ψ, θ, φ
    with pytest.raises(ValueError, match=r"would take .* GiB for this model's 8 state components and 13 outputs"):
        g.solve(orthogonal.OrthogonalModel(g.Body([2.0, 3.0, 4.0]), 0.1, attitude=True), W0, (0, 1), n_out=20_000_000)


def test_the_options_cache_keeps_what_each_keyword_means():
    """solve keeps the Options of recent keyword combinations (its key: the values, typed only where
    True == 1 == 1.0 could mix them, and the output times, typed where one is a boolean). A value that is refused stays refused
    after an equal one was accepted and kept: max_steps=True after max_steps=1, every_step=1 after
    every_step=True; integer output times give the run of the same times as floats."""
    model = g.Model(g.Body([1.0, 2.0, 3.0]))
    y0 = [0.1, 0.2, 0.3]
    g.solve(model, y0, (0.0, 1.0), max_steps=1)
    with pytest.raises(ValueError, match="max_steps = True must be a number"):
        g.solve(model, y0, (0.0, 1.0), max_steps=True)
    g.solve(model, y0, (0.0, 1.0), every_step=True)
    with pytest.raises(ValueError, match="every_step = 1 must be True or False"):
        g.solve(model, y0, (0.0, 1.0), every_step=1)
    ints, floats = (g.solve(model, y0, (0.0, 1.0), t_eval=t) for t in ([0, 1], [0.0, 1.0]))
    assert np.array_equal(ints.t, [0.0, 1.0]) and np.array_equal(ints.y, floats.y)
    # output times equal to booleans (1.0 == True, 0 == False), kept, leave the booleans refused
    assert g.solve(model, y0, (0.0, 1.0), t_eval=[1.0]).t.tolist() == [1.0]
    assert g.solve(model, y0, (0.0, 1.0), t_eval=[0]).t.tolist() == [0.0]
    for booleans in ([True], [False]):
        with pytest.raises(ValueError, match="t_eval must be output times"):
            g.solve(model, y0, (0.0, 1.0), t_eval=booleans)
