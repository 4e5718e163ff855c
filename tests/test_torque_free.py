"""The torque-free triaxial body against its analytic solution (Jacobi elliptic functions,
written independently in tests/references.py with scipy.special.ellipj)."""

import warnings

import numpy as np
import pytest

import gyrostat as g
from references import euler_poinsot

MOMENTS = [1.0, 2.0, 3.0]
OMEGA0 = [1.0, 0.5, -0.3]

# Measured max |ω − ω_exact| over the run (|ω| ≈ 1.2, atol = 1e-3·rtol), per method, rtol and
# number of periods (build/scratch run of this test's own loop, SUNDIALS 6.4, x86-64). The bound
# is 10× the measured error: a wrong right-hand side or a broken step control moves the error by
# far more. The largest possible error is ≈ 2.2 (two opposite points of the polhode), so no bound
# above HORIZON_CAP = 0.5 is set: where 10× the measured error would exceed it the bound is the
# cap (dop853/auto at rtol 1e-6 over 2000 periods: 0.24 measured), and where the measured error
# is itself ≈ the amplitude (cvode_bdf, cvode_adams, arkode_verner6 at rtol 1e-6 over 2000
# periods: 1.2-1.3, the phase is lost) the case is not run: it could not fail.
#   cvode_*: variable-order multistep, K = error/(rtol·periods) up to 5e4;
#   arkode_verner6: the ARKODE_VERNER_8_5_6 table of SUNDIALS 6.4 converges at order 3, not 6
#     (docs/integrators.md), hence K up to 1e6 at tight tolerances;
#   taylor: K ≤ 30 (steps sized for a local error of rtol/10: docs/integrators.md);
#   splitting: with no torque it is the exact flow (rounding per step, step 1.0), no tolerance;
#   auto: the torque-free body is not stiff: auto is DOP853 step for step.
MEASURED = {
    "dop853": {(1e-6, 10): 1.3e-05, (1e-6, 2000): 2.4e-01, (1e-9, 10): 1.1e-08, (1e-9, 2000): 3.2e-04, (1e-12, 10): 5.9e-12, (1e-12, 2000): 1.7e-07},
    "cvode_bdf": {(1e-6, 10): 8.2e-04, (1e-6, 2000): 1.2e+00, (1e-9, 10): 2.3e-06, (1e-9, 2000): 5.5e-02, (1e-12, 10): 4.3e-09, (1e-12, 2000): 1.1e-04},
    "cvode_adams": {(1e-6, 10): 2.0e-04, (1e-6, 2000): 1.2e+00, (1e-9, 10): 8.3e-07, (1e-9, 2000): 1.5e-02, (1e-12, 10): 6.1e-10, (1e-12, 2000): 1.1e-6},
    "arkode_verner6": {(1e-6, 10): 3.4e-04, (1e-6, 2000): 1.3e+00, (1e-9, 10): 2.7e-06, (1e-9, 2000): 3.6e-01, (1e-12, 10): 2.1e-08, (1e-12, 2000): 1.9e-03},
    "arkode_fehlberg8": {(1e-6, 10): 9.4e-11, (1e-6, 2000): 4.8e-02, (1e-9, 10): 9.3e-11, (1e-9, 2000): 3.3e-05, (1e-12, 10): 9.4e-14, (1e-12, 2000): 1.5e-08},
    "taylor": {(1e-6, 10): 2.0e-06, (1e-6, 2000): 6.0e-02, (1e-9, 10): 1.8e-09, (1e-9, 2000): 5.7e-05, (1e-12, 10): 2.0e-13, (1e-12, 2000): 7.0e-09},
    "splitting": {(1e-6, 10): 9.6e-14, (1e-6, 2000): 1.2e-10, (1e-9, 10): 9.6e-14, (1e-9, 2000): 1.2e-10, (1e-12, 10): 9.6e-14, (1e-12, 2000): 1.2e-10},
    "auto": {(1e-6, 10): 1.3e-05, (1e-6, 2000): 2.4e-01, (1e-9, 10): 1.1e-08, (1e-9, 2000): 3.2e-04, (1e-12, 10): 5.9e-12, (1e-12, 2000): 1.7e-07},
}
HORIZON_CAP = 0.5
LOST_PHASE = {("cvode_bdf", 1e-6, 2000), ("cvode_adams", 1e-6, 2000), ("arkode_verner6", 1e-6, 2000)}


@pytest.fixture(scope="module")
def period():
    return g.TorqueFreeSolution(g.Body(MOMENTS), OMEGA0).period


@pytest.mark.parametrize("method", g.METHODS)
@pytest.mark.parametrize("rtol", [1e-6, 1e-9, 1e-12])
@pytest.mark.parametrize("periods", [10, 2000])
def test_integrators_against_elliptic_solution(method, rtol, periods, period):
    if (method, rtol, periods) in LOST_PHASE:
        pytest.skip("the phase is lost (measured error ≈ the amplitude): no bound could fail")
    t = np.linspace(0.0, periods * period, 1001)
    exact = euler_poinsot(MOMENTS, OMEGA0, t)
    with warnings.catch_warnings(record=True) as doubts, _verner_warning(method):
        warnings.simplefilter("always", g.AccuracyWarning)
        sol = g.solve(g.Model(g.Body(MOMENTS)), OMEGA0, (0.0, t[-1]), t_eval=t, method=method, rtol=rtol,
                      atol=1e-3 * rtol, max_steps=10**8, step=1.0 if method == "splitting" else None)
    assert sol.success, sol.message
    error = np.max(np.abs(sol.y - exact))
    if method == "splitting":  # its fixed step's rounding floor, 1.2e-10 over 2000 periods, misses rtol 1e-12: said
        said = any("exceeds rtol" in str(w.message) for w in doubts)
        assert said == (sol.error_estimate > rtol) and (said or error < rtol), (error, sol.error_estimate)
    else:
        assert not [w for w in doubts if issubclass(w.category, g.AccuracyWarning)], [str(w.message) for w in doubts]
    measured = MEASURED[method][(rtol, periods)]
    bound = min(10 * measured, HORIZON_CAP)
    assert error < bound, f"{method} rtol={rtol}: error {error:.3e} over {periods} periods exceeds {bound:.3e} (measured {measured:.1e})"


