"""Sensitivities on every path a user meets them: against heyoka's variational equations (a peer),
through solve_ensemble (each member as its own run), with events (∂t_event/∂p against central
differences of the event times), in a scene file's outputs and in a sweep's Dataset, and the
inputs they refuse. tests/test_sensitivities.py checks the derivatives of every family."""

import json
import warnings
from pathlib import Path

import numpy as np
import pytest

import gyrostat
from gyrostat.events import Event

DATA = Path(__file__).resolve().parent / "data"


def heyoka_errors(case, method):
    """A run of heyoka's case (tests/data/heyoka_sensitivities.json) by ``method`` at rtol 1e-13,
    each sensitivity held to the tolerance (``sensitivity_error_control``: the peer comparison is
    of the derivatives at the run's accuracy): the state's largest error, and each sensitivity's
    largest error relative to the size of its vector at each time (rows where that vector is 0 are
    measured absolutely)."""
    data = json.loads((DATA / "heyoka_sensitivities.json").read_text())["cases"][case]
    torques = [gyrostat.LinearDamping(matrix=data["D"])] if np.any(data["D"]) else []
    model = gyrostat.Model(gyrostat.Body(data["moments"]), torques)
    sol = gyrostat.solve(model, data["omega0"], (0.0, data["t"][-1]), t_eval=data["t"], rtol=1e-13, atol=1e-15,
                         method=method, sensitivities=data["parameters"], sensitivity_error_control=True)
    assert sol.method == method, sol.method
    errors = {}
    for name in data["parameters"]:
        reference = np.array(data["sensitivity"][name])
        scale = np.max(np.abs(reference), axis=1, keepdims=True)
        errors[name] = float(np.max(np.abs(sol.sensitivity(name) - reference) / np.where(scale > 0, scale, 1.0)))
    return float(np.max(np.abs(sol.y - np.array(data["y"])))), errors


@pytest.mark.parametrize("case", ["free", "damped"])
def test_against_heyoka_variational_equations(case):
    """heyoka 7.13's var_ode_sys at its default tolerance (ε, order 20; checked in
    tests/data/make_heyoka_sensitivities.py against an 80-bit run and 9-point differences to 3e-15)."""
    state, errors = heyoka_errors(case, "dop853")
    assert state <= 1e-12, state
    for name, error in errors.items():
        # the 1e-10, relative to each vector's size: our run at rtol 1e-13 is good to ~1e-12, the
        # parameter's central difference of the right-hand side is exact (affine) or ~1e-11 (the moments)
        assert error <= 1e-10, (name, error)


def _cavity_model(viscosity=0.8):
    body = gyrostat.Body([10.0, 10.0, 14.0])
    return gyrostat.Model(body, [gyrostat.ViscousCavity(density=10.0, viscosity=viscosity, p0=0.02),
                                 gyrostat.LinearDamping(diagonal=[0.0, 0.0, 0.02])])


def test_ensemble_members_equal_their_single_runs():
    model = _cavity_model()
    names = ["ViscousCavity.viscosity", "p"]
    y0s = np.array([[0.3, 0.0, 1.0], [0.2, 0.0, 1.0], [0.1, 0.05, 1.2]])
    members = gyrostat.solve_ensemble([model, _cavity_model(0.9), model], y0s, (0.0, 50.0), n_out=6, rtol=1e-10,
                                      sensitivities=names, threads=2)
    for i, member in enumerate(members):
        single = gyrostat.solve([model, _cavity_model(0.9), model][i], y0s[i], (0.0, 50.0), n_out=6, rtol=1e-10,
                                sensitivities=names)
        assert member.sensitivities == tuple(names)
        for name in names:  # the same code on the same data: bit for bit
            assert np.array_equal(member.sensitivity(name), single.sensitivity(name)), (i, name)
        assert np.isfinite(member.error_estimate)


def _event_times(viscosity, p0, events):
    run = gyrostat.solve(_cavity_model(viscosity), [p0, 0.0, 1.0], (0.0, 200.0), n_out=6, rtol=1e-13, atol=1e-15,
                         events=events)
    return run.t_events


