"""Forward sensitivities by the Taylor method (``method="taylor"``: the variational equations of
the gyrostat under constant and linear torques, polynomial, by their Taylor recursion;
cpp/include/gyrostat/integrate/variational_taylor.hpp) against references that do not use it:

1. heyoka's variational equations (tests/data/heyoka_sensitivities.json, as
   test_sensitivity_paths.py's test of the DOP853 path);
2. the DOP853 path on a damped gyrostat with a rotor and a constant torque, with and without the
   attitude, and on an orbit;
3. central differences of plain Taylor runs (Richardson), for parameters the right-hand side is
   affine in;
4. the dense output against a run with its times as output times;
5. an ensemble's members against their single runs, and the measured errors against the truth;
6. the models and torques it does not apply to, refused by name.

An error is max over times and components of |mine − reference| / max |reference| unless said.
"""

import numpy as np
import pytest

import gyrostat as g
from test_sensitivity_paths import heyoka_errors
D = [[0.05, 0.01, 0.0], [0.01, 0.08, 0.0], [0.0, 0.0, 0.03]]
W0 = [0.15, 0.3, 1.0]
T = np.linspace(0.0, 30.0, 31)
STATE_NAMES = ["p", "r"]
PARAMETERS = ["moments[0]", "moments[2]", "rotor[0]", "rotor[2]", "LinearDamping.matrix[0,1]",
              "LinearDamping.matrix[2,2]", "ConstantTorque.moment[1]"]


def rel_error(mine, ref):
    mine, ref = np.asarray(mine, float), np.asarray(ref, float)
    assert mine.shape == ref.shape, f"shape {mine.shape}, reference {ref.shape}"
    return float(np.max(np.abs(mine - ref)) / np.max(np.abs(ref)))


def damped(attitude=True, rotor0=0.05, moment1=-0.02, **kw):
    body = g.Body([1.0, 1.4, 2.1], rotor=[rotor0, -0.02, 0.1])
    return g.Model(body, [g.LinearDamping(matrix=D), g.ConstantTorque([0.01, moment1, 0.005])], attitude=attitude, **kw)


def run(model, method, rtol, names, **kw):
    return g.solve(model, W0, (T[0], T[-1]), t_eval=T, rtol=rtol, atol=1e-15, method=method, sensitivities=names,
                   error_estimate=False, progress=False, **kw)


@pytest.mark.parametrize("case", ["free", "damped"])
def test_against_heyoka_variational_equations(case):
    """heyoka 7.13's var_ode_sys at its default tolerance (test_sensitivity_paths.py: the same cases
    by DOP853)."""
    state, errors = heyoka_errors(case, "taylor")
    # the state at rtol 1e-13 over t = 20 (measured 7e-16 and 1e-16 off heyoka's)
    assert state <= 1e-12, state
    for name, error in errors.items():
        # 1e-10 relative to each vector's size, as the DOP853 path's test. Measured: the initial state's
        # columns 3.4e-15 (the run at rtol 1e-13), the damping entries ≤ 9.8e-12 (the rounding of their
        # coefficients' central difference), the moments ≤ 9.4e-11: their step ε^(1/3)·max J moves J_0 by
        # 1.3e-5 of itself, a truncation (h/J)² ~ 1e-10 of the difference in 1/J, in the Python layer's
        # moved models, so the same in the DOP853 path (9.5e-11)
        assert error <= 1e-10, (name, error)


