"""The engine's measurement primitives the accuracy contract stands on (gyrostat.accuracy):
``measured_differences`` (how far two runs are apart on each measured quantity, relative to its
largest size) and ``first_crossing`` (the first output time past a given one at which a run has
crossed a separatrix), each against the same quantity computed here in NumPy from the runs' arrays."""

from __future__ import annotations

import math

import numpy as np
import pytest

import gyrostat as g
from gyrostat import _core
from gyrostat.options import make_options

CAVITY = g.Model(g.Body([1.0, 1.6, 2.1]), [g.ViscousCavity(1.0, 100.0, 1.0)])
W0 = np.array([1.0, 0.5, -0.3])  # near the smallest axis: the cavity carries it through the separatrix
T1 = 500.0  # (tests/test_accuracy_contract.py's crossing case: it crosses once, in the middle of the span)


def run(model, y0, t1, rtol, n_out=101):
    return _core.solve(model._core, np.asarray(y0, float), 0.0, t1, make_options(rtol=rtol, atol=rtol * 1e-3,
                                                                                   n_out=n_out), None)


def numpy_differences(core, reference, other, rows_a, rows_b):
    """Each measured quantity's distance |x - z| (a vector's norm), relative to its largest size in
    the reference over the compared rows, as gyrostat.accuracy documents it."""
    made = []
    for name, role, columns in core.measured_quantities:
        a = (reference.y if role == "state" else reference.outputs)[rows_a][:, columns]
        b = (other.y if role == "state" else other.outputs)[rows_b][:, columns]
        unit = np.abs(a).max()
        unit = unit if 0 < unit < math.inf else 1.0
        scale = np.linalg.norm(a / unit, axis=1).max()
        made.append(np.linalg.norm((a - b) / unit, axis=1) / (scale if scale > 0 else 1.0))
    return np.array(made)


@pytest.mark.parametrize("rows", [None, "array", "list", "uint"])
def test_measured_differences_against_numpy(rows):
    """Two runs of the damped body with attitude (ω and the quaternion as vectors, |G| and T as
    outputs) at rtol 1e-6 and 1e-9: the engine's differences equal NumPy's to 1e-13 relative (the
    same arithmetic in another order), on every row and on rows chosen by an integer array, a
    list or unsigned integers (read without a Python object per number)."""
    model = g.Model(g.Body([1.0, 1.4, 2.1]), [g.LinearDamping(diagonal=[1e-3, 2e-3, 5e-4])], attitude=True)
    y0 = np.r_[0.15, 0.3, 1.0, 1.0, 0.0, 0.0, 0.0]
    a, b = run(model, y0, 200.0, 1e-9), run(model, y0, 200.0, 1e-6)
    core = model._core
    picked = np.arange(3, 90, 7)
    given = {None: None, "array": picked, "list": picked.tolist(), "uint": picked.astype(np.uint32)}[rows]
    engine = core.measured_differences(a, b, given, given)
    chosen = slice(None) if rows is None else picked
    expected = numpy_differences(core, a, b, chosen, chosen)
    assert engine.shape == expected.shape == (4, 101 if rows is None else len(picked))
    assert np.max(np.abs(engine - expected)) <= 1e-13 * np.max(expected), \
        f"engine and NumPy differ by {np.max(np.abs(engine - expected)):.3g} (rows {rows})"
    assert np.max(expected) > 1e-8, "the two runs must differ for the comparison to mean anything"


def test_measured_differences_refuses_bad_rows_by_name():
    """A negative row, a row past the run's end, a float and mismatched counts are refused with
    the value named (ValueError, not a crash or a silent wrap-around)."""
    a = run(CAVITY, W0, 10.0, 1e-8, n_out=11)
    core = CAVITY._core
    with pytest.raises(ValueError, match="row -1 is negative"):
        core.measured_differences(a, a, np.array([0, -1]), np.array([0, 1]))
    with pytest.raises(ValueError, match="row 11 of a run with 11"):
        core.measured_differences(a, a, [11], [0])
    with pytest.raises(ValueError, match="reference_rows must be row numbers"):
        core.measured_differences(a, a, [0.5], [0])
    with pytest.raises(ValueError, match="compare 2 and 1 rows"):
        core.measured_differences(a, a, [0, 1], [0])
    assert np.array_equal(core.measured_differences(a, a, [], []), np.zeros((len(core.measured_quantities), 11))), \
        "no rows given means every row (a run against itself: zero apart)"


