"""Torques declare their capabilities in their headers and everything else reads the declarations:
no model, integrator or binding names a torque by its type (no type switch), and the contract
comment of torque/set.hpp lists exactly the capabilities its traits detect. The declarations are
checked to take effect where they are read (the folded affine part, the nutation-averaged top, the
measured quantities)."""

import re
from pathlib import Path

import numpy as np
import pytest

import gyrostat as g
from gyrostat import _core
from gyrostat import lagrange as lg

ROOT = Path(__file__).resolve().parent.parent
CPP = ROOT / "cpp"
SET = CPP / "include" / "gyrostat" / "torque" / "set.hpp"
TYPE_SWITCH = re.compile(r"(get_if|holds_alternative|std::get)\s*<\s*torque::\w+\s*>")


def type_switches(text: str) -> list[str]:
    return [m.group(0) for m in TYPE_SWITCH.finditer(text)]


def test_no_code_switches_on_a_torques_type():
    found = {str(path.relative_to(ROOT)): type_switches(path.read_text())
             for path in sorted(CPP.rglob("*")) if path.suffix in (".hpp", ".cpp")}
    found = {path: hits for path, hits in found.items() if hits}
    assert found == {}, f"read a declared capability (torque/set.hpp) instead of the type: {found}"


def test_the_check_sees_a_planted_type_switch():
    planted = "if (const auto* c = std::get_if<torque::Constant>(&part)) constant_ += c->moment;"
    assert type_switches(planted) == ["get_if<torque::Constant>"]
    assert type_switches("std::holds_alternative< torque::Custom >(part)") == ["holds_alternative< torque::Custom >"]


def detected(text: str) -> set[str]:
    """The capabilities set.hpp's traits detect: members called on declval<const T&>() and static
    flags read as T::name in enable_if."""
    return set(re.findall(r"declval<const T&>\(\)\.(\w+)\(", text)) | set(re.findall(r"enable_if_t<T::(\w+)>", text))


def contract(text: str) -> str:
    start = text.index("/// Every torque the library knows")
    return text[start:text.index("using AnyTorque")]


def test_the_contract_comment_names_every_detected_capability_and_no_other():
    text = SET.read_text()
    capabilities = detected(text)
    assert {"averaged", "affine_form", "constant_coefficients", "vector_form", "user_function", "needs_attitude",
            "on_orbit", "prepared"} <= capabilities, capabilities
    comment = contract(text)
    missing = sorted(name for name in capabilities if not re.search(rf"\b{name}\b", comment))
    assert missing == [], f"the contract comment of torque/set.hpp does not name {missing}"
    # and every optional capability the comment lists is detected (a declaration nothing reads is a lie)
    listed = set(re.findall(r"^///   (?:static constexpr bool |[\w:<>&, ]+ )?(\w+)(?:\(| = true)", comment, re.M))
    required = {"operator", "add_jacobian", "axisymmetric", "name", "parameters", "from", "values"}
    assert listed - required - capabilities == set(), listed - required - capabilities


def test_constant_and_linear_damping_fold_into_one_affine_torque():
    """Constant + LinearDamping fold into M0 − D ω (the declaration constant_coefficients): the
    right-hand side equals Euler's equation with that torque written here, to 1e-15 relative (a few
    roundings of O(1) terms: the library evaluates J⁻¹(M − ω × Jω) in another order), and Taylor
    covers the model (it refuses any torque that is not folded)."""
    J = np.array([1.0, 2.0, 3.0])
    M0, D = np.array([0.01, -0.02, 0.03]), np.diag([0.1, 0.2, 0.3])
    model = g.Model(g.Body(J), [g.ConstantTorque(M0), g.LinearDamping(matrix=D)])
    w = np.array([0.3, -0.2, 1.1])
    expected = (np.cross(J * w, w) + M0 - D @ w) / J  # J ω̇ = Jω × ω + M0 − D ω
    assert np.allclose(model.rhs(0.0, w), expected, rtol=1e-15, atol=1e-16), "folded affine right-hand side"
    g.solve(model, w, (0.0, 1.0), method="taylor", error_estimate=False)  # covered: no ValueError


def test_the_averaged_top_reads_the_affine_forms():
    """The nutation-averaged top takes every torque with an affine form of the paper's class and
    refuses the others by name."""
    top = lg.LagrangeAveraged(1.5, 1.0, 0.5, [g.LinearDamping(diagonal=[0.01, 0.01, 0.02]),
                                              g.ConstantTorque([0.0, 0.0, 0.003]),
                                              g.ResistiveMedium([np.diag([0.001, 0.001, 0.002]),
                                                                 np.diag([1e-5, 1e-5, 3e-5])])])
    assert top.state_names == ("G_z", "H", "r")
    with pytest.raises(ValueError, match="LinearDamping matrix must be diag"):
        lg.LagrangeAveraged(1.5, 1.0, 0.5, [g.LinearDamping(diagonal=[0.01, 0.02, 0.02])])
    with pytest.raises(ValueError, match="ConstantTorque's constant torque must be axial"):
        lg.LagrangeAveraged(1.5, 1.0, 0.5, [g.ConstantTorque([0.1, 0.0, 0.0])])
    with pytest.raises(ValueError, match="nutation average of torque 'viscous_cavity' is not implemented"):
        lg.LagrangeAveraged(1.5, 1.0, 0.5, [g.ViscousCavity(1.0, 100.0, 0.5)])


@pytest.mark.parametrize("make, expected", [
    (lambda: g.Model(g.Body([1.0, 2.0, 3.0])), [("omega", "state", [0, 1, 2]),
                                                 ("angular_momentum_norm", "output", [0]),
                                                 ("kinetic_energy", "output", [1])]),
    (lambda: g.Model(g.Body([1.0, 2.0, 3.0]), attitude=True),
     [("omega", "state", [0, 1, 2]), ("quaternion", "state", [3, 4, 5, 6]),
      ("angular_momentum_norm", "output", [0]), ("kinetic_energy", "output", [1])]),
    (lambda: g.TriaxialAveragedModel(g.Body([1.0, 2.0, 3.0]), [g.LinearDamping(diagonal=[0.01, 0.01, 0.01])]),
     [("G2", "state", [0]), ("pb", "state", [1]), ("phase", "state", [3]),
      ("angular_momentum_norm", "output", [0]), ("kinetic_energy", "output", [1])]),
])
def test_measured_quantities_are_the_models_declarations(make, expected):
    """What a run's error is measured on comes from the C++ declarations (vectors, labels, measured
    outputs): ω and the quaternion as vectors, the branch label left out."""
    got = [(name, role, list(columns)) for name, role, columns in make()._core.measured_quantities]
    assert got == expected
