"""Property-based tests (Hypothesis): random bodies, torques, states and tolerances through solve
and solve_ensemble, and random scene documents (valid, and with one key mutated) through the
scene loader. Each result is either an error naming a value or a finite trajectory whose
invariants behave as the physics says. Derandomized, no example database: the same examples on
every machine, and a bounded run time."""

import copy
import math
import tomllib

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import gyrostat as g
from gyrostat.scene import SCENES, Scene
from gyrostat.schema import SceneError

SETTINGS = settings(max_examples=40, deadline=None, database=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])

finite = st.floats(-3.0, 3.0, allow_nan=False)
omega = st.lists(finite, min_size=3, max_size=3)
method = st.sampled_from(["dop853", "taylor", "cvode_bdf", "cvode_adams", "arkode_fehlberg8"])
rtol = st.sampled_from([1e-5, 1e-7, 1e-9, 1e-11])


@st.composite
def bodies(draw):
    """Principal moments that satisfy the triangle inequality (a physical rigid body)."""
    a = draw(st.floats(0.5, 5.0))
    b = draw(st.floats(0.5, 5.0))
    c = draw(st.floats(max(abs(a - b), 0.1) * 1.01, (a + b) * 0.99))
    return [a, b, c]


@SETTINGS
@given(bodies(), omega, method, rtol)
def test_a_free_body_keeps_its_momentum_and_energy(moments, w, method, rtol):
    body = g.Body(moments)
    sol = g.solve(g.Model(body), w, (0.0, 10.0), method=method, rtol=rtol, atol=rtol * 1e-2, n_out=11,
                  progress=False)
    assert sol.success, sol.message
    assert np.all(np.isfinite(sol.y))
    G, T = sol["angular_momentum_norm"], sol["kinetic_energy"]
    # |G| and T are first integrals. Measured over these 40 (derandomized) examples, the largest
    # drift of |G| and T in units of rtol·|G(0)| and rtol·T(0): dop853 2.1 and 4.0, cvode_bdf 13 and
    # 27, cvode_adams 14 and 29, taylor 0.035 and 0.074, arkode_fehlberg8 2.2e-5 and 5.1e-5 (its
    # steps are far below rtol's need here). The bound is 10× the larger of the two, per method,
    # plus 1e-12 for the examples with ω ≈ 0.
    factor = DRIFT_PER_RTOL[method]
    scale = max(G[0], 1e-12)
    assert np.max(np.abs(G - G[0])) <= factor * rtol * scale + 1e-12, (method, rtol)
    assert np.max(np.abs(T - T[0])) <= factor * rtol * max(T[0], 1e-12) + 1e-12, (method, rtol)


DRIFT_PER_RTOL = {"dop853": 40.0, "cvode_bdf": 300.0, "cvode_adams": 300.0, "taylor": 0.75,
                  "arkode_fehlberg8": 5e-4}


@settings(max_examples=25, deadline=None, database=None, derandomize=True,
          suppress_health_check=[HealthCheck.filter_too_much, HealthCheck.too_slow])
@given(bodies(), st.floats(-30.0, -1.0), st.sampled_from([1.0, -1.0]), st.sampled_from([1.0, -1.0]),
       st.floats(0.05, 0.95))
