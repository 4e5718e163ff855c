"""The accuracy contract through every path besides a single solve (tests/test_accuracy_contract.py
checks that one against SciPy): ensembles (an estimate per member), scenes (integration.accuracy a
contract for every run, the report's estimate and verdict), sweeps (the estimate as a Dataset
variable) and the model ladder (its estimates measured, not the accuracy restated)."""

from __future__ import annotations

import copy
import math
import tomllib
import warnings
from pathlib import Path

import numpy as np
import pytest

import gyrostat as g
from gyrostat import runner
from gyrostat.scene import Scene

SCENES = Path(g.__file__).parent / "scenes"
EPS = 1e-4
BODY = g.Body([1.0, 1.4, 2.1])
DAMPED = g.Model(BODY, [g.LinearDamping(diagonal=[EPS, 2.5 * EPS, 0.7 * EPS])])


def _true_error(solution, reference) -> float:
    """The contract's measure (gyrostat.accuracy's, restated): ω as a vector, |G|, T, each relative
    to its largest size in the reference."""
    def rel(a, b):
        a, b = np.atleast_2d(a.T).T, np.atleast_2d(b.T).T
        return float(np.max(np.linalg.norm(a - b, axis=1)) / np.max(np.linalg.norm(b, axis=1)))
    return max(rel(solution.y[:, :3], reference.y[:, :3]),
               rel(solution["angular_momentum_norm"], reference["angular_momentum_norm"]),
               rel(solution["kinetic_energy"], reference["kinetic_energy"]))


def test_an_ensemble_meets_the_accuracy_member_by_member():
    """Three spins of the damped triaxial body over t = 0.2/ε: one rtol for all (the tightest any
    member needs; a member that misses runs again, tighter), each member's own estimate within [1/2, 30] of its true error (against the
    engine at rtol 1e-13, whose own error is ~1e-11 here: three decades below) and below 1e-6."""
    y0s = np.array([[0.15, 0.3, 1.0], [0.3, 0.1, 0.8], [0.05, 0.5, 1.2]])
    span = (0.0, 0.2 / EPS)
    runs = g.solve_ensemble(DAMPED, y0s, span, n_out=201, accuracy=1e-6)
    for y0, run in zip(y0s, runs):
        reference = g.solve(DAMPED, y0, span, n_out=201, rtol=1e-13, atol=1e-15, error_estimate=False)
        true = _true_error(run, reference)
        assert run.estimate.met and true <= 1e-6, (run.error_estimate, true)
        assert 0.5 <= run.error_estimate / true <= 30, (run.error_estimate, true, run.error_basis)


def test_an_ensembles_window_estimate_is_each_members_own():
    """Explicit rtol: each member measured by the window (the same as a single solve's, to the
    rounding of the batch lanes: 1e-3 relative), error_estimate=False measures nothing."""
    y0s = np.array([[0.15, 0.3, 1.0], [0.3, 0.1, 0.8]])
    runs = g.solve_ensemble(DAMPED, y0s, (0.0, 2000.0), n_out=101, rtol=1e-9)
    for y0, run in zip(y0s, runs):
        alone = g.solve(DAMPED, y0, (0.0, 2000.0), n_out=101, rtol=1e-9)
        assert run.error_estimate == pytest.approx(alone.error_estimate, rel=1e-3), run.error_basis
    off = g.solve_ensemble(DAMPED, y0s, (0.0, 2000.0), n_out=101, rtol=1e-9, error_estimate=False)
    assert all(math.isnan(run.error_estimate) and run.estimate is None for run in off)


def _scene(**integration) -> dict:
    return {"title": "damped triaxial", "kind": "rigid_body", "body": {"moments": [1.0, 1.4, 2.1]},
            "torques": [{"type": "linear_damping", "diagonal": [EPS, 2.5 * EPS, 0.7 * EPS]}],
            "initial": {"omega": [0.15, 0.3, 1.0]},
            "integration": {"model": "full", "t_span": [0.0, 0.2 / EPS], "n_out": 201, "method": "dop853",
                            **integration},
            "outputs": {"plots": []}}


def _solve(doc: dict):
    scene = Scene.from_dict(copy.deepcopy(doc), "scene")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        solutions, report, _ = runner.solve_scene(scene, progress=False)
    return next(iter(solutions.values())), report


