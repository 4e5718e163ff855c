"""Ensembles: identical to single runs, in index order; a bad member keeps its own error."""

import numpy as np

import gyrostat as g


def test_ensemble_equals_single_runs_exactly():
    rng = np.random.default_rng(1)
    y0s = rng.normal(size=(24, 3))
    model = g.Model(g.Body([1, 2, 3]), [g.LinearDamping(0.01 * np.eye(3))])
    # batch=False: bit for bit (SIMD batches equal single runs to the tolerance: tests/test_batch.py)
    ensemble = g.solve_ensemble(model, y0s, (0, 50), rtol=1e-10, n_out=51, threads=2, batch=False)
    assert len(ensemble) == 24
    for i, member in enumerate(ensemble):
        single = g.solve(model, y0s[i], (0, 50), rtol=1e-10, n_out=51)
        assert np.array_equal(member.y, single.y)  # same numbers, not "close"
        assert member.stats == single.stats


def test_ensemble_with_one_model_per_member():
    bodies = [g.Body([1, 2, 2.5 + 0.1 * i]) for i in range(6)]
    models = [g.Model(b, [g.ConstantTorque([0, 0, 0.1])]) for b in bodies]
    y0s = np.tile([1.0, 0.5, -0.3], (6, 1))
    ensemble = g.solve_ensemble(models, y0s, (0, 20), method="cvode_bdf", rtol=1e-9, n_out=11)
    for model, member in zip(models, ensemble):
        single = g.solve(model, [1.0, 0.5, -0.3], (0, 20), method="cvode_bdf", rtol=1e-9, n_out=11)
        assert np.array_equal(member.y, single.y)


def test_bad_member_does_not_spoil_the_others():
    y0s = np.tile([1.0, 0.5, -0.3], (5, 1))
    y0s[2, 1] = np.nan
    model = g.Model(g.Body([1, 2, 3]))
    ensemble = g.solve_ensemble(model, y0s, (0, 10), n_out=11)
    assert ensemble[2].status == "invalid_input"
    assert "member 2" in ensemble[2].message and "nan" in ensemble[2].message.lower()
    for i in (0, 1, 3, 4):
        assert ensemble[i].success
        assert np.array_equal(ensemble[i].y, ensemble[0].y)


def test_failing_member_reports_its_own_failure():
    models = [g.Model(g.Body([1, 2, 3])), g.Model(g.Body([1, 2, 3]), [g.LinearDamping(1e6 * np.eye(3))])]
    ensemble = g.solve_ensemble(models, np.tile([1.0, 0.5, -0.3], (2, 1)), (0, 10), max_steps=3000)
    assert ensemble[0].success
    assert ensemble[1].status == "max_steps_reached" and "cvode_bdf" in ensemble[1].message