def test_event_time_derivatives_against_central_differences():
    events = [Event("nutation_angle", 0.1, direction=-1), Event("r", 0.9, terminal=True),
              lambda t, y: y[0] - 0.05]
    sol = gyrostat.solve(_cavity_model(), [0.3, 0.0, 1.0], (0.0, 200.0), n_out=6, rtol=1e-11, events=events,
                         sensitivities=["ViscousCavity.viscosity", "p"])
    assert sol.terminal_event == 1 and sol.t[-1] <= sol.t_events[1][0]
    for name, value, step, at in (("ViscousCavity.viscosity", 0.8, 1e-5 * 0.8, lambda v: (v, 0.3)),
                                  ("p", 0.3, 1e-6, lambda v: (0.8, v))):
        plus, minus = _event_times(*at(value + step), events), _event_times(*at(value - step), events)
        for k in range(3):
            central = (np.asarray(plus[k]) - np.asarray(minus[k])) / (2 * step)
            derivative = sol.sensitivity(name, event=k)
            assert derivative.shape == central.shape == (len(sol.t_events[k]),)
            # runs at rtol 1e-13 over steps of 1e-5 relative: the central differences hold ~1e-7 of the value
            assert np.allclose(derivative, central, rtol=1e-6, atol=1e-6 * np.max(np.abs(central))), (name, k)


def test_scene_files_and_sweeps_carry_them(tmp_path):
    scene = (Path(gyrostat.__file__).parent / "scenes" / "forced_damped.toml").read_text()
    scene = scene.replace("n_out = 2001", 'n_out = 21\nsensitivities = ["LinearDamping.matrix[0,0]", "p"]')
    scene = scene.replace('plots = ["omega", "invariants", "euler_angles"]', "plots = []")
    path = tmp_path / "forced.toml"
    path.write_text(scene)
    from gyrostat.runner import run_scene
    run_scene(path, tmp_path / "out", progress=False)
    with np.load(tmp_path / "out" / "forced" / "result.npz") as file:  # (closed: no ResourceWarning)
        saved = dict(file)
    from gyrostat.scene import Scene
    loaded = Scene.from_file(path)
    run = loaded.runs[0]
    direct = gyrostat.solve(run.model, run.y0, run.t_span, **run.options)
    assert np.array_equal(saved["d_r__d_LinearDamping.matrix_0_0"], direct.sensitivity("LinearDamping.matrix[0,0]", of="r"))
    assert np.array_equal(saved["d_kinetic_energy__d_p"], direct.sensitivity("p", of="kinetic_energy"))

    from gyrostat import sweeps
    plan = sweeps.Plan(path, {"torques[0].moment[2]": [0.05, 0.1]})
    chunk = sweeps.solve_chunk(plan, 0, 2, trajectories=False)
    again = gyrostat.solve(run.model, run.y0, run.t_span, **run.options)
    # member 0 is the scene as written (moment[2] = 0.05): its final derivatives are the run's
    assert chunk["final_d_r__d_p"][0] == again.sensitivity("p", of="r")[-1]
    assert np.isfinite(chunk["final_d_nutation_angle__d_LinearDamping.matrix_0_0"]).all()


def test_what_they_refuse():
    model = _cavity_model()
    with pytest.raises(ValueError, match="accuracy"):
        gyrostat.solve(model, [0.3, 0.0, 1.0], (0.0, 10.0), accuracy=1e-6, sensitivities="p")
    with pytest.raises(ValueError, match="closed form"):
        gyrostat.solve(gyrostat.TorqueFreeModel(gyrostat.Body([1.0, 2.0, 3.0])), [0.3, 0.0, 1.0], (0.0, 10.0),
                       sensitivities="p")
    with pytest.raises(ValueError, match="asked twice"):
        gyrostat.solve(model, [0.3, 0.0, 1.0], (0.0, 10.0), sensitivities=["p", "p"])
    with pytest.raises(ValueError, match="'auto'"):
        gyrostat.solve(model, [0.3, 0.0, 1.0], (0.0, 10.0), method="auto", sensitivities="p")
    # a parameter whose move breaks the model's own rule is refused with the parameter named
    averaged = gyrostat.lagrange.LagrangeAveraged(2.0, 1.0, 0.5, [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.01])])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.ValidityWarning)
        with pytest.raises(ValueError, match=r"LinearDamping.matrix\[0,0\] = 0.01 cannot be moved"):
            gyrostat.solve(averaged, [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0], (0.0, 1.0),
                           sensitivities="LinearDamping.matrix[0,0]")