def test_a_scenes_accuracy_chooses_the_tolerances_and_is_reported():
    """integration.accuracy without rtol: the run's rtol is chosen (not the 1e-8 default), the
    report carries the measured estimate, its basis and met = True, and the true error (the
    engine at rtol 1e-13) is below the accuracy."""
    solution, report = _solve(_scene(accuracy=1e-7))
    entry = report["runs"]["full"]["error_estimate"]
    assert entry["met"] is True and entry["accuracy"] == 1e-7 and "chosen for the accuracy" in entry["basis"]
    assert solution.options.rtol != 1e-8
    reference = g.solve(DAMPED, [0.15, 0.3, 1.0], (0.0, 0.2 / EPS), n_out=201, rtol=1e-13, atol=1e-15,
                        error_estimate=False)
    true = _true_error(solution, reference)
    assert true <= 1e-7 and 0.5 <= entry["value"] / true <= 30, (entry["value"], true)
    assert report["verdict"] == "ok"


def test_a_scene_whose_stated_rtol_misses_its_accuracy_says_so():
    """rtol stated (1e-6) and accuracy 1e-8: the stated rtol wins, the run is measured (its error
    is ~1e-4 here), the report's verdict is not ok and the warning names the measured error."""
    solution, report = _solve(_scene(accuracy=1e-8, rtol=1e-6))
    assert solution.options.rtol == 1e-6
    assert report["verdict"].startswith("accuracy not met"), report["verdict"]
    assert any("exceeds the accuracy 1e-08" in w for w in report["accuracy_warnings"]), report["accuracy_warnings"]


def test_a_scene_without_accuracy_keeps_its_tolerances_and_still_reports_an_estimate():
    solution, report = _solve(_scene())
    assert solution.options.rtol == 1e-8
    entry = report["runs"]["full"]["error_estimate"]
    assert entry["accuracy"] is None and entry["met"] is None and entry["value"] > 0


def test_a_sweep_records_each_members_estimate():
    """The estimate is a variable of the sweep's Dataset: finite, positive, per member, and equal
    to the member's own single run's (the same window estimate; 1e-3 for the batch lanes)."""
    doc = _scene(rtol=1e-9)
    doc["integration"]["t_span"] = [0.0, 500.0]
    ds = g.sweep(doc, {"initial.omega[2]": [0.8, 1.0]}, progress=False)
    values = ds["error_estimate"].values
    assert values.shape == (2,) and np.all(np.isfinite(values)) and np.all(values > 0), values
    assert "global error" in ds["error_estimate"].attrs["description"]
    alone = g.solve(DAMPED, [0.15, 0.3, 1.0], (0.0, 500.0), n_out=201, rtol=1e-9)
    assert values[1] == pytest.approx(alone.error_estimate, rel=1e-3)


def test_the_ladders_estimates_are_measurements_not_the_accuracy():
    """The shipped flat-spin scene (accuracy 0.01): the averaged rung's estimate is the probe's
    measurement (far below the accuracy, not equal to it), and the ladder chart's full-model point
    is its own measured estimate, not zero."""
    with open(SCENES / "explorer1_flat_spin.toml", "rb") as handle:
        doc = tomllib.load(handle)
    doc["outputs"]["plots"] = ["ladder"]
    solution, report = _solve(doc)
    ladder = report["ladder"]
    assert ladder["chosen"] == "averaged_triaxial"
    assert ladder["estimate"]["value"] < 1e-3, ladder["estimate"]["value"]  # measured ~1e-6, the accuracy is 1e-2
    rows = {row["rung"]: row for row in ladder["measured"]}
    assert 0 < rows["full"]["error"] == rows["full"]["estimate"] < 1e-2
    averaged = rows["averaged_triaxial"]
    # the estimate against the chart's own measurement over the whole span (within [1/2, 30]x)
    assert 0.5 <= averaged["estimate"] / averaged["error"] <= 30, (averaged["estimate"], averaged["error"])
    assert solution.error_estimate == pytest.approx(report["runs"][next(iter(report["runs"]))]["error_estimate"]["value"])


@pytest.mark.parametrize("bad", [0.0, -1e-6, float("nan"), 1.5, "1e-6", True])
def test_a_bad_accuracy_is_refused_by_name(bad):
    with pytest.raises(ValueError, match="accuracy"):
        g.solve_ensemble(DAMPED, np.array([[0.1, 0.2, 1.0]]), (0.0, 1.0), accuracy=bad)


