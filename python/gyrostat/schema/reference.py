"""A schema as a Markdown reference: :func:`describe` (one section per table and variant, a row
per key) and :class:`Common` with :func:`describe_common` (what several schemas share, described
once)."""

from __future__ import annotations

import json
from collections.abc import Iterable, Mapping
from typing import Any

from gyrostat.schema.fields import ArrayOf, Field, OneOf, Table, Variants, _Type
from gyrostat.schema.messages import MISSING, _bare


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
