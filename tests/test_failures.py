"""Each failure mode on a case built to provoke it: the run stops, keeps its partial trajectory
and says why."""

import numpy as np
import pytest

import gyrostat as g

OMEGA0 = [1.0, 0.5, -0.3]


def stiff_model():
    # damping rate 1e6 against rotation rates ~1: an explicit method's step is held at ~1e-6
    return g.Model(g.Body([1, 2, 3]), [g.LinearDamping(1e6 * np.eye(3))])


@pytest.mark.parametrize("method", ["dop853", "arkode_fehlberg8", "cvode_adams"])
def test_stiff_problem_exhausts_explicit_steps_and_suggests_bdf(method):
    sol = g.solve(stiff_model(), OMEGA0, (0, 10), method=method, max_steps=3000)
    assert sol.status == "max_steps_reached"
    assert "stiff" in sol.message and "cvode_bdf" in sol.message
    assert 0 < sol.t.size < 1001 and sol.t[0] == 0.0  # partial trajectory kept


def test_bdf_solves_the_stiff_problem():
    sol = g.solve(stiff_model(), OMEGA0, (0, 10), method="cvode_bdf", rtol=1e-8)
    assert sol.success
    # ω decays as exp(−1e6 t / A_i) (the gyroscopic coupling is negligible by then): zero to atol
    assert np.max(np.abs(sol.omega[-1])) < 1e-9
    assert sol.stats["steps"] < 2000


@pytest.mark.parametrize("method", ["dop853", "taylor", "cvode_bdf", "arkode_fehlberg8", "auto"])
def test_overflow_gives_non_finite_state(method):
    # spherical body, anti-damping: ω = ω0 exp(100 t) overflows double precision at t ≈ 7.09
    model = g.Model(g.Body([1, 1, 1]), [g.LinearDamping(-100 * np.eye(3))])
    sol = g.solve(model, OMEGA0, (0, 10), method=method, n_out=201)
    assert sol.status == "non_finite_state", sol.message
    assert "non-finite" in sol.message
    # the kept trajectory is finite and ends before the overflow time ln(1.8e308/1.16)/100 ≈ 7.08
    assert np.all(np.isfinite(sol.y)) and 3.0 < sol.t[-1] < 7.1


@pytest.mark.parametrize("method", ["dop853", "taylor", "cvode_bdf"])
def test_step_size_underflow(method):
    # at t ≈ 1e15 the spacing of doubles is 0.125: rtol 1e-10 needs steps below that
    model = g.Model(g.Body([1, 2, 3]), [g.ConstantTorque([0, 0, 0.1])])
    sol = g.solve(model, OMEGA0, (1e15, 1e15 + 1000), method=method, rtol=1e-10, max_steps=20000)
    assert sol.status == "step_size_underflow", sol.message
    assert "resolution of t" in sol.message


def test_max_steps_plain():
    sol = g.solve(g.Model(g.Body([1, 2, 3])), OMEGA0, (0, 1000), max_steps=10)
    assert sol.status == "max_steps_reached" and "max_steps = 10" in sol.message
    with pytest.raises(RuntimeError, match="max_steps_reached"):
        sol.raise_for_status()