def numpy_first_crossing(model, result, after):
    """The first output time past ``after`` (in the run's direction) where the sign of the model's
    separatrix differs from the output before (NaN: none)."""
    side = np.sign(model._core.separatrix(result.y))
    t = np.asarray(result.t)
    forward = 1.0 if t[-1] >= t[0] else -1.0
    changed = np.flatnonzero((side[:-1] * side[1:] < 0) & ((t[1:] - after) * forward > 0))
    return float(t[changed[0] + 1]) if changed.size else math.nan


@pytest.mark.parametrize("t1, w0", [(T1, W0), (-T1, [0.3, 0.5, 1.0])])
def test_first_crossing_against_numpy(t1, w0):
    """The cavity carries the body from near its smallest axis through the separatrix forward in
    time, and from near its largest axis backward in time (the cavity then feeds energy in): the
    engine's crossing time equals NumPy's sign change of the separatrix, past t0 and past a time
    just after the crossing, and is NaN past the end of the run."""
    options = make_options(rtol=1e-10, atol=1e-13, n_out=401)
    result = _core.solve(CAVITY._core, np.asarray(w0, float), 0.0, t1, options, None)
    first = numpy_first_crossing(CAVITY, result, 0.0)
    assert math.isfinite(first), "the case must cross the separatrix"
    assert CAVITY._core.first_crossing(result, 0.0) == first
    assert math.isnan(CAVITY._core.first_crossing(result, t1)), "nothing past the end of the run"
    later = first + (1.0 if t1 > 0 else -1.0)
    assert _same(CAVITY._core.first_crossing(result, later), numpy_first_crossing(CAVITY, result, later))


def _same(x: float, y: float) -> bool:
    return x == y or (math.isnan(x) and math.isnan(y))


def test_a_model_without_a_separatrix_never_crosses():
    """Models that declare no separatrix (the averaged (a, r) model, the moving mass) give NaN."""
    averaged = g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48)])
    result = run(averaged, [1.0, 1.0], 60.0, 1e-8)
    assert math.isnan(averaged._core.first_crossing(result, 0.0))
    mass = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=98.0)
    result = run(mass, mass.quasi_static_state([1.0, 0.0, 1.0]), 5.0, 1e-8)
    assert math.isnan(mass._core.first_crossing(result, 0.0))


@pytest.mark.parametrize("t0, t1, count", [(0.0, 3.75, 41), (10.0, -5.0, 201), (1e5, 1.2e5, 41), (0.0, 1e-300, 2)])
def test_the_windows_even_times_are_numpys_linspace(t0, t1, count):
    """The probe's and the window's sampling times (gyrostat.accuracy.even_times, cheaper than
    np.linspace): NumPy's linspace to 2 ulp of the span (a different order of the same
    arithmetic), both ends exact (the runs end on them), monotone in the run's direction."""
    from gyrostat.accuracy import even_times

    made, numpy = even_times(t0, t1, count), np.linspace(t0, t1, count)
    assert np.max(np.abs(made - numpy)) <= 2 * np.spacing(abs(t1 - t0)) + np.spacing(max(abs(t0), abs(t1)))
    assert made[0] == t0 and made[-1] == t1
    assert np.all(np.sign(np.diff(made)) == np.sign(t1 - t0))


# ------------------------------------------------------------------------------------ the window estimate
def python_grow(last, half, end, middle, far, least=1.0):
    """The window's growth rule (gyrostat.accuracy's module doc), written here: t^k from the window's
    second half, k within [least, 2]."""
    if far <= end or last == 0.0:
        return last, 1.0
    k = 1.0 if half <= 0 else min(2.0, max(least, math.log(last / half) / math.log(end / middle)))
    return last * (far / end) ** k, k


