"""The reliability issue's table of bad inputs, rerun as one table: every case ends in a clear
error naming the value, a warning, a failure status with its reason, or a correct answer; never a
wrong answer marked success, a crash or a traceback. `pytest -q tests/test_reliability_table.py`
prints nothing but the count; each row names its case."""

import math
import warnings

import numpy as np
import pytest

import gyrostat as g
from gyrostat import lagrange, orthogonal

BODY = g.Body([1.0, 2.0, 3.0])
W0 = [1.0, 0.5, -0.3]


def error(call, *words):
    """The case raises ValueError in one line holding every word (the value it names)."""
    with pytest.raises(ValueError) as raised:
        call()
    message = str(raised.value)
    assert "\n" not in message and "Invoked with" not in message, message
    for word in words:
        assert word in message, message


def failed(solution, status):
    """The case returns, but says that it failed and why; never success."""
    assert not solution.success and solution.status == status and solution.message


def zero_quaternion_top():
    top = lagrange.LagrangeTop(1.5, 1.0, 0.5)
    g.solve(top, [0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0], (0, 1))


CASES = {
    "zero quaternion, gyrostat": lambda: error(
        lambda: g.solve(g.Model(BODY, attitude=True), W0 + [0, 0, 0, 0], (0, 1)), "quaternion"),
    "zero quaternion, Lagrange top": lambda: error(zero_quaternion_top, "quaternion"),
    "zero quaternion, orthogonal torque": lambda: error(lambda: g.solve(
        orthogonal.OrthogonalModel(g.Body([2, 3, 4]), 0.1, attitude=True), W0 + [0, 0, 0, 0, 0], (0, 1)), "quaternion"),
    "cvode_bdf from |omega0| = 1e100": lambda: failed(
        g.solve(g.Model(BODY), [1e100] * 3, (0, 10), method="cvode_bdf"), "solver_failure"),
    "atol = 1e300 (dop853)": lambda: _atol_case(),
    "LagrangeAveraged from unreachable (G_z, H, r)": lambda: error(
        lambda: g.solve(lagrange.LagrangeAveraged(1.5, 1.0, 0.5), [0.5, -10.0, 1.0], (0, 1)), "H", "-10"),
    "averaging the unstable sleeping top": lambda: _sleeping_top_case(),
    "tabulated law over the whole double range": lambda: _equal(
        orthogonal.tabulated([-1e308, 1e308], [0.0, 1.0])(0.0), 0.5),
    "n_out = 2.7": lambda: error(lambda: g.solve(g.Model(BODY), W0, (0, 1), n_out=2.7), "n_out", "2.7"),
    "averaged state with a < 0": lambda: error(
        lambda: g.solve(g.AveragedModel(g.Body([2, 2, 1]), [g.LinearDamping(np.eye(3))]), [-1.0, 1.0], (0, 1)),
        "a = -1"),
    "dop853 with atol = 0 and a zero component": lambda: _equal(
        g.solve(g.Model(BODY), [1.0, 0.0, 0.0], (0, 10), atol=0.0, n_out=3).status, "success"),
    "Body([1, 2])": lambda: error(lambda: g.Body([1, 2]), "moments", "[1, 2]"),
    "ConstantTorque([0, 1])": lambda: error(lambda: g.ConstantTorque([0, 1]), "moment"),
    "LinearDamping(np.eye(2))": lambda: error(lambda: g.LinearDamping(np.eye(2)), "3x3"),
    "max_steps = 2**70": lambda: error(lambda: g.solve(g.Model(BODY), W0, (0, 1), max_steps=2**70), "max_steps"),
    "threads = 2**40": lambda: error(lambda: g.solve_ensemble(g.Model(BODY), [W0], (0, 1), threads=2**40), "threads"),
    "n_out = 1e9 (memory named first)": lambda: error(
        lambda: g.solve(g.Model(BODY), W0, (0, 1), n_out=10**9), "GiB"),
    "negative moment of inertia": lambda: error(lambda: g.Body([-1.0, 2.0, 2.5]), "-1"),
    "NaN in the initial state": lambda: error(lambda: g.solve(g.Model(BODY), [1.0, math.nan, 0.0], (0, 1)), "nan"),
    "a run stopped by max_steps says where": lambda: _max_steps_case(),
}


def _equal(value, expected):
    assert value == expected, value


def _atol_case():
    with pytest.warns(UserWarning, match=r"atol = 1e\+300 exceeds every component of the initial state"):
        sol = g.solve(g.Model(BODY), W0, (0, 100), atol=1e300)
    reference = g.torque_free(BODY, W0, sol.t)
    error_ = np.max(np.abs(sol.omega - reference.omega)) if len(sol) else math.inf
    assert not (sol.success and error_ > 1e-3), "a wrong answer marked success"


def _sleeping_top_case():
    y0 = lagrange.initial_state([0.0, 0.0, 1.0], theta=1e-12)  # C r = 1 < 2 sqrt(A mu): unstable
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        sol = g.solve(lagrange.LagrangeAveraged(1.5, 1.0, 0.5, [lagrange.paper_torque(0.01)]), y0, (0, 50))
    said = [str(w.message) for w in caught if issubclass(w.category, g.ValidityWarning)]
    assert any("separatrix" in m for m in said), said
    assert any("separatrix" in note for note in sol.notes)


def _max_steps_case():
    part = g.solve(g.Model(BODY), W0, (0, 100), max_steps=10)
    failed(part, "max_steps_reached")
    assert 0 < part.t_last < 100 and len(part.y_last) == 3
    assert g.solve(g.Model(BODY), part, (part.t_last, 100)).success


@pytest.mark.parametrize("case", list(CASES))
def test_case(case):
    with warnings.catch_warnings():
        warnings.simplefilter("error", RuntimeWarning)  # no stray runtime warning either
        CASES[case]()
