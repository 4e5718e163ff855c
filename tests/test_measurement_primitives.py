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