WINDOW_CASES = {
    "averaged": (g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48),
                                                          g.ConstantTorque([0.0, 0.0, -0.01])]), [1.0, 1.0], 60.0),
    "attitude": (g.Model(g.Body([1.0, 1.4, 2.1]), [g.LinearDamping(diagonal=[1e-3, 2e-3, 5e-4])], attitude=True),
                 [0.15, 0.3, 1.0, 1.0, 0.0, 0.0, 0.0], 400.0),
    "moving mass": (g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=10.0, damping=98.0),
                    [1.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0], 40.0),
}


@pytest.mark.parametrize("case", sorted(WINDOW_CASES))
@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
def test_the_engines_window_estimate_is_the_rule_computed_here(case, rtol):
    """``_core.window_estimate`` (one engine call: the companion over the first 20 % of the span at
    rtol/4, the differences, the growth) against the same rule computed here from a companion run
    through ``_core.solve`` and NumPy's running maxima: equal to 1e-14 relative (the same runs,
    the same operations on both sides, libm's log and pow)."""
    model, y0, t1 = WINDOW_CASES[case]
    y0 = np.asarray(y0, float)
    core, answer = model._core, run(model, y0, t1, rtol, n_out=201)
    companion = make_options(rtol=rtol / 4, atol=rtol * 1e-3 / 4)
    gain = 4.0 / 3.0
    rule = _core.WindowRule(fraction=0.2, least_times=16, safety=3.0, floor=1e-16, gain=gain, fit_steps=8)
    values, k, grown, end, count, failure, stats, _, fitted = _core.window_estimate(core, answer, 0.0, y0, t1, companion,
                                                                                    rule)
    times = np.asarray(answer.t)
    inside = int(np.sum(times <= 0.2 * t1))
    window_options = make_options(rtol=rtol / 4, atol=rtol * 1e-3 / 4, t_eval=times[:inside])
    other = _core.solve(core, y0, 0.0, float(times[inside - 1]), window_options, None)
    apart = numpy_differences(core, other, answer, slice(None), slice(0, inside))
    middle = inside // 2
    expected, ks = [], []
    fit = other.stats.steps >= 8  # (fewer companion steps over the window: k = 1, not fitted)
    for row in apart:
        value, k_row = python_grow(row.max() * gain, row[:middle + 1].max() * gain if fit else 0.0, times[inside - 1],
                                   times[middle], t1)
        expected.append(max(3.0 * value, 1e-16))
        ks.append(k_row)
    assert failure == "" and grown and count == inside and end == times[inside - 1], (failure, grown, count, end)
    assert fitted == fit, (fitted, other.stats.steps)
    assert stats.rhs_evals == other.stats.rhs_evals and stats.steps == other.stats.steps, "the window's companion's statistics"
    assert np.allclose(values, expected, rtol=1e-14, atol=0.0), f"{case}: engine {values}, rule {expected}"
    assert k == pytest.approx(max(ks), rel=1e-14), (k, ks)
    assert max(expected) > 1e-13, "the runs must differ for the comparison to mean anything"


@pytest.mark.parametrize("case", sorted(WINDOW_CASES))
@pytest.mark.parametrize("whole_span", [False, True])
def test_a_run_and_its_estimate_in_one_call_are_the_two_calls(case, whole_span):
    """``_core.solve_measured`` (what a single solve with its default estimate makes: the run, then its
    window estimate, in one engine call) equals ``_core.solve`` then ``_core.window_estimate`` bit for
    bit: the same runs in the same order; and it makes none where the run measures itself or failed.
    With ``measured_only`` (the contract's short single run: a whole span's companion recording only
    the measured outputs), the same numbers, the tuple ending with the companion's Stats."""
    model, y0, t1 = WINDOW_CASES[case]
    y0 = np.asarray(y0, float)
    options = make_options(rtol=1e-8, atol=1e-11, n_out=201)
    companion = make_options(rtol=2.5e-9, atol=2.5e-12)
    rule = _core.WindowRule(fraction=0.2, least_times=16, safety=3.0, floor=1e-16, gain=4.0 / 3.0, fit_steps=8)
    answer, made = _core.solve_measured(model._core, y0, 0.0, t1, options, companion, rule, None, whole_span)
    alone = _core.solve(model._core, y0, 0.0, t1, options, None)
    apart = _core.window_estimate(model._core, alone, 0.0, y0, t1, companion, rule, None, whole_span)
    assert np.array_equal(answer.y, alone.y) and np.array_equal(answer.outputs, alone.outputs, equal_nan=True)
    assert made[:6] == apart[:6], (made[:6], apart[:6])
    _, lean = _core.solve_measured(model._core, y0, 0.0, t1, options, companion, rule, None, whole_span, True)
    assert lean[:6] == made[:6] and isinstance(lean[6], _core.Stats), (lean[:6], made[:6])
    assert lean[6].rhs_evals == getattr(made[6], "stats", made[6]).rhs_evals
    assert max(lean[0]) > 1e-12, "the runs must differ for the comparison to mean anything"
    starved = make_options(rtol=1e-8, atol=1e-11, n_out=201, max_steps=2)
    failed, none = _core.solve_measured(model._core, y0, 0.0, t1, starved, companion, rule, None, whole_span)
    assert failed.status == "max_steps_reached" and none is None, failed.status


