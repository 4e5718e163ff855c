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


def public_names():
    """(label, owner, name, member, docstring, needs Parameters) of every public name."""
    seen = set()
    for name in gyrostat.__all__:
        obj = getattr(gyrostat, name)
        if isinstance(obj, types.ModuleType):
            yield f"gyrostat.{name}", None, name, obj, inspect.getdoc(obj) or "", None
            continue
        if not callable(obj):
            continue  # plain values: documented beside their assignment
        if inspect.isclass(obj):
            init = obj.__dict__.get("__init__")
            if init is not None and not isinstance(init, types.WrapperDescriptorType):
                needs = takes_parameters(init, inspect.getdoc(init) or "") or obj in gyrostat._core.torque_types
            else:
                needs = bool(getattr(obj, "__dataclass_fields__", None))
            yield f"gyrostat.{name}", None, name, obj, inspect.getdoc(obj) or "", needs
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
        else:
            doc = inspect.getdoc(obj) or ""
            yield f"gyrostat.{name}", None, name, obj, doc, takes_parameters(obj, doc)


NAMES = list(public_names())


def test_the_walk_covers_the_public_api():
    labels = {label for label, *_ in NAMES}
    for expected in ("gyrostat.Body", "gyrostat.ViscousCavity", "gyrostat.solve", "gyrostat.Solution",
                     "gyrostat.solution.Solution.__call__", "gyrostat.solution.Solution.state_names",
                     "gyrostat.solution.Solution.output_names", "gyrostat.solution.Solution.event_names",
                     "gyrostat.solution.Solution.success", "gyrostat.solution.Solution.notes",
                     "gyrostat._core.ViscousCavity.p0", "gyrostat._core.ViscousCavity.__call__",
                     "gyrostat._core.Body.moments", "gyrostat.modelbase.ModelBase.units",
                     "gyrostat._core.Options.rtol"):
        assert expected in labels, expected
    assert len(NAMES) > 140


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
            assert p["description"] in entry.group(1) and f"in {p['unit']}" in entry.group(1), entry.group(1)
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
    assert attempted > 130
