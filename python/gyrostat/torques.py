"""Every torque, as the C++ core declares it: the registry that scenes, models and the package's
namespace use. Nothing about a torque is written here.

Each torque class of :mod:`gyrostat._core` (one per alternative of the core's ``AnyTorque``,
listed in ``_core.torque_types``) carries its declaration (``cpp/include/gyrostat/torque/*.hpp``):
``kind`` (its scene ``type``), ``description`` and ``parameters`` (name, shape, unit,
description, constraint, and the choice it belongs to). From that this module makes the scene
schema of a ``[[torques]]`` entry, builds the torque from a validated entry (the class's own
constructor takes the same keywords), and checks that a Python object is a torque. Adding a
torque to the core adds it here, to the scene format and to ``gyrostat``'s namespace.
"""

from __future__ import annotations

import importlib

import numpy as np

from gyrostat import _core
from gyrostat.schema import (Field, ListOf, Matrix, NamedValues, Table, Variants, Vector, all_finite, elementwise,
                             non_negative, positive)

__all__ = ["TORQUE_TYPES", "BY_KIND", "TORQUE", "build", "names", "schema", "importable"]

TORQUE_TYPES: tuple[type, ...] = tuple(_core.torque_types)
"""Every torque class, in the core's order."""

BY_KIND: dict[str, type] = {cls.kind: cls for cls in TORQUE_TYPES}
"""The torque class of each scene ``type``."""


def names() -> str:
    """``ConstantTorque, LinearDamping, …``: for messages that list the torques."""
    return ", ".join(cls.__name__ for cls in TORQUE_TYPES)


@elementwise
def _finite(values) -> None:
    all_finite(values)


_SHAPES = {"scalar": lambda: float, "vector3": lambda: Vector(3), "matrix3": lambda: Matrix(3, 3),
           "matrices": lambda: ListOf(Matrix(3, 3), min_len=1)}
_CHECKS = {"finite": _finite, "positive": positive, "non_negative": [_finite, non_negative]}


def importable(name: str):
    """The object at ``"module:attribute"`` (``"package.module:function"``, dotted attributes
    allowed), or ``ValueError`` saying what could not be found."""
    module_name, colon, attribute = name.partition(":")
    if not colon or not module_name or not attribute:
        raise ValueError(f"must be an importable name 'module:attribute', got {name!r}")
    try:
        target = importlib.import_module(module_name)
    except ImportError as error:
        raise ValueError(f"cannot import module {module_name!r}: {error}") from None
    for part in attribute.split("."):
        if not hasattr(target, part):
            raise ValueError(f"module {module_name!r} has no attribute {attribute!r}")
        target = getattr(target, part)
    return target


# The user's torque holds a function, not physical parameters: its scene keys are written here
# (its C++ side, torque/custom.hpp, only calls the function).
_CUSTOM = Table({
    "function": Field(str, required=True, check=importable,
                      doc="the torque function, an importable name 'module:attribute': a Python callable "
                          "f(t, omega[, quaternion]) -> M, or a scipy.LowLevelCallable (see gyrostat.CustomTorque); "
                          "with `parameters`, a factory called once with them that returns one"),
    "jacobian": Field(str, check=importable,
                      doc="its Jacobian dM/domega, an importable name of the same kind (default: difference quotients)"),
    "parameters": Field(NamedValues(), doc="keyword arguments of the factories `function` and `jacobian` name"),
    "attitude": Field(bool, default=False, doc="the function takes the attitude quaternion (models with attitude)"),
}, doc=_core.CustomTorque.description)


def _custom(entry: dict):
    """A ``custom`` entry → ``CustomTorque``: the named objects, called with ``parameters`` when given."""
    parameters = entry.get("parameters")
    function = importable(entry["function"])
    jacobian = importable(entry["jacobian"]) if "jacobian" in entry else None
    if parameters is not None:
        function = function(**parameters)
        jacobian = jacobian(**parameters) if jacobian is not None else None
    return _core.CustomTorque(function, jacobian, attitude=entry["attitude"], name=entry["function"])


def schema(cls: type) -> Table:
    """The scene table of one torque, from its declared parameters."""
    if cls is _core.CustomTorque:
        return _CUSTOM
    fields, choices = {}, {}
    for p in cls.parameters:
        required = p["choice"] == 0 and p["default"] is None
        doc = p["description"] + (f' (default {p["default"]})' if p["default"] is not None else "")
        fields[p["name"]] = Field(_SHAPES[p["shape"]](), required=required, doc=doc,
                                  unit="" if p["unit"] == "1" else p["unit"], check=_CHECKS[p["constraint"]])
        if p["choice"]:
            choices.setdefault(p["choice"], []).append(p["name"])
    return Table(fields, one_of=[tuple(group) for group in choices.values()], doc=cls.description)


TORQUE = Variants("type", {kind: schema(cls) for kind, cls in BY_KIND.items()}, doc="a perturbation torque")
"""The schema of one ``[[torques]]`` entry."""


def build(entry: dict):
    """The torque of a validated ``[[torques]]`` entry (its ``type`` and parameters)."""
    if entry["type"] == _core.CustomTorque.kind:
        return _custom(entry)
    return BY_KIND[entry["type"]](**{key: value for key, value in entry.items() if key != "type"})