def test_the_engines_window_leaves_what_it_cannot_measure_to_python():
    """None (the Python window then samples or measures the whole span) where the run holds fewer
    than 16 output times in the window, or crosses a separatrix after the window's first half;
    a companion that stops is named."""
    core = CAVITY._core
    rule = _core.WindowRule(fraction=0.2, least_times=16, safety=3.0, floor=1e-16, gain=4.0 / 3.0, fit_steps=8)
    tighter = make_options(rtol=2.5e-9, atol=2.5e-12)
    few = run(CAVITY, W0, 50.0, 1e-8, n_out=11)
    assert _core.window_estimate(core, few, 0.0, W0, 50.0, tighter, rule) is None
    crossing = run(CAVITY, W0, T1, 1e-8, n_out=401)
    assert core.first_crossing(crossing, 0.1 * T1) > 0.1 * T1, "the case must cross after the window's first half"
    assert _core.window_estimate(core, crossing, 0.0, W0, T1, tighter, rule) is None
    short = run(CAVITY, W0, 50.0, 1e-8, n_out=201)
    starved = make_options(rtol=2.5e-9, atol=2.5e-12, max_steps=3)
    values, *_, failure, stats, _, _ = _core.window_estimate(core, short, 0.0, W0, 50.0, starved, rule)
    assert failure.startswith("max_steps_reached") and values == [] and stats.steps == 3, (failure, stats.steps)
    *_, failure, companion, _, _ = _core.window_estimate(core, short, 0.0, W0, 50.0, starved, rule, whole_span=True)
    assert failure.startswith("max_steps_reached") and companion.status == "max_steps_reached", failure
    estimate = g.accuracy._window_estimate((values, 1.0, False, 10.0, 0, failure), ["omega"], 0.0, 50.0, 0.2, "x",
                                            4 / 3)
    assert math.isnan(estimate.value) and "max_steps_reached" in estimate.basis, estimate.basis


@pytest.mark.parametrize("args, expected", [
    ((1e-6, 5e-7, 2.0, 1.0, 10.0), (5e-6, 1.0)),           # k = 1: linear drift
    ((1e-6, 2.5e-7, 2.0, 1.0, 10.0), (2.5e-5, 2.0)),       # k = 2: quadratic
    ((1e-6, 1e-9, 2.0, 1.0, 10.0), (2.5e-5, 2.0)),         # k capped at 2
    ((1e-6, 1e-6, 2.0, 1.0, 10.0), (5e-6, 1.0)),           # flat: k raised to least
    ((1e-6, 0.0, 2.0, 1.0, 10.0), (5e-6, 1.0)),            # no error at the middle: k = 1
    ((1e-6, 5e-7, 2.0, 1.0, 1.5), (1e-6, 1.0)),            # horizon inside the window
    ((0.0, 0.0, 2.0, 1.0, 10.0), (0.0, 1.0)),              # no error
])
def test_grow_at_its_limits(args, expected):
    """The growth rule at its limits, against the values derived by hand (exact but for pow's last
    ulp: 1e-15 relative)."""
    value, k = _core.grow(*args)
    assert (value, k) == pytest.approx(expected, rel=1e-15, abs=0.0), (args, value, k)
    assert (value, k) == pytest.approx(python_grow(*args), rel=1e-15, abs=0.0)


