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
"""

from __future__ import annotations

import copy
import difflib
import json
import math
import re
from collections.abc import Callable, Iterable, Mapping
from typing import Any

import numpy as np

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
]

_LIMIT = 60  # values shown in messages are cut to this many characters


class SceneError(ValueError):
    """A document does not match its schema; the message is a single line naming the key, its
    table and, for a misspelled key, the nearest valid one.

    Examples
    --------
    >>> from gyrostat.scene import Scene, SceneError
    >>> try:
    ...     Scene.from_dict({"body": {"moment": [1.0, 2.0, 3.0]}})
    ... except SceneError as error:
    ...     print(error)
    unknown key 'moment' in [body]; did you mean 'moments'?
    """


class _Missing:
    def __repr__(self) -> str:
        return "MISSING"


MISSING: Any = _Missing()  # "no default": an optional key without a default stays absent


# ---------------------------------------------------------------------------------------------
# Showing values and places in messages


def _render(value: Any, budget: int) -> str:
    """TOML-like text of a value, built only as far as about ``budget`` characters."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return repr(value[: budget + 1])
    if isinstance(value, (int, float)):
        return repr(value)
    if isinstance(value, (list, tuple)):
        items: list[str] = []
        size = 2
        for item in value:
            if size > budget:
                items.append("...")
                break
            text = _render(item, budget - size)
            items.append(text)
            size += len(text) + 2
        return "[" + ", ".join(items) + "]"
    if isinstance(value, Mapping):
        items = []
        size = 2
        for key, item in value.items():
            if size > budget:
                items.append("...")
                break
            text = f"{_bare(str(key))} = {_render(item, budget - size)}"
            items.append(text)
            size += len(text) + 2
        return "{" + ", ".join(items) + "}"
    return " ".join(str(value).split())


def _show(value: Any) -> str:
    """One line, at most ``_LIMIT`` characters, ending with '...' when cut."""
    text = _render(value, _LIMIT)
    return text if len(text) <= _LIMIT else text[: _LIMIT - 3] + "..."


def _got(value: Any) -> str:
    text = _show(value)
    if isinstance(value, str):
        try:
            float(value)
        except ValueError:
            if value.strip().lower() in ("true", "false"):
                text += " (a string)"
        else:
            text += " (a string)"
    return text


def _one_line(error: Exception) -> str:
    return " ".join(str(error).split()) or type(error).__name__


def _bare(key: str) -> str:
    return key if re.fullmatch(r"[A-Za-z0-9_-]+", key) else json.dumps(key)


def _dotted(parts: tuple) -> str:
    text = ""
    for part in parts:
        text += f"[{part}]" if isinstance(part, int) else ("." if text else "") + _bare(part)
    return text


def _suggest(word: Any, options: Iterable[str]) -> str:
    if not isinstance(word, str):
        return ""
    close = difflib.get_close_matches(word, list(options), n=1, cutoff=0.6)
    return f"; did you mean '{close[0]}'?" if close else ""


def _alternatives(names: Iterable[str], quote: str = "'") -> str:
    names = [f"{quote}{name}{quote}" for name in names]
    return names[0] if len(names) == 1 else ", ".join(names[:-1]) + " or " + names[-1]


class _Path:
    """Where a value sits: the document's name and the keys / indices leading to it."""

    __slots__ = ("root", "parts")

    def __init__(self, root: str, parts: tuple = ()):
        self.root = root
        self.parts = parts

    def __truediv__(self, part: str | int) -> "_Path":
        return _Path(self.root, self.parts + (part,))

    def table(self) -> str:
        """``[integration]``, ``[torques[1]]``; the document's name at the top level."""
        return f"[{_dotted(self.parts)}]" if self.parts else self.root

    def inside(self) -> str:
        return f"in [{_dotted(self.parts)}]" if self.parts else "at the top level"

    def key(self) -> str:
        """``[integration] n_out``, ``[outputs] plots[1]``, ``scene: title``."""
        cut = max((i for i, part in enumerate(self.parts) if isinstance(part, str)), default=0)
        head, tail = self.parts[:cut], self.parts[cut:]
        return f"[{_dotted(head)}] {_dotted(tail)}" if head else f"{self.root}: {_dotted(tail)}"


