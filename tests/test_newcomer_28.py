"""What a newcomer meets first (issue 28): the command line's help, its listing of the integrators,
a closed pipe, the summary and the index of a run of several scenes, the shipped scenes' broken
assumptions reported as expected with their reason and measured agreement, report.json's
conserved quantities, events' default names, and the nutation angle every family records."""

import json
import subprocess
import sys

import numpy as np
import pytest

import gyrostat as g
from gyrostat import _core, lagrange, orthogonal
from gyrostat.cli import example_scenes, main
from gyrostat.events import Event, labels
from gyrostat.runner import run_scene
from gyrostat.scene import Scene
from gyrostat.validity import ValidityWarning


def _scene(stem: str):
    return next(p for p in example_scenes() if p.stem == stem)


# ------------------------------------------------------------------------------------ point 6
def test_run_help_says_where_results_go_and_shows_an_example(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["run", "--help"])
    assert stop.value.code == 0
    text = capsys.readouterr().out
    assert "OUT/<scene>/" in text and "report.json" in text and "index.html" in text
    assert "example:" in text and "gyrostat run my_scene.toml --out results" in text
    with pytest.raises(SystemExit):
        main(["examples", "--help"])
    assert "OUT/<scene>/" in capsys.readouterr().out


def test_methods_lists_one_line_each(capsys):
    assert main(["methods"]) == 0
    rows = capsys.readouterr().out.splitlines()
    assert [row.split()[0] for row in rows] == list(g.METHODS)
    # each name with its line from C++ (status.cpp): more than the name, and no two alike
    descriptions = [row.split(None, 1)[1] for row in rows]
    assert all(len(d) > 20 for d in descriptions) and len(set(descriptions)) == len(rows)
    assert "BDF" in dict(zip(g.METHODS, descriptions))["cvode_bdf"]