def test_grow_keeps_nan():
    value, k = _core.grow(math.nan, 1e-7, 2.0, 1.0, 10.0)
    assert math.isnan(value) and k == 1.0, (value, k)


def every_family():
    """One model of every family (the closed form too), with an initial state and a span."""
    from gyrostat.lagrange import LagrangeAveraged, LagrangeTop
    from gyrostat.orthogonal import OrthogonalModel

    body = g.Body([1.0, 1.4, 2.1])
    damping = g.LinearDamping(diagonal=[1e-3, 2e-3, 5e-4])
    return {
        **WINDOW_CASES,
        "gyrostat": (g.Model(body, [damping]), [0.15, 0.3, 1.0], 400.0),
        "orbiting": (g.Model(g.Body([2.0, 3.0, 1.5]), [g.GravityGradient()], orbit=g.Orbit(rate=0.3)),
                     [0.1, -0.4, 0.3, 1.0, 0.0, 0.0, 0.0], 40.0),
        "averaged triaxial": (g.TriaxialAveragedModel(body, [damping]), [0.15, 0.3, 1.0], 400.0),
        "Lagrange top": (LagrangeTop(2.0, 1.0, 0.5), [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0], 20.0),
        "Lagrange averaged": (LagrangeAveraged(2.0, 1.0, 0.5, [g.LinearDamping(diagonal=[0.01, 0.01, 0.01])]),
                              [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0], 20.0),
        "orthogonal": (OrthogonalModel(body, 0.01), [0.15, 0.3, 1.0], 20.0),
        "closed form": (g.TorqueFreeModel(body), [0.15, 0.3, 1.0], 20.0),
    }


EVERY_FAMILY = every_family()


@pytest.mark.parametrize("case", sorted(EVERY_FAMILY))
@pytest.mark.parametrize("full", [False, True])
def test_one_runs_estimate_in_the_engine_equals_the_general_path(case, full):
    """A single run's estimate made in one engine call (``accuracy.SingleRun``: the window, or with
    ``full`` the whole span) equals the general path's (any runner: ensembles, the model ladder)
    exactly: the same runs, differences and rule; its basis reads the same and the whole span's
    companion is kept alike."""
    model, y0, t1 = EVERY_FAMILY[case]
    y0, core = np.asarray(y0, float), model._core
    opts = make_options(rtol=1e-7, atol=1e-10, n_out=201)
    answer = _core.solve(core, y0, 0.0, t1, opts, None)
    kept_here, kept_there = {}, {}
    here = g.accuracy.estimate_runs(g.accuracy.SingleRun(core, y0, 0.0), [core], opts, 0.0, t1, [answer], full=full,
                                    companions=kept_here)[0]
    there = g.accuracy.estimate_runs(lambda o, t, members: [_core.solve(core, y0, 0.0, t, o, None)], [core], opts, 0.0,
                                     t1, [answer], full=full, companions=kept_there)[0]
    assert (here.value, here.per_quantity, here.basis) == (there.value, there.per_quantity, there.basis)
    assert here.value > (1e-15 if case == "closed form" else 1e-12), "the estimate must measure something"
    if full and case != "closed form":
        assert np.array_equal(kept_here[0].y, kept_there[0].y), "the whole span's companion must be kept"