def _kind_of(value: Any) -> str:
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, (int, float)):
        return "number"
    if isinstance(value, str):
        return "string"
    if isinstance(value, (list, tuple)):
        return "array"
    if isinstance(value, Mapping):
        return "table"
    return "other"


# ---------------------------------------------------------------------------------------------
# Types


class _Type:
    kinds: frozenset = frozenset()  # TOML kinds of the accepted values (see _kind_of)
    expected = ""  # completes "must be ...": "a number"
    name = ""  # short name for describe(): "number"
    plural = ""  # for lists: "numbers"

    def convert(self, value: Any, path: _Path) -> Any:
        raise NotImplementedError

    def fail(self, value: Any, path: _Path, note: str = "") -> None:
        raise SceneError(f"{path.key()} must be {self.expected}, got {_got(value)}{note}")

    def __repr__(self) -> str:
        return f"<{self.name}>"


ValueType = _Type
"""The base of a field's type, for a value another module converts itself (subclass it: ``kinds``,
``expected``, ``name``, ``plural`` and ``convert(value, path)``, raising :class:`SceneError`)."""


class _Float(_Type):
    kinds = frozenset({"number"})
    expected, name, plural = "a number", "number", "numbers"

    def convert(self, value, path):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(value, path)
        return float(value)


class _Integer(_Type):
    kinds = frozenset({"number"})
    expected, name, plural = "an integer", "integer", "integers"

    def convert(self, value, path):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            self.fail(value, path)
        if isinstance(value, float):
            if not value.is_integer():
                self.fail(value, path)
            return int(value)
        return value


class _Boolean(_Type):
    kinds = frozenset({"boolean"})
    expected, name, plural = "true or false", "boolean", "booleans"

    def convert(self, value, path):
        if not isinstance(value, bool):
            self.fail(value, path)
        return value


class _String(_Type):
    kinds = frozenset({"string"})
    expected, name, plural = "a string", "string", "strings"

    def convert(self, value, path):
        if not isinstance(value, str):
            self.fail(value, path)
        return value


class NamedValues(_Type):
    """A table of any keys (named values passed on as they are, e.g. a user function's keyword
    arguments): only the keys' being strings is checked."""

    kinds = frozenset({"table"})
    expected, name, plural = "a table of named values", "table of named values", "tables of named values"

    def convert(self, value, path):
        if not isinstance(value, Mapping) or not all(isinstance(key, str) for key in value):
            self.fail(value, path)
        return dict(value)


class Choice(_Type):
    """One of some strings: ``Choice("auto", "full", "closed_form")``."""

    kinds = frozenset({"string"})
    plural = "strings"

    def __init__(self, *options: str):
        if len(options) == 1 and not isinstance(options[0], str):
            options = tuple(options[0])
        if not options or not all(isinstance(option, str) for option in options):
            raise TypeError("Choice needs one or more strings")
        self.options = tuple(options)
        self.expected = "one of: " + ", ".join(self.options)
        self.name = "one of " + ", ".join(f'"{option}"' for option in self.options)

    def fail(self, value, path, note=""):
        raise SceneError(f"{path.key()} must be {self.expected}; got {_got(value)}{note}")

    def convert(self, value, path):
        if not isinstance(value, str):
            self.fail(value, path)
        if value not in self.options:
            raise SceneError(f"{path.key()} = {_show(value)} is not {self.expected}"
                             f"{_suggest(value, self.options)}")
        return value


def _as_type(spec: Any) -> _Type:
    builtin = {float: _Float, int: _Integer, bool: _Boolean, str: _String}
    if spec in builtin:
        return builtin[spec]()
    if isinstance(spec, _Type):
        return spec
    raise TypeError(f"not a schema type: {spec!r} (use float, int, bool, str or a gyrostat.schema type)")


_FLOATS = frozenset({float})


def _numbers(value: Any, size: int | None) -> bool:
    if type(value) is list and (size is None or len(value) == size) and set(map(type, value)) <= _FLOATS:
        return True  # a list of floats (what a scene or a sweep member mostly holds): no check per item
    return (isinstance(value, (list, tuple)) and (size is None or len(value) == size)
            and all(isinstance(x, (int, float)) and not isinstance(x, bool) for x in value))