def test_the_ladders_full_model_meets_the_accuracy_on_what_the_ladder_compares():
    """The issue's case: model = "auto" at accuracy 1e-7, ε = 1e-4: the ladder takes the full model
    (the averaged rung's measured error is above 1e-7), whose rtol is then chosen for 1e-7 on what
    the ladder compares for a triaxial body, |G| and T (not ω's phase): the true error of |G| and T
    (the engine at rtol 1e-13) is at most 1e-7 and the estimate within [1/2, 30] of it."""
    solution, report = _solve(_scene(model="auto", accuracy=1e-7))
    assert report["model"] == "full" and list(solution.error_estimates) == ["compared"]
    reference = g.solve(DAMPED, [0.15, 0.3, 1.0], (0.0, 0.2 / EPS), n_out=201, rtol=1e-13, atol=1e-15,
                        error_estimate=False)
    invariants = np.column_stack([reference["angular_momentum_norm"], reference["kinetic_energy"]])
    mine = np.column_stack([solution["angular_momentum_norm"], solution["kinetic_energy"]])
    true = float(np.max(np.linalg.norm(mine - invariants, axis=1)) / np.max(np.linalg.norm(invariants, axis=1)))
    assert true <= 1e-7 and 0.5 <= solution.error_estimate / true <= 30, (solution.error_estimate, true)


@pytest.mark.parametrize("name", ["p004_triaxial", "p001_xy_ratio_map", "p003_case1_theta0_5deg",
                                  "p001_explicit_moving_mass", "p000_A1p3_C1_M3-0p1"])
def test_every_familys_scenes_take_the_accuracy(name):
    """integration.accuracy is a key of every scene kind (one [integration] table for all:
    gyrostat.kind.integration_table): given without rtol and atol, each run of a shipped scene of
    every family chooses its tolerances for it and reports met = True with its measured estimate."""
    with open(SCENES / f"{name}.toml", "rb") as handle:
        doc = tomllib.load(handle)
    doc["integration"]["accuracy"] = 1e-6
    for key in ("rtol", "atol"):
        doc["integration"].pop(key, None)
    _, report = _solve(doc)
    for run, entry in report["runs"].items():
        estimate = entry["error_estimate"]
        assert estimate["met"] is True and 0 < estimate["value"] <= 1e-6, (run, estimate)
        assert "chosen for the accuracy 1e-06" in estimate["basis"], (run, estimate["basis"])


def test_the_contract_chooses_the_integrator_when_none_is_given():
    """accuracy without a method: DOP853's and Taylor's probes are timed and the cheaper taken (the
    basis names both predictions); the choice meets the accuracy (true error against the engine at
    rtol 1e-13, ~1e-11 here). A model Taylor does not cover (a viscous cavity) stays on DOP853."""
    span = (0.0, 0.5 / EPS)
    solution = g.solve(DAMPED, [0.15, 0.3, 1.0], span, n_out=201, accuracy=1e-8)
    assert "chosen: predicted dop853" in solution.error_basis and "taylor" in solution.error_basis
    assert solution.method in ("dop853", "taylor")
    reference = g.solve(DAMPED, [0.15, 0.3, 1.0], span, n_out=201, rtol=1e-13, atol=1e-15, error_estimate=False)
    assert _true_error(solution, reference) <= 1e-8
    cavity = g.Model(g.Body([12.0, 12.0, 4.0]), [g.ViscousCavity(density=970.0, viscosity=2.0, radius=0.25)])
    other = g.solve(cavity, [0.05, 0.0, 2.0], (0.0, 2000.0), n_out=101, accuracy=1e-8)
    assert other.method == "dop853" and other.estimate.met, other.error_basis
    assert g.solve(DAMPED, [0.15, 0.3, 1.0], span, n_out=201, accuracy=1e-8, method="dop853").method == "dop853"


