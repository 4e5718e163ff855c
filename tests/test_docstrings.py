"""Every public name of ``gyrostat`` has a numpydoc docstring: a Parameters section where it
takes any parameter, and an Examples section whose examples run and print what they show
(doctest). Walked: ``gyrostat.__all__`` and the public attributes of each public class
(methods, properties, slots, the generated torque classes' members), each checked once where it
is defined. Modules need a docstring; plain values (``simd_lanes``, ``METHODS``) are documented
where they are assigned."""

import doctest
import inspect
import re
import types
import warnings

import pytest

import gyrostat

SECTION = r"^\s*{}\s*\n\s*-{{3,}}\s*$"
ROUTINES = (types.FunctionType, types.BuiltinFunctionType, staticmethod, classmethod, types.MethodDescriptorType)
DUNDERS = ("__call__", "__getitem__", "__contains__", "__len__")


def doc_of(owner, name, member) -> str:
    if isinstance(member, (staticmethod, classmethod)):
        member = member.__func__
    if isinstance(member, types.MemberDescriptorType) and isinstance(getattr(owner, "__slots__", None), dict):
        return owner.__slots__.get(name) or ""  # documented slots: __slots__ = {name: docstring}
    return inspect.getdoc(member) or ""


def pybind_signature(doc: str) -> str | None:
    """The signature line pybind11 puts first in a docstring: ``name(self: T, t: float) -> R``."""
    first = doc.split("\n", 1)[0]
    return first if re.match(r"^\w+\(.*\)", first) else None


def takes_parameters(member, doc: str) -> bool:
    function = member.__func__ if isinstance(member, (staticmethod, classmethod)) else member
    if isinstance(function, types.FunctionType):
        names = [p for p in inspect.signature(function).parameters if p not in ("self", "cls")]
        return bool(names)
    signature = pybind_signature(doc)
    if signature is None:
        return False
    arguments = [a.strip() for a in signature[signature.index("(") + 1:signature.rindex(")")].split(",") if a.strip()]
    return any(not a.startswith("self") for a in arguments)


def class_names(label: str, obj: type, seen: set):
    """The class and the public attributes of it and of its gyrostat bases, each once."""
    init = obj.__dict__.get("__init__")
    if init is not None and not isinstance(init, types.WrapperDescriptorType):
        needs = takes_parameters(init, inspect.getdoc(init) or "") or obj in gyrostat._core.torque_types
    else:
        needs = bool(getattr(obj, "__dataclass_fields__", None))
    if obj.__doc__ is None and any(b is not object for b in obj.__bases__):
        needs = None  # a class without its own docstring (inherits its base's): checked with the base
    yield label, None, label, obj, inspect.getdoc(obj) or "", needs
    for klass in obj.__mro__:
        if klass.__module__ in ("builtins", "pybind11_builtins") or klass in seen:
            continue
        seen.add(klass)
        for attr, member in vars(klass).items():
            if attr.startswith("_") and attr not in DUNDERS:
                continue
            if attr in getattr(klass, "__dataclass_fields__", {}):
                continue  # a dataclass field: in the class's Parameters
            if not (isinstance(member, ROUTINES) or isinstance(member, (property, types.MemberDescriptorType))
                    or type(member).__name__ in ("instancemethod", "pybind11_static_property")):
                continue  # a plain class constant (kind = "full"): documented with its class
            if isinstance(member, types.FunctionType) and member.__doc__ is None and any(
                    attr in vars(base) for base in klass.__mro__[1:]):
                continue  # an override without a docstring: its base's (checked there) is its own
            doc = doc_of(klass, attr, member)
            yield (f"{klass.__module__}.{klass.__qualname__}.{attr}", klass, attr, member, doc,
                   takes_parameters(member, doc) and not isinstance(member, property))


def public_names():
    """(label, owner, name, member, docstring, needs Parameters) of every public name: those of
    ``gyrostat.__all__`` and everything its submodules export (their ``__all__``)."""
    seen: set = set()
    modules = []
    for name in gyrostat.__all__:
        obj = getattr(gyrostat, name)
        if isinstance(obj, types.ModuleType):
            modules.append(obj)
            yield f"gyrostat.{name}", None, name, obj, inspect.getdoc(obj) or "", None
        elif inspect.isclass(obj):
            yield from class_names(f"gyrostat.{name}", obj, seen)
        elif callable(obj):  # plain values are documented beside their assignment
            doc = inspect.getdoc(obj) or ""
            yield f"gyrostat.{name}", None, name, obj, doc, takes_parameters(obj, doc)
    for module in (gyrostat.attitude, gyrostat.averaged, gyrostat.lagrange, gyrostat.orthogonal, gyrostat.scene,
                   gyrostat.sweeps, gyrostat.validity):
        for name in module.__all__:
            obj = getattr(module, name)
            if inspect.isclass(obj) and obj not in seen:
                yield from class_names(f"{module.__name__}.{name}", obj, seen)
            elif inspect.isfunction(obj) and obj.__module__.startswith("gyrostat"):
                doc = inspect.getdoc(obj) or ""
                yield f"{module.__name__}.{name}", None, name, obj, doc, takes_parameters(obj, doc)


NAMES = list(public_names())


