"""A forced case (constant torque plus damping, with attitude) against a SciPy DOP853 run at
rtol 1e-12 whose right-hand side is written in tests/references.py."""

import contextlib

import numpy as np
import pytest

import gyrostat as g
from references import scipy_reference

MOMENTS = [1.0, 2.0, 2.5]
ROTOR = [0.1, -0.2, 0.3]
M0 = np.array([0.02, -0.01, 0.05])
D = np.array([[0.05, 0.01, 0.0], [0.0, 0.04, 0.005], [0.0, 0.0, 0.03]])
Y0 = [1.0, 0.5, -0.3, 1.0, 0.0, 0.0, 0.0]


@pytest.fixture(scope="module")
def reference():
    t = np.linspace(0, 60, 301)
    return t, scipy_reference(MOMENTS, ROTOR, lambda t, w: M0 - D @ w, Y0, t)


@pytest.mark.parametrize("method", g.METHODS)
def test_forced_gyrostat_against_scipy(method, reference):
    t, ref = reference
    model = g.Model(g.Body(MOMENTS, ROTOR), [g.ConstantTorque(M0), g.LinearDamping(D)], attitude=True)
    if method == "splitting":  # an asymmetric gyrostat with a rotor: no exact free flow to split on
        with pytest.raises(ValueError, match="closed form here only"):
            g.solve(model, Y0, (0, 60), method=method, step=0.1)
        return
    context = pytest.warns(UserWarning) if method == "arkode_verner6" else contextlib.nullcontext()
    with context:
        sol = g.solve(model, Y0, (0, 60), t_eval=t, method=method, rtol=1e-11, atol=1e-13)
    assert sol.success, sol.message
    # max |y − y_SciPy| over t ∈ [0, 60] at rtol 1e-11, measured (the reference, SciPy at rtol
    # 1e-12, contributes a few 1e-12: the floor of fehlberg's and taylor's values); 10× it
    measured = {"dop853": 3.2e-11, "auto": 3.2e-11, "cvode_bdf": 6.0e-10, "cvode_adams": 6.5e-11,
                "arkode_verner6": 1.5e-11, "arkode_fehlberg8": 4.4e-12, "taylor": 4.6e-12}[method]
    error = np.max(np.abs(sol.y - ref))
    assert error < 10 * measured, f"{method}: {error:.2e} (measured {measured:.1e})"
    # the rhs of the core equals the test's own
    from references import euler_rhs

    f = euler_rhs(MOMENTS, ROTOR, lambda t, w: M0 - D @ w)
    for row in ref[::50]:
        np.testing.assert_allclose(model.rhs(0.0, row), f(0.0, row), rtol=1e-14, atol=1e-15)