@pytest.mark.parametrize("attitude", [True, False])
def test_against_dop853(attitude):
    """Every kind of column (initial state, moments, rotor, damping matrix entry, constant torque) on
    a damped gyrostat with a rotor, against the DOP853 path at rtol 1e-13."""
    names = STATE_NAMES + (["q_x"] if attitude else []) + PARAMETERS
    reference = run(damped(attitude), "dop853", 1e-13, names)
    taylor = run(damped(attitude), "taylor", 1e-12, names)
    assert taylor.success and taylor.method == "taylor", taylor.message
    # the states: both runs good to ~1e-13 over t = 30 (measured 3e-14 apart with the attitude)
    assert np.allclose(taylor.y, reference.y, rtol=0, atol=1e-11)
    for name in names:
        error = rel_error(taylor.sensitivity(name), reference.sensitivity(name))
        if name in STATE_NAMES or name == "q_x":
            # an initial component's column has no ∂f/∂p: both runs' own errors, ~1e-13 (measured ≤ 3e-14)
            assert error < 1e-11, (name, error)
        else:
            # a parameter's ∂f/∂p is a central difference in both paths, DOP853's of the two models'
            # rates (its rounding ε|f|/2h ≈ 1e-10 of the derivative for the rotor and the torque: measured
            # against Richardson below), the Taylor one's of their coefficients; measured apart ≤ 6.8e-11
            assert error < 5e-10, (name, error)
        if name == "q_x":
            continue  # (T does not depend on the attitude)
        # an output's derivative (∂T/∂p: the central difference along S_j, the same code after the run)
        assert rel_error(taylor.sensitivity(name, of="kinetic_energy"),
                         reference.sensitivity(name, of="kinetic_energy")) < 5e-9, name


def test_on_an_orbit():
    """The orbit model forwards the gyrostat's coefficients: its sensitivities by Taylor as DOP853's,
    its orbit outputs' derivatives too."""
    model = damped(orbit=g.Orbit(rate=0.01))
    names = ["q", "moments[1]", "LinearDamping.matrix[2,2]"]
    reference = run(model, "dop853", 1e-13, names)
    taylor = run(model, "taylor", 1e-12, names)
    for name in names:
        # as test_against_dop853 (measured ≤ 1.3e-11; pitch's derivative, a central difference along S_j
        # after the run, ≤ 1.7e-10)
        assert rel_error(taylor.sensitivity(name), reference.sensitivity(name)) < 5e-10, name
        assert rel_error(taylor.sensitivity(name, of="pitch"), reference.sensitivity(name, of="pitch")) < 5e-9, name


@pytest.mark.parametrize(("name", "keyword", "value"), [("rotor[0]", "rotor0", 0.05),
                                                        ("ConstantTorque.moment[1]", "moment1", -0.02)])
def test_affine_parameters_against_richardson(name, keyword, value):
    """∂y/∂p for a parameter the right-hand side is affine in, against (4 C(h/2) − C(h))/3 of the
    central differences C(h) of plain Taylor runs at rtol 1e-14 (h = 1e-3: truncation after
    Richardson O(h⁴), the runs' rounding ~1e-14/h)."""
    def state(p):
        return g.solve(damped(False, **{keyword: p}), W0, (T[0], T[-1]), t_eval=T, rtol=1e-14, atol=1e-17,
                       method="taylor", error_estimate=False).y

    def central(h):
        return (state(value + h) - state(value - h)) / (2 * h)

    reference = (4 * central(5e-4) - central(1e-3)) / 3
    taylor = run(damped(False), "taylor", 1e-13, [name])
    # the coefficients' central difference rounds to ~ε/(2h) ≈ 2e-11 of ∂f/∂p (measured 2.9e-12 for
    # the rotor, 9.8e-12 for the torque, where the DOP853 path's central difference of the rates
    # gives 1.0e-10 and 8.8e-10)
    assert rel_error(taylor.sensitivity(name), reference) < 1e-10, name