def test_an_ensemble_of_every_family_carries_each_members_estimate():
    """solve_ensemble with accuracy on a model of each family (moving mass, Lagrange top, the
    orthogonal torque, both averaged models): every member meets it by its own measured estimate,
    which equals a single solve's to the batch lanes' rounding (the same rtol chosen: 1e-3), or is
    at most the accuracy where the ensemble's shared rtol is tighter."""
    scenes = {"p001_explicit_moving_mass": "full", "p003_case1_theta0_5deg": "averaged",
              "p004_triaxial": "constant", "p000_A1p3_C1_M3-0p1": "averaged", "explorer1_flat_spin": None}
    for name, run_name in scenes.items():
        with open(SCENES / f"{name}.toml", "rb") as handle:
            doc = tomllib.load(handle)
        if run_name is None:
            doc["integration"]["model"] = "averaged_triaxial"
        scene = Scene.from_dict(doc, name)
        run = scene.runs[0] if run_name is None else next(r for r in scene.runs if r.name == run_name)
        span = (run.t_span[0], run.t_span[0] + 0.2 * (run.t_span[1] - run.t_span[0]))
        members = g.solve_ensemble(run.model, [run.y0, run.y0], span, n_out=51, accuracy=1e-6, check_validity=False)
        for member in members:
            assert member.estimate.met and 0 < member.error_estimate <= 1e-6, (name, member.error_basis)


def test_the_companion_is_made_once_for_shared_options_and_afresh_for_a_callers_own():
    # the companion's options (tolerances / rho) are kept for the options cache's own Options, which are
    # never modified; a caller's Options may change between calls, and its companion must follow it
    from gyrostat import accuracy, options

    w0 = np.array([0.15, 0.3, 1.0])
    first = g.solve(DAMPED, w0, (0.0, 50.0), rtol=1e-7, n_out=11)
    again = g.solve(DAMPED, w0, (0.0, 50.0), rtol=1e-7, n_out=11)
    shared = options.options_of(None, tuple(1e-7 if name == "rtol" else None for name in options.OPTION_NAMES))
    assert accuracy.companion_of(shared) is accuracy.companion_of(shared)
    assert accuracy.companion_of(shared)[0].rtol == pytest.approx(1e-7 / 4.0, rel=1e-15)  # dop853's rho = 4
    assert first.error_estimate == again.error_estimate  # the same companion, the same measurement

    own = g.Options()
    own.rtol = 1e-7
    before = accuracy.companion_of(own)
    own.rtol = 1e-9
    after = accuracy.companion_of(own)
    assert before is not after and after[0].rtol == pytest.approx(1e-9 / 4.0, rel=1e-15)
    mutated = g.solve(DAMPED, w0, (0.0, 50.0), options=own, n_out=11)
    assert mutated.error_estimate < first.error_estimate / 10  # rtol 100x tighter: its estimate follows


def test_the_basis_is_written_when_read_in_its_place_among_the_notes():
    # the basis text of a run's estimate is written when first read (the default estimate of a ~20 us
    # averaged run spent ~3 us formatting it): the words and the notes' order must be what eager
    # formatting gave, once, and a pickled estimate must carry the text
    import pickle

    from gyrostat import accuracy

    w0 = np.array([0.15, 0.3, 1.0])
    sol = g.solve(DAMPED, w0, (0.0, 500.0), rtol=1e-7, n_out=201)
    estimate = sol.estimate
    shared = g.options.options_of(None, tuple(1e-7 if name == "rtol" else 201 if name == "n_out" else None
                                              for name in g.options.OPTION_NAMES))
    companion, gain, _ = accuracy.companion_of(shared)
    made = g._core.window_estimate(DAMPED._core, sol._result, 0.0, w0, 500.0, companion, accuracy._rule(gain))
    values, k, grown, window, count, failure, _, _, fitted = made
    assert fitted, "a run of many steps: its growth is fitted"
    assert estimate.basis == (f"measured over the first 20% of the span ([0, {window:.6g}], {count} times) against a run "
                              f"with rtol and atol / 4 (difference x 1.33), grown as t^{k:.2g} to t = 500, times 3")
    sol.doubt("a doubt added after the run")
    assert sol.notes[-2] == f"error estimate {estimate.value:.3g}: {estimate.basis}"
    assert sol.notes[-1] == "a doubt added after the run" and sol.accuracy_warnings == ("a doubt added after the run",)
    again = pickle.loads(pickle.dumps(estimate))
    assert again == estimate and again.basis == estimate.basis and again.value == estimate.value

    fresh = g.solve(DAMPED, w0, (0.0, 500.0), rtol=1e-7, n_out=201)
    first_look = list(fresh.notes)  # the line written once, on the first look
    assert fresh.notes == first_look and sum(n.startswith("error estimate") for n in first_look) == 1, first_look

    chosen = g.solve(DAMPED, w0, (0.0, 500.0), accuracy=1e-5, n_out=201)
    assert chosen.error_basis.startswith("rtol ") and " chosen for the accuracy 1e-05 (" in chosen.error_basis, \
        chosen.error_basis
    assert "); measured at 201 output times over the whole run against a run with rtol and atol / " in chosen.error_basis, \
        chosen.error_basis


