"""Every scene kind is strict: a misspelled key, a wrong type or a missing key is a one-line error
naming the key, its table and (for a misspelling) the nearest valid key; the command line prints
it without a traceback and exits with code 2."""

import copy
import tomllib

import pytest

from gyrostat.cli import example_scenes, main
from gyrostat.scene import KINDS, Scene, SceneError, scene_format


def _example(stem):
    path = next(p for p in example_scenes() if p.stem == stem)
    with path.open("rb") as handle:
        return tomllib.load(handle)


AVERAGED = {"kind": "averaged", "body": {"moments": [8, 8, 4]},
            "torques": [{"type": "viscous_cavity", "density": 1260.0, "viscosity": 1000.0, "p0": 0.48}],
            "initial": {"a": 1.0, "r": 1.0}, "integration": {"t_span": [0, 10]}}

# kind → (a valid document, a misspelled key: (table path, wrong, right), a wrong type:
# (table path, key, value, expected words), a required key to delete: (table path, key))
CASES = {
    "rigid_body": (lambda: _example("forced_damped"), (("integration",), "modle", "model"),
                   (("integration",), "n_out", "10", "must be an integer, got '10' (a string)"),
                   (("initial",), "omega")),
    "averaged": (lambda: copy.deepcopy(AVERAGED), (("initial",), "aa", "a"),
                 (("integration",), "rtol", [1e-8], "must be a number"), (("integration",), "t_span")),
    "moving_mass": (lambda: _example("p001_explicit_moving_mass"), (("damper",), "dampin", "damping"),
                    (("damper",), "mass", "heavy", "must be a number"), (("damper",), "frequency")),
    "lagrange_top": (lambda: _example("p003_case1_theta0_5deg"), (("initial",), "theta", "theta_deg"),
                     (("torque",), "a", "1, 1", "must be a list of"), (("body",), "mu")),
    "orthogonal_torque": (lambda: _example("p004_triaxial"), (("runs", 1, "law"), "amplitude", "amplitudes"),
                          (("integration",), "t_span", "0:60", "must be a list of 2 numbers"), (("runs", 0), "law")),
}


def _table(doc, path):
    for part in path:
        doc = doc[part]
    return doc


def _where(path):
    return "[" + ".".join(p if isinstance(p, str) else f"[{p}]" for p in path).replace(".[", "[") + "]"


@pytest.fixture(params=sorted(CASES))
def kind(request):
    return request.param


def test_every_kind_is_covered():
    assert set(CASES) == set(KINDS)


def test_valid_documents_load(kind):
    scene = Scene.from_dict(CASES[kind][0](), name="x")
    assert scene.kind.name == kind and scene.runs


def test_misspelled_key_names_the_nearest(kind):
    make, (path, wrong, right), _, _ = CASES[kind]
    doc = make()
    table = _table(doc, path)
    table[wrong] = table.pop(right, 1.0)
    with pytest.raises(SceneError) as error:
        Scene.from_dict(doc)
    message = str(error.value)
    # a table chosen by a discriminator names it too: "in [runs[1].law] (kind = 'harmonic');"
    assert message.startswith(f"unknown key '{wrong}' in {_where(path)}")
    assert message.endswith(f"; did you mean '{right}'?") and "\n" not in message


def test_wrong_type_names_key_and_type(kind):
    make, _, (path, key, value, expected), _ = CASES[kind]
    doc = make()
    _table(doc, path)[key] = value
    with pytest.raises(SceneError) as error:
        Scene.from_dict(doc)
    message = str(error.value)
    assert message.startswith(f"{_where(path)} {key} ") and expected in message and "\n" not in message


def test_missing_key_is_named(kind):
    make, _, _, (path, key) = CASES[kind]
    doc = make()
    del _table(doc, path)[key]
    with pytest.raises(SceneError) as error:
        Scene.from_dict(doc)
    message = str(error.value)
    assert f"{_where(path)} is missing required key '{key}'" in message and "\n" not in message