@pytest.mark.parametrize("full", [False, True])
def test_an_ensembles_estimates_in_the_engine_equal_the_general_path(full):
    """An ensemble's estimates made in the engine (``accuracy.EnsembleRun``: the companions as one
    ensemble, ``_core.window_estimates``) equal the general path's exactly, member by member: the
    cavity's members here cross the separatrix or not by their start (those crossing are left to
    the general path's whole span), and a member that failed is estimated by neither."""
    core = CAVITY._core
    y0s = np.array([W0, [1.0, 0.2, -1.0], [0.2, 0.3, 1.0], W0 * 1.01])
    opts = make_options(rtol=1e-7, atol=1e-10, n_out=201)
    answers = list(_core.solve_ensemble([core], y0s, 0.0, T1, opts, 1, None, batch=True))
    starved = make_options(rtol=1e-7, atol=1e-10, n_out=201, max_steps=5)
    answers[1] = _core.solve(core, y0s[1], 0.0, T1, starved, None)
    assert not answers[1].success
    crossing = [core.first_crossing(a, 0.1 * T1) > 0.1 * T1 for a in answers]
    assert crossing[0] and not crossing[2], "the case must have members on both sides"
    here, there, kept_here, kept_there = [], [], {}, {}
    here = g.accuracy.estimate_runs(g.accuracy.EnsembleRun([core], y0s, 0.0, 4, 1), [core] * 4, opts, 0.0, T1,
                                    answers, full=full, companions=kept_here)

    def general(o, t_end, members):
        return _core.solve_ensemble([core], y0s[members], 0.0, t_end, o, 1, None, batch=True)
    there = g.accuracy.estimate_runs(general, [core] * 4, opts, 0.0, T1, answers, full=full, companions=kept_there)
    assert here[1] is None and there[1] is None, "a failed run estimates nothing"
    for i in (0, 2, 3):
        assert (here[i].value, here[i].per_quantity, here[i].basis) == \
            (there[i].value, there[i].per_quantity, there[i].basis), f"member {i}"
        assert here[i].value > 1e-12
    assert sorted(kept_here) == sorted(kept_there)
    for i in kept_here:
        assert np.array_equal(kept_here[i].y, kept_there[i].y), f"member {i}'s companion"


@pytest.mark.parametrize("case", sorted(set(EVERY_FAMILY) - {"closed form"}))
def test_every_familys_ensemble_estimates_in_the_engine_equal_the_general_path(case):
    """Three members of each family (starts scaled by 1, 1.01, 0.99), through ``solve_ensemble``'s
    runner: the engine's estimates equal the general path's exactly, member by member."""
    model, y0, t1 = EVERY_FAMILY[case]
    core, y0 = model._core, np.asarray(y0, float)
    y0s = np.array([y0, y0 * 1.01, y0 * 0.99])
    opts = make_options(rtol=1e-7, atol=1e-10, n_out=201)
    answers = list(_core.solve_ensemble([core], y0s, 0.0, t1, opts, 1, None, batch=True))
    assert all(a.success for a in answers), [a.message for a in answers]
    here = g.accuracy.estimate_runs(g.accuracy.EnsembleRun([core], y0s, 0.0, 3, 1), [core] * 3, opts, 0.0, t1, answers)
    there = g.accuracy.estimate_runs(
        lambda o, t_end, members: _core.solve_ensemble([core], y0s[members], 0.0, t_end, o, 1, None, batch=True),
        [core] * 3, opts, 0.0, t1, answers)
    for i in range(3):
        assert (here[i].value, here[i].per_quantity, here[i].basis) == \
            (there[i].value, there[i].per_quantity, there[i].basis), f"{case}, member {i}"
        assert here[i].value > 1e-12


def test_the_engines_window_refuses_mismatched_inputs_by_name():
    """Differences at a number of times other than the times given, and an ensemble's initial
    states or models not one per answer: a ValueError with the counts."""
    rule = _core.WindowRule(fraction=0.2, least_times=16, safety=3.0, floor=1e-16, gain=4.0 / 3.0, fit_steps=8)
    with pytest.raises(ValueError, match="3 differences at 2 times"):
        _core.window_from_differences(np.zeros((2, 3)), [0.0, 1.0], 0.0, 10.0, rule)
    core = CAVITY._core
    answer = run(CAVITY, W0, 50.0, 1e-8)
    tighter = make_options(rtol=2.5e-9, atol=2.5e-12)
    with pytest.raises(ValueError, match="1 initial states for 2 answers"):
        _core.window_estimates([core], [answer, answer], 0.0, np.array([W0]), 50.0, tighter, rule)
    with pytest.raises(ValueError, match="3 models for 2 answers"):
        _core.window_estimates([core] * 3, [answer, answer], 0.0, np.array([W0, W0]), 50.0, tighter, rule)