def _length_note(value: Any, size: int) -> str:
    return f" (length {len(value)})" if isinstance(value, (list, tuple)) and len(value) != size else ""


class Vector(_Type):
    """A list of exactly ``n`` numbers; validated as a list of floats."""

    kinds = frozenset({"array"})

    def __init__(self, n: int):
        self.n = n
        self.expected = f"a list of {n} numbers"
        self.name = f"{n} numbers"
        self.plural = f"lists of {n} numbers"

    def convert(self, value, path):
        if not _numbers(value, self.n):
            self.fail(value, path, _length_note(value, self.n))
        return [float(x) for x in value]


class Matrix(_Type):
    """``n`` lists of ``m`` numbers each; validated as a list of lists of floats."""

    kinds = frozenset({"array"})

    def __init__(self, n: int, m: int):
        self.n, self.m = n, m
        self.expected = f"a {n}x{m} matrix ({n} lists of {m} numbers)"
        self.name = f"{n}x{m} matrix"
        self.plural = f"{n}x{m} matrices"

    def convert(self, value, path):
        if not (isinstance(value, (list, tuple)) and len(value) == self.n
                and all(_numbers(row, self.m) for row in value)):
            self.fail(value, path, _length_note(value, self.n))
        return [[float(x) for x in row] for row in value]


class ListOf(_Type):
    """A list of any length (at least ``min_len``) of ``item`` (float, int, str, Vector, ...);
    ``choices`` restricts a list of strings to those values."""

    kinds = frozenset({"array"})

    def __init__(self, item: Any, min_len: int = 0, choices: Iterable[str] | None = None):
        if choices is not None:
            if item is not str:
                raise TypeError("ListOf(choices=...) needs item str")
            item = Choice(*choices)
        self.item = _as_type(item)
        if "table" in self.item.kinds:
            raise TypeError("a list of tables is an ArrayOf")
        self.min_len = min_len
        at_least_ = f"at least {min_len} " if min_len else ""
        self.expected = f"a list of {at_least_}{self.item.plural}"
        self.name = f"list of {self.item.plural}"
        if isinstance(self.item, Choice):
            self.name += ", each one of " + ", ".join(f'"{option}"' for option in self.item.options)
        if min_len:
            self.name += f" (at least {min_len})"
        self.plural = "lists"

    def convert(self, value, path):
        if not isinstance(value, (list, tuple)) or len(value) < self.min_len:
            self.fail(value, path, f" (length {len(value)})" if isinstance(value, (list, tuple)) else "")
        return [self.item.convert(item, path / i) for i, item in enumerate(value)]


class Field:
    """One key of a table: its type, required or not, default, one-line doc, unit and checks.

    ``check`` is a callable (or a list of them) called with the validated value; it raises
    ``ValueError("must be ...")`` to reject it. A default is validated like a value (so
    ``default={}`` for a table means "all of its defaults") and copied for every document.
    """

    __slots__ = ("type", "required", "default", "doc", "unit", "checks")

    def __init__(self, type: Any, *, required: bool = False, default: Any = MISSING, doc: str = "",
                 unit: str = "", check: Callable[[Any], Any] | Iterable[Callable[[Any], Any]] = ()):
        self.type = _as_type(type)
        self.required = required
        self.doc = doc
        self.unit = unit
        self.checks = (check,) if callable(check) else tuple(check)
        if required and default is not MISSING:
            raise TypeError("a required field takes no default")
        if default is not MISSING and default is not None:
            try:
                default = self.type.convert(default, _Path("default", ("value",)))
            except SceneError as error:
                raise TypeError(f"invalid default {default!r}: {error}") from None
        self.default = default

    def validate(self, raw: Any, where: "_Path") -> Any:
        """The value converted to the field's type and passed through its checks."""
        value = self.type.convert(raw, where)
        for check in self.checks:
            try:
                check(value)
            except ValueError as error:
                raise SceneError(f"{where.key()} = {_show(raw)}: {_one_line(error)}") from None
        return value

    def about(self) -> str:
        """`` (doc [unit])`` for messages, or nothing."""
        text = " ".join(part for part in (self.doc, f"[{self.unit}]" if self.unit else "") if part)
        return f" ({text})" if text else ""

    def __repr__(self) -> str:
        return f"Field({self.type!r}, required={self.required}, default={self.default!r})"