def test_unknown_kind():
    with pytest.raises(SceneError, match=r"kind = 'lagrange' is not a scene kind .*did you mean 'lagrange_top'\?"):
        Scene.from_dict({"kind": "lagrange"})


def _toml(value, key=None):
    """A minimal TOML writer for the test documents (inline tables and arrays)."""
    if isinstance(value, dict):
        return "{ " + ", ".join(f"{k} = {_toml(v)}" for k, v in value.items()) + " }"
    if isinstance(value, list):
        return "[" + ", ".join(_toml(v) for v in value) + "]"
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return '"' + value.replace("\\", "\\\\").replace('"', '\\"').replace("\n", "\\n") + '"'
    return repr(float(value)) if isinstance(value, float) else str(value)


def _write(doc, path):
    lines = [f"{k} = {_toml(v)}" for k, v in doc.items()]
    path.write_text("\n".join(lines) + "\n")


def test_command_line_error_is_one_line(tmp_path, capsys, kind):
    make, (path, wrong, right), _, _ = CASES[kind]
    doc = make()
    table = _table(doc, path)
    table[wrong] = table.pop(right, 1.0)
    scene = tmp_path / f"{kind}.toml"
    _write(doc, scene)
    assert main(["run", str(scene), "--out", str(tmp_path / "out"), "--quiet"]) == 2
    captured = capsys.readouterr()
    lines = [line for line in captured.err.splitlines() if line]
    assert len(lines) == 1 and "Traceback" not in captured.err
    assert f"unknown key '{wrong}'" in lines[0] and f"did you mean '{right}'" in lines[0]
    assert not (tmp_path / "out" / kind).exists()


def test_scene_format_documents_every_kind():
    text = scene_format()
    for name, kind in KINDS.items():
        assert f'kind = "{name}"' in text
    for key in ("moments", "tau_end", "nearly_spherical", "damping", "epsilon", "law"):
        assert key in text


def test_docs_scene_reference_is_current():
    # docs/scenes.md is `gyrostat scene-format`: regenerate it when a schema changes
    from pathlib import Path

    doc = Path(__file__).resolve().parent.parent / "docs" / "scenes.md"
    assert doc.read_text() == scene_format() + "\n", "docs/scenes.md is stale: run `gyrostat scene-format > docs/scenes.md`"


def test_scene_events_are_located_and_reported(tmp_path):
    from gyrostat.runner import run_scene
    from gyrostat.validity import ValidityWarning

    doc = _example("p000_A8_C4_M3-0p1")
    doc["events"] = [{"quantity": "r", "name": "r = 0"}, {"quantity": "slow_to_fast", "value": 0.5, "direction": 1}]
    scene_file = tmp_path / "events.toml"
    _write(doc, scene_file)
    with pytest.warns(ValidityWarning):  # the paper's own scene breaks the cavity's "small" assumption
        report = run_scene(scene_file, tmp_path / "out", progress=False)
    full, slow = report["runs"]["full"]["events"], report["runs"]["averaged"]["events"]
    # r = 0 in both models (the reduction is exact here: the same time to the tolerance);
    # slow_to_fast is an output of the averaged model only
    assert len(full["r = 0"]) == 1 and abs(full["r = 0"][0] - slow["r = 0"][0]) < 1e-6
    assert "slow_to_fast rises through 0.5" not in full and len(slow["slow_to_fast rises through 0.5"]) == 1
    doc["events"] = [{"quantity": "theta"}]
    with pytest.raises(SceneError, match=r"\[events\[0\]\] quantity = 'theta' is neither"):
        Scene.from_dict(doc)
    doc["events"] = [{"quantity": "r", "direction": 2}]
    with pytest.raises(SceneError, match=r"\[events\[0\]\] direction = 2: must be -1, 0 or 1"):
        Scene.from_dict(doc)