def test_bdf_on_a_stiff_moving_mass():
    """The stiff moving mass of bench/auto_method.py (Ω = 100, λ = 2e4: |λ|·t ~ 1e5): cvode_bdf's
    sensitivities against dop853's at a tight tolerance (which pays the stability limit but is
    accurate) and against central differences of plain BDF runs."""
    model = gyrostat.MovingMassModel(gyrostat.Body([4.0, 4.0, 2.0]), mass=1.0, arm=1.0, frequency=100.0,
                                     damping=2e4)
    y0 = [0.2, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
    names = ["damping", "p"]
    bdf = gyrostat.solve(model, y0, (0.0, 5.0), n_out=6, method="cvode_bdf", rtol=1e-9, atol=1e-12,
                         sensitivities=names)
    explicit = gyrostat.solve(model, y0, (0.0, 5.0), n_out=6, rtol=1e-11, atol=1e-14, sensitivities=names)
    assert bdf.stats["steps"] < explicit.stats["steps"] / 5, "BDF is the method for this model"
    for name, size in (("damping", 2e4), ("p", 0.2)):
        for quantity in ("p", "q", "r", "kinetic_energy"):
            # the change of the quantity for a relative change of the parameter, against the quantity's
            # size: BDF's global error at rtol 1e-9 over this span is ~1e-7 of it (measured 2e-8)
            scale = np.max(np.abs(explicit[quantity]))
            change = size * (bdf.sensitivity(name, of=quantity) - explicit.sensitivity(name, of=quantity))
            assert np.max(np.abs(change)) < 1e-6 * scale, (name, quantity)


@pytest.mark.parametrize("method", ["dop853", "cvode_bdf"])
def test_dense_output_carries_them(method):
    """sol.sensitivity(name, t=...) between the output times, against a run with those times as its
    outputs; the state's dense output (sol(t)) is the run's as before."""
    model = gyrostat.Model(gyrostat.Body([1.0, 1.4, 2.1]), [gyrostat.ViscousCavity(density=1.0, viscosity=0.1, p0=0.5)],
                           attitude=True)
    names = ["ViscousCavity.viscosity", "q"]
    middle = np.linspace(0.37, 19.6, 23)
    rtol = 1e-10 if method == "dop853" else 1e-8
    sol = gyrostat.solve(model, [0.15, 0.3, 1.0], (0.0, 20.0), n_out=5, rtol=rtol, atol=1e-12, method=method,
                         dense_output=True, sensitivities=names)
    there = gyrostat.solve(model, [0.15, 0.3, 1.0], (0.0, 20.0), t_eval=middle, rtol=rtol, atol=1e-12, method=method,
                           sensitivities=names)
    for name in names:
        reference = there.sensitivity(name)
        scale = np.max(np.abs(reference))
        # two runs with different output grids take different steps (BDF's interpolant is of its own order):
        # they agree to their tolerance's reach, ~100 rtol of the sensitivity's size
        assert np.allclose(sol.sensitivity(name, t=middle), reference, rtol=0, atol=100 * rtol * scale), name
        assert np.allclose(sol.sensitivity(name, t=sol.t), sol.sensitivity(name), rtol=0, atol=10 * rtol * scale), name
        assert np.allclose(sol.sensitivity(name, of="r", t=middle), reference[:, 2], rtol=0, atol=100 * rtol * scale)
        # one time: one row, as sol(t) gives for one time
        assert sol.sensitivity(name, t=middle[3]).shape == sol(middle[3]).shape == (7,)
        assert np.array_equal(sol.sensitivity(name, t=middle[3]), sol.sensitivity(name, t=middle)[3])
        assert np.ndim(sol.sensitivity(name, of="r", t=middle[3])) == 0
    assert np.allclose(sol(middle)[:, :3], there.y[:, :3], rtol=0, atol=100 * rtol)
    with pytest.raises(ValueError, match="dense_output=True"):
        there.sensitivity(names[0], t=1.0)


@pytest.mark.parametrize("control", [False, True])
@pytest.mark.parametrize("rtol", [1e-6, 1e-8, 1e-10])
def test_sensitivity_errors_are_measured(rtol, control):
    """Each sensitivity's reported error against its true error (heyoka's reference): between ½
    and 30 times it, both floored at 1e-10 (rounding and the parameters' central differences, which
    no companion sees: the report says so and floors a parameter's there), whether the sensitivities
    join the step-size control or not. Measured: 0.84-2.2 at rtol 1e-6 and 1e-8."""
    data = json.loads((DATA / "heyoka_sensitivities.json").read_text())["cases"]["damped"]
    model = gyrostat.Model(gyrostat.Body(data["moments"]), [gyrostat.LinearDamping(matrix=data["D"])])
    sol = gyrostat.solve(model, data["omega0"], (0.0, 20.0), t_eval=data["t"], rtol=rtol, atol=1e-2 * rtol,
                         sensitivities=data["parameters"], sensitivity_error_control=control)
    assert any(note.startswith("sensitivities' error estimate") for note in sol.notes)
    # the state's own estimate: the variational run is the answer, measured against a tighter variational
    # run (with control, more accurate than a plain run at this rtol, its steps held by the sensitivities'
    # error too: a plain companion read 3700-7300 times the true error here): measured 0.99-1.56
    true_state = np.max(np.linalg.norm(sol.y - np.array(data["y"]), axis=1)) / np.max(np.linalg.norm(data["y"], axis=1))
    assert 0.5 <= max(sol.error_estimate, 1e-10) / max(true_state, 1e-10) <= 30, (sol.error_estimate, true_state)
    for name in data["parameters"]:
        reference = np.array(data["sensitivity"][name])
        true = max(np.max(np.abs(sol.sensitivity(name) - reference)) / np.max(np.abs(reference)), 1e-10)
        reported = max(sol.sensitivity_errors[name], 1e-10)  # (both floored: below it, rounding decides)
        assert 0.5 <= reported / true <= 30, (name, sol.sensitivity_errors[name], true)
    members = gyrostat.solve_ensemble(model, np.array([data["omega0"]] * 2), (0.0, 20.0), t_eval=data["t"], rtol=rtol,
                                      atol=1e-2 * rtol, sensitivities=["p", "moments[0]"])
    single = gyrostat.solve(model, data["omega0"], (0.0, 20.0), t_eval=data["t"], rtol=rtol, atol=1e-2 * rtol,
                            sensitivities=["p", "moments[0]"])
    for member in members:  # each member measured as its single run is (the same runs: to rounding)
        assert member.sensitivity_errors == pytest.approx(single.sensitivity_errors, rel=1e-9)
        assert member.error_estimate == pytest.approx(single.error_estimate, rel=1e-9)


def _family_cases():
    body = gyrostat.Body([1.0, 1.4, 2.1])
    damping = gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.01])
    top = [0.1, 0.0, 5.0, 1.0, 0.0, 0.0, 0.0]
    return [
        (gyrostat.AveragedModel(gyrostat.Body([2.0, 2.0, 1.0]), [gyrostat.LinearDamping(diagonal=[0.01, 0.01, 0.02])]),
         [0.3, 0.0, 1.0], ["a", "LinearDamping.matrix[2,2]"]),
        (gyrostat.TriaxialAveragedModel(body, [gyrostat.LinearDamping(diagonal=[1e-3, 2.5e-3, 7e-4])]), [0.15, 0.3, 1.0],
         ["G2", "moments[0]"]),
        (gyrostat.MovingMassModel(gyrostat.Body([2.0, 2.0, 1.0]), 0.1, 0.2, 10.0, 0.5), [0.1, 0, 1.0, 0, 0, 0, 0, 0, 0],
         ["q", "damping"]),
        (gyrostat.lagrange.LagrangeTop(2.0, 1.0, 0.5), top, ["p", "mu"]),
        (gyrostat.lagrange.LagrangeAveraged(2.0, 1.0, 0.5, [damping]), top, ["r", "mu"]),
        (gyrostat.orthogonal.OrthogonalModel(body, 0.01), [0.15, 0.3, 1.0], ["p", "moments[0]"]),
        (gyrostat.Model(body, [gyrostat.ViscousCavity(density=1.0, viscosity=0.1, p0=0.5)], attitude=True),
         [0.15, 0.3, 1.0], ["q_x", "ViscousCavity.viscosity"]),
    ]