def test_the_docs_table_is_the_measured_errors():
    """docs/integrators.md, "Global error on the torque-free body": its table is MEASURED at the
    printed two digits (the bounds above are 10× these)."""
    from pathlib import Path
    text = (Path(__file__).parent.parent / "docs" / "integrators.md").read_text()
    for method in ("dop853", "cvode_bdf", "cvode_adams", "arkode_fehlberg8", "arkode_verner6", "taylor"):
        row = next(line for line in text.splitlines() if line.startswith(f"| {method} |") and line.count("/") == 4)
        printed = [float(v) for v in row.replace("|", "/").split("/")[2:8]]
        measured = [MEASURED[method][(rtol, n)] for n in (10, 2000) for rtol in (1e-6, 1e-9, 1e-12)]
        assert printed == [float(f"{m:.1e}") for m in measured], (method, printed, measured)


def test_verner_table_converges_at_order_3_with_fixed_steps():
    """docs/integrators.md: ARKODE_VERNER_8_5_6 of SUNDIALS 6.4 integrates at order 3. Fixed steps
    h = 0.2 … 0.025 (first_step = max_step = h, tolerances too loose to reject a step) on the
    torque-free body over t = 4 against the elliptic solution: measured error ratios 2^3.03,
    2^3.01, 2^3.00 (Fehlberg 8 for comparison: 2^6.9, 2^6.4 before rounding)."""
    exact = euler_poinsot(MOMENTS, OMEGA0, np.array([4.0]))[-1]

    def errors(method, steps):
        out = []
        for h in steps:
            sol = g.solve(g.Model(g.Body(MOMENTS)), OMEGA0, (0.0, 4.0), t_eval=[0.0, 4.0], method=method, rtol=0.5,
                          atol=0.5, first_step=h, max_step=h)
            assert sol.stats["steps"] == round(4.0 / h) and sol.stats["rejected_steps"] == 0
            out.append(np.max(np.abs(sol.y[-1] - exact)))
        return np.array(out)

    with pytest.warns(UserWarning, match="order 3"):
        verner = errors("arkode_verner6", (0.2, 0.1, 0.05, 0.025))
    orders = np.log2(verner[:-1] / verner[1:])
    assert np.all(np.abs(orders - 3.0) < 0.1), orders  # an order-6 table would give ≈ 6
    fehlberg = errors("arkode_fehlberg8", (0.2, 0.1))
    assert np.log2(fehlberg[0] / fehlberg[1]) > 6.0


def test_closed_form_matches_independent_reference():
    """The library's closed form (GSL) against the test's own (SciPy), over 50 periods and for
    several bodies and initial states covering both polhode families; 1e-10 allows the phase
    rounding growth ε·ν·t of elliptic functions at large argument."""
    for moments in ([1, 2, 3], [3, 1, 2], [2, 3, 1.5], [1.5, 1, 2]):
        for omega0 in ([0.1, 0.2, 3.0], [-2, 0.3, 0.1], [0.3, -1, 0.2], [0.2, 1, 0.01]):
            body = g.Body(moments)
            t = np.linspace(0, 50 * g.TorqueFreeSolution(body, omega0).period, 501)
            closed = g.torque_free(body, omega0, t)
            assert np.max(np.abs(closed.y - euler_poinsot(moments, omega0, t))) < 1e-10, (moments, omega0)


def test_closed_form_rejects_a_rotor():
    with pytest.raises(ValueError, match="rotor"):
        g.TorqueFreeSolution(g.Body([1, 2, 3], [0, 0, 0.1]), [1, 0, 0])


def _verner_warning(method):
    if method == "arkode_verner6":
        return pytest.warns(UserWarning, match="order 3")
    import contextlib

    return contextlib.nullcontext()


@pytest.mark.parametrize("rtol", [1e-8, 1e-10, 1e-12])
def test_taylor_rtol_gives_a_global_error_like_heyokas(rtol):
    """taylor's rtol means what heyoka's tol means (issue 12): on I = (2, 3, 4), ω0 = (0.4, 0.9,
    −0.3) over t = 2000 (bench/taylor_vs_heyoka.py) heyoka's final error is 53, 115 and 87 × tol
    at tol 1e-8, 1e-10, 1e-12 (measured, heyoka 7.13), taylor's 123, 61 and 139 × rtol; the goal
    is within ~10× of heyoka's, so the bound is 1000 × rtol. The previous rule (order +3, local
    error rtol·e^−0.7) gave 2790, 1204 and 933 × rtol here."""
    moments, omega0, t1 = [2.0, 3.0, 4.0], [0.4, 0.9, -0.3], 2000.0
    exact = euler_poinsot(moments, omega0, np.array([t1]))[-1]  # SciPy's ellipj: ~1e-12 here
    sol = g.solve(g.Model(g.Body(moments)), omega0, (0.0, t1), t_eval=[t1], method="taylor", rtol=rtol,
                  atol=1e-3 * rtol)
    assert sol.success, sol.message
    error = np.max(np.abs(sol.y[-1] - exact))
    assert error < 1000 * rtol, f"taylor rtol={rtol}: error {error:.3e} at t = 2000 exceeds 1000·rtol = {1000 * rtol:.1e}"