class Table(_Type):
    """A TOML table: ``Table({"key": Field(...), ...}, one_of=[("a", "b")], check=..., doc=...)``.

    Keys not in ``fields`` are rejected. Each group in ``one_of`` needs exactly one of its keys.
    ``check`` is called with the validated dict and raises ``ValueError`` to reject it.
    """

    kinds = frozenset({"table"})
    expected, name, plural = "a table", "table", "tables"

    def __init__(self, fields: Mapping[str, Field], *, one_of: Iterable[Iterable[str]] = (),
                 check: Callable[[dict], Any] | None = None, doc: str = ""):
        self.fields = dict(fields)
        for key, spec in self.fields.items():
            if not isinstance(spec, Field):
                raise TypeError(f"field {key!r} must be a Field, got {spec!r}")
        self.one_of = [tuple(group) for group in one_of]
        for group in self.one_of:
            for key in group:
                if key not in self.fields:
                    raise TypeError(f"one_of group {group}: no field {key!r}")
                if self.fields[key].required or self.fields[key].default is not MISSING:
                    raise TypeError(f"one_of group {group}: field {key!r} must be optional without a default")
        self.check = check
        self.doc = doc

    def convert(self, value, path):
        return self.validate_table(value, path)

    def validate_table(self, value: Any, path: _Path, extra: tuple = (), note: str = "") -> dict:
        if not isinstance(value, Mapping):
            self.fail(value, path)
        valid = list(extra) + list(self.fields)
        for key in value:
            if key not in valid:
                hint = _suggest(key, valid) or (
                    "; valid keys: " + ", ".join(valid) if valid else "; this table takes no keys")
                raise SceneError(f"unknown key {_show(key)} {path.inside()}{note}{hint}")
        for group in self.one_of:
            given = [key for key in group if key in value]
            if len(given) != 1:
                got = "none is given" if not given else "got " + " and ".join(f"'{key}'" for key in given)
                raise SceneError(f"{path.table()} needs exactly one of {_alternatives(group)}; {got}")
        out: dict = {}
        for key, spec in self.fields.items():
            where = path / key
            if key in value:
                out[key] = spec.validate(value[key], where)
            elif spec.required:
                if isinstance(spec.type, ArrayOf):
                    raise SceneError(f"missing required array of tables [[{_dotted(where.parts)}]]")
                if "table" in spec.type.kinds and not isinstance(spec.type, OneOf):
                    raise SceneError(f"missing required table [{_dotted(where.parts)}]")
                raise SceneError(f"{path.table()} is missing required key '{key}'{spec.about()}")
            elif spec.default is not MISSING:
                out[key] = copy.deepcopy(spec.default)
        if self.check is not None:
            try:
                self.check(out)
            except ValueError as error:
                raise SceneError(f"{path.table()}: {_one_line(error)}") from None
        return out


class Variants(_Type):
    """A table whose ``key`` (e.g. ``type``) selects which :class:`Table` checks the other keys:
    ``Variants("type", {"constant": Table(...), "linear_damping": Table(...)})``."""

    kinds = frozenset({"table"})
    expected, plural = "a table", "tables"

    def __init__(self, key: str, variants: Mapping[str, Table], doc: str = ""):
        self.key = key
        self.variants = dict(variants)
        for name, table in self.variants.items():
            if not isinstance(table, Table):
                raise TypeError(f"variant {name!r} must be a Table")
            if key in table.fields:
                raise TypeError(f"variant {name!r} must not declare the discriminator {key!r}")
        self.choice = Choice(*self.variants)
        self.doc = doc
        self.name = f"table (kind set by `{key}`)"

    def convert(self, value, path):
        if not isinstance(value, Mapping):
            self.fail(value, path)
        if self.key not in value:
            raise SceneError(f"{path.table()} is missing required key '{self.key}' ({self.choice.expected})")
        tag = self.choice.convert(value[self.key], path / self.key)
        out = self.variants[tag].validate_table(value, path, extra=(self.key,), note=f" ({self.key} = '{tag}')")
        return {self.key: tag, **out}


