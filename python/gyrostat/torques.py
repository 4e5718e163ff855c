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

import inspect


from gyrostat import _core, scene_code
from gyrostat.scene_code import ImportName
from gyrostat.schema import (Field, ListOf, Matrix, NamedValues, Table, Variants, Vector, all_finite,
                             elementwise, non_negative, positive)

__all__ = ["TORQUE_TYPES", "BY_KIND", "TORQUE", "build", "names", "schema"]

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


# The user's torque holds a function, not physical parameters: its scene keys are written here
# (its C++ side, torque/custom.hpp, only calls the function). The names it holds run code: they
# are checked against what the scene's user allowed (gyrostat.scene_code) and imported only when
# the torque is built.
_CUSTOM = Table({
    "function": Field(ImportName(), required=True,
                      doc="the torque function, an importable name 'module:attribute': a Python callable "
                          "f(t, omega[, quaternion]) -> M, or a scipy.LowLevelCallable (see gyrostat.CustomTorque); "
                          "with `parameters`, a factory called once with them that returns one"),
    "jacobian": Field(ImportName(),
                      doc="its Jacobian dM/domega, an importable name of the same kind (default: difference quotients)"),
    "parameters": Field(NamedValues(), doc="keyword arguments of the factories `function` and `jacobian` name"),
    "attitude": Field(bool, default=False, doc="the function takes the attitude quaternion (models with attitude)"),
}, doc=_core.CustomTorque.description + ". **Such a scene runs code**: the module it names is imported and its "
       "function (or factory) called. A scene names code only from modules in its own folder or below it, and from "
       "modules its user allows (`gyrostat run|sweep|check --allow-import PACKAGE`, `Scene.from_file(path, "
       "allow_import=[...])`, `gyrostat.sweep(..., allow_import=[...])`); any other name is refused before anything "
       "is imported. Nothing is imported or called until the whole scene has passed its checks.")


def _stand_in(name: str):
    """A torque function that refuses to run: it stands in for the user's while a scene is checked."""
    def refuse(t, omega, quaternion=None):
        raise RuntimeError(f"CustomTorque {name!r} is a stand-in: the scene was only checked (Scene.checked, "
                           f"gyrostat check); load it with Scene.from_file to run its code")
    return refuse


def _made(entry: dict, function, jacobian, parameters: dict):
    """``CustomTorque(function, jacobian, parameters=...)``: the factories called with the scene's
    ``parameters``, or ValueError naming one that is no factory or whose signature refuses them."""
    for field, factory in (("function", function), ("jacobian", jacobian)):
        if factory is None:
            continue
        if not callable(factory) or type(factory).__name__ == "LowLevelCallable":
            raise ValueError(f"{entry[field].field} = {str(entry[field])!r} with `parameters` must name a factory "
                             f"(a callable), got {type(factory).__name__}")
        try:
            inspect.signature(factory).bind(**parameters)
        except ValueError:  # a signature Python cannot read: the call decides
            pass
        except TypeError as error:
            raise ValueError(f"{entry[field].field} = {str(entry[field])!r}: the factory refused the scene's "
                             f"`parameters` ({', '.join(parameters) or 'none'}): {error}") from None
    return _core.CustomTorque(function, jacobian, attitude=entry["attitude"], name=str(entry["function"]),
                              parameters=parameters)


def _check_signature(name, function, attitude: bool) -> None:
    """A Python torque function must take (t, omega) or (t, omega, quaternion): ValueError naming
    ``name`` otherwise (e.g. a factory named without its ``parameters``). Compiled functions and
    callables whose signature Python cannot read are left to the torque's own checks."""
    if not callable(function) or type(function).__name__ == "LowLevelCallable":
        return
    try:
        signature = inspect.signature(function)
    except (TypeError, ValueError):
        return
    arguments = ("t", "omega", "quaternion") if attitude else ("t", "omega")
    try:
        signature.bind(*arguments)
    except TypeError:
        raise ValueError(f"{name.field} = {str(name)!r} takes {signature}, but a torque function takes "
                         f"({', '.join(arguments)}); if it is a factory, give its arguments in `parameters`") from None


def _custom(entry: dict):
    """A ``custom`` entry → ``CustomTorque``: the named objects (imported now, as allowed), called
    with ``parameters`` when given. Inside :func:`gyrostat.scene_code.stand_ins` nothing is
    imported or called: a function that refuses to run stands in for it, to check the scene's models."""
    if scene_code.standing_in():
        return _core.CustomTorque(_stand_in(str(entry["function"])), None, attitude=entry["attitude"], name=str(entry["function"]))
    parameters = entry.get("parameters")
    function = entry["function"].load()
    jacobian = entry["jacobian"].load() if "jacobian" in entry else None
    if parameters is not None:  # factories: the torque keeps them, and sensitivities move its parameters
        torque = _made(entry, function, jacobian, parameters)
        _check_signature(entry["function"], torque.function, entry["attitude"])
        return torque
    _check_signature(entry["function"], function, entry["attitude"])
    return _core.CustomTorque(function, jacobian, attitude=entry["attitude"], name=str(entry["function"]))


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