def test_the_closed_form_next_to_the_separatrix(moments, log_gap, side, sign, split):
    """A state whose polhode passes within 1 - k^2 ~ 10^log_gap of the separatrix, on either side
    (A(A-B)p^2 + C(C-B)r^2 of sign `side`), against SciPy with Euler's equations written here
    (DOP853, rtol 1e-13, atol 1e-20: its own error over t <= 20 stays below 1e-12 there,
    tests/test_separatrix.py) over about two swings: relative error below 1e-9."""
    from scipy.integrate import solve_ivp

    A, B, C = sorted(moments)
    assume(min(B - A, C - B) >= 0.05 * C)  # a nearly symmetric body has no separatrix worth the name
    # q = 1 about the middle axis; p, r of size sqrt(gap) with A(A-B)p^2 + C(C-B)r^2 = side·gap·B(B-A)
    gap = 10.0**log_gap
    r2 = split * gap
    p2 = (C * (C - B) * r2 - side * gap * B * (B - A)) / (A * (B - A))
    assume(p2 > 0)
    w0 = [math.sqrt(p2), sign * 1.0, math.sqrt(r2)]
    J = [A, B, C]
    t = np.linspace(0.0, 20.0, 21)
    sol = g.solve(g.TorqueFreeModel(g.Body(J)), w0, (0.0, 20.0), t_eval=t)

    def f(_, w):
        return [(B - C) * w[1] * w[2] / A, (C - A) * w[2] * w[0] / B, (A - B) * w[0] * w[1] / C]
    ref = solve_ivp(f, (0.0, 20.0), w0, method="DOP853", t_eval=t, rtol=1e-13, atol=1e-20).y.T
    assert np.max(np.abs(sol.omega - ref)) < 1e-9 * np.linalg.norm(w0), np.max(np.abs(sol.omega - ref))


@SETTINGS
@given(bodies(), omega, st.lists(st.floats(0.0, 0.5), min_size=3, max_size=3), method)
def test_damping_never_adds_energy(moments, w, damping, method):
    model = g.Model(g.Body(moments), [g.LinearDamping(np.diag(damping))])
    sol = g.solve(model, w, (0.0, 10.0), method=method, rtol=1e-9, atol=1e-12, n_out=21, progress=False)
    assert sol.success and np.all(np.isfinite(sol.y))
    T = sol["kinetic_energy"]
    # dT/dt = -omega . D omega <= 0: T never grows by more than the integration error
    assert np.all(np.diff(T) <= 1e-7 * max(T[0], 1e-12) + 1e-14)


bad_number = st.one_of(st.just(float("nan")), st.just(float("inf")), st.floats(-5.0, 0.0), st.just(1e308))


@SETTINGS
@given(st.lists(st.one_of(st.floats(0.5, 5.0), bad_number), min_size=3, max_size=3))
def test_a_body_is_physical_or_an_error_naming_the_value(moments):
    try:
        body = g.Body(moments)
    except ValueError as error:
        message = str(error)
        assert "\n" not in message and ("A1" in message or "A2" in message or "A3" in message or "moment" in message)
        return
    a, b, c = moments
    assert min(moments) > 0 and all(math.isfinite(m) for m in moments)
    assert a <= b + c and b <= a + c and c <= a + b
    assert np.allclose(np.asarray(body.moments), moments)


@SETTINGS
@given(st.lists(st.one_of(finite, st.just(float("nan")), st.just(float("inf"))), min_size=3, max_size=3),
       st.one_of(st.floats(-1e3, 1e3), st.just(float("nan")), st.just(float("inf")), st.just(1e-300)))
def test_bad_states_and_tolerances_are_errors_naming_the_value(w, tolerance):
    model = g.Model(g.Body([1.0, 2.0, 2.5]))
    good_state = bool(np.all(np.isfinite(w)))
    good_tolerance = math.isfinite(tolerance) and 1e-14 <= tolerance < 1  # below 1e-14: unattainable, refused
    try:
        sol = g.solve(model, w, (0.0, 1.0), rtol=tolerance, n_out=3, progress=False)
    except ValueError as error:
        message = str(error)
        assert "\n" not in message and not (good_state and good_tolerance), message
        if good_state:
            assert "rtol" in message and (repr(tolerance) in message or f"{tolerance:g}" in message), message
        elif good_tolerance:
            assert "y0" in message and "not finite" in message, message
        return
    assert good_state and good_tolerance
    assert sol.status in ("success", "step_size_underflow") and np.all(np.isfinite(sol.y))