class ArrayOf(_Type):
    """An array of tables, ``[[name]]`` in TOML: ``ArrayOf(Table(...))`` or ``ArrayOf(Variants(...))``."""

    kinds = frozenset({"array"})
    expected, name, plural = "an array of tables", "array of tables", "arrays of tables"

    def __init__(self, table: Table | Variants):
        if not isinstance(table, (Table, Variants)):
            raise TypeError("ArrayOf needs a Table or Variants")
        self.table = table

    def convert(self, value, path):
        if not isinstance(value, (list, tuple)):
            self.fail(value, path)
        out = []
        for i, item in enumerate(value):
            if not isinstance(item, Mapping):
                raise SceneError(f"{(path / i).table()} must be a table, got {_got(item)}")
            out.append(self.table.convert(item, path / i))
        return out


class OneOf(_Type):
    """A value of one of several types, picked by its TOML kind (number, string, array, table...):
    ``OneOf(float, LAW)`` takes ``law = 0.1`` as well as ``law = { kind = "harmonic", ... }``."""

    def __init__(self, *types: Any):
        self.types = tuple(_as_type(spec) for spec in types)
        if len(self.types) < 2:
            raise TypeError("OneOf needs two or more types")
        self.kinds = frozenset().union(*(spec.kinds for spec in self.types))
        self.expected = " or ".join(spec.expected for spec in self.types)
        self.name = " or ".join(spec.name for spec in self.types)
        self.plural = " or ".join(spec.plural for spec in self.types)

    def convert(self, value, path):
        kind = _kind_of(value)
        for spec in self.types:
            if kind in spec.kinds:
                return spec.convert(value, path)
        self.fail(value, path)


def validate(schema: Table | Variants, document: Any, where: str = "scene") -> dict:
    """Check ``document`` (a dict from :mod:`tomllib`) against ``schema`` and return a new plain
    dict with defaults filled in and numbers normalised; raise :class:`SceneError` otherwise.
    ``where`` names the document in messages about its top-level keys."""
    if not isinstance(schema, (Table, Variants)):
        raise TypeError("validate() needs a Table or Variants schema")
    path = _Path(where)
    if not isinstance(document, Mapping):
        raise SceneError(f"{where} must be a table, got {_got(document)}")
    return schema.convert(document, path)


class Located:
    """Where a path into a validated document leads: the :class:`Field` that holds the value,
    the keys and indices up to that field (``field_parts``), and those inside its value
    (``inner``: indices into a vector or a matrix)."""

    __slots__ = ("field", "field_parts", "inner", "root", "numbers_alone")

    def __init__(self, field: Field, field_parts: tuple, inner: tuple, root: str):
        self.field, self.field_parts, self.inner, self.root = field, field_parts, inner, root
        # a number, a vector or a matrix whose checks all hold number by number (elementwise)
        self.numbers_alone = (isinstance(field.type, (_Float, Vector, Matrix))
                              and all(getattr(check, "elementwise", False) for check in field.checks))

    def accepts_number(self, number: Any) -> bool:
        """Whether a float set into a valid value of this field (one number, or entries of a
        vector or a matrix) leaves it valid, judged from the number alone: the field holds numbers
        and each of its checks is :func:`elementwise`. False means "not known": :meth:`validate`
        the whole value then (which names what is wrong)."""
        if not (self.numbers_alone and type(number) is float):
            return False
        try:
            for check in self.field.checks:
                check(number)
        except ValueError:
            return False
        return True

    def revalidate(self, document: Mapping) -> Any:
        """Validates the field's (changed) value in ``document`` as :func:`validate` would."""
        value = document
        for part in self.field_parts:
            value = value[part]
        return self.validate(value)

    def validate(self, value: Any) -> Any:
        """Validates a value of the field as :func:`validate` would (a sweep member's)."""
        return self.field.validate(value, _Path(self.root, self.field_parts))


