"""A small, strict, declarative validator for TOML scene documents.

A schema is made of :class:`Table` (a TOML table) and :class:`Field` (one key: its type, whether it
is required, its default, a one-line doc and a unit). :func:`validate` checks a document parsed by
:mod:`tomllib` against a schema and returns a new plain dict with the defaults filled in and the
numbers normalised (ints become floats where a float is expected), or raises :class:`SceneError`
with a one-line message naming the key, its table and what was expected. :func:`describe` renders
the same schema as a Markdown reference, so the format is documented from one source. Example::

    import tomllib
    from gyrostat.schema import ArrayOf, Field, Matrix, Table, Variants, Vector, validate

    BODY = Table({
        "moments": Field(Vector(3), required=True, doc="principal moments A1, A2, A3", unit="kg m^2"),
        "rotor": Field(Vector(3), default=[0, 0, 0], doc="rotor momentum k", unit="kg m^2/s"),
    })
    TORQUE = Variants("type", {
        "constant": Table({"moment": Field(Vector(3), required=True, unit="N m")}),
        "linear_damping": Table({"matrix": Field(Matrix(3, 3)), "diagonal": Field(Vector(3))},
                                one_of=[("matrix", "diagonal")]),
    })
    SCENE = Table({
        "title": Field(str, default=""),
        "body": Field(BODY, required=True),
        "torques": Field(ArrayOf(TORQUE), default=[]),
    })
    scene = validate(SCENE, tomllib.loads(text))
    # SceneError: unknown key 'momnets' in [body]; did you mean 'moments'?

Types: ``float`` (an int or a float, never a bool), ``int`` (an integral float such as 2.0 is
accepted), ``bool``, ``str``, :class:`Choice` (one of some strings), :class:`Vector` (n numbers),
:class:`Matrix` (n x m numbers), :class:`ListOf` (a list of any length), :class:`Table`,
:class:`ArrayOf` (``[[name]]``), :class:`Variants` (a table whose keys are selected by a
discriminator key such as ``type = "constant"``) and :class:`OneOf` (a value of one of several
types, picked by its TOML kind: e.g. a number or a table). ``Table(one_of=[("a", "b")])`` asks
for exactly one key of a group. Extra checks are callables given as ``Field(..., check=...)``
(or ``Table(..., check=...)`` for the whole table) that raise ``ValueError("must be ...")``;
:func:`positive`, :func:`non_negative`, :func:`at_least` and :func:`increasing` are ready-made.

The package, one concern a module: ``messages`` (:class:`SceneError`, values shown in
messages), ``fields`` (the types, :class:`Field`, :func:`validate`, :func:`locate`), ``checks``
(the ready-made checks) and ``reference`` (:func:`describe`, :class:`Common`,
:func:`describe_common`).
"""

from gyrostat.schema.checks import (all_finite, at_least, elementwise, finite, increasing, non_negative,
                                    nonzero_quaternion, positive, span_order)
from gyrostat.schema.fields import (ArrayOf, Choice, Field, ListOf, Located, Matrix, NamedValues, OneOf, Table,
                                    ValueType, Variants, Vector, locate, validate)
from gyrostat.schema.messages import SceneError
from gyrostat.schema.reference import Common, describe, describe_common

__all__ = [
    "SceneError",
    "Field",
    "Table",
    "ArrayOf",
    "Variants",
    "OneOf",
    "Choice",
    "ValueType",
    "Vector",
    "Matrix",
    "ListOf",
    "validate",
    "locate",
    "Located",
    "describe",
    "positive",
    "non_negative",
    "at_least",
    "increasing",
    "finite",
    "all_finite",
    "span_order",
    "nonzero_quaternion",
    "elementwise",
    "NamedValues",
    "Common",
    "describe_common",
]
