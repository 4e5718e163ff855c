"""Scenes and the command line: every shipped scene runs, saves named arrays with units, plots."""

import csv
import json

import numpy as np
import pytest

import gyrostat as g
from gyrostat.cli import example_scenes, main
from gyrostat.scene import Scene
from references import euler_poinsot


def test_examples_run_and_write_results(examples):
    """The session's one run of `gyrostat examples` (conftest.py), as `bash run.sh main` runs it."""
    assert examples.code == 0
    tmp_path = examples.folder
    names = [p.stem for p in example_scenes()]
    assert {"torque_free_triaxial", "torque_free_integrated", "forced_damped"} <= set(names)
    for name in names:
        folder = tmp_path / name
        report = json.loads((folder / "report.json").read_text())
        assert report["status"] == "success", (name, report.get("broken_assumptions"))
        # a shipped scene runs where its models hold, or names each assumption it breaks on
        # purpose ([[expected_broken]]: why, and the console shows the measured agreement)
        assert report["unexpected_broken"] == [] and report["expected_but_held"] == [], (name, report["verdict"])
        csvs = sorted(folder.glob("*.csv"))
        assert csvs, name
        for path in csvs:  # a column per quantity, with its unit, time first
            with path.open() as handle:
                header = next(csv.reader(handle))
            assert header[0] == "t [s]" and all("[" in column for column in header), (path, header)
        for path in folder.glob("*.npz"):
            assert "units" in np.load(path).files
        pngs = list(folder.glob("*.png"))
        assert pngs and all(p.stat().st_size > 10_000 for p in pngs), name
    for name in ("torque_free_integrated", "forced_damped"):
        with (tmp_path / name / "result.csv").open() as handle:
            assert next(csv.reader(handle))[:4] == ["t [s]", "p [rad/s]", "q [rad/s]", "r [rad/s]"]
        assert json.loads(str(np.load(tmp_path / name / "result.npz")["units"]))["kinetic_energy"] == "J"
    with (tmp_path / "p000_A8_C4_M3-0p1" / "result_averaged.csv").open() as handle:
        assert next(csv.reader(handle))[:3] == ["t [s]", "a [rad/s]", "r [rad/s]"]
    out = examples.out
    assert "model: closed_form" in out and "WARNING" not in out
    assert set(out[out.index("\nsummary"):].split()) >= set(names)  # the summary has a row per scene
    assert all(f"href='{name}/report.json'" in (tmp_path / "index.html").read_text() for name in names)


def test_closed_form_scene_values(tmp_path):
    main(["run", str(next(p for p in example_scenes() if p.stem == "torque_free_triaxial")), "--out", str(tmp_path),
          "--quiet"])
    with np.load(tmp_path / "torque_free_triaxial" / "result.npz") as data:  # closed: no ResourceWarning later
        t, omega = data["t"], np.column_stack([data["p"], data["q"], data["r"]])
    exact = euler_poinsot([1, 2, 3], [1.0, 0.5, -0.3], t)
    # closed form (GSL) against the test's SciPy closed form: rounding of the elliptic functions
    assert np.max(np.abs(omega - exact)) < 1e-11


def test_integrated_scene_reports_error_against_closed_form(tmp_path):
    path = next(p for p in example_scenes() if p.stem == "torque_free_integrated")
    main(["run", str(path), "--out", str(tmp_path), "--quiet"])
    report = json.loads((tmp_path / "torque_free_integrated" / "report.json").read_text())
    assert report["model"] == "full"
    # 200 periods at rtol 1e-10 with dop853: measured 2.3e-7 (global error grows with the periods)
    assert report["max_error_vs_closed_form"] < 1e-6


def test_auto_model_choice():
    base = {"body": {"moments": [1, 2, 3]}, "initial": {"omega": [1, 0, 0.1]},
            "integration": {"t_span": [0, 1]}}
    assert Scene.from_dict(base).model_choice == "closed_form"
    forced = dict(base, torques=[{"type": "constant", "moment": [0, 0, 1]}])
    scene = Scene.from_dict(forced)
    assert scene.model_choice == "full" and "1 torque" in scene.model_reason
    rotor = dict(base, body={"moments": [1, 2, 3], "rotor": [0, 0, 0.5]})
    assert Scene.from_dict(rotor).model_choice == "full"


@pytest.mark.parametrize(
    "change, message",
    [
        ({"body": {"moments": [1, 2]}}, "\\[body\\] moments must be a list of 3 numbers"),
        ({"body": {"moments": [1, 1, 5]}}, "\\[body\\] .*triangle inequality"),
        ({"torques": [{"type": "solar_pressure"}]}, "\\[torques\\[0\\]\\] type = 'solar_pressure' is not one of"),
        ({"integration": {"t_span": [0, 1], "model": "reduced"}}, "\\[integration\\] model = 'reduced'"),
        ({"outputs": {"plots": ["spectrum"]}}, "'spectrum' is not one of"),
    ],
)
def test_bad_scenes(change, message):
    base = {"body": {"moments": [1, 2, 3]}, "initial": {"omega": [1, 0, 0.1]},
            "integration": {"t_span": [0, 1]}}
    base.update(change)
    with pytest.raises(ValueError, match=message):
        Scene.from_dict(base)


def test_cli_reports_a_bad_file(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text("[body\nmoments = 1")
    assert main(["run", str(bad), "--out", str(tmp_path)]) == 2
    assert "not valid TOML" in capsys.readouterr().err


def test_methods_command(capsys):
    assert main(["methods"]) == 0
    assert [line.split()[0] for line in capsys.readouterr().out.splitlines()] == list(g.METHODS)


def test_module_entry_point_and_version():
    import subprocess
    import sys

    out = subprocess.run([sys.executable, "-m", "gyrostat", "--version"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == f"gyrostat {g.__version__}" and g.__version__.count(".") == 2
    methods = subprocess.run([sys.executable, "-m", "gyrostat", "methods"], capture_output=True, text=True, check=True)
    assert [line.split()[0] for line in methods.stdout.splitlines()] == list(g.METHODS)


def test_report_is_plain_json_with_units_inputs_and_version(tmp_path):
    path = next(p for p in example_scenes() if p.stem == "forced_damped")
    main(["run", str(path), "--out", str(tmp_path), "--quiet"])
    report = json.loads((tmp_path / "forced_damped" / "report.json").read_text())
    assert report["version"] == g.__version__ and report["kind"] == "rigid_body"
    assert report["inputs"]["integration"]["rtol"] == 1e-10 and report["units"]["kinetic_energy"] == "J"
    assert all(isinstance(a["holds"], bool) for a in report["assumptions"])
    run = report["runs"]["full"]
    # damped and forced: |G| and T are first integrals of the free body, which the torques change:
    # listed apart from what the model conserves; Euler angles are in neither
    assert run["conserved"] == {} and set(run["changed_by_torques"]) == {"angular_momentum_norm", "kinetic_energy"}
    changed = run["changed_by_torques"]["kinetic_energy"]
    assert changed["relative_change"] == pytest.approx(changed["end"] / changed["start"] - 1, rel=1e-12)


def test_relative_change_only_where_it_means_something():
    from gyrostat.output import change

    assert "relative_change" not in change(np.array([2e-16, 1.0, 0.5]), conserved=True)   # starts at ~0
    assert "relative_change" not in change(np.array([1.0, 2.0]), conserved=False)        # not a first integral
    assert change(np.array([2.0, 2.5]), conserved=True)["relative_change"] == 0.25