def locate(schema: Table, document: Mapping, parts: tuple, where: str = "scene") -> Located:
    """The field a path (``("torques", 1, "viscosity")``, ``("body", "moments", 0)``) of a
    document validated against ``schema`` leads to; SceneError naming the path when it leads
    nowhere (an unknown key with the nearest valid one, an index out of range, a key the
    document does not set, a table rather than a value)."""
    spec: _Type = schema
    value: Any = document
    shown = _Path(where)
    for i, part in enumerate(parts):
        if isinstance(spec, Variants):
            spec = spec.variants[value[spec.key]]
        if isinstance(spec, ArrayOf):
            if not isinstance(part, int) or not 0 <= part < len(value):
                raise SceneError(f"{shown.table()} has {len(value)} entries; {_dotted(parts[:i + 1])} is not one of them")
            spec, value, shown = spec.table, value[part], shown / part
            continue
        if not isinstance(spec, Table) or not isinstance(part, str):
            raise SceneError(f"{_dotted(parts[:i + 1])}: {shown.table()} is not an array")
        if part not in spec.fields:
            raise SceneError(f"unknown key {_show(part)} {shown.inside()}{_suggest(part, list(spec.fields))}")
        if part not in value:
            raise SceneError(f"{(shown / part).key()} is not set in the scene: set it to vary it")
        field = spec.fields[part]
        if not isinstance(field.type, (Table, Variants, ArrayOf)):
            return Located(field, parts[:i + 1], tuple(parts[i + 1:]), where)
        spec, value, shown = field.type, value[part], shown / part
    raise SceneError(f"{_dotted(parts) or where} is a table, not a value")


# ---------------------------------------------------------------------------------------------
# Ready-made checks (for Field(check=...)); a list of numbers is checked element by element


def elementwise(check: Callable[[Any], Any]) -> Callable[[Any], Any]:
    """Marks ``check`` as one that a list of numbers passes when each of its numbers passes it
    alone (and that takes a single number): a number changed inside a valid value is then checked
    by itself (:meth:`Located.accepts_number`, what a sweep member's values go through)."""
    check.elementwise = True
    return check


def _each(value: Any) -> list:
    if isinstance(value, (list, tuple)):
        return [x for item in value for x in _each(item)]
    return [value]


@elementwise
def positive(value: Any) -> None:
    """Every number is > 0."""
    if not all(x > 0 for x in _each(value)):
        raise ValueError("must be positive")


@elementwise
def non_negative(value: Any) -> None:
    """Every number is >= 0."""
    if not all(x >= 0 for x in _each(value)):
        raise ValueError("must not be negative")


def at_least(bound: float) -> Callable[[Any], None]:
    """Every number is >= ``bound``."""

    @elementwise
    def check(value: Any) -> None:
        if not all(x >= bound for x in _each(value)):
            raise ValueError(f"must be at least {bound}")

    return check


def increasing(value: Any) -> None:
    """A list of numbers is strictly increasing."""
    if not all(a < b for a, b in zip(value, value[1:])):
        raise ValueError("must be increasing")


@elementwise
def finite(value: Any, _: Any = None) -> None:
    """A number is finite."""
    if not math.isfinite(value):
        raise ValueError("must be finite")


def _flat_floats(values: Any) -> Any:
    """A float, a list of floats or a list of lists of floats as one iterable of them; None for
    anything else."""
    if type(values) is float:
        return (values,)
    if type(values) is list:
        if set(map(type, values)) <= _FLOATS:
            return values
        if all(type(row) is list and set(map(type, row)) <= _FLOATS for row in values):
            return [x for row in values for x in row]
    return None


@elementwise
def all_finite(values: Any) -> None:
    """Every number is finite."""
    flat = _flat_floats(values)  # validated values are floats: checked without NumPy
    if not (all(map(math.isfinite, flat)) if flat is not None else np.all(np.isfinite(np.asarray(values, float)))):
        raise ValueError("must be finite numbers")


def span_order(values: Any) -> None:
    """A time span (t0, t1) of two finite times."""
    if not (math.isfinite(values[0]) and math.isfinite(values[1])):
        raise ValueError("must be two finite times")


def nonzero_quaternion(values: Any) -> None:
    """A finite, non-zero quaternion (w, x, y, z)."""
    q = np.asarray(values, float)
    if not np.all(np.isfinite(q)) or not np.any(q):
        raise ValueError("must be a finite, non-zero quaternion (w, x, y, z)")