@pytest.mark.parametrize("case", ["attitude", "averaged"])
def test_every_rows_differences_are_those_of_the_rows_listed(case):
    """``measured_differences`` over every row (a whole span's measurement: read with the rows' strides)
    equals the same rows listed one by one (read through offsets) bit for bit: the same arithmetic in
    the same order, for vectors (ω, the quaternion) and single columns (|G|, T, a, r) alike."""
    model, y0, t1 = WINDOW_CASES[case]
    a, b = run(model, y0, t1, 1e-9, n_out=201), run(model, y0, t1, 1e-6, n_out=201)
    every = np.arange(201)
    whole = model._core.measured_differences(a, b, None, None)
    listed = model._core.measured_differences(a, b, every, every)
    assert np.array_equal(whole, listed), np.max(np.abs(whole - listed))
    assert np.max(whole) > 1e-9, "the two runs must differ for the comparison to mean anything"


def test_only_the_measured_outputs_are_recorded_when_asked():
    """``Options.only_measured_outputs`` (what the contract's probes and companions record): the
    averaged model's measured outputs (|G|, T) and its state are those of the full recording bit for
    bit, every other output NaN (its slow-to-fast ratio needs the right-hand side, its nutation angle
    an atan2: not computed)."""
    model, y0, t1 = WINDOW_CASES["averaged"]
    y0 = np.asarray(y0, float)
    options = make_options(rtol=1e-8, atol=1e-11, n_out=51)
    everything = _core.solve(model._core, y0, 0.0, t1, options, None)
    options.only_measured_outputs = True
    measured = _core.solve(model._core, y0, 0.0, t1, options, None)
    names = list(model._core.output_names)
    kept = [names.index(name) for name, role, _ in model._core.measured_quantities if role == "output"]
    assert kept == [names.index("angular_momentum_norm"), names.index("kinetic_energy")], kept
    assert np.array_equal(measured.y, everything.y) and np.array_equal(measured.t, everything.t)
    assert np.array_equal(measured.outputs[:, kept], everything.outputs[:, kept])
    others = [i for i in range(len(names)) if i not in kept]
    assert np.all(np.isnan(measured.outputs[:, others])) and np.all(np.isfinite(everything.outputs[:, others]))


def test_a_run_that_measures_itself_is_left_to_python():
    """The engine makes no companion estimate of a splitting (Richardson over its own step) or a
    closed form (its rounding): ``window_estimate`` returns None for them, over a window or the whole
    span, and Python takes their own measures (``Solution.error_estimate`` still set)."""
    body = g.Body([1.0, 1.4, 2.1])
    y0 = np.array([0.15, 0.3, 1.0])
    rule = _core.WindowRule(fraction=0.2, least_times=16, safety=3.0, floor=1e-16, gain=4.0 / 3.0, fit_steps=8)
    tighter = make_options(rtol=2.5e-9, atol=2.5e-12)
    for model, method in ((g.Model(body, [g.LinearDamping(diagonal=[1e-3, 2e-3, 5e-4])]), "splitting"),
                          (g.TorqueFreeModel(body), None)):
        options = make_options(rtol=1e-8, atol=1e-11, n_out=201, method=method)
        answer = _core.solve(model._core, y0, 0.0, 50.0, options, None)
        assert answer.method in ("splitting", "closed_form") and answer.success, answer.method
        for whole_span in (False, True):
            assert _core.window_estimate(model._core, answer, 0.0, y0, 50.0, tighter, rule, None, whole_span) is None
        solution = g.solve(model, y0, (0.0, 50.0), rtol=1e-8, n_out=201, method=method)
        # (who measures is what is checked here: the splitting's Richardson estimate and the closed form's
        # rounding, each far below 1e-6 for this run, are checked against references in test_splitting.py
        # and test_torque_free.py)
        assert 0 < solution.error_estimate < 1e-6, (answer.method, solution.error_basis)
        assert ("Richardson" in solution.error_basis or "steps of h" in solution.error_basis) if method else \
            "round" in solution.error_basis, solution.error_basis