@settings(max_examples=15, deadline=None, database=None, derandomize=True)
@given(st.lists(omega, min_size=1, max_size=12), method)
def test_an_ensemble_equals_its_single_runs(states, method):
    model = g.Model(g.Body([1.0, 2.0, 2.5]), [g.ConstantTorque([0.0, 0.0, 0.1])])
    # batch=False: bit for bit (SIMD batches equal single runs to the tolerance: tests/test_batch.py)
    runs = g.solve_ensemble(model, np.array(states), (0.0, 5.0), method=method, n_out=6, threads=2, progress=False,
                            batch=False)
    for w, run in zip(states, runs):
        single = g.solve(model, w, (0.0, 5.0), method=method, n_out=6, progress=False)
        assert run.status == single.status and np.array_equal(run.y, single.y)


class CallbackError(Exception):
    """An exception type of the user's own."""


@SETTINGS
@given(st.sampled_from([KeyError, TypeError, ValueError, CallbackError]), st.text(max_size=20),
       st.floats(0.0, 1.0), method)
def test_an_event_callbacks_exception_propagates_as_raised(kind, text, when, method):
    raised = kind(text)

    def event(t, y):
        if t >= when:
            raise raised
        return y[0] - 10.0

    with pytest.raises(kind) as caught:
        g.solve(g.Model(g.Body([1.0, 2.0, 3.0])), [1.0, 0.5, -0.3], (0.0, 1.0), method=method, events=event,
                progress=False)
    assert caught.value is raised


# ------------------------------------------------------------------------------------ scene documents
SHIPPED = sorted(SCENES.glob("*.toml"))


def load(path):
    with open(path, "rb") as handle:
        return tomllib.load(handle)


def paths_of(doc, prefix=()):
    """Every (path, value) in a document, tables and arrays of tables included."""
    for key, value in doc.items():
        here = prefix + (key,)
        yield here, value
        if isinstance(value, dict):
            yield from paths_of(value, here)
        elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
            for i, item in enumerate(value):
                yield from paths_of(item, here + (i,))


def at(doc, path):
    for part in path[:-1]:
        doc = doc[part]
    return doc


@settings(max_examples=60, deadline=None, database=None, derandomize=True)
@given(st.sampled_from(SHIPPED), st.data())
def test_a_mutated_scene_is_an_error_naming_the_key_or_a_valid_scene(path, data):
    doc = load(path)
    entries = [(p, v) for p, v in paths_of(doc) if isinstance(p[-1], str)]
    where, value = data.draw(st.sampled_from(entries))
    mutation = data.draw(st.sampled_from(["rename", "retype", "drop"]))
    mutated = copy.deepcopy(doc)
    parent = at(mutated, where)
    key = where[-1]
    if mutation == "rename":
        parent[key + "x"] = parent.pop(key)
    elif mutation == "retype":
        parent[key] = "oops" if not isinstance(value, str) else 12345
    else:
        del parent[key]
    try:
        scene = Scene.from_dict(mutated, name=path.stem)
    except SceneError as error:
        message = str(error)
        # one line naming a key of the document (the mutated one, or the first that no longer fits, as
        # when renaming `kind` turns a top scene into a rigid body with an unknown key 'torque')
        named = {str(p[-1]) for p, _ in paths_of(mutated) if isinstance(p[-1], str)} | {key}
        assert "\n" not in message and any(f"'{k}'" in message or f"{k} " in message or f"[{k}" in message
                                           for k in named), message
        return
    # accepted: the mutation removed an optional key or gave a string where a string is right
    assert mutation in ("drop", "retype") and scene.runs


def test_every_shipped_scene_loads_and_its_runs_start_finite():
    for path in SHIPPED:
        scene = Scene.from_toml(path)
        for run in scene.runs:
            assert np.all(np.isfinite(run.y0)) and run.t_span[1] != run.t_span[0], (path.name, run.name)
