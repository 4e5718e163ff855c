"""A schema's types and their validation: the value types (numbers, strings, :class:`Choice`,
:class:`Vector`, :class:`Matrix`, :class:`ListOf`, :class:`Table`, :class:`ArrayOf`,
:class:`Variants`, :class:`OneOf`), :class:`Field` (one key), :func:`validate` (a document
checked and normalised) and :func:`locate` (a key found by its path, for a sweep)."""

from __future__ import annotations

import copy
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from gyrostat.schema.messages import (MISSING, SceneError, _alternatives, _dotted, _got, _kind_of, _one_line, _Path,
                                      _show, _suggest)


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
            if key in value and value[key] is None and spec.default is None:  # an optional value left unset
                out[key] = None
            elif key in value:
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