@pytest.mark.parametrize("control", [False, True])
@pytest.mark.parametrize("case", range(7))
def test_every_family_through_solve_ensemble(case, control):
    """Each family's ensemble member equals its single run bit for bit (the same code on the same
    data), its sensitivities' errors measured (finite, below 1e-6 at rtol 1e-9 and atol 1e-13: ~100
    rtol at most, with or without the sensitivities in the step-size control; at the default atol
    1e-10 the moving mass's displacements of ~1e-4 are held by atol, and its damping's derivative read
    2.6e-6 with the state's steps alone)."""
    model, y0, names = _family_cases()[case]
    y0s = np.array([y0, np.asarray(y0) * 1.01])
    given = dict(n_out=4, rtol=1e-9, atol=1e-13, sensitivities=names, sensitivity_error_control=control)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.ValidityWarning)
        members = gyrostat.solve_ensemble(model, y0s, (0.0, 5.0), **given)
        single = gyrostat.solve(model, y0s[1], (0.0, 5.0), **given)
    for name in names:
        assert np.array_equal(members[1].sensitivity(name), single.sensitivity(name)), name
        assert 0 < members[1].sensitivity_errors[name] < 1e-6, (name, members[1].sensitivity_errors[name])


@pytest.mark.parametrize("case", range(7))
def test_sensitivities_leave_the_answer_as_it_was(case):
    """By default the steps are chosen on the state alone (``sensitivity_error_control=False``,
    CVODES's errconS default): a run with sensitivities takes the plain run's steps, and its state
    agrees with the plain run's to rounding (1e-12 of the state's size over these short runs: the two
    integrators order their sums differently). With the control, the sensitivities' errors hold the
    steps too: as many steps or more."""
    model, y0, names = _family_cases()[case]
    given = dict(n_out=6, rtol=1e-9, error_estimate=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.ValidityWarning)
        plain = gyrostat.solve(model, y0, (0.0, 5.0), **given)
        derived = gyrostat.solve(model, y0, (0.0, 5.0), sensitivities=names, **given)
        controlled = gyrostat.solve(model, y0, (0.0, 5.0), sensitivities=names, sensitivity_error_control=True,
                                    **given)
    assert derived.method == plain.method == "dop853", (derived.method, plain.method)
    assert derived.stats["steps"] == plain.stats["steps"], (derived.stats, plain.stats)
    assert np.max(np.abs(derived.y - plain.y)) <= 1e-12 * np.max(np.abs(plain.y)), np.max(np.abs(derived.y - plain.y))
    assert controlled.stats["steps"] >= plain.stats["steps"], (controlled.stats, plain.stats)