def test_dense_output_against_output_times():
    """sol.sensitivity(name, t=...) between the output times, against a run with those times as its
    outputs: the Taylor steps depend on (t, y) alone, not on the outputs, so both runs take the same
    steps and evaluate the same polynomials (the dense output's in s = (t' − t)/h, the outputs'
    in t' − t)."""
    names = ["q_y", "moments[1]", "rotor[2]", "LinearDamping.matrix[0,1]"]
    middle = np.linspace(0.37, 29.6, 23)
    model = damped()
    sol = g.solve(model, W0, (0.0, 30.0), n_out=5, rtol=1e-10, atol=1e-12, method="taylor", dense_output=True,
                  sensitivities=names)
    there = g.solve(model, W0, (0.0, 30.0), t_eval=middle, rtol=1e-10, atol=1e-12, method="taylor", sensitivities=names)
    assert sol.stats["steps"] == there.stats["steps"], (sol.stats, there.stats)
    for name in names:
        reference = there.sensitivity(name)
        scale = np.max(np.abs(reference))
        # the same polynomials evaluated two ways: rounding (measured ≤ 2.7e-16 of the size)
        assert np.allclose(sol.sensitivity(name, t=middle), reference, rtol=0, atol=1e-13 * scale), name
        assert np.allclose(sol.sensitivity(name, t=sol.t), sol.sensitivity(name), rtol=0, atol=1e-12 * scale), name
        assert np.allclose(sol.sensitivity(name, of="r", t=middle), reference[:, 2], rtol=0, atol=1e-12 * scale), name
    assert np.allclose(sol(middle), there.y, rtol=0, atol=1e-12)


def test_ensemble_members_equal_their_single_runs():
    models = [damped(), damped(rotor0=0.07)]
    y0s = np.array([W0, [0.2, 0.1, 0.9]])
    names = ["p", "rotor[0]"]
    members = g.solve_ensemble(models, y0s, (0.0, 20.0), n_out=6, rtol=1e-10, method="taylor", sensitivities=names,
                               threads=2)
    for i, member in enumerate(members):
        single = g.solve(models[i], y0s[i], (0.0, 20.0), n_out=6, rtol=1e-10, method="taylor", sensitivities=names)
        for name in names:  # the same code on the same data: bit for bit
            assert np.array_equal(member.sensitivity(name), single.sensitivity(name)), (i, name)


def test_error_is_measured():
    """The companion run (rtol / 100 for taylor) measures the sensitivities' errors, against the DOP853
    path at rtol 1e-13 (the truth here to ~1e-10, 27× below the run's error)."""
    names = ["p", "moments[0]"]
    sol = g.solve(damped(), W0, (T[0], T[-1]), t_eval=T, rtol=1e-7, method="taylor", sensitivities=names)
    reference = run(damped(), "dop853", 1e-13, names)
    for name in names:
        true = rel_error(sol.sensitivity(name), reference.sensitivity(name))
        reported = sol.sensitivity_errors[name]
        # a companion 100× tighter sees the run's own error (measured reported/true 1.01 and 1.01)
        assert true / 2 <= reported <= 2 * true, (name, reported, true)


@pytest.mark.parametrize("model, y0, named", [
    (g.Model(g.Body([1.0, 1.4, 2.1]), [g.ViscousCavity(density=1.0, viscosity=0.1, p0=0.5)]), W0, "ViscousCavity"),
    (g.Model(g.Body([1.0, 1.4, 2.1]), [g.GravityGradient()], orbit=g.Orbit(rate=0.01)), W0, "GravityGradient"),
    (g.AveragedModel(g.Body([2.0, 2.0, 1.0]), [g.LinearDamping(diagonal=[0.01, 0.01, 0.02])]), [0.1, 0.0, 1.0],
     "averaged_symmetric"),
])
def test_refused_where_it_does_not_apply(model, y0, named):
    """A torque that is not constant or linear in ω, or a model other than the gyrostat: refused by
    name, the message pointing to dop853 and cvode_bdf."""
    with pytest.raises(ValueError) as info:
        g.solve(model, y0, (0.0, 10.0), n_out=3, method="taylor", sensitivities=["moments[2]"])
    message = str(info.value)
    assert named in message and "taylor" in message, message
    assert "use dop853 or cvode_bdf" in message, message