def test_the_walk_covers_the_public_api():
    labels = {label for label, *_ in NAMES}
    for expected in ("gyrostat.Body", "gyrostat.ViscousCavity", "gyrostat.solve", "gyrostat.Solution",
                     "gyrostat.solution.Solution.__call__", "gyrostat.solution.Solution.state_names",
                     "gyrostat.solution.Solution.output_names", "gyrostat.solution.Solution.event_names",
                     "gyrostat.solution.Solution.success", "gyrostat.solution.Solution.notes",
                     "gyrostat._core.ViscousCavity.p0", "gyrostat._core.ViscousCavity.__call__",
                     "gyrostat._core.Body.moments", "gyrostat.modelbase.ModelBase.units",
                     "gyrostat._core.Options.rtol", "gyrostat.lagrange.LagrangeTop", "gyrostat.orthogonal.OrthogonalModel",
                     "gyrostat.families.orthogonal_torque.models.OrthogonalModel.tau_rate", "gyrostat.scene.load",
                     "gyrostat.validity.check", "gyrostat.averaged.lotka_volterra", "gyrostat.attitude.euler_angles",
                     "gyrostat.sweeps.Plan", "gyrostat.sweeps.plan.Plan.member", "gyrostat.orthogonal.NearlySpherical"):
        assert expected in labels, expected
    assert len(NAMES) > 230


@pytest.mark.parametrize("label, owner, name, member, doc, needs", NAMES, ids=[n[0] for n in NAMES])
def test_numpydoc_sections(label, owner, name, member, doc, needs):
    if pybind_signature(doc):
        doc = doc.split("\n", 1)[1] if "\n" in doc else ""
    assert doc.strip(), f"{label} has no docstring"
    if needs is None:  # a module
        return
    if needs:
        assert re.search(SECTION.format("Parameters"), doc, flags=re.M), f"{label}: no Parameters section"
    assert re.search(SECTION.format("Examples"), doc, flags=re.M), f"{label}: no Examples section"
    assert ">>> " in doc.split("Examples", 1)[1], f"{label}: an Examples section without an example"


def test_torque_docstrings_are_generated_from_the_declarations():
    for cls in gyrostat._core.torque_types:
        doc = cls.__doc__
        for p in cls.parameters:
            entry = re.search(rf"^{p['name']} : .*\n\s+(.*)$", doc, flags=re.M)
            assert entry, (cls.__name__, p["name"])
            sentence = p["description"][:1].upper() + p["description"][1:]
            assert entry.group(1).startswith(f"{sentence}, in {p['unit']} ("), entry.group(1)
        assert f'scene type ``"{cls.kind}"``' in doc


def run_examples(doc: str, label: str, globs: dict, failed: list) -> dict:
    test = doctest.DocTestParser().get_doctest(doc, globs, label, None, 0)
    runner = doctest.DocTestRunner(optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # a ValidityWarning an example may raise is not its point
        runner.run(test, clear_globs=False)  # prints each failure (pytest shows it)
    if runner.failures:
        failed.append(label)
    return test.globs


def test_every_example_prints_what_it_shows():
    """The examples run: a class's examples first, its attributes' examples in what they defined
    (``sol`` of Solution's example, ``model`` of ModelBase's)."""
    class_globs: dict = {}
    attempted, failed = 0, []
    for label, owner, name, member, doc, needs in NAMES:
        if needs is None or ">>> " not in doc:
            continue
        if owner is None:
            globs = run_examples(doc, label, {}, failed)
            if inspect.isclass(member):
                class_globs[member] = globs
        else:
            if owner not in class_globs:
                class_globs[owner] = run_examples(inspect.getdoc(owner) or "", owner.__qualname__, {}, failed)
            run_examples(doc, label, dict(class_globs[owner]), failed)
        attempted += 1
    assert not failed, f"examples that print something else: {failed}"
    assert attempted > 200


def test_solution_call_gives_named_outputs_between_output_times():
    """``sol(t, name)``: a state component or a named output at any time, the output computed by the
    C++ model at the interpolated state (here |G| and T of a torque-free body: exactly constant)."""
    import numpy as np

    model = gyrostat.Model(gyrostat.Body([3.0, 2.0, 1.0]), attitude=True)
    sol = gyrostat.solve(model, [0.1, 0.2, 1.0], (0.0, 10.0), n_out=11, dense_output=True, rtol=1e-12, atol=1e-14)
    times = np.array([[0.25, 3.3], [7.1, 9.99]])
    energy = sol(times, "kinetic_energy")
    assert energy.shape == (2, 2)
    assert np.allclose(energy, sol["kinetic_energy"][0], rtol=1e-11, atol=0)
    assert np.array_equal(sol(times, "r"), sol(times)[..., 2])
    theta = sol(4.0, "theta")  # at an output time: what the engine recorded there
    assert abs(theta - sol["theta"][4]) < 1e-12 and np.ndim(theta) == 0
    with pytest.raises(KeyError, match="neither a state component"):
        sol(1.0, "x")
    detached = gyrostat.Solution(sol._result)  # a solution that does not know its model
    with pytest.raises(ValueError, match="does not know its model"):
        detached(1.0, "theta")
