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

import numpy as np

from gyrostat import _core
from gyrostat.schema import Field, ListOf, Matrix, Table, Variants, Vector, non_negative, positive

__all__ = ["TORQUE_TYPES", "BY_KIND", "TORQUE", "build", "names", "schema"]

TORQUE_TYPES: tuple[type, ...] = tuple(_core.torque_types)
"""Every torque class, in the core's order."""

BY_KIND: dict[str, type] = {cls.kind: cls for cls in TORQUE_TYPES}
"""The torque class of each scene ``type``."""


def names() -> str:
    """``ConstantTorque, LinearDamping, …``: for messages that list the torques."""
    return ", ".join(cls.__name__ for cls in TORQUE_TYPES)


def _finite(values) -> None:
    if not np.all(np.isfinite(np.asarray(values, float))):
        raise ValueError("must be finite numbers")


_SHAPES = {"scalar": lambda: float, "vector3": lambda: Vector(3), "matrix3": lambda: Matrix(3, 3),
           "matrices": lambda: ListOf(Matrix(3, 3), min_len=1)}
_CHECKS = {"finite": _finite, "positive": positive, "non_negative": [_finite, non_negative]}


def schema(cls: type) -> Table:
    """The scene table of one torque, from its declared parameters."""
    fields, choices = {}, {}
    for p in cls.parameters:
        fields[p["name"]] = Field(_SHAPES[p["shape"]](), required=p["choice"] == 0, doc=p["description"],
                                  unit="" if p["unit"] == "1" else p["unit"], check=_CHECKS[p["constraint"]])
        if p["choice"]:
            choices.setdefault(p["choice"], []).append(p["name"])
    return Table(fields, one_of=[tuple(group) for group in choices.values()], doc=cls.description)


TORQUE = Variants("type", {kind: schema(cls) for kind, cls in BY_KIND.items()}, doc="a perturbation torque")
"""The schema of one ``[[torques]]`` entry."""


def build(entry: dict):
    """The torque of a validated ``[[torques]]`` entry (its ``type`` and parameters)."""
    return BY_KIND[entry["type"]](**{key: value for key, value in entry.items() if key != "type"})