def test_a_closed_pipe_ends_quietly():
    """``gyrostat scene-format | head``: the reader leaves before the output is written (its end
    of the pipe is closed before the interpreter has even started). On main this ended in a
    BrokenPipeError traceback."""
    process = subprocess.Popen([sys.executable, "-m", "gyrostat", "scene-format"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE)
    process.stdout.close()
    error = process.stderr.read().decode()
    process.stderr.close()
    process.wait(timeout=120)
    assert "Traceback" not in error and "BrokenPipe" not in error, error
    assert process.returncode == 0


def test_several_scenes_end_with_a_summary_and_an_index(tmp_path, capsys):
    scenes = [_scene("torque_free_triaxial"), _scene("p002_paper_scene")]
    assert main(["run", *map(str, scenes), "--out", str(tmp_path), "--quiet"]) == 0
    out = capsys.readouterr().out
    summary = out[out.index("\nsummary"):].splitlines()
    assert summary[2].split() == ["scene", "model", "verdict", "time", "[s]", "folder"]
    rows = {line.split()[0]: line for line in summary[4:6]}
    assert set(rows) == {"torque_free_triaxial", "p002_paper_scene"}
    assert " ok " in rows["torque_free_triaxial"] and "3 broken as expected" in rows["p002_paper_scene"]
    assert str(tmp_path / "p002_paper_scene") in rows["p002_paper_scene"]
    page = (tmp_path / "index.html").read_text()
    for name in ("torque_free_triaxial", "p002_paper_scene"):
        assert f"href='{name}/report.json'" in page
        for png in (tmp_path / name).glob("*.png"):
            assert f"src='{name}/{png.name}'" in page
    assert "(p002_paper_scene/phase.png)" in (tmp_path / "index.md").read_text()


def test_console_time_says_what_it_measures(tmp_path, capsys):
    main(["run", str(_scene("torque_free_triaxial")), "--out", str(tmp_path), "--quiet"])
    out = capsys.readouterr().out
    report = json.loads((tmp_path / "torque_free_triaxial" / "report.json").read_text())
    assert f"solving took {report['seconds']:.3g} s ({report['seconds_total']:.3g} s with the checks, files and " \
           "plots)" in out
    assert 0 < report["seconds"] < report["seconds_total"]


def test_report_lists_as_conserved_only_what_the_model_keeps(tmp_path, capsys):
    """forced_damped: a constant torque and damping change |G| and T (on main both were listed
    under conserved, T growing by 206%); the torque-free run keeps both."""
    main(["run", str(_scene("forced_damped")), str(_scene("torque_free_integrated")), "--out", str(tmp_path),
          "--quiet"])
    out = capsys.readouterr().out
    forced = json.loads((tmp_path / "forced_damped" / "report.json").read_text())["runs"]["full"]
    assert forced["conserved"] == {} and set(forced["changed_by_torques"]) == {"angular_momentum_norm", "kinetic_energy"}
    assert forced["changed_by_torques"]["kinetic_energy"]["relative_change"] > 1  # T(end)/T(0) − 1 = 2.06
    free = json.loads((tmp_path / "torque_free_integrated" / "report.json").read_text())["runs"]["full"]
    assert set(free["conserved"]) == {"angular_momentum_norm", "kinetic_energy"} and free["changed_by_torques"] == {}
    assert "changed by the torques, relative change from t0 to the end: angular_momentum_norm +1.268e+00" in out
    assert "conserved, relative change from t0 to the end (integration error): angular_momentum_norm -1.9" in out


def test_the_model_says_which_first_integrals_its_torques_keep():
    body = g.Body([1.0, 2.0, 3.0])
    free = g.solve(g.Model(body, []), [1.0, 0.5, -0.3], (0, 1))
    assert free.kept == free.conserved == ("angular_momentum_norm", "kinetic_energy")
    cavity = g.solve(g.Model(body, [g.ViscousCavity(density=1.0, viscosity=1.0, p0=0.1)]), [1.0, 0.5, -0.3], (0, 1))
    assert cavity.kept == ("angular_momentum_norm",)  # Jω·M = 0: |G| kept, T dissipated
    forced = g.solve(g.Model(body, [g.ConstantTorque([0, 0, 0.1])]), [1.0, 0.5, -0.3], (0, 1))
    assert forced.kept == () and forced.conserved == ("angular_momentum_norm", "kinetic_energy")


def test_events_on_one_quantity_get_distinct_default_names():
    up, down = Event("r", direction=1), Event("r", direction=-1)
    assert (up.label, down.label, Event("r").label) == ("r rises through 0", "r falls through 0", "r = 0")
    assert labels([Event("r"), Event("r", terminal=True), lambda t, y: y[0], lambda t, y: y[1]]) == [
        "r = 0", "r = 0 (2)", "<lambda>", "<lambda> (2)"]
    # a run with both: each reported under its own name (on main one name swallowed the other)
    sol = g.solve(g.Model(g.Body([1.0, 2.0, 3.0]), []), [1.0, 0.5, -0.3], (0, 20), events=[up, down, Event("r")])
    times = dict(zip(sol.event_names, sol.t_events))
    assert list(times) == ["r rises through 0", "r falls through 0", "r = 0"]
    assert len(times["r = 0"]) == len(times["r rises through 0"]) + len(times["r falls through 0"]) > 2


# ------------------------------------------------------------------------------------ point 1
def test_a_paper_scene_reports_its_broken_assumptions_as_expected(tmp_path, capsys):
    """p002_paper_scene: the paper's own numbers break three assumptions; each is reported as
    expected with the reason the scene gives and the agreement measured (averaged against full,
    ~1e-10 here); without the scene's markers the same three are WARNINGs."""
    path = _scene("p002_paper_scene")
    main(["run", str(path), "--out", str(tmp_path), "--quiet"])
    out = capsys.readouterr().out
    report = json.loads((tmp_path / "p002_paper_scene" / "report.json").read_text())
    assert "WARNING" not in out and len(report["expected_broken"]) == 3 and report["unexpected_broken"] == []
    assert out.count("expected, the scene breaks it on purpose: ") == 3 and "why: the paper's fluid" in out
    measured = report["averaged_vs_full"]
    assert max(measured.values()) < 1e-8  # the integrators' tolerance (rtol 1e-10) on a, r of order 10
    assert f"measured: averaged vs full: max_abs_error_a {measured['max_abs_error_a']:.2g}" in out
    scene = Scene.from_toml(path)
    scene.doc["expected_broken"] = []
    with pytest.warns(ValidityWarning):
        bare = run_scene(scene, tmp_path / "bare", progress=False)
    assert len(bare["unexpected_broken"]) == 3 and bare["verdict"] == "ok, WARNING 3 assumption(s) broken"


def test_a_marker_for_an_assumption_that_holds_is_reported_stale(tmp_path):
    scene = Scene.from_toml(_scene("torque_free_triaxial"))
    scene.doc["expected_broken"] = [{"assumption": "viscous cavity: Reynolds", "why": "none here"}]
    report = run_scene(scene, tmp_path, progress=False)
    assert report["expected_but_held"] == ["viscous cavity: Reynolds"]
    assert report["verdict"] == "ok, 1 expected break(s) not seen"


def test_expected_broken_is_part_of_the_strict_schema():
    doc = {"body": {"moments": [1, 2, 3]}, "initial": {"omega": [1, 0, 0.1]}, "integration": {"t_span": [0, 1]},
           "expected_broken": [{"assumption": "x", "because": "y"}]}
    with pytest.raises(ValueError, match="because"):
        Scene.from_dict(doc)


# ------------------------------------------------------------------------------------ point 3
def _nutation(G):
    G = np.atleast_2d(G)
    return np.arccos(np.clip(G[:, 2] / np.linalg.norm(G, axis=1), -1, 1))


def test_every_model_with_omega_records_the_nutation_angle_to_G():
    """ϑ = angle(body z, G) from ω alone (G = Jω + k), against arccos(G_z/|G|) computed here;
    tolerance 1e-7: arccos loses √ε near 0 and π, C++'s atan2 does not."""
    J, k = np.array([2.0, 2.5, 3.0]), np.array([0.1, -0.2, 0.4])
    body, rigid_body = g.Body(J.tolist(), k.tolist()), g.Body(J.tolist())
    for model, rotor in ((g.Model(body, []), k), (g.Model(body, [g.ConstantTorque([0, 0, 0.1])], attitude=True), k),
                         (g.TorqueFreeModel(rigid_body), 0 * k), (orthogonal.OrthogonalModel(body, 0.15), k)):
        sol = g.solve(model, [0.3, -0.4, 1.2], (0, 2), n_out=11)
        np.testing.assert_allclose(sol["nutation_angle"], _nutation(J * sol.omega + rotor), rtol=0, atol=1e-7)
    assert np.array_equal(sol["nutation_angle"], sol["theta_G"])  # the orthogonal model's own name for it
    # the moving mass: the angle of the system's K (carrier and mass); with the mass at rest on
    # its arm at the start (u = v = 0, d = (0, 0, ρ)), K = carrier ω + μ d × (ω × d) = J ω with
    # the system's moments J (the carrier's A1,2 are J1,2 − μρ²)
    mass = g.MovingMassModel(g.Body([4.0, 4.0, 2.0]), mass=0.1, arm=1.0, frequency=10.0, damping=1.0)
    sol = g.solve(mass, [0.3, -0.4, 1.2, 0, 0, 0, 0, 0, 0], (0, 1), n_out=3)
    K0 = np.array([4.0, 4.0, 2.0]) * np.array([0.3, -0.4, 1.2])
    assert sol["nutation_angle"][0] == pytest.approx(_nutation(K0)[0], abs=1e-7)
    # the torque-free body: G is fixed in space, so ϑ is also the angle between body z and G's
    # inertial direction, read off the integrated attitude
    rigid = g.Model(g.Body([1.0, 2.0, 3.0]), [], attitude=True)
    free = g.solve(rigid, [1.0, 0.5, -0.3], (0, 5), n_out=21, rtol=1e-12, atol=1e-14)
    G0 = np.array([1.0, 2.0 * 0.5, -3.0 * 0.3])
    body_z = g.attitude.rotate(free.y[:, 3:7], np.array([0.0, 0.0, 1.0]))
    np.testing.assert_allclose(free["nutation_angle"], np.arccos(body_z @ G0 / np.linalg.norm(G0)), atol=1e-7)
    # the z-x-z θ is another angle (to the start frame's inertial z), and says so
    assert not np.allclose(free["theta"], free["nutation_angle"], atol=1e-2)
    assert "not the nutation angle" in dict((q["name"], q["description"]) for q in rigid.quantities)["theta"]


def test_the_averaged_model_gives_the_nutation_angle_from_a_and_r():
    """tan ϑ = A a / (C r) on the generating motion: the same ϑ as the full model's at any phase."""
    A, C = 8.0, 4.0
    averaged = g.solve(g.AveragedModel(g.Body([A, A, C]), []), [0.5, -1.0], (0, 1), n_out=3)
    assert averaged["nutation_angle"] == pytest.approx(np.arctan2(A * 0.5, C * -1.0), abs=1e-15)
    full = g.solve(g.Model(g.Body([A, A, C]), []), [0.5 * np.cos(0.7), 0.5 * np.sin(0.7), -1.0], (0, 1), n_out=3)
    assert full["nutation_angle"][0] == pytest.approx(averaged["nutation_angle"][0], abs=1e-15)  # the same ω
    # later the full run's ϑ is constant to its integration error only (default rtol: 2e-11 measured)
    assert full["nutation_angle"] == pytest.approx(averaged["nutation_angle"], abs=1e-9)


def test_the_heavy_top_records_both_angles():
    """The Lagrange top: cos_theta is the symmetry axis against the vertical, nutation_angle the
    symmetry axis against G = Jω; at a sleeping start (ω along the axis) both vanish."""
    top = lagrange.LagrangeTop(1.5, 1.0, 0.5, [])
    y0 = lagrange.initial_state([0.2, -0.1, 1.7], 0.6)
    sol = g.solve(top, y0, (0, 2), n_out=5)
    G = np.column_stack([1.5 * sol.omega[:, 0], 1.5 * sol.omega[:, 1], 1.0 * sol.omega[:, 2]])
    np.testing.assert_allclose(sol["nutation_angle"], _nutation(G), rtol=0, atol=1e-7)
    assert not np.allclose(np.arccos(sol["cos_theta"]), sol["nutation_angle"], atol=1e-3)  # two different angles
    assert "vertical" in dict((q["name"], q["description"]) for q in top.quantities)["cos_theta"]


def test_the_gallerys_commands_work_from_the_root_of_a_clone(tmp_path, monkeypatch):
    """docs/gallery.py prints one command per scene; on main it was ``gyrostat run NAME.toml
    --out results/NAME``, a file that is not where a clone has it (and results/NAME/NAME/)."""
    from pathlib import Path

    root = Path(__file__).resolve().parents[1]
    monkeypatch.syspath_prepend(str(root / "docs"))
    import gallery

    scenes = sorted(gallery.SCENES.glob("*.toml"))
    commands = [gallery.run_command(scene).split("#")[0].split() for scene in scenes]
    for scene, command in zip(scenes, commands):
        assert command[:2] == ["gyrostat", "run"] and (root / command[2]).resolve() == scene.resolve()
        assert command[3:] == ["--out", "results"]
    monkeypatch.chdir(root)
    (command,) = [c for c, s in zip(commands, scenes) if s.stem == "torque_free_triaxial"]
    assert main([*command[1:3], "--out", str(tmp_path), "--quiet"]) == 0  # as written, but for --out
    assert (tmp_path / "torque_free_triaxial" / "report.json").is_file()


def test_the_ladder_chart_draws_no_made_up_error_and_names_the_rungs_left_out(tmp_path, monkeypatch):
    """The reference rung has no error of its own: on main it was drawn at 1e-2 of the smallest
    error (1e-10 here), where it read as a measured one; a rung that could not run was left out
    without a word."""
    from gyrostat import figures, plots

    drawn = {}

    def keep(fig, path):
        fig.canvas.draw()
        drawn["axes"] = fig.axes
        return path

    monkeypatch.setattr(figures, "finish", keep)
    rows = [{"rung": "averaged", "seconds": 1e-3, "error": 1e-8, "chosen": True, "estimate": 2e-8},
            {"rung": "full", "seconds": 1e-1, "error": 0.0, "chosen": False, "estimate": None, "reference": True},
            {"rung": "closed_form", "skipped": "the torques are not zero", "chosen": False}]
    plots.ladder(rows, "ladder", tmp_path / "ladder.png", 1e-3)
    (ax,) = drawn["axes"]
    points = [(float(x), float(y)) for line in ax.get_lines() if line.get_transform() == ax.transData
              for x, y in zip(line.get_xdata(), line.get_ydata())]
    assert all(y >= 1e-8 for x, y in points if x == 1e-1) and not any(y == 1e-10 for _, y in points)
    # the rungs not run are named under the axis label (an annotation, so the label keeps its unit last)
    assert any("not run: closed_form (the torques are not zero)" in text.get_text() for text in ax.texts)
    assert any(text.get_text().startswith("full: the reference") for text in ax.texts)