# ---------------------------------------------------------------------------------------------
# Markdown reference


def _toml(value: Any) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, (list, tuple)):
        return "[" + ", ".join(_toml(item) for item in value) + "]"
    if isinstance(value, Mapping):
        return "{ " + ", ".join(f"{_bare(k)} = {_toml(v)}" for k, v in value.items()) + " }" if value else "{}"
    return repr(value)


def _cell(text: str) -> str:
    return " ".join(text.split()).replace("|", "\\|")


def _inner(spec: _Type) -> list[Table | Variants]:
    """The tables a type contains, to be described in their own sections."""
    if isinstance(spec, (Table, Variants)):
        return [spec]
    if isinstance(spec, ArrayOf):
        return [spec.table]
    if isinstance(spec, OneOf):
        return [table for alternative in spec.types for table in _inner(alternative)]
    return []


def _signature(key: str, spec: Field, table: Table) -> tuple | None:
    """What a key's row says (type, need, default, unit, doc, the tables it holds), for finding the
    keys several schemas share; None for a key of a one_of group (its row names the group)."""
    if any(key in group for group in table.one_of):
        return None
    return (key, spec.type.name, spec.required, _toml(spec.default) if spec.default is not MISSING else None, spec.unit,
            spec.doc, tuple(id(t) for t in _inner(spec.type)))


def _tables(schema: Table | Variants, dotted: str, found: dict[str, Table], nested: list) -> None:
    """Every table of ``schema`` by its dotted path into ``found``; every table or set of variants
    it holds into ``nested`` as (table, heading, path)."""
    if isinstance(schema, Variants):
        return
    found[dotted] = schema
    for key, spec in schema.fields.items():
        child = f"{dotted}.{_bare(key)}" if dotted else _bare(key)
        for table in _inner(spec.type):
            nested.append((table, ("[[{}]]" if isinstance(spec.type, ArrayOf) else "[{}]").format(child), child))
            _tables(table, child, found, nested)


class Common:
    """What several schemas share, to be described once (:func:`describe_common`) and referred to
    from each (:func:`describe` with ``common=``): the tables two or more of them hold (the same
    object: events, sweep, torques, …) and, at each dotted path, the keys whose rows would read
    the same in two or more (title, rtol, t_span, …)."""

    def __init__(self, schemas: Iterable[Table]):
        schemas = list(schemas)
        users: dict[int, set[int]] = {}
        first: dict[int, tuple] = {}
        rows: dict[tuple[str, tuple], set[int]] = {}
        self.fields: dict[tuple[str, tuple], tuple[str, Field]] = {}
        for index, schema in enumerate(schemas):
            found: dict[str, Table] = {}
            nested: list = []
            _tables(schema, "", found, nested)
            for table, heading, path in nested:
                users.setdefault(id(table), set()).add(index)
                first.setdefault(id(table), (table, heading, path))
            for path, table in found.items():
                for key, spec in table.fields.items():
                    signature = _signature(key, spec, table)
                    if signature is not None:
                        rows.setdefault((path, signature), set()).add(index)
                        self.fields.setdefault((path, signature), (key, spec))
        shared = {i for i, who in users.items() if len(who) > 1}
        inside = set()  # tables held by a shared table are described with it
        for i in shared:
            found, nested = {}, []
            _tables(first[i][0], first[i][2], found, nested)
            inside |= {id(t) for t, _, _ in nested}
        #: the shared tables, outermost only: id → (table, heading, path)
        self.tables = {i: where for i, where in first.items() if i in shared and i not in inside}
        #: (path, row) of every shared key, in the order the schemas first declare them
        self.keys = [k for k, who in rows.items() if len(who) > 1 and not self._in_shared_table(k[0])]

    def _in_shared_table(self, path: str) -> bool:
        return any(path == p or path.startswith(p + ".") for _, _, p in self.tables.values())

    def shared(self, dotted: str, key: str, spec: Field, table: Table) -> bool:
        """Whether this key's row is described once, among the shared keys."""
        return (dotted, _signature(key, spec, table)) in self.keys

    def seen(self) -> dict[int, str]:
        return {i: f"{heading} (shared)" for i, (_, heading, _) in self.tables.items()}