@pytest.mark.parametrize("case", ["short", "probed"])
def test_a_single_runs_contract_is_the_general_one(case):
    # gyrostat.solve(accuracy=) runs contract.meet_single: a short run (the averaged model, ~100 right-hand
    # sides) is run and measured in one engine call, its companion recording only the measured outputs; a
    # longer one goes on to contract.meet with the probe's first run. Both must give the general path's
    # answer and estimate bit for bit (the same runs), and its words
    from gyrostat import accuracy, contract

    if case == "short":
        model = g.AveragedModel(g.Body([8.0, 8.0, 4.0]), [g.ViscousCavity(1260, 1000, 0.48),
                                                          g.ConstantTorque([0.0, 0.0, -0.01])])
        y0, t1, asked, method = np.array([1.0, 1.0]), 60.0, 1e-6, None
    else:
        model, y0, t1, asked, method = DAMPED, np.array([0.15, 0.3, 1.0]), 0.2 / EPS, 1e-6, "dop853"
    kw = {} if method is None else {"method": method}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # (the averaged model's validity: not what is tested here)
        single = g.solve(model, y0, (0.0, t1), accuracy=asked, n_out=201, check_validity=False, **kw)
    opts = g.options.make_options(n_out=201, **kw)
    answers, estimates = contract.meet(accuracy.SingleRun(model._core, y0, 0.0), [model._core], opts, 0.0, t1, asked,
                                       float(np.abs(y0).max()), choose=method is None)
    assert np.array_equal(single.y, answers[0].y) and np.array_equal(single.t, answers[0].t)
    assert single.error_estimate == estimates[0].value and single.estimate.per_quantity == estimates[0].per_quantity
    assert single.error_basis == estimates[0].basis, (single.error_basis, estimates[0].basis)
    assert 0 < single.error_estimate <= asked and single.estimate.met
    if case == "short":
        assert "no probe: a short run" in single.error_basis, single.error_basis
        # against SciPy on the (a, r) system written here (paper 000 (5) with the axial torque -0.01:
        # a' = k C (A - C) r^2 a / A^3, r' = k (C - A) a^2 r / (A C) - 0.01 / C, k = rho P0 / nu), as
        # tests/test_accuracy_contract.py's averaged scene; a, r, |G| = sqrt(A^2 a^2 + C^2 r^2) and
        # T = (A a^2 + C r^2) / 2 each relative to its largest size
        from scipy.integrate import solve_ivp

        big_a, big_c, k = 8.0, 4.0, 1260 * 0.48 / 1000

        def rhs(t, z):
            a, r = z
            return [k * big_c * (big_a - big_c) * r * r * a / big_a**3,
                    k * (big_c - big_a) * a * a * r / (big_a * big_c) - 0.01 / big_c]

        def quantities(a, r):
            return [a, r, np.sqrt(big_a**2 * a * a + big_c**2 * r * r), 0.5 * (big_a * a * a + big_c * r * r)]

        def apart(one, other):
            return max(float(np.max(np.abs(x - z)) / np.max(np.abs(x))) for x, z in zip(one, other))

        runs = [solve_ivp(rhs, (0.0, t1), y0, method="DOP853", t_eval=single.t, rtol=r, atol=r * 1e-3).y
                for r in (1e-13, 1e-12)]
        reference = quantities(*runs[0])
        true = apart(reference, quantities(*np.asarray(single.y, float).T))
        own = apart(reference, quantities(*runs[1]))  # (the rtol-1e-12 run bounds the reference's own error)
        assert true > 10 * own, (true, own)
        # the band the contract promises: the estimate within [1/2, 30] of the true error
        assert 0.5 <= single.error_estimate / true <= 30, (single.error_estimate, true)
    else:
        assert "probe at three tolerances" in single.error_basis, single.error_basis