@pytest.mark.parametrize("scene, name", [("p001_explicit_moving_mass", "damping"),
                                         ("p003_case1_theta0_5deg", "mu"),
                                         ("p004_triaxial", "p")])
def test_every_kind_of_scene_writes_them(tmp_path, scene, name):
    """A scene of the moving mass, the Lagrange top (its full and averaged runs) and the orthogonal
    torque (three runs): each run's saved derivatives equal the same run solved directly."""
    import re

    from gyrostat.runner import run_scene
    from gyrostat.scene import Scene

    text = (Path(gyrostat.__file__).parent / "scenes" / f"{scene}.toml").read_text()
    text = re.sub(r"(\[integration\]\n)", rf'\1sensitivities = ["{name}"]\n', text, count=1)
    text = re.sub(r"^plots = .*$", "plots = []", text, flags=re.M)
    path = tmp_path / f"{scene}.toml"
    path.write_text(text)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", gyrostat.ValidityWarning)
        run_scene(path, tmp_path / "out", progress=False)
        for run in Scene.from_file(path).runs:
            direct = gyrostat.solve(run.model, run.y0, run.t_span, **run.options)
            folder = tmp_path / "out" / scene
            file = folder / f"result_{run.name}.npz"  # (the first run's is result.npz)
            quantity = run.model.state_names[0]
            with np.load(file if file.is_file() else folder / "result.npz") as saved:  # (closed: no ResourceWarning)
                column = saved[f"d_{quantity}__d_{name}"]
            assert np.array_equal(column, direct.sensitivity(name, of=quantity)), run.name
