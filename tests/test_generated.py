"""Files generated from the C++ declarations are current, and what Python shows of a torque or a
model is what C++ declares (nothing restated).

* ``python/gyrostat/_core.pyi`` equals a fresh ``docs/stubs.py`` run on the built module
  (pybind11-stubgen, pinned in the ``test`` extra); ``docs/scenes.md`` is checked in
  tests/test_scene_errors.py.
* The torque registry, the scene schema of ``[[torques]]`` and the package namespace hold
  exactly the core's torques, with the core's parameters and units.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import gyrostat as g
from gyrostat import _core, torques

ROOT = Path(__file__).resolve().parent.parent


def test_type_stubs_are_current():
    # Fails when a binding changed and `python docs/stubs.py` was not run (checked by adding a
    # method to a binding without regenerating: this test failed).
    run = subprocess.run([sys.executable, str(ROOT / "docs" / "stubs.py"), "--check"], capture_output=True, text=True)
    assert run.returncode == 0, run.stderr


def test_every_core_torque_is_registered_once_and_exported():
    kinds = [cls.kind for cls in _core.torque_types]
    # the five torques of the papers, four that need the attitude and the user's own (torque/set.hpp)
    assert len(set(kinds)) == len(kinds) == len(torques.TORQUE_TYPES) == 10
    for cls in _core.torque_types:
        assert getattr(g, cls.__name__) is cls, f"gyrostat.{cls.__name__} is not the core's class"
        assert torques.BY_KIND[cls.kind] is cls
        if cls is not _core.CustomTorque:  # it holds a function: its scene keys are torques.py's own
            assert set(torques.TORQUE.variants[cls.kind].fields) == {p["name"] for p in cls.parameters}
    assert set(torques.TORQUE.variants["custom"].fields) == {"function", "jacobian", "parameters", "attitude"}


def test_scene_fields_carry_the_declared_units_and_choices():
    cavity = torques.TORQUE.variants["viscous_cavity"]
    assert cavity.fields["radius"].unit == "m" and cavity.fields["p0"].unit == "m^5"
    assert ("p0", "radius") in cavity.one_of  # exactly one of them, as C++ declares
    damping = torques.TORQUE.variants["linear_damping"]
    assert damping.fields["matrix"].unit == "N m s" and not damping.fields["matrix"].required


@pytest.mark.parametrize("make, expected", [
    # the keyword form of every constructor builds what the positional form builds
    (lambda: g.LinearDamping(diagonal=[1.0, 2.0, 3.0]).matrix, np.diag([1.0, 2.0, 3.0])),
    (lambda: g.ViscousCavity(density=1.26, viscosity=33.4, radius=2.0).p0, 8 * np.pi * 2.0**7 / 525),
])
def test_alternative_parameters_build_the_same_torque(make, expected):
    np.testing.assert_allclose(make(), expected, rtol=1e-15)  # one formula, rounding only


@pytest.mark.parametrize("make, message", [
    (lambda: g.ViscousCavity(1.0, 2.0), r"ViscousCavity: give exactly one of p0 or radius \(got 0\)"),
    (lambda: g.ViscousCavity(1.0, 2.0, 3.0, radius=1.0), r"exactly one of p0 or radius \(got 2\)"),
    (lambda: g.ConstantTorque(moment=[0, 0, 1], torque=1), r"ConstantTorque: unknown parameter 'torque' \(parameters: moment\)"),
    (lambda: g.MovingMassDamper(1.0, 1.0, 10.0), r"MovingMassDamper: missing parameter 'damping'"),
    (lambda: g.MovingMassDamper(1.0, -1.0, 10.0, 1.0), r"arm rho = -1 must be finite and non-negative"),
    (lambda: g.Model(g.Body([1, 2, 3]), [object()]), r"ConstantTorque, LinearDamping, ResistiveMedium, ViscousCavity, "
                                                      r"MovingMassDamper"),
])
def test_bad_torque_arguments_are_named(make, message):
    with pytest.raises((TypeError, ValueError), match=message):
        make()


def test_units_of_a_run_come_from_the_model():
    sol = g.solve(g.Model(g.Body([1.0, 2.0, 3.0]), [], attitude=True), [1.0, 0.5, -0.3], (0, 1), n_out=3)
    assert sol.units["p"] == "rad/s" and sol.units["q_w"] == "1"
    assert sol.units["angular_momentum_norm"] == "kg m^2/s" and sol.units["psi"] == "rad"
    declared = {q["name"]: q["unit"] for q in g.Model(g.Body([1.0, 2.0, 3.0]), [], attitude=True)._core.quantities}
    assert sol.units == {"t": "s", **declared}


@pytest.mark.parametrize("key, value, message", [
    ("rtol", 2.0, r"\[integration\] rtol = 2\.0: must be below 1"),           # was accepted by the schema
    ("rtol", 1e-16, r"\[integration\] rtol = 1e-16: is below 1e-14"),
    ("atol", -1.0, r"\[integration\] atol = -1\.0: must be finite and non-negative"),
    ("n_out", 1, r"\[integration\] n_out = 1: must be at least 2 \(or 0: t0 and t1 only\)"),
])
def test_scene_options_take_the_engine_rule_at_their_key(key, value, message):
    from gyrostat.scene import Scene, SceneError

    doc = {"body": {"moments": [1.0, 2.0, 3.0]}, "initial": {"omega": [1.0, 0.0, 0.0]},
           "integration": {"t_span": [0.0, 1.0], key: value}}
    with pytest.raises(SceneError, match=message):
        Scene.from_dict(doc, "bad")
    with pytest.raises(ValueError, match=rf"{key} = "):  # the same rule, from the engine itself
        _core.Options.check(key, value)


def test_every_kind_takes_the_engine_defaults_or_says_why():
    from gyrostat.kind import KINDS

    defaults = _core.Options()
    for name, kind in KINDS.items():
        integration = kind.schema.fields["integration"].type
        for key in ("rtol", "atol", "n_out"):
            field = integration.fields.get(key)
            if field is None:
                continue
            if field.default != getattr(defaults, key):
                assert "default" in field.doc and ":" in field.doc, f"{name}.{key}: own default without its reason"


def test_a_run_records_its_options_and_report_json_writes_them(tmp_path):
    sol = g.solve(g.Model(g.Body([1.0, 2.0, 3.0]), []), [1.0, 0.5, -0.3], (0, 1), rtol=1e-9, atol=1e-11, n_out=5)
    assert sol.options.rtol == 1e-9 and sol.options.atol == 1e-11 and sol.options.n_out == 5
    assert sol.options.method == "dop853"
    from gyrostat.runner import run_scene

    scene = ROOT / "python" / "gyrostat" / "scenes" / "torque_free_integrated.toml"
    report = run_scene(scene, tmp_path, progress=False)
    import tomllib

    integration = tomllib.loads(scene.read_text())["integration"]
    for run in report["runs"].values():
        for key in ("rtol", "atol", "n_out"):
            if key in integration:
                assert run["options"][key] == integration[key]