def _section(schema: Table | Variants, heading: str, dotted: str, level: int, out: list[str],
             seen: dict[int, str], tag: tuple[str, str] | None = None, common: Common | None = None) -> None:
    out += [f"{'#' * min(level, 6)} {heading}", ""]
    if schema.doc:
        out += [_cell(schema.doc), ""]
    if isinstance(schema, Variants):
        kinds = ", ".join(f'`"{name}"`' for name in schema.variants)
        out += [f"`{schema.key}` selects the kind: {kinds}.", ""]
        for name, table in schema.variants.items():
            _section(table, f'{heading} with {schema.key} = "{name}"', dotted, level + 1, out, seen,
                     tag=(schema.key, name), common=common)
        return
    pending = []
    rows = ["| key | type | required / default | unit | description |", "|---|---|---|---|---|"]
    if tag is not None:
        rows.append(f'| `{tag[0]}` | `"{tag[1]}"` | required | | selects this kind |')
    grouped = {key: group for group in schema.one_of for key in group}
    elsewhere = []
    for key, spec in schema.fields.items():
        if common is not None and common.shared(dotted, key, spec, schema):
            elsewhere.append(f"`{_bare(key)}`")
            continue
        child = f"{dotted}.{_bare(key)}" if dotted else _bare(key)
        kind = spec.type.name
        for table in _inner(spec.type):
            if id(table) not in seen:
                array = "[[{}]]" if isinstance(spec.type, ArrayOf) else "[{}]"
                seen[id(table)] = array.format(child) + (f' ({tag[0]} = "{tag[1]}")' if tag else "")
                pending.append((table, seen[id(table)], child))
            kind += f", see `{seen[id(table)]}`"
        if spec.required:
            need = "required"
        elif key in grouped:
            need = "exactly one of " + ", ".join(f"`{name}`" for name in grouped[key])
        elif spec.default is MISSING:
            need = "optional"
        elif isinstance(spec.default, Mapping) and spec.default:
            need = "optional (defaults below)"
        else:
            need = f"default `{_toml(spec.default)}`"
        rows.append(f"| `{_bare(key)}` | {_cell(kind)} | {_cell(need)} | {_cell(spec.unit)} | {_cell(spec.doc)} |")
    if len(rows) == 2 and tag is None:
        rows = [] if elsewhere else ["No keys."]
    out += rows + ([""] if rows else [])
    if elsewhere:
        out += [f"And the shared keys {', '.join(elsewhere)} (see *Shared keys and tables*).", ""]
    for table, child_heading, child in pending:
        _section(table, child_heading, child, level + 1, out, seen, common=common)


def describe(schema: Table | Variants, title: str = "Top level", common: Common | None = None) -> str:
    """A Markdown reference of ``schema``: one section per table (and per variant) listing every
    key with its type, required / default, unit and doc. With ``common``, the keys and tables it
    shares with other schemas are named, not described (:func:`describe_common` describes them)."""
    out: list[str] = []
    seen = {id(schema): title, **(common.seen() if common is not None else {})}
    _section(schema, title, "", 2, out, seen, common=common)
    return "\n".join(out).rstrip() + "\n"


def describe_common(common: Common, title: str = "Shared keys and tables") -> str:
    """The Markdown reference of what several schemas share (:class:`Common`): the shared keys of
    each table, then each shared table, once."""
    out = [f"## {title}", "", "Keys and tables several kinds have, described once; each kind's section names "
           "the ones it has.", ""]
    seen = common.seen()
    by_path: dict[str, dict[str, Field]] = {}
    for path, signature in sorted(common.keys, key=lambda k: k[0]):  # stable: declaration order in a path
        key, spec = common.fields[(path, signature)]
        by_path.setdefault(path, {})[key] = spec
    for path, fields in by_path.items():
        heading = "Top-level keys" if not path else f"Keys of [{path}]"
        _section(Table(fields), heading, path, 3, out, dict(seen))
    for i, (table, heading, path) in common.tables.items():
        others = {k: v for k, v in seen.items() if k != i}
        _section(table, heading, path, 3, out, others)
    return "\n".join(out).rstrip() + "\n"
